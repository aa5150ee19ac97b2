#include <cstdio>

#include <nlohmann/json.hpp>

#include "loom/framegraph/export.hpp"

namespace loom::fg {
namespace {

using nlohmann::json;

json usage_json(rhi::TextureUsage usage) {
    json flags = json::array();
    for (auto flag : {rhi::TextureUsage::Sampled, rhi::TextureUsage::ColorAttachment,
                      rhi::TextureUsage::DepthStencilAttachment, rhi::TextureUsage::Storage,
                      rhi::TextureUsage::CopySrc, rhi::TextureUsage::CopyDst}) {
        if (rhi::has_all(usage, flag)) flags.push_back(describe_usage(flag));
    }
    return flags;
}

json spec_json(const ResolvedSpec& spec) {
    return json{{"format", rhi::format_name(spec.format)},
                {"format_match", format_match_name(spec.format_match)},
                {"width", spec.extent.width},
                {"height", spec.extent.height},
                {"samples", spec.samples},
                {"mips", spec.mips},
                {"layers", spec.layers},
                {"usage", usage_json(spec.usage)}};
}

}  // namespace

std::string plan_to_json(const Plan& plan, int indent) {
    json out;
    out["allocator"] = plan.allocator;
    out["frame"] = {{"width", plan.frame.width}, {"height", plan.frame.height}};
    out["sharing"] = spec_sharing_name(plan.sharing);
    char hash[24];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(plan_hash(plan)));
    out["hash"] = hash;

    const PlanSummary& s = plan.summary;
    out["summary"] = {{"textures", s.textures},
                      {"bytes", s.bytes},
                      {"naive_textures", s.naive_textures},
                      {"naive_bytes", s.naive_bytes},
                      {"lower_bound_textures", s.lower_bound_textures},
                      {"lower_bound_bytes", s.lower_bound_bytes}};

    json order = json::array();
    json passes = json::array();
    for (const PlanPass& pass : plan.order) {
        order.push_back(pass.name);
        json ports = json::array();
        for (const PlanPort& port : pass.ports) {
            json p{{"name", port.name}, {"kind", port_kind_name(port.kind)}, {"optional", port.optional}};
            if (port.resource) {
                p["resource"] = *port.resource;
                p["texture"] = plan.resources[*port.resource].texture;
                p["usage"] = usage_json(port.usage);
            } else {
                p["resource"] = nullptr;
                p["texture"] = nullptr;
            }
            ports.push_back(std::move(p));
        }
        passes.push_back(json{{"name", pass.name},
                              {"declaration_index", pass.declaration_index},
                              {"side_effect", pass.side_effect},
                              {"ports", std::move(ports)}});
    }
    out["order"] = std::move(order);
    out["culled"] = plan.culled;
    out["passes"] = std::move(passes);

    json edges = json::array();
    for (const PlanEdge& e : plan.edges) {
        const PlanPass& from = plan.order[e.from_pass];
        const PlanPass& to = plan.order[e.to_pass];
        edges.push_back(json{{"from", from.name + "." + from.ports[e.from_port].name},
                             {"to", to.name + "." + to.ports[e.to_port].name},
                             {"resource", e.resource},
                             {"texture", plan.resources[e.resource].texture}});
    }
    out["edges"] = std::move(edges);
    out["graph_outputs"] = plan.graph_outputs;

    json resources = json::array();
    for (const PlanResource& r : plan.resources) {
        json item{{"name", r.name}, {"ports", r.ports}};
        item["requested_format"] = r.requested_format ? json(describe_features(*r.requested_format)) : json(nullptr);
        item.update(spec_json(r.spec));
        item["lifetime"] = {r.lifetime.first, r.lifetime.last};
        item["graph_output"] = r.graph_output;
        item["spec_class"] = r.spec_class;
        item["bytes"] = r.bytes;
        item["alignment"] = r.alignment;
        item["texture"] = r.texture;
        resources.push_back(std::move(item));
    }
    out["resources"] = std::move(resources);

    json classes = json::array();
    for (const SpecClass& c : plan.spec_classes) {
        json item = spec_json(c.spec);
        item["resources"] = c.resources;
        item["peak_live"] = c.peak_live;
        classes.push_back(std::move(item));
    }
    out["spec_classes"] = std::move(classes);

    json textures = json::array();
    for (const PlanTexture& t : plan.textures) {
        json item{{"name", t.name}};
        item.update(spec_json(t.spec));
        item["resources"] = t.resources;
        item["bytes"] = t.bytes;
        item["alignment"] = t.alignment;
        if (t.placement) {
            item["heap"] = t.placement->heap;
            item["offset"] = t.placement->offset;
        }
        textures.push_back(std::move(item));
    }
    out["textures"] = std::move(textures);
    out["heaps"] = plan.heaps;
    return out.dump(indent);
}

}  // namespace loom::fg

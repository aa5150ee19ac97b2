#include <cstdio>
#include <ostream>
#include <sstream>
#include <string_view>

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

// Writes one JSON object member by member, so a large plan is never held as one document:
// each member (and each element of an array member) is built as a small json value and
// dumped in place. The text is what json::dump(indent) prints for the whole document, as long
// as members come in nlohmann's key order (sorted) and the values dump without raw newlines
// inside strings (dump escapes them).
class ObjectWriter {
public:
    ObjectWriter(std::ostream& out, int indent) : out_(out), indent_(indent) { out_ << '{'; }

    void member(std::string_view key, const json& value) {
        begin_member(key);
        write_value(value, 1);
    }

    /// An array member whose elements come from `element(i)`, i < count.
    template <class Element>
    void array_member(std::string_view key, std::size_t count, Element&& element) {
        begin_member(key);
        if (count == 0) {
            out_ << "[]";
            return;
        }
        out_ << '[';
        for (std::size_t i = 0; i < count; ++i) {
            if (i > 0) out_ << ',';
            newline(2);
            write_value(element(i), 2);
        }
        newline(1);
        out_ << ']';
    }

    void finish() {
        if (members_ > 0) newline(0);
        out_ << '}';
    }

private:
    void begin_member(std::string_view key) {
        if (members_++ > 0) out_ << ',';
        newline(1);
        out_ << json(key).dump() << (indent_ >= 0 ? ": " : ":");
    }

    void newline(int depth) {
        if (indent_ < 0) return;
        out_ << '\n' << std::string(static_cast<std::size_t>(depth) * static_cast<std::size_t>(indent_), ' ');
    }

    // `value` as dump() prints it at `depth`: every line after the first indented by depth.
    void write_value(const json& value, int depth) {
        const std::string text = value.dump(indent_);
        if (indent_ <= 0 || text.find('\n') == std::string::npos) {
            out_ << text;
            return;
        }
        const std::string margin(static_cast<std::size_t>(depth) * static_cast<std::size_t>(indent_), ' ');
        std::size_t from = 0;
        for (std::size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', from)) {
            out_.write(text.data() + from, static_cast<std::streamsize>(at + 1 - from));
            out_ << margin;
            from = at + 1;
        }
        out_.write(text.data() + from, static_cast<std::streamsize>(text.size() - from));
    }

    std::ostream& out_;
    int indent_;
    std::size_t members_ = 0;
};

json pass_json(const Plan& plan, const PlanPass& pass) {
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
    return json{{"name", pass.name},
                {"declaration_index", pass.declaration_index},
                {"side_effect", pass.side_effect},
                {"ports", std::move(ports)}};
}

json edge_json(const Plan& plan, const PlanEdge& e) {
    const PlanPass& from = plan.order[e.from_pass];
    const PlanPass& to = plan.order[e.to_pass];
    return json{{"from", from.name + "." + from.ports[e.from_port].name},
                {"to", to.name + "." + to.ports[e.to_port].name},
                {"resource", e.resource},
                {"texture", plan.resources[e.resource].texture}};
}

json resource_json(const PlanResource& r) {
    json item{{"name", r.name}, {"ports", r.ports}};
    item["requested_format"] = r.requested_format ? json(describe_features(*r.requested_format)) : json(nullptr);
    item.update(spec_json(r.spec));
    item["lifetime"] = {r.lifetime.first, r.lifetime.last};
    item["graph_output"] = r.graph_output;
    item["spec_class"] = r.spec_class;
    item["bytes"] = r.bytes;
    item["alignment"] = r.alignment;
    item["texture"] = r.texture;
    return item;
}

json spec_class_json(const SpecClass& c) {
    json item = spec_json(c.spec);
    item["resources"] = c.resources;
    item["peak_live"] = c.peak_live;
    return item;
}

json texture_json(const PlanTexture& t) {
    json item{{"name", t.name}};
    item.update(spec_json(t.spec));
    item["resources"] = t.resources;
    item["bytes"] = t.bytes;
    item["alignment"] = t.alignment;
    if (t.placement) {
        item["heap"] = t.placement->heap;
        item["offset"] = t.placement->offset;
    }
    return item;
}

}  // namespace

void write_plan_json(std::ostream& out, const Plan& plan, int indent) {
    char hash[24];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(plan_hash(plan)));
    const PlanSummary& s = plan.summary;

    // Members in key order, as json's sorted objects print them.
    ObjectWriter writer(out, indent);
    writer.member("allocator", plan.allocator);
    writer.array_member("culled", plan.culled.size(), [&](std::size_t i) { return json(plan.culled[i]); });
    writer.array_member("edges", plan.edges.size(), [&](std::size_t i) { return edge_json(plan, plan.edges[i]); });
    writer.member("frame", json{{"width", plan.frame.width}, {"height", plan.frame.height}});
    writer.array_member("graph_outputs", plan.graph_outputs.size(),
                        [&](std::size_t i) { return json(plan.graph_outputs[i]); });
    writer.member("hash", hash);
    writer.array_member("heaps", plan.heaps.size(), [&](std::size_t i) { return json(plan.heaps[i]); });
    writer.array_member("order", plan.order.size(), [&](std::size_t i) { return json(plan.order[i].name); });
    writer.array_member("passes", plan.order.size(), [&](std::size_t i) { return pass_json(plan, plan.order[i]); });
    writer.array_member("resources", plan.resources.size(),
                        [&](std::size_t i) { return resource_json(plan.resources[i]); });
    writer.member("sharing", spec_sharing_name(plan.sharing));
    writer.array_member("spec_classes", plan.spec_classes.size(),
                        [&](std::size_t i) { return spec_class_json(plan.spec_classes[i]); });
    writer.member("summary", json{{"textures", s.textures},
                                  {"bytes", s.bytes},
                                  {"naive_textures", s.naive_textures},
                                  {"naive_bytes", s.naive_bytes},
                                  {"lower_bound_textures", s.lower_bound_textures},
                                  {"lower_bound_bytes", s.lower_bound_bytes}});
    writer.array_member("textures", plan.textures.size(), [&](std::size_t i) { return texture_json(plan.textures[i]); });
    writer.finish();
}

std::string plan_to_json(const Plan& plan, int indent) {
    std::ostringstream out;
    write_plan_json(out, plan, indent);
    return std::move(out).str();
}

}  // namespace loom::fg

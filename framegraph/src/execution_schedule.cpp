#include "loom/framegraph/execution_schedule.hpp"

#include <algorithm>
#include "text.hpp"

namespace loom::fg {
namespace {

Error graph_error(std::string message) { return make_error(ErrorCode::Graph, std::move(message)); }

struct PortLocation {
    uint32_t position = 0;  // in Plan::order
    uint32_t port = 0;      // in PlanPass::ports
};

// Finds a scheduled port; the error says whether the pass is unknown, culled, or lacks the port.
Result<PortLocation> locate(const Plan& plan, const PortRef& ref, std::string_view what) {
    for (uint32_t p = 0; p < plan.order.size(); ++p) {
        const PlanPass& pass = plan.order[p];
        if (pass.name != ref.pass) continue;
        for (uint32_t i = 0; i < pass.ports.size(); ++i) {
            if (pass.ports[i].name == ref.port) return PortLocation{p, i};
        }
        std::string names;
        for (const PlanPort& port : pass.ports) names += (names.empty() ? "" : ", ") + port.name;
        return graph_error(std::string(what) + " " + ref.to_string() + ": pass '" + ref.pass + "' has no port '" +
                           ref.port + "' (ports: " + (names.empty() ? "none" : names) + ")");
    }
    if (std::find(plan.culled.begin(), plan.culled.end(), ref.pass) != plan.culled.end()) {
        return graph_error(std::string(what) + " " + ref.to_string() + ": pass '" + ref.pass +
                           "' is culled (nothing reads its results)");
    }
    return graph_error(std::string(what) + " " + ref.to_string() + ": unknown pass '" + ref.pass + "'");
}

// Positions in Plan::order where each resource is used, in order.
std::vector<std::vector<uint32_t>> resource_uses(const Plan& plan) {
    std::vector<std::vector<uint32_t>> uses(plan.resources.size());
    for (uint32_t p = 0; p < plan.order.size(); ++p) {
        for (const PlanPort& port : plan.order[p].ports) {
            if (port.resource && (uses[*port.resource].empty() || uses[*port.resource].back() != p)) {
                uses[*port.resource].push_back(p);
            }
        }
    }
    return uses;
}

}  // namespace

std::string describe_slot(const TextureSlot& slot) {
    switch (slot.kind) {
        case TextureSlot::Kind::None: return "none";
        // detail::concat, not "literal" + std::to_string: GCC 12 at -O3 warns falsely on that (text.hpp).
        case TextureSlot::Kind::Plan: return detail::concat("t", slot.index);
        case TextureSlot::Kind::Import: return detail::concat("import ", slot.index);
        case TextureSlot::Kind::History: return detail::concat("history ", slot.index);
    }
    return "none";
}

std::string describe_slot(const BufferSlot& slot) {
    switch (slot.kind) {
        case BufferSlot::Kind::None: return "none";
        case BufferSlot::Kind::Plan: return detail::concat("b", slot.index);
        case BufferSlot::Kind::Import: return detail::concat("buffer import ", slot.index);
    }
    return "none";
}

rhi::ResourceState buffer_state(PortKind kind, rhi::BufferUsage usage) {
    using rhi::BufferUsage;
    using rhi::ResourceState;
    if (port_writes(kind)) return usage == BufferUsage::CopyDst ? ResourceState::CopyDst : ResourceState::Storage;
    switch (usage) {
        case BufferUsage::Vertex: return ResourceState::VertexBuffer;
        case BufferUsage::Index: return ResourceState::IndexBuffer;
        case BufferUsage::Indirect: return ResourceState::IndirectArgument;
        case BufferUsage::CopySrc: return ResourceState::CopySrc;
        default: return ResourceState::ShaderRead;
    }
}

rhi::ResourceState sampled_state(rhi::Format format) {
    return rhi::format_info(format).is_depth_stencil() ? rhi::ResourceState::DepthRead : rhi::ResourceState::ShaderRead;
}

Result<ExecutionSchedule> build_execution_schedule(const Plan& plan, std::span<const ImportBinding> imports,
                                                   std::span<const HistoryBinding> histories,
                                                   std::span<const ImportBinding> buffer_imports) {
    ExecutionSchedule schedule;
    schedule.resource_import.assign(plan.resources.size(), std::nullopt);
    schedule.texture_needed.assign(plan.textures.size(), false);
    schedule.buffer_needed.assign(plan.buffers.size(), false);
    const auto uses = resource_uses(plan);

    // Imports: a port with a resource hands over the resource, a port without one gets its own.
    std::vector<std::optional<uint32_t>> port_import;  // by flat (position, port) below
    std::vector<uint32_t> port_offset(plan.order.size() + 1, 0);
    for (uint32_t p = 0; p < plan.order.size(); ++p) {
        port_offset[p + 1] = port_offset[p] + static_cast<uint32_t>(plan.order[p].ports.size());
    }
    port_import.assign(port_offset.back(), std::nullopt);
    std::vector<std::optional<uint32_t>> port_history(port_offset.back(), std::nullopt);
    std::vector<std::optional<uint32_t>> port_buffer_import(port_offset.back(), std::nullopt);

    // Texture imports on texture ports, buffer imports on buffer ports; per resource the import
    // numbered in its type's list.
    auto bind = [&](std::span<const ImportBinding> bindings, ResourceType type,
                    std::vector<std::optional<uint32_t>>& port_bound) -> Status {
        const bool texture = type == ResourceType::Texture;
        const std::string what = texture ? "import" : "buffer import";
        for (uint32_t i = 0; i < bindings.size(); ++i) {
            auto at = locate(plan, bindings[i].port, what);
            if (!at) return at.take_error();
            const PlanPort& port = plan.order[at->position].ports[at->port];
            if (port.type != type) {
                return graph_error(what + " " + bindings[i].port.to_string() +
                                   (texture ? ": a buffer port takes a buffer (Executor::import_buffer), not a texture"
                                            : ": a texture port takes a texture (Executor::import_texture), not a buffer"));
            }
            if (!port.resource) {
                port_bound[port_offset[at->position] + at->port] = i;
                continue;
            }
            if (auto& existing = schedule.resource_import[*port.resource]) {
                return graph_error(what + " " + bindings[i].port.to_string() + ": its " +
                                   std::string(resource_type_name(type)) + " (resource " +
                                   plan.resources[*port.resource].name + ") is already imported through " +
                                   bindings[*existing].port.to_string());
            }
            schedule.resource_import[*port.resource] = i;
        }
        return {};
    };
    LOOM_TRY(bind(imports, ResourceType::Texture, port_import));
    LOOM_TRY(bind(buffer_imports, ResourceType::Buffer, port_buffer_import));
    for (uint32_t t = 0; t < plan.textures.size(); ++t) {
        for (uint32_t r : plan.textures[t].resources) {
            if (!schedule.resource_import[r]) schedule.texture_needed[t] = true;
        }
    }
    for (uint32_t b = 0; b < plan.buffers.size(); ++b) {
        for (uint32_t r : plan.buffers[b].resources) {
            if (!schedule.resource_import[r]) schedule.buffer_needed[b] = true;
        }
    }
    auto buffer_slot = [&](uint32_t r) {
        if (auto import = schedule.resource_import[r]) return BufferSlot{BufferSlot::Kind::Import, *import};
        return BufferSlot{BufferSlot::Kind::Plan, plan.resources[r].buffer};
    };
    auto resource_slot = [&](uint32_t r) {
        if (auto import = schedule.resource_import[r]) return TextureSlot{TextureSlot::Kind::Import, *import};
        return TextureSlot{TextureSlot::Kind::Plan, plan.resources[r].texture};
    };

    // Histories: one texture (or pair) per source resource, shared by its readers.
    for (const HistoryBinding& binding : histories) {
        auto reader = locate(plan, binding.reader, "history reader");
        if (!reader) return reader.take_error();
        const PlanPort& reader_port = plan.order[reader->position].ports[reader->port];
        if (reader_port.type != ResourceType::Texture) {
            return graph_error("history reader " + binding.reader.to_string() + " is a buffer port; history is kept for textures");
        }
        if (reader_port.kind != PortKind::Input) {
            return graph_error("history reader " + binding.reader.to_string() + " is an " +
                               std::string(port_kind_name(reader_port.kind)) + " port; history is read through inputs");
        }
        if (reader_port.resource) {
            return graph_error("history reader " + binding.reader.to_string() +
                               " is connected in the graph; a history input must be left unconnected (declare it optional)");
        }
        if (port_import[port_offset[reader->position] + reader->port]) {
            return graph_error("history reader " + binding.reader.to_string() + " also has an imported texture");
        }
        auto source = locate(plan, binding.source, "history source");
        if (!source) return source.take_error();
        const PlanPort& source_port = plan.order[source->position].ports[source->port];
        if (!source_port.resource) {
            return graph_error("history source " + binding.source.to_string() +
                               " has no texture in the plan (an unconnected optional port)");
        }
        if (source_port.type != ResourceType::Texture) {
            return graph_error("history source " + binding.source.to_string() + " is a buffer port; history is kept for textures");
        }
        const uint32_t r = *source_port.resource;
        uint32_t h = 0;
        while (h < schedule.histories.size() && schedule.histories[h].resource != r) ++h;
        if (h == schedule.histories.size()) {
            HistoryTexture history;
            history.source = plan.resources[r].name;
            history.resource = r;
            history.spec = plan.resources[r].spec;
            history.copy_after = uses[r].back();
            schedule.histories.push_back(std::move(history));
        }
        HistoryTexture& history = schedule.histories[h];
        history.readers.push_back(binding.reader.to_string());
        // A reader after the copy would see this frame's contents in a single texture.
        if (reader->position > history.copy_after) history.textures = 2;
        port_history[port_offset[reader->position] + reader->port] = h;
    }

    // Per pass: textures, load/store, transitions.
    schedule.passes.resize(plan.order.size());
    for (uint32_t p = 0; p < plan.order.size(); ++p) {
        const PlanPass& pass = plan.order[p];
        PassSchedule& out = schedule.passes[p];
        out.name = pass.name;
        for (uint32_t i = 0; i < pass.ports.size(); ++i) {
            const PlanPort& port = pass.ports[i];
            PortSchedule ps;
            ps.name = port.name;
            ps.kind = port.kind;
            ps.resource = port.resource;
            ps.usage = port.usage;
            if (port.type == ResourceType::Texture && port.resource) ps.range = port.range;
            // Transitions of a port that uses every subresource name the whole texture.
            rhi::TextureRange moved = ps.range;
            if (port.resource && port.type == ResourceType::Texture) {
                const ResolvedSpec& spec = plan.resources[*port.resource].spec;
                if (moved == rhi::TextureRange{0, spec.mips, 0, spec.layers}) moved = rhi::TextureRange{};
            }
            if (port.type == ResourceType::Buffer) {
                ps.buffer_usage = port.buffer_usage;
                if (port.resource) {
                    ps.buffer = buffer_slot(*port.resource);
                    ps.first_write = port_writes(port.kind) && plan.resources[*port.resource].name == pass.name + "." + port.name;
                } else if (auto import = port_buffer_import[port_offset[p] + i]) {
                    ps.buffer = {BufferSlot::Kind::Import, *import};
                    out.buffers_after.push_back({ps.buffer, buffer_imports[*import].final_state});
                }
                if (!ps.buffer.empty()) out.buffers_before.push_back({ps.buffer, buffer_state(port.kind, ps.buffer_usage)});
                out.ports.push_back(std::move(ps));
                continue;
            }
            rhi::Format format = rhi::Format::Undefined;
            const bool storage = rhi::has_all(port.usage, rhi::TextureUsage::Storage);
            if (port.resource) {
                const uint32_t r = *port.resource;
                const PlanResource& resource = plan.resources[r];
                format = resource.spec.format;
                ps.texture = resource_slot(r);
                const bool imported = schedule.resource_import[r].has_value();
                // The starting port is the resource's first use (lifetime.first) and writes.
                ps.first_write = port_writes(port.kind) && resource.name == pass.name + "." + port.name;
                if (ps.first_write && !(imported && port.kind == PortKind::InOut)) {
                    ps.load = rhi::LoadOp::Clear;
                } else {
                    ps.load = rhi::LoadOp::Load;
                }
                const bool history_source = std::any_of(schedule.histories.begin(), schedule.histories.end(),
                                                        [&](const HistoryTexture& h) { return h.resource == r; });
                const bool read_later = uses[r].back() > p;
                ps.store = (read_later || resource.graph_output || imported || history_source) ? rhi::StoreOp::Store
                                                                                               : rhi::StoreOp::DontCare;
                if (!port_writes(port.kind)) ps.store = rhi::StoreOp::Store;  // an input never discards
            } else if (auto import = port_import[port_offset[p] + i]) {
                ps.texture = {TextureSlot::Kind::Import, *import};
                ps.first_write = port_writes(port.kind);
                // The plan gave the port no usage (it had no texture); its role says it.
                if (ps.usage == rhi::TextureUsage::None) {
                    ps.usage = port_writes(port.kind) ? rhi::TextureUsage::ColorAttachment : rhi::TextureUsage::Sampled;
                }
                ps.load = port.kind == PortKind::Output ? rhi::LoadOp::Clear : rhi::LoadOp::Load;
                ps.store = rhi::StoreOp::Store;
                out.after.push_back({ps.texture, imports[*import].final_state});
            } else if (auto history = port_history[port_offset[p] + i]) {
                ps.texture = {TextureSlot::Kind::History, *history};
                format = schedule.histories[*history].spec.format;
                ps.usage = rhi::TextureUsage::Sampled;
                ps.load = rhi::LoadOp::Load;
                ps.store = rhi::StoreOp::Store;
            }
            if (!ps.texture.empty()) {
                if (pass.kind == PassKind::Copy) {
                    out.before.push_back(
                        {ps.texture, port_writes(port.kind) ? rhi::ResourceState::CopyDst : rhi::ResourceState::CopySrc, moved});
                } else if (storage) {
                    out.before.push_back({ps.texture, rhi::ResourceState::Storage, moved});
                } else if (!port_writes(port.kind) && rhi::has_all(ps.usage, rhi::TextureUsage::Sampled)) {
                    // Imported inputs without a plan resource: format known only at run time;
                    // the executor substitutes DepthRead for depth textures.
                    out.before.push_back({ps.texture,
                                          format == rhi::Format::Undefined ? rhi::ResourceState::ShaderRead : sampled_state(format),
                                          moved});
                }
            }
            out.ports.push_back(std::move(ps));
        }
    }
    // Imports of resources reach their final state after the resource's last use.
    for (uint32_t r = 0; r < plan.resources.size(); ++r) {
        if (plan.resources[r].type == ResourceType::Buffer) {
            if (auto import = schedule.resource_import[r]) {
                schedule.passes[uses[r].back()].buffers_after.push_back(
                    {BufferSlot{BufferSlot::Kind::Import, *import}, buffer_imports[*import].final_state});
            }
            continue;
        }
        if (auto import = schedule.resource_import[r]) {
            schedule.passes[uses[r].back()].after.push_back(
                {TextureSlot{TextureSlot::Kind::Import, *import}, imports[*import].final_state});
        }
    }
    for (uint32_t h = 0; h < schedule.histories.size(); ++h) {
        const HistoryTexture& history = schedule.histories[h];
        schedule.passes[history.copy_after].copies.push_back({h, resource_slot(history.resource)});
    }
    return schedule;
}

}  // namespace loom::fg

// Re-planning from the previous plan for another frame size or other texture specs
// (plan_resize.hpp).
#include "plan_resize.hpp"

#include <algorithm>

#include "loom/framegraph/allocator.hpp"
#include "loom/framegraph/memory_model.hpp"
#include "loom/framegraph/resolved_spec.hpp"
#include "plan_phases.hpp"

namespace loom::fg::detail {
namespace {

// A frame size changes nothing of a resource whose joined size is absolute.
bool sized_by_frame(const std::optional<SizeSpec>& size) { return !size || size->kind == SizeSpec::Kind::Relative; }

// The textures' extents for `frame`, each with its bytes; false where one does not resolve.
bool resize_textures(const ResizeBasis& basis, Extent2D frame, MemoryModel& memory, std::vector<PlanResource>& resources) {
    for (uint32_t r = 0; r < resources.size(); ++r) {
        PlanResource& resource = resources[r];
        if (resource.type != ResourceType::Texture || !sized_by_frame(basis.joined_sizes[r])) continue;
        auto spec = resolve_for_frame(resource.spec, basis.joined_sizes[r], frame, resource.name);
        if (!spec) return false;
        if (spec->extent == resource.spec.extent) continue;
        resource.spec = *spec;
        if (!measure_resource(resource, memory)) return false;
    }
    return true;
}

// The buffers' sizes for `frame`, each with its bytes, and the byte ranges of their ports made
// concrete for the new sizes (plan_passes); false where one does not resolve or a port's range
// no longer fits.
bool resize_buffers(const FrameGraph& graph, const ResizeBasis& basis, Extent2D frame, MemoryModel& memory,
                    Plan& plan) {
    std::vector<bool> resized;
    for (const auto& [r, size] : basis.joined_buffer_sizes) {
        if (size.kind == BufferSize::Kind::Absolute) continue;
        PlanResource& resource = plan.resources[r];
        // The resolved alignment stands for the joined one (1 when none was asked), and the
        // usage is the ports' as before: resolving gives the same spec with the new size.
        BufferSpec joined;
        joined.size = size;
        joined.alignment = resource.buffer_spec.alignment;
        joined.usage = resource.buffer_spec.usage;
        auto spec = resolve_buffer(joined, frame, resource.name);
        if (!spec) return false;
        if (spec->size == resource.buffer_spec.size) continue;
        resource.buffer_spec = *spec;
        if (!measure_resource(resource, memory)) return false;
        resized.resize(plan.resources.size(), false);
        resized[r] = true;
    }
    if (resized.empty()) return true;
    for (PlanPass& pass : plan.order) {
        for (uint32_t i = 0; i < pass.ports.size(); ++i) {
            PlanPort& port = pass.ports[i];
            if (!port.resource || !resized[*port.resource]) continue;
            const BufferRange& declared = graph.port_at({pass.declaration_index, i}).bytes;
            auto bytes = resolve_bytes(declared, plan.resources[*port.resource].buffer_spec.size);
            if (!bytes) return false;
            port.bytes = *bytes;
        }
    }
    return true;
}

// The resources of the texture ports of the passes `respecified` joined and resolved again for
// `frame`, and the usages and ranges of their ports; false where that fails or a respecified
// pass reaches a pass that does not run.
bool respecify(const FrameGraph& graph, ResizeBasis& basis, std::span<const uint32_t> respecified, Extent2D frame,
               MemoryModel& memory, Plan& plan) {
    const std::vector<uint32_t>& position = basis.position;
    std::vector<bool> affected(plan.resources.size(), false);
    for (uint32_t pass : respecified) {
        // The groups of a culled pass are joined too: whether they still join is build_plan's to say.
        if (position[pass] == kNotScheduled) return false;
        const std::vector<PlanPort>& ports = plan.order[position[pass]].ports;
        for (uint32_t i = 0; i < ports.size(); ++i) {
            if (ports[i].type != ResourceType::Texture) continue;
            if (ports[i].resource) {
                affected[*ports[i].resource] = true;
            } else if (!graph.consumers({pass, i}).empty()) {
                return false;  // an optional output only culled passes read: a group without a resource
            }
        }
    }
    std::vector<PortAddress> running;
    for (uint32_t r = 0; r < plan.resources.size(); ++r) {
        if (!affected[r]) continue;
        PlanResource& resource = plan.resources[r];
        if (!rejoin_resource(graph, basis.starts[r], position, frame, memory, resource, basis.joined_sizes[r], running)) {
            return false;
        }
        for (const PortAddress& address : running) {
            // A plan pass's ports are its declared ports, in order.
            PlanPort& port = plan.order[position[address.pass]].ports[address.port];
            port.usage = port_texture_usage(graph.facts(address), resource.spec.format);
            // Checked by rejoin_resource.
            port.range =
                resolve_range(graph.port_at(address).range, resource.spec.mips, resource.spec.layers).value_or(SubresourceRange{});
        }
    }
    return true;
}

}  // namespace

bool replan(const FrameGraph& graph, ResizeBasis& basis, const PlanOptions& options,
            std::span<const uint32_t> respecified, Plan& plan) {
    std::shared_ptr<MemoryModel> memory = options.memory_model;
    if (!memory) memory = std::make_shared<DefaultMemoryModel>();
    // Respecified resources first, for the new frame: resizing then finds them resolved.
    if (!respecified.empty() && !respecify(graph, basis, respecified, options.frame, *memory, plan)) return false;
    if (options.frame != plan.frame) {
        if (!resize_textures(basis, options.frame, *memory, plan.resources)) return false;
        if (!resize_buffers(graph, basis, options.frame, *memory, plan)) return false;
        plan.frame = options.frame;
    }
    const std::unique_ptr<Allocator> allocator = make_allocator(options.allocator);
    return allocate_resized_plan(plan, options, *allocator, *memory, basis.graph_output_resources).ok();
}

}  // namespace loom::fg::detail

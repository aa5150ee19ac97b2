#include "loom/framegraph/planner.hpp"

#include <algorithm>
#include <array>
#include <functional>
#include <map>
#include <numeric>
#include <queue>
#include <tuple>

#include "graph_analysis.hpp"
#include "plan_phases.hpp"
#include "loom/framegraph/allocator.hpp"
#include "loom/framegraph/graph.hpp"
#include "loom/framegraph/join.hpp"

namespace loom::fg {
namespace {

using rhi::TextureUsage;

constexpr uint32_t kNone = UINT32_MAX;

// A spec that asks for exactly what `resolved` is, to join resolved specs with each other.
TextureSpec as_spec(const ResolvedSpec& resolved) {
    TextureSpec spec = TextureSpec::of(resolved.format).with_size(resolved.extent.width, resolved.extent.height);
    spec.samples = resolved.samples;
    spec.mips = resolved.mips;
    spec.layers = resolved.layers;
    spec.usage = resolved.usage;
    return spec;
}

// Join of two resolved specs; nullopt when they do not join.
std::optional<ResolvedSpec> join_resolved(const ResolvedSpec& a, const ResolvedSpec& b, Extent2D frame) {
    if (same_texture_shape(a, b)) {
        ResolvedSpec out = a;
        out.usage = a.usage | b.usage;
        return out;
    }
    JoinContext context;
    context.frame = frame;
    auto joined = join(as_spec(a), as_spec(b), context);
    if (!joined) return std::nullopt;
    auto resolved = resolve(*joined, frame, "joined texture");
    if (!resolved) return std::nullopt;
    return *resolved;
}

// Most members of each class alive at once, and the peak of live bytes, over the order.
struct Peaks {
    std::vector<uint32_t> live_per_class;
    uint64_t bytes = 0;
};

Peaks measure_peaks(const std::vector<PlanResource>& resources, uint32_t pass_count, uint32_t class_count) {
    // Sweep: +1 at first, -1 after last.
    std::vector<std::vector<uint32_t>> starting(pass_count + 1);
    std::vector<std::vector<uint32_t>> ending(pass_count + 1);
    for (uint32_t r = 0; r < resources.size(); ++r) {
        starting[resources[r].lifetime.first].push_back(r);
        ending[resources[r].lifetime.last + 1].push_back(r);
    }
    Peaks peaks;
    peaks.live_per_class.assign(class_count, 0);
    std::vector<uint32_t> live(class_count, 0);
    uint64_t live_bytes = 0;
    for (uint32_t position = 0; position < pass_count; ++position) {
        for (uint32_t r : ending[position]) {
            --live[resources[r].spec_class];
            live_bytes -= resources[r].bytes;
        }
        for (uint32_t r : starting[position]) {
            const uint32_t c = resources[r].spec_class;
            peaks.live_per_class[c] = std::max(peaks.live_per_class[c], ++live[c]);
            live_bytes += resources[r].bytes;
        }
        peaks.bytes = std::max(peaks.bytes, live_bytes);
    }
    return peaks;
}

}  // namespace

Result<Plan> build_plan(const FrameGraph& graph, const PlanOptions& options) {
    if (options.frame.width == 0 || options.frame.height == 0) {
        return make_error(ErrorCode::InvalidArgument, "plan: frame size " + std::to_string(options.frame.width) + "x" +
                                                          std::to_string(options.frame.height) + " is empty");
    }
    auto allocator = make_allocator(options.allocator);
    if (!allocator) return allocator.take_error();
    std::shared_ptr<MemoryModel> memory = options.memory_model;
    if (!memory) memory = std::make_shared<DefaultMemoryModel>();

    auto dependencies = detail::analyze(graph);
    if (!dependencies) return dependencies.take_error();

    auto kept = detail::cull_passes(graph, *dependencies);
    if (!kept) return kept.take_error();
    const detail::Schedule schedule = detail::schedule_passes(*dependencies, *kept);
    const auto scheduled = static_cast<uint32_t>(schedule.order.size());
    auto resolved =
        detail::resolve_resources(graph, detail::join_port_groups(graph, options.frame), schedule, options.frame, *memory);
    if (!resolved) return resolved.take_error();

    Plan plan;
    plan.allocator = std::string((*allocator)->name());
    plan.frame = options.frame;
    plan.sharing = options.sharing;
    plan.order = detail::plan_passes(graph, schedule, *resolved);
    plan.culled = detail::culled_pass_names(graph, *kept);
    plan.edges = detail::plan_edges(graph, schedule, resolved->resource_of_port);
    for (const PortAddress& out : graph.outputs()) plan.graph_outputs.push_back(graph.port_name(out));
    plan.resources = std::move(resolved->resources);

    // ---- spec classes: which resources may share a texture -------------------------------
    // Equal sharing: a class per texture shape (its shape never changes, only its usage
    // grows), found by key rather than by trying every class.
    using ShapeKey = std::tuple<rhi::Format, uint32_t, uint32_t, uint32_t, uint32_t, uint32_t>;
    auto shape_key = [](const ResolvedSpec& spec) {
        return ShapeKey{spec.format, spec.extent.width, spec.extent.height, spec.samples, spec.mips, spec.layers};
    };
    std::map<ShapeKey, uint32_t> class_of_shape;
    for (uint32_t r = 0; r < plan.resources.size(); ++r) {
        PlanResource& resource = plan.resources[r];
        uint32_t chosen = kNone;
        if (options.sharing == SpecSharing::Equal) {
            auto it = class_of_shape.find(shape_key(resource.spec));
            if (it != class_of_shape.end()) {
                chosen = it->second;
                plan.spec_classes[chosen].spec.usage |= resource.spec.usage;
            } else {
                class_of_shape.emplace(shape_key(resource.spec), static_cast<uint32_t>(plan.spec_classes.size()));
            }
        }
        for (uint32_t c = 0; options.sharing != SpecSharing::Equal && c < plan.spec_classes.size() && chosen == kNone;
             ++c) {
            SpecClass& spec_class = plan.spec_classes[c];
            if (auto joined = join_resolved(spec_class.spec, resource.spec, options.frame)) {
                spec_class.spec = *joined;
                chosen = c;
            }
        }
        if (chosen == kNone) {
            chosen = static_cast<uint32_t>(plan.spec_classes.size());
            plan.spec_classes.push_back(SpecClass{resource.spec, {}, 0});
        }
        resource.spec_class = chosen;
        plan.spec_classes[chosen].resources.push_back(r);
    }
    const auto class_count = static_cast<uint32_t>(plan.spec_classes.size());
    const Peaks peaks = measure_peaks(plan.resources, scheduled, class_count);
    for (uint32_t c = 0; c < class_count; ++c) plan.spec_classes[c].peak_live = peaks.live_per_class[c];

    // ---- the allocation problem ----------------------------------------------------------
    AllocationProblem problem;
    problem.spec_class_count = class_count;
    problem.max_heap_bytes = options.max_heap_bytes;
    problem.passes.resize(scheduled);
    for (uint32_t at = 0; at < scheduled; ++at) {
        AllocationPass& step = problem.passes[at];
        for (const PlanPort& port : plan.order[at].ports) {
            if (!port.resource) continue;
            if (port_reads(port.kind)) step.inputs.push_back(*port.resource);
            if (port_writes(port.kind)) step.non_inputs.push_back(*port.resource);
        }
    }
    for (uint32_t r = 0; r < plan.resources.size(); ++r) {
        const PlanResource& resource = plan.resources[r];
        problem.passes[resource.lifetime.first].begins.push_back(r);
        problem.resources.push_back(
            AllocationResource{resource.spec_class, resource.lifetime, resource.bytes, resource.alignment, resource.name});
    }
    problem.graph_outputs = resolved->graph_output_resources;

    // ---- allocation -----------------------------------------------------------------------
    auto allocation = (*allocator)->allocate(problem);
    if (!allocation) return allocation.take_error();
    const bool placed = !allocation->texture_placement.empty();
    const bool well_formed =
        allocation->texture_of_resource.size() == plan.resources.size() &&
        std::all_of(allocation->texture_of_resource.begin(), allocation->texture_of_resource.end(),
                    [&](uint32_t t) { return t < allocation->texture_count; }) &&
        (!placed || allocation->texture_placement.size() == allocation->texture_count);
    if (!well_formed) return make_error(ErrorCode::Graph, "allocator '" + plan.allocator + "' returned a malformed allocation");
    // Number textures by first use, so plans read the same whatever an allocator's own numbering.
    std::vector<uint32_t> first_user(allocation->texture_count, kNone);
    for (uint32_t r = 0; r < plan.resources.size(); ++r) {
        uint32_t& first = first_user[allocation->texture_of_resource[r]];
        first = std::min(first, r);
    }
    if (std::find(first_user.begin(), first_user.end(), kNone) != first_user.end()) {
        return make_error(ErrorCode::Graph, "allocator '" + plan.allocator + "' made a texture no resource uses");
    }
    std::vector<uint32_t> by_first_use(allocation->texture_count);
    std::iota(by_first_use.begin(), by_first_use.end(), 0u);
    std::sort(by_first_use.begin(), by_first_use.end(),
              [&](uint32_t a, uint32_t b) { return first_user[a] < first_user[b]; });
    std::vector<uint32_t> renumbered(allocation->texture_count);
    for (uint32_t t = 0; t < by_first_use.size(); ++t) renumbered[by_first_use[t]] = t;

    plan.textures.resize(allocation->texture_count);
    for (uint32_t t = 0; t < allocation->texture_count; ++t) {
        plan.textures[t].name = "t" + std::to_string(t);
        if (placed) plan.textures[t].placement = allocation->texture_placement[by_first_use[t]];
    }
    for (uint32_t r = 0; r < plan.resources.size(); ++r) {
        const uint32_t t = renumbered[allocation->texture_of_resource[r]];
        PlanResource& resource = plan.resources[r];
        PlanTexture& texture = plan.textures[t];
        resource.texture = t;
        if (texture.resources.empty()) {
            texture.spec = resource.spec;
        } else if (auto joined = join_resolved(texture.spec, resource.spec, options.frame)) {
            texture.spec = *joined;
        } else {
            return make_error(ErrorCode::Graph, "allocator '" + plan.allocator + "' put " + resource.name +
                                                    " into a texture of a spec it does not join with");
        }
        texture.resources.push_back(r);
    }
    for (uint32_t t = 0; t < plan.textures.size(); ++t) {
        PlanTexture& texture = plan.textures[t];
        if (texture.resources.size() == 1) {
            texture.bytes = plan.resources[texture.resources.front()].bytes;
            texture.alignment = plan.resources[texture.resources.front()].alignment;
        } else {
            auto requirements = memory->requirements(to_texture_desc(texture.spec, texture.name));
            if (!requirements) return requirements.take_error();
            texture.bytes = requirements->size;
            texture.alignment = std::max<uint64_t>(requirements->alignment, 1);
        }
    }
    plan.heaps = allocation->heap_sizes;

    // ---- summary --------------------------------------------------------------------------
    PlanSummary& summary = plan.summary;
    summary.textures = static_cast<uint32_t>(plan.textures.size());
    if (placed) {
        summary.bytes = std::accumulate(plan.heaps.begin(), plan.heaps.end(), uint64_t{0});
    } else {
        for (const PlanTexture& texture : plan.textures) summary.bytes += texture.bytes;
    }
    summary.naive_textures = static_cast<uint32_t>(plan.resources.size());
    for (const PlanResource& resource : plan.resources) summary.naive_bytes += resource.bytes;
    for (const SpecClass& spec_class : plan.spec_classes) summary.lower_bound_textures += spec_class.peak_live;
    summary.lower_bound_bytes = peaks.bytes;
    return plan;
}

}  // namespace loom::fg

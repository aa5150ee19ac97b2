#include "loom/framegraph/planner.hpp"

#include <algorithm>
#include <optional>
#include <ranges>

#include "graph_analysis.hpp"
#include "loom/framegraph/allocator.hpp"
#include "loom/framegraph/graph.hpp"
#include "plan_order.hpp"
#include "plan_phases.hpp"
#include "plan_resize.hpp"

namespace loom::fg {
namespace {

// The cost of running `resolved`'s passes in `schedule`'s order with their queues: occupancies
// from the queues phase.
detail::OrderCost held_cost(const FrameGraph& graph, const detail::Dependencies& dependencies,
                            const detail::Schedule& schedule, const detail::ResolvedResources& resolved) {
    const std::vector<PlanPass> order = detail::plan_passes(graph, schedule, resolved);
    detail::QueuePlan queues = detail::plan_queues(order, resolved.resources, dependencies, schedule);
    std::vector<PlanResource> held = resolved.resources;
    for (uint32_t r = 0; r < held.size(); ++r) held[r].occupancy = queues.occupancy[r];
    return detail::held_cost(held, static_cast<uint32_t>(schedule.order.size()));
}

// Order: under PassOrder::Memory the heuristic's order is a candidate when it costs less. It
// weighs lifetimes; with async compute passes the occupancies of both orders decide, so that
// the memory order never holds more bytes at its peak than the declared one.
struct OrderCandidate {
    detail::Schedule schedule;
    detail::ResolvedResources resolved;
};
std::optional<OrderCandidate> memory_order_candidate(const FrameGraph& graph, const detail::Dependencies& dependencies,
                                                     const detail::Schedule& schedule,
                                                     const detail::ResolvedResources& resolved,
                                                     uint64_t& declared_peak) {
    const detail::OrderProblem problem = detail::make_order_problem(graph, dependencies, schedule, resolved);
    detail::OrderCost declared_cost;
    const std::vector<uint32_t> order = detail::memory_order(problem, &declared_cost);
    // Without async passes this is the declared plan's lower bound; with them, occupancies only
    // widen lifetimes, so it is at most that bound.
    declared_peak = declared_cost.peak;
    if (std::ranges::equal(order, std::views::iota(0u, problem.pass_count()))) return std::nullopt;  // declared
    OrderCandidate candidate{detail::reorder_schedule(schedule, order), {}};
    candidate.resolved = detail::reorder_resources(resolved, candidate.schedule);
    const bool any_async = std::any_of(schedule.order.begin(), schedule.order.end(), [&](uint32_t pass) {
        return graph.pass(PassId{pass}).queue() != Queue::Graphics;
    });
    if (any_async && !(held_cost(graph, dependencies, candidate.schedule, candidate.resolved) <
                       held_cost(graph, dependencies, schedule, resolved))) {
        return std::nullopt;
    }
    return candidate;
}

// A lower bound of the bytes an allocator that places nothing in heaps needs for `resolved` in
// its order, under equal sharing: a texture (or buffer) of such an allocator holds resources of
// one shape, one at a time, so each class needs at least its peak count of live resources, each
// at least as big as its smallest member. (Lifetimes: async occupancies only widen them.)
uint64_t pooled_lower_bound(const detail::ResolvedResources& resolved, const PlanOptions& options,
                            uint32_t positions) {
    const detail::SpecClassAssignment classes =
        detail::assign_spec_classes(resolved.resources, SpecSharing::Equal, options.frame, positions);
    uint64_t bytes = 0;
    for (const SpecClass& c : classes.classes) {
        uint64_t smallest = UINT64_MAX;
        for (uint32_t r : c.resources) smallest = std::min(smallest, resolved.resources[r].bytes);
        if (!c.resources.empty()) bytes += smallest * c.peak_live;
    }
    return bytes;
}

// The phases after the order is fixed (queues, spec classes, allocation, summary), each a
// function of plain data (plan_phases.hpp); what they decide is put together into the plan.
Result<Plan> plan_in_order(const FrameGraph& graph, const PlanOptions& options, const Allocator& allocator,
                           MemoryModel& memory, const detail::Dependencies& dependencies,
                           const std::vector<bool>& kept, const detail::Schedule& schedule,
                           detail::ResolvedResources resolved) {
    Plan plan;
    plan.allocator = std::string(allocator.name());
    plan.frame = options.frame;
    plan.sharing = options.sharing;
    plan.pass_order = options.order;
    plan.order = detail::plan_passes(graph, schedule, resolved);
    detail::QueuePlan queues = detail::plan_queues(plan.order, resolved.resources, dependencies, schedule);
    if (!queues.syncs.empty() && options.allocator == AllocatorKind::Paper) {
        const auto async = std::find_if(plan.order.begin(), plan.order.end(),
                                        [](const PlanPass& pass) { return pass.queue != Queue::Graphics; });
        return make_error(ErrorCode::InvalidArgument,
                          "allocator 'paper' colours ports pass by pass and cannot keep apart the resources of "
                          "passes that run at the same time on two queues (async compute pass '" +
                              async->name + "'): use 'interval' or 'heap'");
    }
    for (uint32_t r = 0; r < resolved.resources.size(); ++r) {
        resolved.resources[r].occupancy = queues.occupancy[r];
        resolved.resources[r].queue_shared = queues.queue_shared[r];
    }
    plan.queue_syncs = std::move(queues.syncs);
    plan.ownership_transfers = std::move(queues.transfers);
    plan.culled = detail::culled_pass_names(graph, kept);
    plan.edges = detail::plan_edges(graph, schedule, resolved.resource_of_port);
    for (const PortAddress& out : graph.outputs()) plan.graph_outputs.push_back(graph.port_name(out));
    detail::name_resource_ports(plan.order, resolved);
    plan.resources = std::move(resolved.resources);
    LOOM_TRY(detail::allocate_plan(plan, options, allocator, memory, std::move(resolved.graph_output_resources)));
    return plan;
}

}  // namespace

namespace detail {

Result<OrderProblem> order_problem_of(const FrameGraph& graph, const PlanOptions& options) {
    std::shared_ptr<MemoryModel> memory = options.memory_model;
    if (!memory) memory = std::make_shared<DefaultMemoryModel>();
    auto dependencies = analyze(graph);
    if (!dependencies) return dependencies.take_error();
    auto kept = cull_passes(graph, *dependencies);
    if (!kept) return kept.take_error();
    const Schedule schedule = schedule_passes(*dependencies, *kept);
    auto resolved = resolve_resources(graph, schedule, options.frame, *memory);
    if (!resolved) return resolved.take_error();
    return make_order_problem(graph, *dependencies, schedule, *resolved);
}

}  // namespace detail

namespace {

// The phases in order (plan_phases.hpp). Under PassOrder::Memory the plan of the memory order
// is kept when its allocation is no bigger than the declared order's, as the chosen allocator
// places them: the declared order is planned too only when the memory order's bytes exceed a
// lower bound of the declared order's (below it no allocation of the declared order can be).
// With `basis`, what re-planning from this plan needs is kept there (plan_resize.hpp).
Result<Plan> plan_graph(const FrameGraph& graph, const PlanOptions& options,
                        std::unique_ptr<detail::ResizeBasis>* basis) {
    if (basis) basis->reset();
    if (options.frame.width == 0 || options.frame.height == 0) {
        return make_error(ErrorCode::InvalidArgument, "plan: frame size " + std::to_string(options.frame.width) + "x" +
                                                          std::to_string(options.frame.height) + " is empty");
    }
    const auto kinds = allocator_kinds();
    if (std::find(kinds.begin(), kinds.end(), options.allocator) == kinds.end()) {
        return make_error(ErrorCode::InvalidArgument,
                          "plan: unknown allocator kind " + std::to_string(static_cast<unsigned>(options.allocator)));
    }
    const std::unique_ptr<Allocator> allocator = make_allocator(options.allocator);
    std::shared_ptr<MemoryModel> memory = options.memory_model;
    if (!memory) memory = std::make_shared<DefaultMemoryModel>();

    auto dependencies = detail::analyze(graph);
    if (!dependencies) return dependencies.take_error();
    auto kept = detail::cull_passes(graph, *dependencies);
    if (!kept) return kept.take_error();
    detail::Schedule schedule = detail::schedule_passes(*dependencies, *kept);
    auto resolved = detail::resolve_resources(graph, schedule, options.frame, *memory);
    if (!resolved) return resolved.take_error();
    if (options.order != PassOrder::Memory) {
        if (basis && !resolved->joins_compared_sizes) {
            *basis = std::make_unique<detail::ResizeBasis>(
                detail::ResizeBasis{std::move(resolved->joined_sizes), std::move(resolved->joined_buffer_sizes),
                                    resolved->graph_output_resources, resolved->starts, schedule.position});
        }
        return plan_in_order(graph, options, *allocator, *memory, *dependencies, *kept, schedule, std::move(*resolved));
    }
    uint64_t declared_peak = 0;
    std::optional<OrderCandidate> candidate =
        memory_order_candidate(graph, *dependencies, schedule, *resolved, declared_peak);
    if (!candidate) {
        return plan_in_order(graph, options, *allocator, *memory, *dependencies, *kept, schedule, std::move(*resolved));
    }
    auto reordered = plan_in_order(graph, options, *allocator, *memory, *dependencies, *kept, candidate->schedule,
                                   std::move(candidate->resolved));
    if (reordered && reordered->summary.bytes <= declared_peak) return reordered;
    // Pooled allocators (interval, paper) rarely come down to the peak of live bytes; their own
    // bound often settles it without planning the declared order.
    if (reordered && reordered->heaps.empty() && options.sharing == SpecSharing::Equal &&
        reordered->summary.bytes <=
            pooled_lower_bound(*resolved, options, static_cast<uint32_t>(schedule.order.size()))) {
        return reordered;
    }
    auto declared =
        plan_in_order(graph, options, *allocator, *memory, *dependencies, *kept, schedule, std::move(*resolved));
    // An order the allocator cannot place (a heap limit) falls back to the other.
    if (!reordered || !declared) return reordered ? std::move(reordered) : std::move(declared);
    // Fewer bytes, then fewer textures; on a tie the memory order (its peak is lower).
    const auto size = [](const Plan& plan) { return std::pair(plan.summary.bytes, plan.summary.textures); };
    return size(*declared) < size(*reordered) ? std::move(declared) : std::move(reordered);
}

}  // namespace

namespace detail {

Result<Plan> build_plan(const FrameGraph& graph, const PlanOptions& options, std::unique_ptr<ResizeBasis>& basis) {
    return plan_graph(graph, options, &basis);
}

}  // namespace detail

Result<Plan> build_plan(const FrameGraph& graph, const PlanOptions& options) { return plan_graph(graph, options, nullptr); }

}  // namespace loom::fg

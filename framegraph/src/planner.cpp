#include "loom/framegraph/planner.hpp"

#include <algorithm>

#include "graph_analysis.hpp"
#include "loom/framegraph/allocator.hpp"
#include "loom/framegraph/graph.hpp"
#include "plan_order.hpp"
#include "plan_phases.hpp"

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

// Order: under PassOrder::Memory the heuristic's order replaces the declared one when it costs
// less. It weighs lifetimes; with async compute passes the occupancies of both orders decide,
// so that the memory order never holds more bytes at its peak than the declared one.
void choose_order(const FrameGraph& graph, const detail::Dependencies& dependencies, detail::Schedule& schedule,
                  detail::ResolvedResources& resolved) {
    const detail::OrderProblem problem = detail::make_order_problem(graph, dependencies, schedule, resolved);
    const std::vector<uint32_t> order = detail::memory_order(problem);
    bool declared = true;
    for (uint32_t at = 0; at < order.size() && declared; ++at) declared = order[at] == at;
    if (declared) return;
    detail::Schedule candidate = detail::reorder_schedule(schedule, order);
    detail::ResolvedResources reordered = detail::reorder_resources(resolved, candidate);
    const bool any_async = std::any_of(schedule.order.begin(), schedule.order.end(), [&](uint32_t pass) {
        return graph.pass(PassId{pass}).queue() != Queue::Graphics;
    });
    if (any_async &&
        !(held_cost(graph, dependencies, candidate, reordered) < held_cost(graph, dependencies, schedule, resolved))) {
        return;
    }
    schedule = std::move(candidate);
    resolved = std::move(reordered);
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

// The phases in order, each a function of plain data (plan_phases.hpp); what they decide is
// put together into the plan here.
Result<Plan> build_plan(const FrameGraph& graph, const PlanOptions& options) {
    if (options.frame.width == 0 || options.frame.height == 0) {
        return make_error(ErrorCode::InvalidArgument, "plan: frame size " + std::to_string(options.frame.width) + "x" +
                                                          std::to_string(options.frame.height) + " is empty");
    }
    const auto kinds = allocator_kinds();
    if (std::find(kinds.begin(), kinds.end(), options.allocator) == kinds.end()) {
        return make_error(ErrorCode::InvalidArgument,
                          "plan: unknown allocator kind " + std::to_string(static_cast<unsigned>(options.allocator)));
    }
    const AllocatorKind allocator_kind = options.allocator;
    const std::unique_ptr<Allocator> allocator = make_allocator(allocator_kind);
    std::shared_ptr<MemoryModel> memory = options.memory_model;
    if (!memory) memory = std::make_shared<DefaultMemoryModel>();

    auto dependencies = detail::analyze(graph);
    if (!dependencies) return dependencies.take_error();
    auto kept = detail::cull_passes(graph, *dependencies);
    if (!kept) return kept.take_error();
    detail::Schedule schedule = detail::schedule_passes(*dependencies, *kept);
    const auto positions = static_cast<uint32_t>(schedule.order.size());
    auto resolved = detail::resolve_resources(graph, schedule, options.frame, *memory);
    if (!resolved) return resolved.take_error();
    if (options.order == PassOrder::Memory) choose_order(graph, *dependencies, schedule, *resolved);

    Plan plan;
    plan.allocator = std::string(allocator->name());
    plan.frame = options.frame;
    plan.sharing = options.sharing;
    plan.pass_order = options.order;
    plan.order = detail::plan_passes(graph, schedule, *resolved);
    detail::QueuePlan queues = detail::plan_queues(plan.order, resolved->resources, *dependencies, schedule);
    if (!queues.syncs.empty() && allocator_kind == AllocatorKind::Paper) {
        const auto async = std::find_if(plan.order.begin(), plan.order.end(),
                                        [](const PlanPass& pass) { return pass.queue != Queue::Graphics; });
        return make_error(ErrorCode::InvalidArgument,
                          "allocator 'paper' colours ports pass by pass and cannot keep apart the resources of "
                          "passes that run at the same time on two queues (async compute pass '" +
                              async->name + "'): use 'interval' or 'heap'");
    }
    for (uint32_t r = 0; r < resolved->resources.size(); ++r) {
        resolved->resources[r].occupancy = queues.occupancy[r];
        resolved->resources[r].queue_shared = queues.queue_shared[r];
    }
    plan.queue_syncs = std::move(queues.syncs);
    plan.ownership_transfers = std::move(queues.transfers);
    detail::SpecClassAssignment classes =
        detail::assign_spec_classes(resolved->resources, options.sharing, options.frame, positions);
    plan.culled = detail::culled_pass_names(graph, *kept);
    plan.edges = detail::plan_edges(graph, schedule, resolved->resource_of_port);
    for (const PortAddress& out : graph.outputs()) plan.graph_outputs.push_back(graph.port_name(out));
    plan.resources = std::move(resolved->resources);
    for (uint32_t r = 0; r < plan.resources.size(); ++r) plan.resources[r].spec_class = classes.class_of_resource[r];
    plan.spec_classes = std::move(classes.classes);

    const AllocationProblem problem =
        detail::make_allocation_problem(plan.order, plan.resources, std::move(resolved->graph_output_resources),
                                        static_cast<uint32_t>(plan.spec_classes.size()), options.max_heap_bytes);
    auto textures = detail::allocate_textures(*allocator, problem, plan.resources, options.frame, *memory);
    if (!textures) return textures.take_error();
    for (uint32_t r = 0; r < plan.resources.size(); ++r) {
        plan.resources[r].texture = textures->texture_of_resource[r];
        plan.resources[r].buffer = textures->buffer_of_resource[r];
    }
    plan.textures = std::move(textures->textures);
    plan.buffers = std::move(textures->buffers);
    plan.heaps = std::move(textures->heaps);
    plan.summary = detail::summarize_plan(plan, classes.peak_live_bytes);
    return plan;
}

}  // namespace loom::fg

#include "loom/framegraph/planner.hpp"

#include <algorithm>

#include "graph_analysis.hpp"
#include "loom/framegraph/allocator.hpp"
#include "loom/framegraph/graph.hpp"
#include "plan_phases.hpp"

namespace loom::fg {

// The phases in order, each a function of plain data (plan_phases.hpp); what they decide is
// put together into the plan here.
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
    const auto positions = static_cast<uint32_t>(schedule.order.size());
    auto resolved = detail::resolve_resources(graph, detail::join_port_groups(graph, options.frame), schedule,
                                              options.frame, *memory);
    if (!resolved) return resolved.take_error();

    Plan plan;
    plan.allocator = std::string((*allocator)->name());
    plan.frame = options.frame;
    plan.sharing = options.sharing;
    plan.order = detail::plan_passes(graph, schedule, *resolved);
    detail::QueuePlan queues = detail::plan_queues(plan.order, resolved->resources, *dependencies, schedule);
    if (!queues.syncs.empty() && plan.allocator == "paper") {
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
    auto textures = detail::allocate_textures(**allocator, problem, plan.resources, options.frame, *memory);
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

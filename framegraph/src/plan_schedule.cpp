// Which passes run and in what order: the cull and schedule phases of build_plan.
#include <functional>
#include <queue>

#include "plan_phases.hpp"

namespace loom::fg::detail {

Result<std::vector<bool>> cull_passes(const FrameGraph& graph, const Dependencies& dependencies) {
    const uint32_t pass_count = graph.pass_count();
    std::vector<bool> kept(pass_count, false);
    std::vector<uint32_t> stack;
    for (uint32_t p = 0; p < pass_count; ++p) {
        if (graph.pass(PassId{p}).side_effect()) stack.push_back(p);
    }
    for (const PortAddress& out : graph.outputs()) stack.push_back(out.pass);
    if (stack.empty()) {
        return make_error(ErrorCode::Graph,
                          "nothing to run: no graph output and no side-effect pass (mark_output the final texture)");
    }
    while (!stack.empty()) {
        const uint32_t p = stack.back();
        stack.pop_back();
        if (kept[p]) continue;
        kept[p] = true;
        for (uint32_t producer : dependencies.producers[p]) {
            if (!kept[producer]) stack.push_back(producer);
        }
    }
    return kept;
}

std::vector<std::string> culled_pass_names(const FrameGraph& graph, const std::vector<bool>& kept) {
    std::vector<std::string> names;
    for (uint32_t p = 0; p < graph.pass_count(); ++p) {
        if (!kept[p]) names.push_back(graph.pass(PassId{p}).name());
    }
    return names;
}

Schedule schedule_passes(const Dependencies& dependencies, const std::vector<bool>& kept) {
    const auto pass_count = static_cast<uint32_t>(kept.size());
    std::vector<uint32_t> in_degree(pass_count, 0);
    for (uint32_t p = 0; p < pass_count; ++p) {
        if (!kept[p]) continue;
        for (uint32_t next : dependencies.successors[p]) {
            if (kept[next]) ++in_degree[next];
        }
    }
    std::priority_queue<uint32_t, std::vector<uint32_t>, std::greater<>> ready;
    for (uint32_t p = 0; p < pass_count; ++p) {
        if (kept[p] && in_degree[p] == 0) ready.push(p);
    }
    Schedule schedule;
    schedule.position.assign(pass_count, kNotScheduled);
    while (!ready.empty()) {
        const uint32_t p = ready.top();
        ready.pop();
        schedule.position[p] = static_cast<uint32_t>(schedule.order.size());
        schedule.order.push_back(p);
        for (uint32_t next : dependencies.successors[p]) {
            if (kept[next] && --in_degree[next] == 0) ready.push(next);
        }
    }
    return schedule;
}

Schedule reorder_schedule(const Schedule& declared, const std::vector<uint32_t>& order) {
    Schedule schedule;
    schedule.position.assign(declared.position.size(), kNotScheduled);
    schedule.order.reserve(order.size());
    for (uint32_t at : order) {
        const uint32_t pass = declared.order[at];
        schedule.position[pass] = static_cast<uint32_t>(schedule.order.size());
        schedule.order.push_back(pass);
    }
    return schedule;
}

}  // namespace loom::fg::detail

#pragma once
// Internal: the phases of build_plan (planner.cpp), each a function from plain data to plain
// data so that each can be tested on its own. In order:
//   cull      → which passes run                         (plan_schedule.cpp)
//   schedule  → their order and positions                 (plan_schedule.cpp)
// The barriers are not a phase of planning: build_execution_schedule (execution_schedule.cpp)
// derives them from a finished plan, once per plan and set of bindings.

#include <cstdint>
#include <string>
#include <vector>

#include "graph_analysis.hpp"
#include "loom/framegraph/graph.hpp"
#include "loom/rhi/result.hpp"

namespace loom::fg::detail {

/// Schedule::position of a pass that does not run.
inline constexpr uint32_t kNotScheduled = UINT32_MAX;

/// Cull: per pass (declaration order), whether it runs: a pass runs when it has side effects,
/// produces a graph output, or produces a texture a running pass reads. ErrorCode::Graph when
/// nothing would run.
Result<std::vector<bool>> cull_passes(const FrameGraph& graph, const Dependencies& dependencies);

/// The names of the passes that do not run, in declaration order (Plan::culled).
std::vector<std::string> culled_pass_names(const FrameGraph& graph, const std::vector<bool>& kept);

/// The execution order of the passes that run.
struct Schedule {
    std::vector<uint32_t> order;     ///< passes by declaration index, in execution order
    std::vector<uint32_t> position;  ///< per pass, its index in `order`; kNotScheduled when culled
};

/// Schedule: Kahn's algorithm over the kept passes; of the passes ready at once, the one
/// declared first runs first.
Schedule schedule_passes(const Dependencies& dependencies, const std::vector<bool>& kept);

}  // namespace loom::fg::detail

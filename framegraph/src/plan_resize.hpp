#pragma once
// Internal: re-planning from the previous plan (FrameGraph::plan, docs/framegraph.md
// "Planning") a graph planned for another frame size, or declared again (redeclare) with other
// texture specs on some ports. In the declared order neither changes the passes that run, their
// order, the resources with their ports and lifetimes, the edges or the queues' semaphores: a
// frame size decides the extents of textures and the sizes of buffers, a texture spec its
// resource's join, and with them their bytes, usages, which ones may share (spec classes), the
// allocation and the summary. So the previous plan becomes the new one by joining and resolving
// what changed and allocating again, and equals what build_plan gives
// (tests/framegraph/plan_resize_test.cpp compares the two over random graphs). The memory order
// is searched with the bytes and may change with them: such plans are planned anew.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "loom/framegraph/buffer_spec.hpp"
#include "loom/framegraph/graph.hpp"
#include "loom/framegraph/plan.hpp"
#include "loom/framegraph/planner.hpp"
#include "loom/framegraph/texture_spec.hpp"
#include "loom/rhi/result.hpp"

namespace loom::fg::detail {

/// What a plan keeps, besides itself, to be re-planned for another frame size.
struct ResizeBasis {
    /// Per resource of the plan, the size its ports joined to (ResolvedResources::joined_sizes).
    std::vector<std::optional<SizeSpec>> joined_sizes;
    /// The buffer resources' joined sizes, by resource index.
    std::vector<std::pair<uint32_t, BufferSize>> joined_buffer_sizes;
    /// The resources of the graph outputs (ResolvedResources::graph_output_resources).
    std::vector<uint32_t> graph_output_resources;
    /// Per resource, the port that starts its group (ResolvedResources::starts).
    std::vector<PortAddress> starts;
    /// Per pass, its position in the plan's order or kNotScheduled (Schedule::position).
    std::vector<uint32_t> position;
};

/// build_plan, also setting `basis` to what resize_plan needs when the plan can be re-planned so:
/// in the declared order, when no join compared differently declared sizes against the frame
/// (such a join may fail, or keep another size, at another frame size). Else `basis` is reset.
Result<Plan> build_plan(const FrameGraph& graph, const PlanOptions& options, std::unique_ptr<ResizeBasis>& basis);

/// Makes `plan`, which build_plan made with `basis`, the plan of `graph` for `options`, and
/// `basis` its basis. `options` may differ from the plan's options in the frame size only, and
/// `graph` must be the graph the plan was made from but for the texture specs of the ports of
/// the passes `respecified` (declaration indices). False when the plan must be made anew: a
/// respecified pass that does not run, or whose texture reaches passes that do not (their joins
/// count too), a join that compares differently declared sizes against the frame, a size that no
/// longer resolves, a join, the memory model or the allocator that fails. `plan` and `basis` are
/// then half changed, and build_plan gives the plan or the error.
bool replan(const FrameGraph& graph, ResizeBasis& basis, const PlanOptions& options,
            std::span<const uint32_t> respecified, Plan& plan);

}  // namespace loom::fg::detail

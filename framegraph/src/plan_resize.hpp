#pragma once
// Internal: re-planning an unchanged graph for another frame size (FrameGraph::plan,
// docs/framegraph.md "Planning"). In the declared order a frame size decides only the extents of
// textures and the sizes of buffers: their bytes, which ones may share (spec classes), the
// allocation and the summary. The passes that run, their order, the resources with their ports,
// usages and lifetimes, the edges and the queues' semaphores are the same for every frame size.
// So the previous plan becomes the new one by resolving its sizes again and allocating again,
// and equals what build_plan gives (tests/framegraph/plan_resize_test.cpp compares the two over
// random graphs). The memory order is searched with the bytes and may change with them: such
// plans are planned anew.

#include <cstdint>
#include <memory>
#include <optional>
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
};

/// build_plan, also setting `basis` to what resize_plan needs when the plan can be re-planned so:
/// in the declared order, when no join compared differently declared sizes against the frame
/// (such a join may fail, or keep another size, at another frame size). Else `basis` is reset.
Result<Plan> build_plan(const FrameGraph& graph, const PlanOptions& options, std::unique_ptr<ResizeBasis>& basis);

/// Makes `plan`, which build_plan made for `graph` with `basis`, the plan of `options.frame`:
/// `options` may differ from the plan's options in the frame size only, and `graph` must be the
/// graph the plan was made from. False when a size no longer resolves, the memory model or the
/// allocator fails at the new size: `plan` is then half changed and build_plan gives the plan
/// or the error.
bool resize_plan(const FrameGraph& graph, const ResizeBasis& basis, const PlanOptions& options, Plan& plan);

}  // namespace loom::fg::detail

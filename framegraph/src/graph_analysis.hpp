#pragma once
// Internal: the dependency structure of a graph and the checks that need no frame size.

#include <cstdint>
#include <vector>

#include "loom/framegraph/graph.hpp"
#include "loom/rhi/result.hpp"

namespace loom::fg::detail {

struct Dependencies {
    /// Per pass, the passes that must run after it (sorted, unique): readers of its textures,
    /// passes that modify in place a texture it reads before the modification, and the passes
    /// FrameGraph::require_order puts after it.
    std::vector<std::vector<uint32_t>> successors;
    /// Per pass, the passes whose textures it reads (sorted, unique). Culling follows these.
    std::vector<std::vector<uint32_t>> producers;
};

/// Builds the dependencies and checks: only compute and copy passes on the async compute queue,
/// required inputs connected, no pass reading a texture it also modifies in place, no cycle. Errors are ErrorCode::Graph naming passes and ports.
Result<Dependencies> analyze(const FrameGraph& graph);

}  // namespace loom::fg::detail

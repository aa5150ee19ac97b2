#pragma once
// Planning: validate the graph, cull, order, join the specs of connected ports, measure
// lifetimes, run an allocator, and summarise. All of it before any GPU work.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "loom/framegraph/allocator.hpp"
#include "loom/framegraph/memory_model.hpp"
#include "loom/framegraph/plan.hpp"
#include "loom/rhi/result.hpp"

namespace loom::fg {

class FrameGraph;

/// How to plan: the frame size, the allocator, which specs may share, the memory model, the heap
/// cap, the pass order.
struct PlanOptions {
    Extent2D frame{1920, 1080};      ///< the size relative sizes scale
    /// Chosen by kind; a user's name is parsed once with parse_allocator (allocator.hpp), which
    /// reports a typo where the name comes from.
    AllocatorKind allocator = AllocatorKind::Interval;
    SpecSharing sharing = SpecSharing::Equal;
    /// Sizes and alignments; null means DefaultMemoryModel. Compared by identity.
    std::shared_ptr<MemoryModel> memory_model;
    uint64_t max_heap_bytes = 0;     ///< "heap" allocator: 0 means a single heap of any size
    /// How to order the passes: for the lowest peak of live bytes (the default) or declared.
    PassOrder order = kDefaultPassOrder;

    friend bool operator==(const PlanOptions&, const PlanOptions&) = default;
};

/// Plans `graph` from scratch. Errors: ErrorCode::Graph (cycle, unconnected required input,
/// nothing to run, ...) and ErrorCode::Join (ports whose specs conflict), each naming the
/// passes and ports at fault; InvalidArgument for bad options (unknown allocator, empty frame).
Result<Plan> build_plan(const FrameGraph& graph, const PlanOptions& options);

}  // namespace loom::fg

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

/// The allocator PlanOptions::allocator asks for: an AllocatorKind. It also takes a std::string
/// name, a deprecated convenience kept only for callers that still hold names in their own
/// settings (the renderer's DeferredPipelineSettings): a known name becomes its kind at once, an
/// unknown one is kept so that build_plan reports it (InvalidArgument naming it). New code
/// passes a kind, or parses a user's name with parse_allocator, which reports a typo there.
class AllocatorChoice {
public:
    constexpr AllocatorChoice(AllocatorKind kind = AllocatorKind::Interval) : kind_(kind) {}  // NOLINT: implicit by design
    /// Deprecated: see the class comment.
    AllocatorChoice(const std::string& name);  // NOLINT: implicit, as the string field it replaces

    /// The kind; an InvalidArgument error for a name that named no allocator (or a value
    /// outside AllocatorKind).
    [[nodiscard]] Result<AllocatorKind> kind() const;

    friend bool operator==(const AllocatorChoice&, const AllocatorChoice&) = default;
    /// True when it is that kind (never for an unknown name).
    friend bool operator==(const AllocatorChoice& choice, AllocatorKind kind) {
        return !choice.unknown_name_ && choice.kind_ == kind;
    }

private:
    AllocatorKind kind_;
    std::optional<std::string> unknown_name_;  ///< the name given when it named no allocator
};

/// How to plan: the frame size, the allocator, which specs may share, the memory model, the heap
/// cap, the pass order.
struct PlanOptions {
    Extent2D frame{1920, 1080};      ///< the size relative sizes scale
    AllocatorChoice allocator = AllocatorKind::Interval;
    SpecSharing sharing = SpecSharing::Equal;
    /// Sizes and alignments; null means DefaultMemoryModel. Compared by identity.
    std::shared_ptr<MemoryModel> memory_model;
    uint64_t max_heap_bytes = 0;     ///< "heap" allocator: 0 means a single heap of any size
    /// How to order the passes: declared (the default) or for the lowest peak of live bytes.
    PassOrder order = PassOrder::Declared;

    friend bool operator==(const PlanOptions&, const PlanOptions&) = default;
};

/// Plans `graph` from scratch. Errors: ErrorCode::Graph (cycle, unconnected required input,
/// nothing to run, ...) and ErrorCode::Join (ports whose specs conflict), each naming the
/// passes and ports at fault; InvalidArgument for bad options (unknown allocator, empty frame).
Result<Plan> build_plan(const FrameGraph& graph, const PlanOptions& options);

}  // namespace loom::fg

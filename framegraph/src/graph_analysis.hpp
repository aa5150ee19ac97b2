#pragma once
// Internal: the dependency structure of a graph and the checks that need no frame size.

#include <cstdint>
#include <initializer_list>
#include <span>
#include <utility>
#include <vector>

#include "loom/framegraph/graph.hpp"
#include "loom/rhi/result.hpp"

namespace loom::fg::detail {

/// Per index (a pass), a sorted list of unique indices, all lists in one array one after
/// another (compressed rows): two allocations for a whole graph instead of one per pass.
/// lists[i] reads as a vector's would.
class IndexLists {
public:
    IndexLists() = default;
    /// The lists of `count` indices from (index, value) pairs in any order: each index's values
    /// sorted, duplicates dropped.
    IndexLists(uint32_t count, const std::vector<std::pair<uint32_t, uint32_t>>& pairs);
    /// The lists as given, one per index (tests write dependencies this way).
    IndexLists(std::initializer_list<std::vector<uint32_t>> lists);

    /// The lists already laid out one after another (list i is values[first[i], first[i + 1]),
    /// `first` one longer than the count): each sorted, duplicates dropped.
    IndexLists(std::vector<uint32_t> first, std::vector<uint32_t> values);

    /// The same pairs the other way: `count` lists, list j holding every i whose list holds j
    /// (sorted and unique as they come, without the sort the pairs constructor needs).
    [[nodiscard]] IndexLists transposed(uint32_t count) const;

    [[nodiscard]] std::span<const uint32_t> operator[](uint32_t index) const {
        return {values_.data() + first_[index], values_.data() + first_[index + 1]};
    }
    /// Number of lists.
    [[nodiscard]] uint32_t size() const { return first_.empty() ? 0 : static_cast<uint32_t>(first_.size() - 1); }

private:
    void sort_and_deduplicate();

    std::vector<uint32_t> first_;   // per index, where its list starts in values_; one more at the end
    std::vector<uint32_t> values_;
};

struct Dependencies {
    /// Per pass, the passes that must run after it (sorted, unique): readers of its textures,
    /// passes that modify in place a texture it reads before the modification, and the passes
    /// FrameGraph::require_order puts after it.
    IndexLists successors;
    /// Per pass, the passes whose textures it reads (sorted, unique). Culling follows these.
    IndexLists producers;
};

/// Builds the dependencies and checks: only compute and copy passes on the async compute queue,
/// required inputs connected, no pass reading a texture it also modifies in place, no cycle. Errors are ErrorCode::Graph naming passes and ports.
Result<Dependencies> analyze(const FrameGraph& graph);

}  // namespace loom::fg::detail

// Byte-level placement for APIs that alias memory (Vulkan): every resource is its own texture,
// placed at an aligned offset in a heap so that no two resources alive at the same position
// overlap in bytes. Finding the smallest heap is NP-hard (dynamic storage allocation), so this
// runs a few greedy strategies and keeps the smallest result:
//   orders:     largest first; longest-lived first; by first use; largest area (bytes × life)
//   placements: lowest offset that fits; the tightest gap that fits (best fit)
// The lower bound is the peak of live bytes over the order; the plan reports both.

#include <algorithm>
#include <cstdint>
#include <functional>
#include <numeric>

#include "allocators.hpp"
#include "loom/framegraph/memory_model.hpp"

namespace loom::fg::detail {
namespace {

struct Range {
    uint64_t begin = 0;
    uint64_t end = 0;
};

// The lifetimes of the resources placed in one heap, to find those overlapping a lifetime in
// time proportional to their number: a segment tree over positions answers "alive at
// position a" (each lifetime is stored in O(log n) canonical nodes, so it is reported once),
// and a list per position answers "starts in (a, b]".
class LifetimeIndex {
public:
    explicit LifetimeIndex(uint32_t positions) : starts_(positions) {
        while (leaves_ < positions) leaves_ *= 2;
        nodes_.resize(2 * leaves_);
    }

    void insert(uint32_t id, const Lifetime& life) {
        starts_[life.first].push_back(id);
        for (uint32_t l = life.first + leaves_, r = life.last + 1 + leaves_; l < r; l /= 2, r /= 2) {
            if (l & 1) nodes_[l++].push_back(id);
            if (r & 1) nodes_[--r].push_back(id);
        }
    }

    /// Calls `visit` once for every inserted lifetime that overlaps `life`.
    template <class Visit>
    void overlapping(const Lifetime& life, Visit&& visit) const {
        for (uint32_t node = life.first + leaves_; node >= 1; node /= 2) {
            for (uint32_t id : nodes_[node]) visit(id);
        }
        for (uint32_t at = life.first + 1; at <= life.last; ++at) {
            for (uint32_t id : starts_[at]) visit(id);
        }
    }

private:
    uint32_t leaves_ = 1;
    std::vector<std::vector<uint32_t>> nodes_;   // 1-based implicit tree; leaves at [leaves_, 2 leaves_)
    std::vector<std::vector<uint32_t>> starts_;  // per position, lifetimes starting there
};

struct HeapState {
    uint64_t capacity = 0;  // 0: unbounded
    uint64_t size = 0;
    LifetimeIndex placed;
};

enum class Fit : uint8_t { Lowest, Best };

struct Placement {
    std::vector<HeapRange> where;  // per resource
    std::vector<uint64_t> heap_sizes;
    uint64_t total = 0;
};

class Placer {
public:
    Placer(const AllocationProblem& problem, Fit fit)
        : problem_(problem), fit_(fit), ranges_(problem.resources.size()) {}

    Placement place(const std::vector<uint32_t>& order) {
        Placement out;
        out.where.resize(problem_.resources.size());
        for (uint32_t r : order) {
            const AllocationResource& resource = problem_.resources[r];
            for (uint32_t h = 0;; ++h) {
                if (h == heaps_.size()) open_heap(resource.bytes);
                auto offset = find_offset(heaps_[h], r);
                if (!offset) continue;
                HeapState& heap = heaps_[h];
                ranges_[r] = {*offset, *offset + resource.bytes};
                heap.placed.insert(r, resource.lifetime);
                heap.size = std::max(heap.size, ranges_[r].end);
                out.where[r] = HeapRange{h, *offset};
                break;
            }
        }
        for (const HeapState& heap : heaps_) {
            out.heap_sizes.push_back(heap.size);
            out.total += heap.size;
        }
        return out;
    }

private:
    void open_heap(uint64_t first_resource_bytes) {
        // A resource larger than the cap gets a heap of its own size.
        const uint64_t capacity =
            problem_.max_heap_bytes == 0 ? 0 : std::max(problem_.max_heap_bytes, first_resource_bytes);
        heaps_.push_back(HeapState{capacity, 0, LifetimeIndex(static_cast<uint32_t>(problem_.passes.size()))});
    }

    std::optional<uint64_t> find_offset(const HeapState& heap, uint32_t r) {
        const AllocationResource& resource = problem_.resources[r];
        // Byte ranges of the resources in this heap whose lifetimes overlap r's.
        busy_.clear();
        heap.placed.overlapping(resource.lifetime, [&](uint32_t other) { busy_.push_back(ranges_[other]); });
        std::sort(busy_.begin(), busy_.end(), [](const Range& a, const Range& b) { return a.begin < b.begin; });

        const uint64_t align = std::max<uint64_t>(resource.alignment, 1);
        std::optional<uint64_t> best;
        uint64_t best_gap = UINT64_MAX;
        uint64_t candidate = 0;
        auto consider = [&](uint64_t gap_end) {  // the free gap [candidate, gap_end)
            if (candidate + resource.bytes > gap_end) return false;
            const uint64_t gap = gap_end - candidate;
            if (!best || (fit_ == Fit::Best && gap < best_gap)) {
                best = candidate;
                best_gap = gap;
            }
            return fit_ == Fit::Lowest;  // the lowest offset is final
        };
        for (const Range& range : busy_) {
            if (range.begin > candidate && consider(range.begin)) return best;
            candidate = std::max(candidate, align_up(range.end, align));
        }
        const uint64_t limit = heap.capacity == 0 ? UINT64_MAX : heap.capacity;
        if (candidate <= limit) consider(limit);
        return best;
    }

    const AllocationProblem& problem_;
    Fit fit_;
    std::vector<HeapState> heaps_;
    std::vector<Range> ranges_;  // per placed resource
    std::vector<Range> busy_;
};

class HeapAllocator final : public Allocator {
public:
    [[nodiscard]] std::string_view name() const override { return "heap"; }

    [[nodiscard]] Result<Allocation> allocate(const AllocationProblem& problem) const override {
        const auto count = static_cast<uint32_t>(problem.resources.size());
        const auto& res = problem.resources;
        auto length = [&](uint32_t r) { return uint64_t{res[r].lifetime.last} - res[r].lifetime.first + 1; };

        using Less = std::function<bool(uint32_t, uint32_t)>;
        const std::array<Less, 4> orders{
            Less([&](uint32_t a, uint32_t b) {
                return std::tuple(res[b].bytes, length(b)) < std::tuple(res[a].bytes, length(a));
            }),
            Less([&](uint32_t a, uint32_t b) {
                return std::tuple(length(b), res[b].bytes) < std::tuple(length(a), res[a].bytes);
            }),
            Less([&](uint32_t a, uint32_t b) {
                return std::tuple(res[a].lifetime.first, res[b].bytes) < std::tuple(res[b].lifetime.first, res[a].bytes);
            }),
            Less([&](uint32_t a, uint32_t b) { return res[b].bytes * length(b) < res[a].bytes * length(a); }),
        };

        std::optional<Placement> best;
        for (const Less& less : orders) {
            std::vector<uint32_t> order(count);
            std::iota(order.begin(), order.end(), 0u);
            std::stable_sort(order.begin(), order.end(), less);
            for (Fit fit : {Fit::Lowest, Fit::Best}) {
                Placement placement = Placer(problem, fit).place(order);
                if (!best || placement.total < best->total) best = std::move(placement);
            }
        }

        Allocation out;
        out.texture_count = count;
        out.texture_of_resource.resize(count);
        std::iota(out.texture_of_resource.begin(), out.texture_of_resource.end(), 0u);
        if (best) {
            out.texture_placement = std::move(best->where);
            out.heap_sizes = std::move(best->heap_sizes);
        }
        return out;
    }
};

}  // namespace

std::unique_ptr<Allocator> make_heap_allocator() { return std::make_unique<HeapAllocator>(); }

}  // namespace loom::fg::detail

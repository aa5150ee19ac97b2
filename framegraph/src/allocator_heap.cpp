// Byte-level placement for APIs that alias memory (Vulkan): every resource is its own texture,
// placed at an aligned offset in a heap so that no two resources alive at the same position
// overlap in bytes. Finding the smallest heap is NP-hard (dynamic storage allocation), so this
// runs a few greedy strategies and keeps the smallest result:
//   orders:     largest first; longest-lived first; by first use; largest area (bytes × life);
//               strictest alignment first when the best needs more than a heap per resource;
//               the resources alive at the peak first when no other order reached the bound
//   placements: lowest offset that fits; the tightest gap that fits (best fit)
// The lower bound is the peak of live bytes over the order; the plan reports both. No placement
// needs less, so the search stops at the first one that reaches it.

#include <algorithm>
#include <cstdint>
#include <functional>
#include <map>
#include <numeric>
#include <optional>
#include <unordered_map>

#include "allocators.hpp"
#include "loom/framegraph/memory_model.hpp"
#include "loom/rhi/checked_math.hpp"

namespace loom::fg::detail {
namespace {

struct Range {
    uint64_t begin = 0;
    uint64_t end = 0;
    uint32_t id = 0;  // the resource
};

// The resources placed in one heap, to find those whose lifetimes overlap a lifetime. A heap
// with few members keeps a plain list. Past kIndexedFrom members it also keeps a segment tree
// over positions, storing only the nodes in use, that answers "alive at position a" (each
// lifetime sits in O(log n) canonical nodes, so it is reported once) and a map that answers
// "starts in (a, b]": a query then costs about the number of lifetimes it reports, and memory
// grows with the members, not with the number of positions (there may be as many heaps as
// resources).
class HeapMembers {
public:
    static constexpr std::size_t kIndexedFrom = 32;

    void insert(uint32_t id, const std::vector<AllocationResource>& resources, uint32_t positions) {
        if (indexed_) {
            index(id, resources[id].lifetime);
            return;
        }
        list_.push_back(id);
        if (list_.size() < kIndexedFrom) return;
        indexed_ = true;
        while (leaves_ < positions) leaves_ *= 2;
        for (uint32_t member : list_) index(member, resources[member].lifetime);
        list_ = {};
    }

    /// Calls `visit` once for every member whose lifetime overlaps `life`.
    template <class Visit>
    void overlapping(const Lifetime& life, const std::vector<AllocationResource>& resources, Visit&& visit) const {
        if (!indexed_) {
            for (uint32_t id : list_) {
                const Lifetime& other = resources[id].lifetime;
                if (other.first <= life.last && life.first <= other.last) visit(id);
            }
            return;
        }
        for (uint32_t node = life.first + leaves_; node >= 1; node /= 2) {
            auto it = nodes_.find(node);
            if (it == nodes_.end()) continue;
            for (uint32_t id : it->second) visit(id);
        }
        for (auto it = starts_.upper_bound(life.first); it != starts_.end() && it->first <= life.last; ++it) {
            for (uint32_t id : it->second) visit(id);
        }
    }

private:
    void index(uint32_t id, const Lifetime& life) {
        starts_[life.first].push_back(id);
        for (uint32_t l = life.first + leaves_, r = life.last + 1 + leaves_; l < r; l /= 2, r /= 2) {
            if (l & 1) nodes_[l++].push_back(id);
            if (r & 1) nodes_[--r].push_back(id);
        }
    }

    std::vector<uint32_t> list_;  // while not indexed
    bool indexed_ = false;
    uint32_t leaves_ = 1;
    std::unordered_map<uint32_t, std::vector<uint32_t>> nodes_;  // 1-based implicit tree; leaves at [leaves_, 2 leaves_)
    std::map<uint32_t, std::vector<uint32_t>> starts_;           // lifetimes by first position
};

// Positions [first, last] during which a heap has no free gap as large as the smallest
// resource: nothing can be placed in it then.
struct FullSpan {
    uint32_t first = UINT32_MAX;  // UINT32_MAX: never known full
    uint32_t last = UINT32_MAX;
};

// Which heaps may take a resource. A tree over heap numbers keeps per subtree the largest
// capacity and, of the heaps' full spans, the latest first and the earliest last position; a
// heap whose capacity is too small or whose full span meets the resource's lifetime cannot
// take it, and a subtree without a heap that could is skipped whole. So placing a resource
// does not try every open heap in turn (with a small heap budget there may be one heap per
// resource), yet finds the same first heap that could take it.
class HeapFinder {
public:
    explicit HeapFinder(std::size_t max_heaps) {
        while (leaves_ < max_heaps) leaves_ *= 2;
        nodes_.resize(2 * leaves_);
    }

    void set(uint32_t heap, uint64_t capacity, FullSpan full) {
        uint32_t node = heap + static_cast<uint32_t>(leaves_);
        nodes_[node] = Node{capacity, full.first, full.last};
        for (node /= 2; node >= 1; node /= 2) {
            const Node& a = nodes_[2 * node];
            const Node& b = nodes_[2 * node + 1];
            nodes_[node] = Node{std::max(a.capacity, b.capacity), std::max(a.full_first, b.full_first),
                                std::min(a.full_last, b.full_last)};
        }
    }

    /// The lowest heap number in [from, count) that may take `bytes` over `life`.
    [[nodiscard]] std::optional<uint32_t> first(uint32_t from, uint32_t count, const Lifetime& life,
                                                uint64_t bytes) const {
        return search(1, 0, leaves_, from, count, life, bytes);
    }

private:
    struct Node {
        uint64_t capacity = 0;          // largest in the subtree (UINT64_MAX: unbounded)
        uint32_t full_first = 0;        // largest first position of a full span
        uint32_t full_last = UINT32_MAX;  // smallest last position of a full span
    };

    [[nodiscard]] std::optional<uint32_t> search(std::size_t node, std::size_t lo, std::size_t hi, uint32_t from,
                                                 uint32_t count, const Lifetime& life, uint64_t bytes) const {
        if (hi <= from || lo >= count) return std::nullopt;
        const Node& n = nodes_[node];
        // Some heap below is free over the whole lifetime only if its full span ends before
        // the lifetime starts or starts after it ends.
        if (n.capacity < bytes || !(n.full_last < life.first || n.full_first > life.last)) return std::nullopt;
        if (hi - lo == 1) return static_cast<uint32_t>(lo);
        const std::size_t mid = (lo + hi) / 2;
        if (auto left = search(2 * node, lo, mid, from, count, life, bytes)) return left;
        return search(2 * node + 1, mid, hi, from, count, life, bytes);
    }

    std::size_t leaves_ = 1;
    std::vector<Node> nodes_;
};

struct HeapState {
    uint64_t capacity = 0;  // 0: unbounded
    uint64_t size = 0;
    HeapMembers members;
    FullSpan full;
};

enum class Fit : uint8_t { Lowest, Best };

struct Placement {
    std::vector<HeapRange> where;  // per resource
    std::vector<uint64_t> heap_sizes;
    uint64_t total = 0;
};

Error overflow_error(const AllocationResource& resource) {
    return make_error(ErrorCode::Graph, "heap allocator: " + resource.name + " (" + std::to_string(resource.bytes) +
                                            " bytes, alignment " + std::to_string(resource.alignment) +
                                            ") does not fit in a heap: its offset would overflow 64 bits");
}

class Placer {
public:
    Placer(const AllocationProblem& problem, Fit fit)
        : problem_(problem), fit_(fit), ranges_(problem.resources.size()), finder_(problem.resources.size()) {
        for (const AllocationResource& resource : problem.resources) smallest_ = std::min(smallest_, resource.bytes);
    }

    Result<Placement> place(const std::vector<uint32_t>& order) {
        Placement out;
        out.where.resize(problem_.resources.size());
        for (uint32_t r : order) {
            const AllocationResource& resource = problem_.resources[r];
            const auto count = static_cast<uint32_t>(heaps_.size());
            std::optional<uint64_t> offset;
            uint32_t h = 0;
            for (uint32_t from = 0; !offset; from = h + 1) {
                auto candidate = finder_.first(from, count, resource.lifetime, resource.bytes);
                if (!candidate) break;
                h = *candidate;
                offset = find_offset(heaps_[h], r);
            }
            if (!offset) {
                h = count;
                open_heap(resource.bytes);
                offset = find_offset(heaps_[h], r);
                if (!offset) return overflow_error(resource);
            }
            HeapState& heap = heaps_[h];
            ranges_[r] = {*offset, *offset + resource.bytes, r};  // find_offset checked the sum
            heap.members.insert(r, problem_.resources, static_cast<uint32_t>(problem_.passes.size()));
            heap.size = std::max(heap.size, ranges_[r].end);
            if (heap.capacity != 0) note_full(h, r);
            out.where[r] = HeapRange{h, *offset};
        }
        for (const HeapState& heap : heaps_) {
            out.heap_sizes.push_back(heap.size);
            auto total = checked::add(out.total, heap.size);
            if (!total) {
                return make_error(ErrorCode::Graph, "heap allocator: the heaps together exceed 2^64 bytes");
            }
            out.total = *total;
        }
        return out;
    }

private:
    void open_heap(uint64_t first_resource_bytes) {
        // A resource larger than the cap gets a heap of its own size.
        const uint64_t capacity =
            problem_.max_heap_bytes == 0 ? 0 : std::max(problem_.max_heap_bytes, first_resource_bytes);
        heaps_.push_back(HeapState{capacity, 0, {}, {}});
        finder_.set(static_cast<uint32_t>(heaps_.size() - 1), capacity == 0 ? UINT64_MAX : capacity, FullSpan{});
    }

    // Fills busy_ with the byte ranges of the members of `heap` whose lifetimes overlap r's, by offset.
    void collect_busy(const HeapState& heap, uint32_t r) {
        busy_.clear();
        heap.members.overlapping(problem_.resources[r].lifetime, problem_.resources,
                                 [&](uint32_t other) { busy_.push_back(ranges_[other]); });
        std::sort(busy_.begin(), busy_.end(), [](const Range& a, const Range& b) { return a.begin < b.begin; });
    }

    std::optional<uint64_t> find_offset(const HeapState& heap, uint32_t r) {
        const AllocationResource& resource = problem_.resources[r];
        collect_busy(heap, r);

        const uint64_t align = std::max<uint64_t>(resource.alignment, 1);
        std::optional<uint64_t> best;
        uint64_t best_gap = UINT64_MAX;
        uint64_t candidate = 0;
        auto consider = [&](uint64_t gap_end) {  // the free gap [candidate, gap_end)
            const auto end = checked::add(candidate, resource.bytes);
            if (!end || *end > gap_end) return false;
            const uint64_t gap = gap_end - candidate;
            if (!best || (fit_ == Fit::Best && gap < best_gap)) {
                best = candidate;
                best_gap = gap;
            }
            return fit_ == Fit::Lowest;  // the lowest offset is final
        };
        for (const Range& range : busy_) {
            if (range.begin > candidate && consider(range.begin)) return best;
            const auto next = checked::align_up(range.end, align);
            if (!next) return best;  // no aligned offset after this range
            candidate = std::max(candidate, *next);
        }
        const uint64_t limit = heap.capacity == 0 ? UINT64_MAX : heap.capacity;
        if (candidate <= limit) consider(limit);
        return best;
    }

    // After r was placed in heap h: if r and the members alive during all of r's lifetime leave
    // no gap as large as the smallest resource, the heap is full for r's lifetime.
    void note_full(uint32_t h, uint32_t r) {
        HeapState& heap = heaps_[h];
        const Lifetime& life = problem_.resources[r].lifetime;
        if (smallest_ == 0) return;
        covering_.clear();
        covering_.push_back(ranges_[r]);
        for (const Range& range : busy_) {  // r's overlapping members, from find_offset
            const Lifetime& other = problem_.resources[range.id].lifetime;
            if (other.first <= life.first && life.last <= other.last) covering_.push_back(range);
        }
        std::sort(covering_.begin(), covering_.end(), [](const Range& a, const Range& b) { return a.begin < b.begin; });
        uint64_t reached = 0;
        for (const Range& range : covering_) {
            if (range.begin > reached && range.begin - reached >= smallest_) return;
            reached = std::max(reached, range.end);
        }
        if (heap.capacity > reached && heap.capacity - reached >= smallest_) return;

        FullSpan& full = heap.full;
        if (full.first == UINT32_MAX) {
            full = {life.first, life.last};
        } else if (life.first <= full.last + uint64_t{1} && full.first <= life.last + uint64_t{1}) {
            full = {std::min(full.first, life.first), std::max(full.last, life.last)};  // overlapping or adjacent
        } else if (life.last - life.first > full.last - full.first) {
            full = {life.first, life.last};  // keep the longer span
        }
        finder_.set(h, heap.capacity, full);
    }

    const AllocationProblem& problem_;
    Fit fit_;
    std::vector<HeapState> heaps_;
    std::vector<Range> ranges_;  // per placed resource
    std::vector<Range> busy_;
    std::vector<Range> covering_;
    HeapFinder finder_;
    uint64_t smallest_ = UINT64_MAX;  // bytes of the smallest resource
};

// The largest sum of the bytes of the resources alive at one position (lifetimes are inclusive
// ranges of positions) and the first position where it is reached; none when a sum does not
// fit in 64 bits.
struct Peak {
    uint64_t bytes = 0;
    uint32_t position = 0;
};

std::optional<Peak> peak_live_bytes(const AllocationProblem& problem) {
    std::vector<uint64_t> starting(problem.passes.size() + 1, 0);
    std::vector<uint64_t> ending(problem.passes.size() + 1, 0);
    for (const AllocationResource& r : problem.resources) {
        if (r.lifetime.last >= problem.passes.size()) return std::nullopt;
        auto start = checked::add(starting[r.lifetime.first], r.bytes);
        auto end = checked::add(ending[r.lifetime.last + 1], r.bytes);
        if (!start || !end) return std::nullopt;
        starting[r.lifetime.first] = *start;
        ending[r.lifetime.last + 1] = *end;
    }
    uint64_t live = 0;
    Peak peak;
    for (uint32_t at = 0; at < problem.passes.size(); ++at) {
        live -= ending[at];  // what ended before `at` was added before it
        auto sum = checked::add(live, starting[at]);
        if (!sum) return std::nullopt;
        live = *sum;
        if (live > peak.bytes) peak = Peak{live, at};
    }
    return peak;
}

class HeapAllocator final : public Allocator {
public:
    /// The most resources for which the peak-first order is tried after the others.
    static constexpr uint32_t kRestartResources = 4096;

    [[nodiscard]] std::string_view name() const override { return "heap"; }
    // Lifetimes and sizes are all it needs.
    [[nodiscard]] bool reads_pass_lists() const override { return false; }

    [[nodiscard]] Result<Allocation> allocate(const AllocationProblem& problem) const override {
        const auto count = static_cast<uint32_t>(problem.resources.size());
        const auto& res = problem.resources;
        auto length = [&](uint32_t r) { return uint64_t{res[r].lifetime.last} - res[r].lifetime.first + 1; };
        // bytes × life, saturating: equal to the exact product whenever that fits.
        auto area = [&](uint32_t r) { return checked::mul(res[r].bytes, length(r)).value_or(UINT64_MAX); };

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
            Less([&](uint32_t a, uint32_t b) { return area(b) < area(a); }),
        };

        std::optional<Placement> best;
        // No placement needs less than the peak of live bytes: one that reaches it is optimal,
        // and the search stops there.
        const std::optional<Peak> peak = peak_live_bytes(problem);
        auto optimal = [&] { return best && peak && best->total <= peak->bytes; };
        auto try_order = [&](const Less& less) -> Status {
            std::vector<uint32_t> order(count);
            std::iota(order.begin(), order.end(), 0u);
            std::stable_sort(order.begin(), order.end(), less);
            for (Fit fit : {Fit::Lowest, Fit::Best}) {
                auto placement = Placer(problem, fit).place(order);
                if (!placement) return placement.take_error();
                if (!best || placement->total < best->total) best = std::move(*placement);
                if (optimal()) return {};
            }
            return {};
        };
        for (const Less& less : orders) {
            LOOM_TRY(try_order(less));
            if (optimal()) break;
        }
        // Mixed alignments (buffers aligned to bytes beside textures aligned to pages): when
        // small-aligned resources pushed page-aligned ones past padding so far that one object
        // per resource would need less, place the strictest alignments first and fill the gaps
        // with the rest. Only then: the usual orders rarely lose this way, and it costs a run.
        uint64_t separate = 0;
        for (const AllocationResource& r : res) separate = checked::add(separate, r.bytes).value_or(UINT64_MAX);
        if (best && best->total > separate) {
            LOOM_TRY(try_order(Less([&](uint32_t a, uint32_t b) {
                return std::tuple(res[b].alignment, res[b].bytes, length(b)) < std::tuple(res[a].alignment, res[a].bytes, length(a));
            })));
        }
        // The resources alive at the peak must tile [0, peak) exactly for the heap to reach the
        // bound; the orders above may scatter them (a buffer placed early between textures
        // leaves padding below the next page-aligned one). So place them first, strictest
        // alignment and then largest first, which stacks them without padding, and fit the rest
        // around them in the same order. One more run costs a fifth more time: microseconds on
        // a frame of a few hundred resources, tens of milliseconds on generated graphs of ten
        // thousand, where it gains a few pages in a gigabyte; so only up to kRestartResources.
        if (!optimal() && peak && count <= kRestartResources) {
            auto alive_at_peak = [&](uint32_t r) {
                return res[r].lifetime.first <= peak->position && peak->position <= res[r].lifetime.last;
            };
            LOOM_TRY(try_order(Less([&](uint32_t a, uint32_t b) {
                return std::tuple(alive_at_peak(a), res[a].alignment, res[a].bytes, length(a)) >
                       std::tuple(alive_at_peak(b), res[b].alignment, res[b].bytes, length(b));
            })));
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

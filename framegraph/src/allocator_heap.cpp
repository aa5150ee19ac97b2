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
//
// Every strategy places every resource, so the cost is the strategies times the cost of one
// placement. A placement needs the members of a heap whose lifetimes overlap the resource's;
// they are found in tables built once for all strategies (LifetimeIndex) and the state of a
// strategy lives in flat arrays that the next strategy reuses: no allocation per resource,
// per heap or per strategy, and a cost per resource that does not grow with the graph.

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <numeric>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "allocators.hpp"
#include "loom/framegraph/memory_model.hpp"
#include "loom/rhi/checked_math.hpp"

namespace loom::fg::detail {
namespace {

constexpr uint32_t kNone = UINT32_MAX;

// The resources' lifetimes, arranged so that those overlapping a lifetime are found by scanning
// a few contiguous runs of a table. Resources are grouped into classes by the length of their
// lifetime (lengths in (2^(c-1), 2^c]) and sorted by first position within a class; their
// places in that table are their slots. A lifetime of a class whose longest member has length
// L overlaps [a, b] only if it starts in [a - L + 1, b], a run of slots, and then exactly when
// it lasts until a. The run holds little else: those that end before a are at least half as
// long as L, so they are alive together near a - L / 2. A run thus costs about what the query
// reports plus the resources alive at one position, whatever the graph's size. (A heap with
// fewer members than its runs hold is searched by its list of members instead.)
class LifetimeIndex {
public:
    explicit LifetimeIndex(const AllocationProblem& problem) {
        const auto& resources = problem.resources;
        const auto count = static_cast<uint32_t>(resources.size());
        // Positions run to the end of the order; a lifetime past it (which the planner never
        // makes) only widens the table, up to the number of resources, or is looked up by a
        // binary search beyond that.
        uint64_t positions = problem.passes.size();
        for (const AllocationResource& r : resources) {
            positions = std::max<uint64_t>(positions, uint64_t{std::max(r.lifetime.first, r.lifetime.last)} + 1);
        }
        // A malformed lifetime (first after last) counts as long as the whole order, so that
        // its window starts at position 0 and the overlap test decides.
        std::vector<uint8_t> class_of(count);
        std::array<uint32_t, 65> class_size{};
        std::array<uint64_t, 65> class_longest{};
        for (uint32_t r = 0; r < count; ++r) {
            const Lifetime& life = resources[r].lifetime;
            const uint64_t length = life.first <= life.last ? uint64_t{life.last} - life.first + 1 : positions;
            const auto c = static_cast<uint8_t>(std::bit_width(length - 1));
            class_of[r] = c;
            ++class_size[c];
            class_longest[c] = std::max(class_longest[c], length);
        }
        std::array<uint32_t, 65> compact{};
        for (uint32_t c = 0; c < class_size.size(); ++c) {
            if (class_size[c] == 0) continue;
            compact[c] = static_cast<uint32_t>(classes_.size());
            const uint32_t begin = classes_.empty() ? 0 : classes_.back().end;
            classes_.push_back(Class{begin, begin + class_size[c], class_longest[c]});
        }
        dense_ = positions <= uint64_t{count} + problem.passes.size() + 1;
        positions_ = positions;

        slot_resource_.resize(count);
        slot_life_.resize(count);
        slot_of_.resize(count);
        if (dense_) {
            // A counting sort by (class, first position) whose counts stay behind as the table
            // of where each class's slots from a position on begin. The table is by position,
            // then class, so that a query's look-ups fall on a few neighbouring lines.
            const std::size_t width = classes_.size();
            auto at = [&](std::size_t c, uint64_t position) -> uint32_t& { return starts_[position * width + c]; };
            starts_.assign((positions + 1) * width, 0);
            for (uint32_t r = 0; r < count; ++r) ++at(compact[class_of[r]], resources[r].lifetime.first);
            uint32_t sum = 0;
            for (std::size_t c = 0; c < width; ++c) {
                for (uint64_t position = 0; position <= positions; ++position) sum += std::exchange(at(c, position), sum);
            }
            for (uint32_t r = 0; r < count; ++r) slot_resource_[at(compact[class_of[r]], resources[r].lifetime.first)++] = r;
            // Each start was moved to the next position's; move them back.
            for (std::size_t c = 0; c < width; ++c) {
                for (uint64_t position = positions; position > 0; --position) at(c, position) = at(c, position - 1);
                at(c, 0) = classes_[c].begin;
            }
        } else {
            std::iota(slot_resource_.begin(), slot_resource_.end(), 0u);
            std::stable_sort(slot_resource_.begin(), slot_resource_.end(), [&](uint32_t a, uint32_t b) {
                return std::pair(class_of[a], resources[a].lifetime.first) <
                       std::pair(class_of[b], resources[b].lifetime.first);
            });
        }
        for (uint32_t s = 0; s < count; ++s) {
            slot_life_[s] = resources[slot_resource_[s]].lifetime;
            slot_of_[slot_resource_[s]] = s;
        }
    }

    [[nodiscard]] uint32_t size() const { return static_cast<uint32_t>(slot_life_.size()); }
    [[nodiscard]] uint32_t slot_of(uint32_t resource) const { return slot_of_[resource]; }
    [[nodiscard]] uint32_t resource(uint32_t slot) const { return slot_resource_[slot]; }
    [[nodiscard]] const Lifetime& life(uint32_t slot) const { return slot_life_[slot]; }
    [[nodiscard]] std::size_t class_count() const { return classes_.size(); }

    /// A run of slots [begin, end) that holds, with others, the lifetimes overlapping one.
    struct Run {
        uint32_t begin = 0;
        uint32_t end = 0;
    };

    /// Fills `runs` (one per class) for the lifetimes overlapping `life`; returns their total length.
    uint32_t runs(const Lifetime& life, std::vector<Run>& runs) const {
        runs.clear();
        uint32_t total = 0;
        for (std::size_t c = 0; c < classes_.size(); ++c) {
            const Class& cls = classes_[c];
            const uint64_t reach = cls.longest - 1;
            const uint64_t from = life.first > reach ? life.first - reach : 0;
            const uint64_t to = uint64_t{life.last} + 1;  // first positions in [from, to)
            if (from >= to) continue;
            const Run run{first_at(c, from), first_at(c, to)};
            if (run.begin >= run.end) continue;
            runs.push_back(run);
            total += run.end - run.begin;
        }
        return total;
    }

private:
    struct Class {
        uint32_t begin = 0;  // its slots
        uint32_t end = 0;
        uint64_t longest = 0;  // the length of its longest lifetime
    };

    // The first slot of class c whose lifetime starts at `position` or later.
    [[nodiscard]] uint32_t first_at(std::size_t c, uint64_t position) const {
        if (position >= positions_) return classes_[c].end;
        if (dense_) return starts_[position * classes_.size() + c];
        const auto begin = slot_life_.begin() + classes_[c].begin;
        const auto end = slot_life_.begin() + classes_[c].end;
        return static_cast<uint32_t>(
            std::partition_point(begin, end, [&](const Lifetime& l) { return l.first < position; }) -
            slot_life_.begin());
    }

    std::vector<Class> classes_;
    std::vector<uint32_t> slot_resource_;  // per slot
    std::vector<Lifetime> slot_life_;      // per slot
    std::vector<uint32_t> slot_of_;        // per resource
    std::vector<uint32_t> starts_;         // per position and class, when dense_
    uint64_t positions_ = 0;
    bool dense_ = true;
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
// resource), yet finds the same first heap that could take it. The tree grows with the heaps
// opened, so that with one heap (no budget) a search is one step.
class HeapFinder {
public:
    /// Forgets every heap, keeping the memory.
    void clear() {
        leaves_ = 1;
        nodes_.assign(2, Node{});
    }

    void set(uint32_t heap, uint64_t capacity, FullSpan full) {
        while (heap >= leaves_) grow();
        std::size_t node = heap + leaves_;
        nodes_[node] = Node{capacity, full.first, full.last};
        for (node /= 2; node >= 1; node /= 2) nodes_[node] = joined(nodes_[2 * node], nodes_[2 * node + 1]);
    }

    /// The lowest heap number in [from, count) that may take `bytes` over `life`.
    [[nodiscard]] std::optional<uint32_t> first(uint32_t from, uint32_t count, const Lifetime& life,
                                                uint64_t bytes) const {
        return search(1, 0, leaves_, from, count, life, bytes);
    }

private:
    struct Node {
        uint64_t capacity = 0;            // largest in the subtree (UINT64_MAX: unbounded)
        uint32_t full_first = 0;          // largest first position of a full span
        uint32_t full_last = UINT32_MAX;  // smallest last position of a full span
    };

    static Node joined(const Node& a, const Node& b) {
        return Node{std::max(a.capacity, b.capacity), std::max(a.full_first, b.full_first),
                    std::min(a.full_last, b.full_last)};
    }

    // Twice the leaves: the old ones move to the new leaf row and the nodes above are joined again.
    void grow() {
        const std::size_t old = leaves_;
        leaves_ *= 2;
        nodes_.resize(2 * leaves_);
        std::copy(nodes_.begin() + static_cast<std::ptrdiff_t>(old), nodes_.begin() + static_cast<std::ptrdiff_t>(2 * old),
                  nodes_.begin() + static_cast<std::ptrdiff_t>(leaves_));
        std::fill(nodes_.begin() + static_cast<std::ptrdiff_t>(leaves_ + old), nodes_.end(), Node{});
        for (std::size_t node = leaves_ - 1; node >= 1; --node) nodes_[node] = joined(nodes_[2 * node], nodes_[2 * node + 1]);
    }

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
    std::vector<Node> nodes_{2};
};

struct HeapState {
    uint64_t capacity = 0;  // 0: unbounded
    uint64_t size = 0;
    FullSpan full;
    uint32_t members = 0;
    uint32_t last_member = kNone;  // a slot; each member's slot names the one placed before it
};

enum class Fit : uint8_t { Lowest, Best };

// What placing a resource reads of it, laid out in the order of a strategy, so that a strategy
// reads its resources one after the other instead of jumping between them.
struct Request {
    uint64_t bytes = 0;
    uint64_t alignment = 1;  // at least 1
    Lifetime life;
    uint32_t resource = 0;
    uint32_t slot = 0;  // in the LifetimeIndex
};

struct Placement {
    std::vector<HeapRange> where;  // per resource
    std::vector<uint64_t> heap_sizes;
    uint64_t total = 0;
};

Error overflow_error(const AllocationResource& resource) {
    return make_error(ErrorCode::Graph, "heap allocator: " + std::string(resource.name) + " (" + std::to_string(resource.bytes) +
                                            " bytes, alignment " + std::to_string(resource.alignment) +
                                            ") does not fit in a heap: its offset would overflow 64 bits");
}

// One strategy at a time: the order and the fit change, the arrays stay.
class Placer {
public:
    Placer(const AllocationProblem& problem, const LifetimeIndex& index)
        : problem_(problem), index_(index), slots_(index.size()), earlier_member_(index.size()) {
        for (const AllocationResource& resource : problem.resources) smallest_ = std::min(smallest_, resource.bytes);
        for (uint32_t slot = 0; slot < index.size(); ++slot) slots_[slot].last = index.life(slot).last;
        runs_.reserve(index.class_count());
    }

    /// Places the resources in `order` into `out`. False when the heaps together reached
    /// `give_up` bytes (UINT64_MAX: never) before the last resource: this placement cannot be
    /// smaller than one of that size (heaps only grow), and `out` is incomplete.
    Result<bool> place(const std::vector<Request>& order, Fit fit, uint64_t give_up, Placement& out) {
        fit_ = fit;
        heaps_.clear();
        finder_.clear();
        for (SlotState& state : slots_) state.heap = kNone;
        out.where.resize(problem_.resources.size());
        out.heap_sizes.clear();
        uint64_t total = 0;
        bool total_overflows = false;
        for (const Request& request : order) {
            const uint32_t slot = request.slot;
            runs_found_ = false;
            const auto count = static_cast<uint32_t>(heaps_.size());
            std::optional<uint64_t> offset;
            uint32_t h = 0;
            for (uint32_t from = 0; !offset; from = h + 1) {
                auto candidate = finder_.first(from, count, request.life, request.bytes);
                if (!candidate) break;
                h = *candidate;
                offset = find_offset(h, request);
            }
            if (!offset) {
                h = count;
                open_heap(request.bytes);
                offset = find_offset(h, request);
                if (!offset) return overflow_error(problem_.resources[request.resource]);
            }
            HeapState& heap = heaps_[h];
            const uint64_t end = *offset + request.bytes;  // find_offset checked the sum
            slots_[slot].heap = h;
            slots_[slot].begin = *offset;
            slots_[slot].end = end;
            earlier_member_[slot] = heap.last_member;
            heap.last_member = slot;
            ++heap.members;
            if (end > heap.size) {
                total_overflows = total_overflows || !checked::add(total, end - heap.size);
                total += end - heap.size;
                heap.size = end;
            }
            if (heap.capacity != 0) note_full(h, slot, *offset, end);
            out.where[request.resource] = HeapRange{h, *offset};
            if (give_up < UINT64_MAX && !total_overflows && total >= give_up) return false;
        }
        if (total_overflows) return make_error(ErrorCode::Graph, "heap allocator: the heaps together exceed 2^64 bytes");
        for (const HeapState& heap : heaps_) out.heap_sizes.push_back(heap.size);
        out.total = total;
        return true;
    }

private:
    struct Busy {
        uint64_t begin = 0;
        uint64_t end = 0;
        uint32_t slot = 0;
    };
    // A resource's place in a strategy, beside the end of its lifetime: what a query reads of a
    // slot it scans, in one place.
    struct SlotState {
        uint64_t begin = 0;  // bytes [begin, end) in its heap, once placed
        uint64_t end = 0;
        uint32_t last = 0;     // the last position of its lifetime
        uint32_t heap = kNone;  // kNone while not placed
    };

    [[nodiscard]] std::span<const Busy> busy() const { return {busy_.data(), busy_count_}; }

    // Up to this many ranges a query's are sorted by counting (sort_busy).
    static constexpr std::size_t kRankedBusy = 32;
    // Below this many members a heap's list is searched without looking at the index.
    static constexpr uint32_t kListedMembers = 16;

    void open_heap(uint64_t first_resource_bytes) {
        // A resource larger than the cap gets a heap of its own size.
        const uint64_t capacity =
            problem_.max_heap_bytes == 0 ? 0 : std::max(problem_.max_heap_bytes, first_resource_bytes);
        heaps_.push_back(HeapState{capacity, 0, {}, 0, kNone});
        finder_.set(static_cast<uint32_t>(heaps_.size() - 1), capacity == 0 ? UINT64_MAX : capacity, FullSpan{});
    }

    // Fills busy_ with the byte ranges of the members of heap h whose lifetimes overlap the
    // lifetime in `slot`, by offset: from the heap's list when it is shorter than the index's
    // runs, else from the runs.
    void collect_busy(uint32_t h, uint32_t slot) {
        const HeapState& heap = heaps_[h];
        const Lifetime& life = index_.life(slot);
        bool listed = heap.members <= kListedMembers;
        if (!listed) {
            if (!runs_found_) {
                runs_length_ = index_.runs(life, runs_);
                runs_found_ = true;
            }
            listed = heap.members <= runs_length_;
        }
        // Every candidate is written and the end advances past those that overlap: no branch
        // to mispredict on the test.
        const uint32_t most = listed ? heap.members : runs_length_;
        if (found_.size() < most) {
            found_.resize(most);
            busy_.resize(most);
        }
        uint32_t* end = found_.data();
        if (listed) {
            for (uint32_t other = heap.last_member; other != kNone; other = earlier_member_[other]) {
                *end = other;
                end += index_.life(other).overlaps(life) ? 1 : 0;
            }
        } else {
            // A run's lifetimes start no later than life.last: they overlap when they last until life.first.
            for (const LifetimeIndex::Run& run : runs_) {
                for (uint32_t other = run.begin; other < run.end; ++other) {
                    const SlotState& state = slots_[other];
                    *end = other;
                    // last >= life.first as the sign of a 64-bit difference, so that GCC does not branch.
                    const uint64_t ended = (uint64_t{state.last} - life.first) >> 63;
                    end += static_cast<uint64_t>(state.heap == h) & (ended ^ 1);
                }
            }
        }
        busy_count_ = static_cast<std::size_t>(end - found_.data());
        sort_busy();
    }

    // Fills busy_ with the ranges of the slots in found_, by offset. A query reports a few dozen
    // ranges at most, usually: those are placed by counting, for each, the ranges below it,
    // which costs more comparisons than a comparison sort but no mispredicted branches, and is
    // faster at that size.
    void sort_busy() {
        const std::size_t count = busy_count_;
        auto range_of = [&](uint32_t slot) { return Busy{slots_[slot].begin, slots_[slot].end, slot}; };
        if (count > kRankedBusy) {
            std::transform(found_.begin(), found_.begin() + static_cast<std::ptrdiff_t>(count), busy_.begin(), range_of);
            std::sort(busy_.begin(), busy_.begin() + static_cast<std::ptrdiff_t>(count),
                      [](const Busy& a, const Busy& b) { return a.begin < b.begin; });
            return;
        }
        uint64_t highest = 0;
        for (std::size_t i = 0; i < count; ++i) highest = std::max(highest, slots_[found_[i]].begin);
        if (highest <= UINT32_MAX) {
            // Heaps under 4 GiB: 32-bit offsets, which the compiler compares four at a time.
            rank_by<uint32_t>();
        } else {
            rank_by<uint64_t>();
        }
    }

    // Writes the range of each of the first busy_count_ slots of found_ to busy_ at its rank by
    // offset, the offsets compared as T (which holds them all).
    template <class T>
    void rank_by() {
        const std::size_t count = busy_count_;
        std::array<T, kRankedBusy> begins;
        for (std::size_t i = 0; i < count; ++i) begins[i] = static_cast<T>(slots_[found_[i]].begin);
        for (std::size_t i = 0; i < count; ++i) {
            const T begin = begins[i];
            uint32_t rank = 0;
            // Equal offsets keep their order, so that every range has its own rank.
            for (std::size_t j = 0; j < i; ++j) rank += begins[j] <= begin ? 1 : 0;
            for (std::size_t j = i + 1; j < count; ++j) rank += begins[j] < begin ? 1 : 0;
            const SlotState& state = slots_[found_[i]];
            busy_[rank] = Busy{state.begin, state.end, found_[i]};
        }
    }

    std::optional<uint64_t> find_offset(uint32_t h, const Request& request) {
        collect_busy(h, request.slot);

        const uint64_t align = request.alignment;
        // Alignments are powers of two but for odd buffers; those round up by a mask.
        const bool power_of_two = (align & (align - 1)) == 0;
        auto align_up = [&](uint64_t value) -> std::optional<uint64_t> {
            if (!power_of_two) return checked::align_up(value, align);
            if (value > UINT64_MAX - (align - 1)) return std::nullopt;
            return (value + (align - 1)) & ~(align - 1);
        };
        std::optional<uint64_t> best;
        uint64_t best_gap = UINT64_MAX;
        uint64_t candidate = 0;
        auto consider = [&](uint64_t gap_end) {  // the free gap [candidate, gap_end)
            const auto end = checked::add(candidate, request.bytes);
            if (!end || *end > gap_end) return false;
            const uint64_t gap = gap_end - candidate;
            if (!best || (fit_ == Fit::Best && gap < best_gap)) {
                best = candidate;
                best_gap = gap;
            }
            return fit_ == Fit::Lowest;  // the lowest offset is final
        };
        for (const Busy& range : busy()) {
            if (range.begin > candidate && consider(range.begin)) return best;
            const auto next = align_up(range.end);
            if (!next) return best;  // no aligned offset after this range
            candidate = std::max(candidate, *next);
        }
        const uint64_t limit = heaps_[h].capacity == 0 ? UINT64_MAX : heaps_[h].capacity;
        if (candidate <= limit) consider(limit);
        return best;
    }

    // After the resource in `slot` was placed at [begin, end) in heap h: if it and the members
    // alive during all of its lifetime leave no gap as large as the smallest resource, the heap
    // is full for its lifetime.
    void note_full(uint32_t h, uint32_t slot, uint64_t begin, uint64_t end) {
        HeapState& heap = heaps_[h];
        const Lifetime& life = index_.life(slot);
        if (smallest_ == 0) return;
        // The resource's range and those of the members alive during all of its lifetime, by
        // offset: busy_ is by offset already, and the resource's range goes where it belongs.
        uint64_t reached = 0;
        auto gap_below = [&](uint64_t range_begin, uint64_t range_end) {
            if (range_begin > reached && range_begin - reached >= smallest_) return true;
            reached = std::max(reached, range_end);
            return false;
        };
        bool own = false;
        for (const Busy& range : busy()) {  // the resource's overlapping members, from find_offset
            const Lifetime& other = index_.life(range.slot);
            if (!(other.first <= life.first && life.last <= other.last)) continue;
            if (!own && begin <= range.begin) {
                own = true;
                if (gap_below(begin, end)) return;
            }
            if (gap_below(range.begin, range.end)) return;
        }
        if (!own && gap_below(begin, end)) return;
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
    const LifetimeIndex& index_;
    Fit fit_ = Fit::Lowest;
    std::vector<HeapState> heaps_;
    std::vector<SlotState> slots_;          // per slot
    std::vector<uint32_t> earlier_member_;  // per placed slot: the member of its heap placed before it
    std::vector<uint32_t> found_;           // the slots of the query's ranges, as found
    std::vector<Busy> busy_;                // their ranges by offset; the first busy_count_ are in use
    std::size_t busy_count_ = 0;
    std::vector<LifetimeIndex::Run> runs_;  // of the resource being placed, once looked up
    uint32_t runs_length_ = 0;
    bool runs_found_ = false;
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

// Sorts the resources by descending key (four words, the first the most significant), ties by
// ascending number: what a stable sort of the resource numbers by those keys gives. A radix
// sort from the least significant byte up that skips the bytes in which all keys agree: keys
// here are sizes, lengths and alignments, which differ in a few bytes, so an order costs a few
// passes over the resources instead of n log n comparisons.
class OrderSorter {
public:
    using Key = std::array<uint64_t, 4>;

    /// `order` receives the numbers of the `count` resources in order; key_of(r) is the key
    /// of resource r (called a few times per resource: it should be cheap).
    template <class KeyOf>
    void sort(uint32_t count, KeyOf&& key_of, std::vector<uint32_t>& order) {
        order.resize(count);
        std::iota(order.begin(), order.end(), 0u);
        Key any{};
        Key all{};
        all.fill(UINT64_MAX);
        for (uint32_t r = 0; r < count; ++r) {
            const Key key = key_of(r);
            for (std::size_t w = 0; w < key.size(); ++w) {
                any[w] |= key[w];
                all[w] &= key[w];
            }
        }
        for (std::size_t w = Key{}.size(); w-- > 0;) {
            const uint64_t varying = any[w] ^ all[w];
            if (varying == 0) continue;
            // The word of each resource, beside it, in the current order: the passes below
            // read them one after the other.
            entries_.resize(count);
            for (std::size_t i = 0; i < count; ++i) entries_[i] = Entry{key_of(order[i])[w], order[i]};
            scratch_.resize(count);
            for (uint32_t shift = 0; shift < 64; shift += 8) {
                if (((varying >> shift) & 0xff) == 0) continue;
                // Descending: the byte's complement ascends.
                auto digit = [shift](const Entry& e) { return 0xff - ((e.word >> shift) & 0xff); };
                std::array<uint32_t, 256> start{};
                for (const Entry& e : entries_) ++start[digit(e)];
                uint32_t sum = 0;
                for (uint32_t& s : start) sum += std::exchange(s, sum);
                for (const Entry& e : entries_) scratch_[start[digit(e)]++] = e;
                entries_.swap(scratch_);
            }
            for (std::size_t i = 0; i < count; ++i) order[i] = entries_[i].resource;
        }
    }

private:
    struct Entry {
        uint64_t word = 0;
        uint32_t resource = 0;
    };
    std::vector<Entry> entries_;
    std::vector<Entry> scratch_;
};

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

        const LifetimeIndex index(problem);
        Placer placer(problem, index);
        using Key = OrderSorter::Key;
        OrderSorter sorter;
        std::vector<uint32_t> sorted;
        std::vector<Request> order(count);
        Placement best;
        Placement placement;
        bool found = false;
        // No placement needs less than the peak of live bytes: one that reaches it is optimal,
        // and the search stops there.
        const std::optional<Peak> peak = peak_live_bytes(problem);
        auto optimal = [&] { return found && peak && best.total <= peak->bytes; };
        // Placing a resource adds at most its bytes and its alignment's padding to the heaps; when
        // all of that fits in 64 bits, no strategy's total can overflow, and one whose heaps
        // already hold as many bytes as the best can stop: it would not be kept.
        uint64_t most = 0;
        for (const AllocationResource& r : res) {
            const uint64_t padding = std::max<uint64_t>(r.alignment, 1) - 1;
            most = checked::add(most, checked::add(r.bytes, padding).value_or(UINT64_MAX)).value_or(UINT64_MAX);
        }
        const bool may_give_up = most < UINT64_MAX;
        auto try_order = [&](auto&& key_of) -> Status {
            sorter.sort(count, key_of, sorted);
            for (uint32_t i = 0; i < count; ++i) {
                const uint32_t r = sorted[i];
                order[i] = Request{res[r].bytes, std::max<uint64_t>(res[r].alignment, 1), res[r].lifetime, r, index.slot_of(r)};
            }
            for (Fit fit : {Fit::Lowest, Fit::Best}) {
                const uint64_t give_up = found && may_give_up ? best.total : UINT64_MAX;
                auto complete = placer.place(order, fit, give_up, placement);
                if (!complete) return complete.take_error();
                if (*complete && (!found || placement.total < best.total)) {
                    std::swap(best, placement);
                    found = true;
                }
                if (optimal()) return {};
            }
            return {};
        };
        LOOM_TRY(try_order([&](uint32_t r) { return Key{res[r].bytes, length(r), 0, 0}; }));
        if (!optimal()) LOOM_TRY(try_order([&](uint32_t r) { return Key{length(r), res[r].bytes, 0, 0}; }));
        if (!optimal()) {
            LOOM_TRY(try_order([&](uint32_t r) { return Key{UINT32_MAX - uint64_t{res[r].lifetime.first}, res[r].bytes, 0, 0}; }));
        }
        if (!optimal()) LOOM_TRY(try_order([&](uint32_t r) { return Key{area(r), 0, 0, 0}; }));
        // Mixed alignments (buffers aligned to bytes beside textures aligned to pages): when
        // small-aligned resources pushed page-aligned ones past padding so far that one object
        // per resource would need less, place the strictest alignments first and fill the gaps
        // with the rest. Only then: the usual orders rarely lose this way, and it costs a run.
        uint64_t separate = 0;
        for (const AllocationResource& r : res) separate = checked::add(separate, r.bytes).value_or(UINT64_MAX);
        if (found && best.total > separate) {
            LOOM_TRY(try_order([&](uint32_t r) { return Key{res[r].alignment, res[r].bytes, length(r), 0}; }));
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
            LOOM_TRY(try_order([&](uint32_t r) {
                return Key{alive_at_peak(r) ? 1u : 0u, res[r].alignment, res[r].bytes, length(r)};
            }));
        }

        Allocation out;
        out.texture_count = count;
        out.texture_of_resource.resize(count);
        std::iota(out.texture_of_resource.begin(), out.texture_of_resource.end(), 0u);
        if (found) {
            out.texture_placement = std::move(best.where);
            out.heap_sizes = std::move(best.heap_sizes);
        }
        return out;
    }
};

}  // namespace

std::unique_ptr<Allocator> make_heap_allocator() { return std::make_unique<HeapAllocator>(); }

}  // namespace loom::fg::detail

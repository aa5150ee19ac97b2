// The memory order (PassOrder::Memory): the ordering problem of a plan, the cost of an order,
// and the heuristic the planner runs. (The exact solver is plan_order_exact.cpp.)
//
// Lowering the peak of live bytes over the orders a DAG allows is NP-hard (it contains register
// sufficiency), so the planner runs a heuristic: three starts (the declared order, and greedy
// list schedules built forwards and backwards that take, of the ready passes, the one that
// raises the peak least and then leaves the fewest bytes live); the cheapest (in small graphs
// each) is improved by moving one pass at a time, with the passes that must move with it, to
// the position that lowers the peak (or the number of positions at it) most. A move is
// evaluated on the positions between its source and target only: the passes before and after
// them, and so the bytes live there, do not change.
#include <algorithm>
#include <bit>
#include <cassert>
#include <numeric>
#include <tuple>

#include "plan_order.hpp"

namespace loom::fg::detail {
namespace {

constexpr uint32_t kNone = UINT32_MAX;

// Per pass: the bytes of the resources it produces and every resource it has a port on.
struct PassResources {
    IndexLists touched;
    std::vector<uint64_t> produced_bytes;
    uint64_t user_count = 0;  // the sum of the resources' user counts: the size of the problem
};

PassResources index_resources(const OrderProblem& problem) {
    const uint32_t n = problem.pass_count();
    PassResources index;
    index.produced_bytes.assign(n, 0);
    for (uint32_t r = 0; r < problem.resources.size(); ++r) {
        const OrderProblem::Resource& resource = problem.resources[r];
        index.produced_bytes[resource.producer] += resource.bytes;
        index.user_count += problem.users[r].size();
    }
    index.touched = problem.users.transposed(n);
    return index;
}

// How many of the ready passes a greedy step weighs: the first ones in declared order. Frames
// have a few ready passes at a time; a graph with thousands (a wide fan-in) then costs linear
// time per step rather than quadratic.
constexpr std::size_t kGreedyCandidates = 64;

// The ready passes of a greedy schedule, visited in preference order (lowest key first): one bit
// per pass, so that a step costs no allocation, and `low_` skips the words emptied before.
class ReadyPasses {
public:
    explicit ReadyPasses(uint32_t n) : words_((n + 63) / 64, 0) {}
    void insert(uint32_t key) {
        words_[key / 64] |= uint64_t{1} << (key % 64);
        low_ = std::min(low_, key / 64);
        ++count_;
    }
    void erase(uint32_t key) {
        words_[key / 64] &= ~(uint64_t{1} << (key % 64));
        --count_;
    }
    [[nodiscard]] bool empty() const { return count_ == 0; }
    // Calls visit(key) for the first `limit` keys in ascending order. (Bounded by the count
    // too: the words past the last key are never read.)
    template <typename Visit>
    void first(std::size_t limit, Visit&& visit) {
        limit = std::min(limit, count_);
        while (low_ < words_.size() && words_[low_] == 0) ++low_;
        for (auto w = static_cast<std::size_t>(low_); w < words_.size() && limit > 0; ++w) {
            for (uint64_t bits = words_[w]; bits != 0 && limit > 0; bits &= bits - 1, --limit) {
                visit(static_cast<uint32_t>(w * 64 + static_cast<std::size_t>(std::countr_zero(bits))));
            }
        }
    }

private:
    std::vector<uint64_t> words_;
    uint32_t low_ = 0;
    std::size_t count_ = 0;
};

// The greedy choice among ready passes: the one that raises the peak least, then leaves the
// fewest bytes live after it, then the first in `preference`.
struct GreedyKey {
    uint64_t peak = 0;
    uint64_t after = 0;
    uint32_t preference = 0;

    friend auto operator<=>(const GreedyKey&, const GreedyKey&) = default;
};

// Counts the live bytes of one more position into an order's cost.
void add_position(OrderCost& cost, uint64_t live) {
    cost.area += live;
    if (live > cost.peak) {
        cost.peak = live;
        cost.at_peak = 1;
    } else if (live == cost.peak) {
        ++cost.at_peak;
    }
}

// A start of the local search: an order and its cost (order_cost's, counted as it is built).
struct Start {
    std::vector<uint32_t> order;
    OrderCost cost;
};

// Forwards: a pass allocates what it produces and frees what it is the last user of.
Start greedy_forward(const OrderProblem& problem, const PassResources& index) {
    const uint32_t n = problem.pass_count();
    std::vector<uint32_t> waiting(n);
    for (uint32_t v = 0; v < n; ++v) waiting[v] = static_cast<uint32_t>(problem.predecessors[v].size());
    std::vector<uint32_t> unplaced_users(problem.resources.size());
    std::vector<uint64_t> frees(n, 0);  // bytes freed right after the pass, were it placed now
    for (uint32_t r = 0; r < problem.resources.size(); ++r) {
        const OrderProblem::Resource& resource = problem.resources[r];
        unplaced_users[r] = static_cast<uint32_t>(problem.users[r].size());
        if (!resource.graph_output && problem.users[r].size() == 1) frees[problem.users[r].front()] += resource.bytes;
    }
    std::vector<bool> placed(n, false);
    ReadyPasses ready(n);
    for (uint32_t v = 0; v < n; ++v) {
        if (waiting[v] == 0) ready.insert(v);
    }
    Start start;
    std::vector<uint32_t>& order = start.order;
    order.reserve(n);
    uint64_t live = 0;
    uint64_t peak = 0;
    while (!ready.empty()) {
        uint32_t chosen = kNone;
        GreedyKey best;
        ready.first(kGreedyCandidates, [&](uint32_t v) {
            const uint64_t step = live + index.produced_bytes[v];
            const GreedyKey key{std::max(step, peak), step - frees[v], v};
            if (chosen == kNone || key < best) {
                best = key;
                chosen = v;
            }
        });
        ready.erase(chosen);
        placed[chosen] = true;
        order.push_back(chosen);
        add_position(start.cost, live + index.produced_bytes[chosen]);
        peak = best.peak;
        live = best.after;
        for (uint32_t r : index.touched[chosen]) {
            const OrderProblem::Resource& resource = problem.resources[r];
            if (--unplaced_users[r] != 1 || resource.graph_output) continue;
            // One user is left: placing it will free the resource.
            for (uint32_t user : problem.users[r]) {
                if (!placed[user]) frees[user] += resource.bytes;
            }
        }
        for (uint32_t next : problem.successors[chosen]) {
            if (--waiting[next] == 0) ready.insert(next);
        }
    }
    return start;
}

// Backwards, from the last position: a pass makes live what it uses that no later pass uses
// (graph outputs are live from the end), and what it produces dies before it.
// The live bytes at a pass are the same as forwards, so its cost is counted in reverse.
Start greedy_backward(const OrderProblem& problem, const PassResources& index) {
    const uint32_t n = problem.pass_count();
    std::vector<uint32_t> waiting(n);
    for (uint32_t v = 0; v < n; ++v) waiting[v] = static_cast<uint32_t>(problem.successors[v].size());
    std::vector<bool> live_resource(problem.resources.size(), false);
    std::vector<uint64_t> allocates(n, 0);  // bytes the pass would make live, were it placed now
    uint64_t live = 0;
    for (uint32_t r = 0; r < problem.resources.size(); ++r) {
        const OrderProblem::Resource& resource = problem.resources[r];
        if (resource.graph_output) {
            live_resource[r] = true;
            live += resource.bytes;
            continue;
        }
        for (uint32_t user : problem.users[r]) allocates[user] += resource.bytes;
    }
    // Ready passes latest-declared first: the mirror of the forward tie break.
    ReadyPasses ready(n);  // keyed n - 1 - pass
    for (uint32_t v = 0; v < n; ++v) {
        if (waiting[v] == 0) ready.insert(n - 1 - v);
    }
    Start start;
    std::vector<uint32_t>& reversed = start.order;
    reversed.reserve(n);
    uint64_t peak = live;
    while (!ready.empty()) {
        uint32_t chosen = kNone;
        GreedyKey best;
        ready.first(kGreedyCandidates, [&](uint32_t key_of_pass) {
            const uint32_t v = n - 1 - key_of_pass;
            const uint64_t step = live + allocates[v];
            const GreedyKey key{std::max(step, peak), step - index.produced_bytes[v], key_of_pass};
            if (chosen == kNone || key < best) {
                best = key;
                chosen = v;
            }
        });
        ready.erase(n - 1 - chosen);
        reversed.push_back(chosen);
        add_position(start.cost, live + allocates[chosen]);
        peak = best.peak;
        live = best.after;
        for (uint32_t r : index.touched[chosen]) {
            if (live_resource[r]) continue;
            live_resource[r] = true;
            for (uint32_t user : problem.users[r]) allocates[user] -= problem.resources[r].bytes;
        }
        for (uint32_t previous : problem.predecessors[chosen]) {
            if (--waiting[previous] == 0) ready.insert(n - 1 - previous);
        }
    }
    std::reverse(reversed.begin(), reversed.end());
    return start;
}

// Moves of one pass at a time, each to the position that lowers the cost most, until no move
// lowers it or the work budget is spent. A pass moved earlier takes along the passes between
// its old and new position that it depends on (directly or through others there), in their
// order; a pass moved later, the passes there that depend on it. So every move keeps every
// constraint, and one move can finish a chain that a plain move of one pass could not start
// (two chains pinned to start in a fixed order: the second moves first with its whole chain).
class LocalSearch {
public:
    LocalSearch(const OrderProblem& problem, const PassResources& index, std::vector<uint32_t> order)
        : problem_(problem), index_(index), order_(std::move(order)) {
        const uint32_t n = problem_.pass_count();
        position_.assign(n, 0);
        window_position_.assign(n, kNone);
        dragged_.assign(n, false);
        ended_bytes_.assign(n, 0);
        ended_delta_.assign(n, 0);
        live_.assign(n, 0);
        carry_.assign(n, 0);
        prefix_max_.assign(n, 0);
        suffix_max_.assign(n, 0);
        prefix_area_.assign(n, 0);
        prefix_at_peak_.assign(n, 0);
        last_user_.assign(problem_.resources.size(), kNone);
        weighed_.assign(problem_.resources.size(), 0);
        new_last_user_.assign(problem_.resources.size(), kNone);
        recompute();
    }

    // Moves passes by up to `radius` positions until no move lowers the cost or about `budget`
    // units of work (a position swept or a user weighed) are spent. Only a move whose positions
    // include one at the peak can lower the peak or the count of positions at it, so only the
    // passes within `radius` of one are tried, the nearest first.
    void run(uint64_t budget, uint32_t radius) {
        const uint32_t n = problem_.pass_count();
        if (n < 2) return;
        std::vector<uint32_t> distance(n);
        std::vector<uint32_t> peaks;
        std::vector<uint32_t> candidates;
        bool improved = true;
        while (improved && work_ < budget) {
            improved = false;
            // The positions at the peak (where the count of them up to a position steps up),
            // then the passes within `radius` of one, in order of position, with their distance
            // to the nearest; only the positions near a peak are visited.
            peaks.clear();
            for (uint32_t j = 1, k = 0; j <= cost_.at_peak; ++j) {
                k = static_cast<uint32_t>(std::lower_bound(prefix_at_peak_.begin() + k, prefix_at_peak_.end(), j) -
                                          prefix_at_peak_.begin());
                peaks.push_back(k);
            }
            candidates.clear();
            auto add = [&](uint32_t k, uint32_t d) {
                distance[k] = d;
                candidates.push_back(order_[k]);
            };
            for (uint32_t k = peaks.front() - std::min(peaks.front(), radius); k < peaks.front(); ++k) {
                add(k, peaks.front() - k);
            }
            for (uint32_t i = 0; i < peaks.size(); ++i) {
                const uint32_t peak = peaks[i];
                add(peak, 0);
                // Up to the next peak (or the end): near this one, then near the next.
                const uint32_t next = i + 1 < peaks.size() ? peaks[i + 1] : UINT32_MAX;
                const uint32_t end = std::min(next, n);
                for (uint32_t k = peak + 1; k < end && k - peak <= radius; ++k) {
                    add(k, next == UINT32_MAX ? k - peak : std::min(k - peak, next - k));
                }
                if (next == UINT32_MAX) continue;
                for (uint32_t k = std::max(peak + radius + 1, next - std::min(next, radius)); k < next; ++k) {
                    add(k, next - k);
                }
            }
            std::stable_sort(candidates.begin(), candidates.end(),
                             [&](uint32_t a, uint32_t b) { return distance[position_[a]] < distance[position_[b]]; });
            work_ += n + candidates.size();
            for (uint32_t v : candidates) {
                if (work_ >= budget) break;
                improved = improve(v, radius) || improved;
            }
        }
    }

    [[nodiscard]] const std::vector<uint32_t>& order() const { return order_; }
    [[nodiscard]] const OrderCost& cost() const { return cost_; }

private:
    // True when positions `first` to `last` include one at the peak.
    [[nodiscard]] bool reaches_peak(uint32_t first, uint32_t last) const {
        return prefix_at_peak_[last] != (first > 0 ? prefix_at_peak_[first - 1] : 0);
    }

    // Tries every move of `v` by up to `radius` positions that spans a position at the peak, and
    // makes the one of lowest cost if it lowers the peak or the count of positions at it (a
    // lower area alone moves nothing: the search ends sooner, and finds the same peaks on the
    // corpus of tests/framegraph/pass_order_test.cpp).
    bool improve(uint32_t v, uint32_t radius) {
        const uint32_t n = problem_.pass_count();
        const uint32_t from = position_[v];
        OrderCost best = cost_;
        best_sequence_.clear();
        uint32_t best_first = 0;
        // Positions `first` to `last` reordered with the dragged passes in front (a move earlier)
        // or behind (a move later), the others keeping their order; kept when the cheapest yet.
        auto consider = [&](uint32_t first, uint32_t last, bool dragged_in_front) {
            sequence_.clear();
            for (const bool dragged : {dragged_in_front, !dragged_in_front}) {
                for (uint32_t k = first; k <= last; ++k) {
                    if (dragged_[order_[k]] == dragged) sequence_.push_back(order_[k]);
                }
            }
            const OrderCost moved = evaluate(first);
            if (moved < best) {
                best = moved;
                best_sequence_ = sequence_;
                best_movers_ = dragged_list_;
                best_first = first;
            }
        };
        // Earlier: the passes between `to` and `from` that v depends on come along.
        dragged_[v] = true;
        dragged_list_.assign(1, v);
        for (uint32_t to = from; to-- > 0 && from - to <= radius;) {
            const uint32_t u = order_[to];
            const bool drag = std::any_of(problem_.successors[u].begin(), problem_.successors[u].end(),
                                          [&](uint32_t s) { return dragged_[s]; });
            work_ += problem_.successors[u].size();
            if (drag) {
                dragged_[u] = true;
                dragged_list_.push_back(u);
            }
            if (dragged_list_.size() == from - to + 1) continue;  // everything moves: no change
            if (!reaches_peak(to, from)) continue;
            consider(to, from, true);
        }
        for (uint32_t u : dragged_list_) dragged_[u] = false;
        // Later: the passes between `from` and `to` that depend on v come along.
        dragged_[v] = true;
        dragged_list_.assign(1, v);
        for (uint32_t to = from + 1; to < n && to - from <= radius; ++to) {
            const uint32_t u = order_[to];
            const bool drag = std::any_of(problem_.predecessors[u].begin(), problem_.predecessors[u].end(),
                                          [&](uint32_t p) { return dragged_[p]; });
            work_ += problem_.predecessors[u].size();
            if (drag) {
                dragged_[u] = true;
                dragged_list_.push_back(u);
            }
            if (dragged_list_.size() == to - from + 1) continue;
            if (!reaches_peak(from, to)) continue;
            consider(from, to, false);
        }
        for (uint32_t u : dragged_list_) dragged_[u] = false;
        if (best_sequence_.empty() || !(std::tie(best.peak, best.at_peak) < std::tie(cost_.peak, cost_.at_peak))) {
            return false;
        }
        apply(best_first, best.peak);
        return true;
    }

    // Makes the move best_sequence_ (from position `first` on, best_movers_ moved), whose peak
    // evaluate() found to be `best_peak`: positions and live bytes change there only, last
    // users only for the moved passes' resources.
    void apply(uint32_t first, uint64_t best_peak) {
        std::copy(best_sequence_.begin(), best_sequence_.end(), order_.begin() + first);
        for (uint32_t k = 0; k < best_sequence_.size(); ++k) position_[best_sequence_[k]] = first + k;
        ++epoch_;
        for (uint32_t mover : best_movers_) {
            for (uint32_t r : index_.touched[mover]) {
                if (problem_.resources[r].graph_output || weighed_[r] == epoch_) continue;
                weighed_[r] = epoch_;
                ended_bytes_[last_user_[r]] -= problem_.resources[r].bytes;
                find_last_user(r);
            }
        }
        uint64_t carry = first > 0 ? carry_[first - 1] : 0;
        for (uint32_t k = first; k < first + best_sequence_.size(); ++k) {
            const uint32_t pass = order_[k];
            live_[k] = carry + index_.produced_bytes[pass];
            carry_[k] = live_[k] - ended_bytes_[pass];
            carry = carry_[k];
        }
        work_ += best_sequence_.size();
        summarize(best_peak, first, static_cast<uint32_t>(first + best_sequence_.size() - 1));
    }

    // The last user of resource r in the current order, and its ended bytes.
    void find_last_user(uint32_t r) {
        const OrderProblem::Resource& resource = problem_.resources[r];
        const std::span<const uint32_t> users = problem_.users[r];
        uint32_t last = users.front();
        for (uint32_t user : users) {
            if (position_[user] > position_[last]) last = user;
        }
        last_user_[r] = last;
        ended_bytes_[last] += resource.bytes;
        work_ += users.size();
    }

    // Positions, last users, live bytes per position and the running figures the moves use.
    void recompute() {
        const uint32_t n = problem_.pass_count();
        for (uint32_t k = 0; k < n; ++k) position_[order_[k]] = k;
        std::fill(ended_bytes_.begin(), ended_bytes_.end(), 0);
        for (uint32_t r = 0; r < problem_.resources.size(); ++r) {
            if (!problem_.resources[r].graph_output) find_last_user(r);  // a graph output never ends
        }
        uint64_t carry = 0;
        for (uint32_t k = 0; k < n; ++k) {
            const uint32_t pass = order_[k];
            live_[k] = carry + index_.produced_bytes[pass];
            carry_[k] = live_[k] - ended_bytes_[pass];
            carry = carry_[k];
        }
        summarize(*std::max_element(live_.begin(), live_.end()), 0, n - 1);
    }

    // The cost and the running figures over positions, from the live bytes, which changed at
    // positions `first` to `last` only and now peak at `peak` (evaluate() computed it). The
    // prefix figures before `first` and the suffix maxima after `last` still hold, unless the
    // peak moved: positions at the peak are counted anew then.
    void summarize(uint64_t peak, uint32_t first, uint32_t last) {
        const uint32_t n = problem_.pass_count();
        if (peak != cost_.peak) first = 0;
        uint64_t running_max = first > 0 ? prefix_max_[first - 1] : 0;
        uint64_t running_area = first > 0 ? prefix_area_[first - 1] : 0;
        uint32_t running_at_peak = first > 0 ? prefix_at_peak_[first - 1] : 0;
        for (uint32_t k = first; k < n; ++k) {
            running_max = std::max(running_max, live_[k]);
            running_area += live_[k];
            running_at_peak += live_[k] == peak ? 1 : 0;
            prefix_max_[k] = running_max;
            prefix_area_[k] = running_area;
            prefix_at_peak_[k] = running_at_peak;
        }
        assert(running_max == peak);
        running_max = last + 1 < n ? suffix_max_[last + 1] : 0;
        for (uint32_t k = last + 1; k-- > 0;) {
            running_max = std::max(running_max, live_[k]);
            suffix_max_[k] = running_max;
        }
        cost_ = OrderCost{peak, running_at_peak, running_area};
        work_ += 3 * uint64_t{n};  // as when every figure was swept again: the same budget
    }

    // The cost with the positions from `first` on holding `sequence_` instead (the same passes
    // in another order, which dragged_list_ lists the moved ones of). The passes before and
    // after keep their positions and so their live bytes; in between, the live bytes are swept
    // again, with the last users of the moved passes' resources as the move makes them (the
    // other passes keep their order among themselves). When the move lowers the peak, the
    // count of positions at the new peak is left at 0 (the area decides between two such
    // moves; improve() counts again).
    OrderCost evaluate(uint32_t first) {
        const auto last_position = static_cast<uint32_t>(first + sequence_.size() - 1);
        for (uint32_t k = 0; k < sequence_.size(); ++k) window_position_[sequence_[k]] = first + k;
        auto moved_position = [&](uint32_t u) {
            return window_position_[u] != kNone ? window_position_[u] : position_[u];
        };
        // A resource's last user changes only if the move changes the order of its users: the
        // moved passes keep their order among themselves, the others theirs. Moved earlier, the
        // last user stays unless it moved (then the users decide again); moved later, a moved
        // user may pass the last one (the moved passes come in order, the latest last).
        ++epoch_;
        const bool later = first == position_[dragged_list_.front()];
        for (uint32_t mover : dragged_list_) {
            for (uint32_t r : index_.touched[mover]) {
                const OrderProblem::Resource& resource = problem_.resources[r];
                if (resource.graph_output) continue;
                const uint32_t last = last_user_[r];
                if (later) {
                    if (dragged_[last] || moved_position(mover) < moved_position(last)) continue;
                    if (weighed_[r] != epoch_) {
                        weighed_[r] = epoch_;
                        changed_.push_back(r);
                    }
                    new_last_user_[r] = mover;
                } else if (dragged_[last] && weighed_[r] != epoch_) {
                    weighed_[r] = epoch_;
                    changed_.push_back(r);
                    const std::span<const uint32_t> users = problem_.users[r];
                    uint32_t latest = users.front();
                    for (uint32_t user : users) {
                        if (moved_position(user) > moved_position(latest)) latest = user;
                    }
                    new_last_user_[r] = latest;
                    work_ += users.size();
                }
            }
            work_ += index_.touched[mover].size();
        }
        for (uint32_t r : changed_) {
            if (new_last_user_[r] == last_user_[r]) continue;
            shift_ended(last_user_[r], -static_cast<int64_t>(problem_.resources[r].bytes));
            shift_ended(new_last_user_[r], static_cast<int64_t>(problem_.resources[r].bytes));
        }
        changed_.clear();
        uint64_t carry = first > 0 ? carry_[first - 1] : 0;
        uint64_t window_max = 0;
        uint64_t window_area = 0;
        uint32_t window_at_peak = 0;
        for (uint32_t pass : sequence_) {
            const uint64_t live = carry + index_.produced_bytes[pass];
            window_max = std::max(window_max, live);
            window_area += live;
            window_at_peak += live == cost_.peak ? 1 : 0;
            carry = static_cast<uint64_t>(static_cast<int64_t>(live - ended_bytes_[pass]) - ended_delta_[pass]);
            window_position_[pass] = kNone;
        }
        work_ += sequence_.size();
        for (uint32_t pass : delta_passes_) ended_delta_[pass] = 0;
        delta_passes_.clear();

        const uint32_t n = problem_.pass_count();
        const uint64_t outside_max =
            std::max(first > 0 ? prefix_max_[first - 1] : 0, last_position + 1 < n ? suffix_max_[last_position + 1] : 0);
        OrderCost moved;
        moved.peak = std::max(outside_max, window_max);
        moved.area = cost_.area - (prefix_area_[last_position] - (first > 0 ? prefix_area_[first - 1] : 0)) + window_area;
        if (moved.peak == cost_.peak) {
            const uint32_t old_in_window = prefix_at_peak_[last_position] - (first > 0 ? prefix_at_peak_[first - 1] : 0);
            moved.at_peak = cost_.at_peak - old_in_window + window_at_peak;
        }
        return moved;
    }

    void shift_ended(uint32_t pass, int64_t bytes) {
        if (ended_delta_[pass] == 0) delta_passes_.push_back(pass);
        ended_delta_[pass] += bytes;
    }

    const OrderProblem& problem_;
    const PassResources& index_;
    std::vector<uint32_t> order_;
    std::vector<uint32_t> position_;         // per pass
    std::vector<uint32_t> window_position_;  // per pass: its position in a move being weighed, or kNone
    std::vector<bool> dragged_;              // per pass: moves with the pass being moved
    std::vector<uint32_t> dragged_list_;     // the pass being moved and those moving with it
    std::vector<uint32_t> sequence_;         // the positions a move changes, in their new order
    std::vector<uint32_t> best_sequence_;    // the best move of improve() so far, and its moved passes
    std::vector<uint32_t> best_movers_;
    std::vector<uint32_t> last_user_;        // per resource; kNone for graph outputs
    std::vector<uint64_t> weighed_;          // per resource: the epoch_ its last user was weighed in
    std::vector<uint32_t> new_last_user_;    // per resource: its last user after the move weighed
    std::vector<uint32_t> changed_;          // the resources whose last user the move may change
    uint64_t epoch_ = 0;
    std::vector<uint64_t> ended_bytes_;      // per pass: bytes of the resources it is the last user of
    std::vector<int64_t> ended_delta_;       // per pass: a move's change to ended_bytes_ (scratch)
    std::vector<uint32_t> delta_passes_;     // the passes with a non-zero ended_delta_
    std::vector<uint64_t> live_;             // per position
    std::vector<uint64_t> carry_;            // per position: live bytes that stay live after it
    std::vector<uint64_t> prefix_max_;       // per position: the most live bytes up to it
    std::vector<uint64_t> suffix_max_;       // per position: the most live bytes from it on
    std::vector<uint64_t> prefix_area_;      // per position: the live bytes summed up to it
    std::vector<uint32_t> prefix_at_peak_;   // per position: positions up to it at the peak
    OrderCost cost_;
    uint64_t work_ = 0;
};

// The local search's allowance in units of work: frames converge long before kBaseWork; on
// 10,000 passes kWorkPerPass bounds it to about a third of the rest of planning's time
// (docs/BENCHMARKS.md, "Pass order").
constexpr uint64_t kBaseWork = 4'000'000;
constexpr uint64_t kWorkPerPass = 200;
// How far a pass moves at once (longer moves are made of several, or come from the greedy
// starts): on the corpora, longer moves found no lower peak and cost up to twice the time.
constexpr uint32_t kRadius = 24;
// Up to this many passes every start is improved, not only the best (the worst gap to the
// optimum on the small corpus falls from 17 % to 0.1 %, for a few tens of microseconds).
constexpr uint32_t kEveryStartPasses = 32;

}  // namespace

OrderProblem make_order_problem(const FrameGraph& graph, const Dependencies& dependencies, const Schedule& declared,
                                const ResolvedResources& resolved) {
    const auto n = static_cast<uint32_t>(declared.order.size());
    OrderProblem problem;
    // (list, value) pairs, made into the lists at the end.
    std::vector<std::pair<uint32_t, uint32_t>> edges;
    uint32_t previous_pinned = kNone;
    for (uint32_t at = 0; at < n; ++at) {
        const uint32_t pass = declared.order[at];
        for (uint32_t next : dependencies.successors[pass]) {
            const uint32_t later = declared.position[next];
            if (later != kNotScheduled) edges.emplace_back(at, later);
        }
        const Pass& declared_pass = graph.pass(PassId{pass});
        if (declared_pass.side_effect() || declared_pass.keeps_declared_order()) {
            if (previous_pinned != kNone) edges.emplace_back(previous_pinned, at);
            previous_pinned = at;
        }
    }
    problem.successors = IndexLists(n, edges);
    problem.predecessors = problem.successors.transposed(n);
    const auto resource_count = static_cast<uint32_t>(resolved.resources.size());
    problem.resources.resize(resource_count);
    for (uint32_t r = 0; r < resource_count; ++r) {
        const PlanResource& resource = resolved.resources[r];
        problem.resources[r].producer = resource.lifetime.first;
        problem.resources[r].bytes = resource.bytes;
        problem.resources[r].graph_output = resource.graph_output;
    }
    // A resource's users: the positions of its running ports' passes, laid out as its ports are.
    std::vector<uint32_t> user_positions(resolved.running_ports.size());
    for (std::size_t k = 0; k < user_positions.size(); ++k) {
        user_positions[k] = declared.position[resolved.running_ports[k].pass];
    }
    problem.users = IndexLists(resolved.first_running_port, std::move(user_positions));
    return problem;
}

namespace {

// The cost of an order from the bytes that start and end at each position: the peak of the live
// bytes, how many positions reach it, and the area under the curve.
OrderCost sweep_cost(const std::vector<uint64_t>& starting, const std::vector<uint64_t>& ending) {
    OrderCost cost;
    uint64_t live = 0;
    for (std::size_t k = 0; k < starting.size(); ++k) {
        live += starting[k];
        add_position(cost, live);
        live -= ending[k];
    }
    return cost;
}

}  // namespace

OrderCost order_cost(const OrderProblem& problem, const std::vector<uint32_t>& order) {
    const auto n = static_cast<uint32_t>(order.size());
    std::vector<uint32_t> position(problem.pass_count(), 0);
    for (uint32_t k = 0; k < n; ++k) position[order[k]] = k;
    std::vector<uint64_t> starting(n, 0);
    std::vector<uint64_t> ending(n, 0);
    for (uint32_t r = 0; r < problem.resources.size(); ++r) {
        const OrderProblem::Resource& resource = problem.resources[r];
        uint32_t last = n - 1;
        if (!resource.graph_output) {
            last = 0;
            for (uint32_t user : problem.users[r]) last = std::max(last, position[user]);
        }
        starting[position[resource.producer]] += resource.bytes;
        ending[last] += resource.bytes;
    }
    return sweep_cost(starting, ending);
}

OrderCost held_cost(const std::vector<PlanResource>& resources, uint32_t position_count) {
    std::vector<uint64_t> starting(position_count, 0);
    std::vector<uint64_t> ending(position_count, 0);
    for (const PlanResource& resource : resources) {
        starting[resource.occupancy.first] += resource.bytes;
        ending[resource.occupancy.last] += resource.bytes;
    }
    return sweep_cost(starting, ending);
}

bool respects_constraints(const OrderProblem& problem, const std::vector<uint32_t>& order) {
    const uint32_t n = problem.pass_count();
    if (order.size() != n) return false;
    std::vector<uint32_t> position(n, kNone);
    for (uint32_t k = 0; k < n; ++k) {
        if (order[k] >= n || position[order[k]] != kNone) return false;
        position[order[k]] = k;
    }
    for (uint32_t v = 0; v < n; ++v) {
        for (uint32_t next : problem.successors[v]) {
            if (position[next] <= position[v]) return false;
        }
    }
    return true;
}

std::vector<uint32_t> memory_order(const OrderProblem& problem, OrderCost* declared_cost) {
    const uint32_t n = problem.pass_count();
    std::vector<uint32_t> declared(n);
    std::iota(declared.begin(), declared.end(), 0u);
    const OrderCost declared_order_cost = order_cost(problem, declared);
    if (declared_cost) *declared_cost = declared_order_cost;
    if (n < 2) return declared;
    const PassResources index = index_resources(problem);
    const uint64_t budget = kBaseWork + kWorkPerPass * (uint64_t{n} + index.user_count);
    const uint32_t radius = std::min(n, kRadius);

    // The starts by cost, the declared order first among equals, so that an order changes only
    // for a lower cost; the best is improved (every one in small graphs).
    std::vector<Start> starts{{declared, declared_order_cost}, greedy_forward(problem, index),
                              greedy_backward(problem, index)};
    std::vector<uint32_t> by_cost{0, 1, 2};
    std::stable_sort(by_cost.begin(), by_cost.end(),
                     [&](uint32_t a, uint32_t b) { return starts[a].cost < starts[b].cost; });
    if (n > kEveryStartPasses) by_cost.resize(1);
    std::vector<uint32_t> best = declared;
    OrderCost best_cost = declared_order_cost;
    for (uint32_t s : by_cost) {
        LocalSearch search(problem, index, std::move(starts[s].order));
        search.run(budget / by_cost.size(), radius);
        if (search.cost() < best_cost) {
            best_cost = search.cost();
            best = search.order();
        }
    }
    return best;
}

}  // namespace loom::fg::detail

// The exact memory order: dynamic programming over the sets of passes placed first. Which
// resources are live between two positions depends only on the set of passes before them
// (produced by one of them, with a user outside it, or a graph output), so the lowest peak of
// a prefix depends only on its set; a pass added to a set is live at its position with those
// resources and what it produces. The sets are visited by size, each kept once with its lowest
// peak; sets above the upper bound are dropped.
#include <algorithm>

#include "plan_order.hpp"

namespace loom::fg::detail {
namespace {

constexpr uint32_t kMaxExactPasses = 64;

// A set of placed passes with the lowest peak any order of it reaches, the bytes live after
// it, and how it was reached (for the order): its set without `pass`, at `parent` in the
// previous layer.
struct State {
    uint64_t placed = 0;
    uint64_t peak = 0;
    uint64_t live = 0;
    uint32_t parent = 0;
    uint32_t pass = 0;
};

uint64_t bit(uint32_t pass) { return uint64_t{1} << pass; }

}  // namespace

std::optional<ExactOrder> exact_memory_order(const OrderProblem& problem, uint64_t max_states, uint64_t upper_bound) {
    const uint32_t n = problem.pass_count();
    if (n > kMaxExactPasses) return std::nullopt;
    if (n == 0) return ExactOrder{};
    std::vector<uint64_t> predecessors(n, 0);
    for (uint32_t v = 0; v < n; ++v) {
        for (uint32_t p : problem.predecessors[v]) predecessors[v] |= bit(p);
    }
    std::vector<uint64_t> produced_bytes(n, 0);
    std::vector<std::vector<uint32_t>> touched(n);
    std::vector<uint64_t> users(problem.resources.size(), 0);
    for (uint32_t r = 0; r < problem.resources.size(); ++r) {
        const OrderProblem::Resource& resource = problem.resources[r];
        produced_bytes[resource.producer] += resource.bytes;
        for (uint32_t user : problem.users[r]) {
            users[r] |= bit(user);
            touched[user].push_back(r);
        }
    }

    std::vector<std::vector<State>> layers(1, std::vector<State>{State{}});
    uint64_t kept = 1;
    for (uint32_t size = 0; size < n; ++size) {
        const std::vector<State>& layer = layers.back();
        std::vector<State> next;
        for (uint32_t i = 0; i < layer.size(); ++i) {
            const State& state = layer[i];
            for (uint32_t v = 0; v < n; ++v) {
                if ((state.placed & bit(v)) != 0 || (predecessors[v] & ~state.placed) != 0) continue;
                const uint64_t at_v = state.live + produced_bytes[v];
                const uint64_t peak = std::max(state.peak, at_v);
                if (peak > upper_bound) continue;
                const uint64_t placed = state.placed | bit(v);
                uint64_t freed = 0;
                for (uint32_t r : touched[v]) {
                    if (!problem.resources[r].graph_output && (users[r] & ~placed) == 0) freed += problem.resources[r].bytes;
                }
                next.push_back(State{placed, peak, at_v - freed, i, v});
            }
            // Duplicates are merged below; this many before merging is already too many.
            if (next.size() > 4 * max_states) return std::nullopt;
        }
        // One state per set, the lowest peak (then the first found) kept.
        std::sort(next.begin(), next.end(), [](const State& a, const State& b) {
            if (a.placed != b.placed) return a.placed < b.placed;
            if (a.peak != b.peak) return a.peak < b.peak;
            return std::pair(a.parent, a.pass) < std::pair(b.parent, b.pass);
        });
        next.erase(std::unique(next.begin(), next.end(),
                               [](const State& a, const State& b) { return a.placed == b.placed; }),
                   next.end());
        kept += next.size();
        if (kept > max_states || next.empty()) return std::nullopt;
        layers.push_back(std::move(next));
    }

    ExactOrder out;
    out.states = kept;
    out.peak = layers.back().front().peak;
    out.order.resize(n);
    uint32_t index = 0;
    for (uint32_t size = n; size > 0; --size) {
        const State& state = layers[size][index];
        out.order[size - 1] = state.pass;
        index = state.parent;
    }
    return out;
}

}  // namespace loom::fg::detail

#pragma once
// Internal: choosing the order of the passes that run for the lowest peak of live bytes
// (PassOrder::Memory). The problem is plain data: the passes are numbered by their positions in
// the declared order, each resource is its producer, the passes that use it and its bytes; a
// resource is live from its producer's position to its last user's (a graph output to the
// end), and the cost of an order is the most bytes live at one position (PlanSummary::
// lower_bound_bytes on one queue).
//
//   memory_order        the heuristic the planner runs: greedy list schedules (forward and
//                       backward) and the declared order as starts, then moves of one pass at
//                       a time that keep every constraint, within a work budget.
//   exact_memory_order  dynamic programming over the sets of passes placed first (each set
//                       closed under predecessors): the optimum, for up to 64 passes and a
//                       bounded number of sets; tests and benchmarks measure the heuristic with it.

#include <compare>
#include <cstdint>
#include <optional>
#include <vector>

#include "graph_analysis.hpp"
#include "plan_phases.hpp"

namespace loom::fg::detail {

/// What ordering needs to know of a graph's passes that run.
struct OrderProblem {
    struct Resource {
        uint32_t producer = 0;        ///< the pass that starts it
        uint64_t bytes = 0;
        bool graph_output = false;    ///< live until the last position
    };
    /// Per pass, the passes that must run after it (sorted, unique): its dependencies (analyze)
    /// and, between consecutive pinned passes (side effects, Pass::keep_declared_order), their
    /// declared relative order. (IndexLists, graph_analysis.hpp: all lists in one array, which
    /// on 10,000 passes made an OrderProblem several times faster than a vector per list.)
    IndexLists successors;
    IndexLists predecessors;  ///< the same edges, the other way
    std::vector<Resource> resources;
    /// Per resource, every pass with a port on it, the producer too (sorted, unique).
    IndexLists users;

    [[nodiscard]] uint32_t pass_count() const { return successors.size(); }
};

/// The problem of the passes `declared` schedules: pass i is declared.order[i]; the resources
/// are `resolved`'s (planned in the declared order), with their indices.
OrderProblem make_order_problem(const FrameGraph& graph, const Dependencies& dependencies, const Schedule& declared,
                                const ResolvedResources& resolved);

/// The problem of `graph` planned with `options` (the phases of build_plan up to resolve, in
/// the declared order), for tests and benchmarks; build_plan's errors.
Result<OrderProblem> order_problem_of(const FrameGraph& graph, const PlanOptions& options);

/// The cost of an order, compared in this order of its fields: the peak of live bytes, how many
/// positions reach it, the sum over positions of live bytes.
struct OrderCost {
    uint64_t peak = 0;
    uint32_t at_peak = 0;
    uint64_t area = 0;

    friend auto operator<=>(const OrderCost&, const OrderCost&) = default;
};

/// The cost of `order` (a permutation of the passes; not checked here).
OrderCost order_cost(const OrderProblem& problem, const std::vector<uint32_t>& order);

/// The cost of resources planned in some order, over `position_count` positions: from their
/// occupancies, which async compute widens (the peak is PlanSummary::lower_bound_bytes).
OrderCost held_cost(const std::vector<PlanResource>& resources, uint32_t position_count);

/// True when `order` is a permutation of the passes that runs every pass after its predecessors.
bool respects_constraints(const OrderProblem& problem, const std::vector<uint32_t>& order);

/// The heuristic: an order that respects the constraints, at most as costly as the declared
/// order 0, 1, ..., n-1 (which it returns when it finds nothing better). Deterministic.
/// `declared_cost`, when given, receives the declared order's cost (which the search weighs).
std::vector<uint32_t> memory_order(const OrderProblem& problem, OrderCost* declared_cost = nullptr);

/// An order of the lowest peak, and how many sets of placed passes the search kept.
struct ExactOrder {
    std::vector<uint32_t> order;
    uint64_t peak = 0;
    uint64_t states = 0;
};

/// The optimum by dynamic programming over the sets of placed passes, keeping only sets whose
/// peak so far is at most `upper_bound` (a known order's peak: the search then finds an order
/// at least as good). nullopt for more than 64 passes, or when more than `max_states` sets
/// would be kept.
std::optional<ExactOrder> exact_memory_order(const OrderProblem& problem, uint64_t max_states,
                                             uint64_t upper_bound = UINT64_MAX);

}  // namespace loom::fg::detail

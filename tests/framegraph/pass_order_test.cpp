// The memory order (PassOrder::Memory): exact orders and peaks of graphs whose declared order
// wastes memory, pins, side effects and order requirements, the exact solver against brute
// force, and on the random corpus the heuristic against the declared order (never worse) and
// against the exact optimum (reached on at least 90 % of small graphs; the figures are printed).
#include <algorithm>
#include <cstdio>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "loom/framegraph/framegraph.hpp"
#include "plan_order.hpp"
#include "random_graph.hpp"

namespace loom::fg {
namespace {

using rhi::Format;

// Texture sizes under the default memory model (64 KiB pages): RGBA8 2048x2048 is 16 MiB,
// RGBA8 256x256 is 256 KiB.
constexpr uint64_t kBig = 16u << 20;
constexpr uint64_t kSmall = 256u << 10;

TextureSpec big() { return TextureSpec::of(Format::RGBA8Unorm).with_size(2048, 2048); }
TextureSpec small() { return TextureSpec::of(Format::RGBA8Unorm).with_size(256, 256); }

std::vector<std::string> order_of(const Plan& plan) {
    std::vector<std::string> names;
    for (const PlanPass& p : plan.order) names.push_back(p.name);
    return names;
}

PlanOptions with_order(PassOrder order, AllocatorKind allocator = AllocatorKind::Heap) {
    PlanOptions options;
    options.frame = {1920, 1080};
    options.allocator = allocator;
    options.order = order;
    return options;
}

Plan must_plan(const FrameGraph& graph, const PlanOptions& options) {
    auto plan = build_plan(graph, options);
    EXPECT_TRUE(plan.ok()) << plan.error().to_string();
    return plan.ok() ? std::move(*plan) : Plan{};
}

// Two chains, each a big temporary reduced to a small result, declared interleaved:
//   a1.big -> a2.in, a2.out -> final.a      b1.big -> b2.in, b2.out -> final.b
// Declared, both big temporaries are live at once (a1, b1, a2, b2, final); finishing one chain
// before starting the other needs one big temporary at a time.
struct Interleaved {
    Pass a1 = Pass("a1").output("big", big());
    Pass b1 = Pass("b1").output("big", big());
    Pass a2 = Pass("a2").input("in").output("out", small());
    Pass b2 = Pass("b2").input("in").output("out", small());
    Pass final = Pass("final").input("a").input("b").output("image", small());

    FrameGraph build() const {
        FrameGraph graph;
        for (const Pass* pass : {&a1, &b1, &a2, &b2, &final}) EXPECT_TRUE(graph.add_pass(*pass).ok());
        EXPECT_TRUE(graph.connect(port("a1", "big"), port("a2", "in")).ok());
        EXPECT_TRUE(graph.connect(port("b1", "big"), port("b2", "in")).ok());
        EXPECT_TRUE(graph.connect(port("a2", "out"), port("final", "a")).ok());
        EXPECT_TRUE(graph.connect(port("b2", "out"), port("final", "b")).ok());
        EXPECT_TRUE(graph.mark_output(port("final", "image")).ok());
        return graph;
    }
};

TEST(PassOrder, MemoryOrderFinishesOneBigTemporaryBeforeStartingTheNext) {
    const FrameGraph graph = Interleaved{}.build();
    const Plan declared = must_plan(graph, with_order(PassOrder::Declared));
    EXPECT_EQ(order_of(declared), (std::vector<std::string>{"a1", "b1", "a2", "b2", "final"}));
    // At a2: both big temporaries and a2's result.
    EXPECT_EQ(declared.summary.lower_bound_bytes, 2 * kBig + kSmall);
    EXPECT_EQ(declared.pass_order, PassOrder::Declared);

    const Plan memory = must_plan(graph, with_order(PassOrder::Memory));
    EXPECT_EQ(order_of(memory), (std::vector<std::string>{"a1", "a2", "b1", "b2", "final"}));
    // At b2: b1's big temporary, a2's and b2's results.
    EXPECT_EQ(memory.summary.lower_bound_bytes, kBig + 2 * kSmall);
    EXPECT_EQ(memory.summary.bytes, kBig + 2 * kSmall);  // the heap allocator reaches it
    EXPECT_EQ(memory.pass_order, PassOrder::Memory);
    // The resources are renumbered by first use in the new order, with lifetimes from it.
    ASSERT_EQ(memory.resources.size(), 5u);
    EXPECT_EQ(memory.resources[0].name, "a1.big");
    EXPECT_EQ(memory.resources[0].lifetime, (Lifetime{0, 1}));
    EXPECT_EQ(memory.resources[1].name, "a2.out");
    EXPECT_EQ(memory.resources[1].lifetime, (Lifetime{1, 4}));
    EXPECT_EQ(memory.resources[2].name, "b1.big");
    EXPECT_EQ(memory.resources[2].lifetime, (Lifetime{2, 3}));
    EXPECT_EQ(memory.resources[3].name, "b2.out");
    EXPECT_EQ(memory.resources[3].lifetime, (Lifetime{3, 4}));
    EXPECT_EQ(memory.resources[4].name, "final.image");
    EXPECT_EQ(memory.resources[4].lifetime, (Lifetime{4, 4}));
    EXPECT_EQ(memory.edges.front().from_pass, 0u);  // a1 -> a2, by positions in the new order
    EXPECT_EQ(memory.edges.front().to_pass, 1u);
    // The interval allocator needs one big texture instead of two.
    EXPECT_EQ(must_plan(graph, with_order(PassOrder::Declared, AllocatorKind::Interval)).summary.textures, 5u);
    EXPECT_EQ(must_plan(graph, with_order(PassOrder::Memory, AllocatorKind::Interval)).summary.textures, 4u);
}

TEST(PassOrder, AnOrderAlreadyAtTheOptimumIsKept) {
    // Declared chain by chain: nothing to gain, and the plan is the declared one but for the mode.
    FrameGraph graph;
    const Interleaved parts;
    for (const Pass* pass : {&parts.a1, &parts.a2, &parts.b1, &parts.b2, &parts.final}) {
        ASSERT_TRUE(graph.add_pass(*pass).ok());
    }
    ASSERT_TRUE(graph.connect(port("a1", "big"), port("a2", "in")).ok());
    ASSERT_TRUE(graph.connect(port("b1", "big"), port("b2", "in")).ok());
    ASSERT_TRUE(graph.connect(port("a2", "out"), port("final", "a")).ok());
    ASSERT_TRUE(graph.connect(port("b2", "out"), port("final", "b")).ok());
    ASSERT_TRUE(graph.mark_output(port("final", "image")).ok());
    const Plan declared = must_plan(graph, with_order(PassOrder::Declared));
    Plan memory = must_plan(graph, with_order(PassOrder::Memory));
    EXPECT_NE(plan_hash(memory), plan_hash(declared));  // the mode is part of the plan
    memory.pass_order = PassOrder::Declared;
    EXPECT_EQ(memory, declared);
    EXPECT_EQ(plan_hash(memory), plan_hash(declared));
}

TEST(PassOrder, PinnedPassesKeepTheirDeclaredRelativeOrder) {
    // a1 before b1 before a2: both big temporaries are live at b1 whatever the order.
    Interleaved parts;
    parts.a1.keep_declared_order();
    parts.b1.keep_declared_order();
    parts.a2.keep_declared_order();
    const Plan memory = must_plan(parts.build(), with_order(PassOrder::Memory));
    const std::vector<std::string> order = order_of(memory);
    auto at = [&](const char* name) { return std::find(order.begin(), order.end(), name) - order.begin(); };
    EXPECT_LT(at("a1"), at("b1"));
    EXPECT_LT(at("b1"), at("a2"));
    EXPECT_EQ(memory.summary.lower_bound_bytes, 2 * kBig + kSmall);
    EXPECT_EQ(order, (std::vector<std::string>{"a1", "b1", "a2", "b2", "final"}));
}

TEST(PassOrder, SideEffectPassesKeepTheirDeclaredRelativeOrder) {
    // b1 and a2 have side effects: b1 runs before a2 as declared, so the b chain goes first.
    Interleaved parts;
    parts.b1.set_side_effect();
    parts.a2.set_side_effect();
    const Plan memory = must_plan(parts.build(), with_order(PassOrder::Memory));
    EXPECT_EQ(order_of(memory), (std::vector<std::string>{"b1", "b2", "a1", "a2", "final"}));
    EXPECT_EQ(memory.summary.lower_bound_bytes, kBig + 2 * kSmall);
}

TEST(PassOrder, RequiredOrdersHoldInEveryOrder) {
    FrameGraph graph = Interleaved{}.build();
    ASSERT_TRUE(graph.require_order("b2", "a1").ok());
    // The requirement reorders the declared order too, like a connection would.
    EXPECT_EQ(order_of(must_plan(graph, with_order(PassOrder::Declared))),
              (std::vector<std::string>{"b1", "b2", "a1", "a2", "final"}));
    const Plan memory = must_plan(graph, with_order(PassOrder::Memory));
    EXPECT_EQ(order_of(memory), (std::vector<std::string>{"b1", "b2", "a1", "a2", "final"}));
    EXPECT_EQ(memory.summary.lower_bound_bytes, kBig + 2 * kSmall);
    // Given twice, kept once.
    const uint64_t revision = graph.revision();
    ASSERT_TRUE(graph.require_order("b2", "a1").ok());
    EXPECT_EQ(graph.order_requirements().size(), 1u);
    EXPECT_EQ(graph.revision(), revision);
}

TEST(PassOrder, RequiredOrderErrorsNameThePasses) {
    FrameGraph graph = Interleaved{}.build();
    auto unknown = graph.require_order("a1", "nowhere");
    ASSERT_FALSE(unknown.ok());
    EXPECT_EQ(unknown.error().code, ErrorCode::Graph);
    EXPECT_EQ(unknown.error().message, "require_order 'a1' before 'nowhere': unknown pass 'nowhere'");
    auto itself = graph.require_order("a1", "a1");
    ASSERT_FALSE(itself.ok());
    EXPECT_EQ(itself.error().message, "require_order 'a1' before 'a1': a pass cannot run before itself");

    // A requirement against the data flow closes a cycle, named with its reason.
    ASSERT_TRUE(graph.require_order("final", "a1").ok());
    for (PassOrder order : {PassOrder::Declared, PassOrder::Memory}) {
        auto plan = build_plan(graph, with_order(order));
        ASSERT_FALSE(plan.ok());
        EXPECT_EQ(plan.error().code, ErrorCode::Graph);
        EXPECT_EQ(plan.error().message,
                  "cycle: a1 -> a2 -> final -> a1 (a1.big feeds a2.in; a2.out feeds final.a; require_order puts final "
                  "before a1)");
    }
}

TEST(PassOrder, InPlaceWritersStayAfterTheReadersOfWhatTheyOverwrite) {
    // "tint" modifies scene.color in place; "probe" reads the colour before it. The peak (at the
    // probe: its big scratch input, the colour and its result) is the same in every order, but
    // making the scratch after the scene lowers the bytes live before it; the tint, which would
    // rather run early too, stays after the probe.
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("scratch").output("big", big())).ok());
    ASSERT_TRUE(graph.add_pass(Pass("scene").output("color", small())).ok());
    ASSERT_TRUE(graph.add_pass(Pass("probe").input("color").input("scratch").output("result", small())).ok());
    ASSERT_TRUE(graph.add_pass(Pass("tint").inout("color")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("final").input("color").input("probe").output("image", small())).ok());
    ASSERT_TRUE(graph.connect(port("scene", "color"), port("probe", "color")).ok());
    ASSERT_TRUE(graph.connect(port("scratch", "big"), port("probe", "scratch")).ok());
    ASSERT_TRUE(graph.connect(port("scene", "color"), port("tint", "color")).ok());
    ASSERT_TRUE(graph.connect(port("tint", "color"), port("final", "color")).ok());
    ASSERT_TRUE(graph.connect(port("probe", "result"), port("final", "probe")).ok());
    ASSERT_TRUE(graph.mark_output(port("final", "image")).ok());
    const Plan declared = must_plan(graph, with_order(PassOrder::Declared));
    EXPECT_EQ(order_of(declared), (std::vector<std::string>{"scratch", "scene", "probe", "tint", "final"}));
    EXPECT_EQ(declared.summary.lower_bound_bytes, kBig + 2 * kSmall);
    const Plan memory = must_plan(graph, with_order(PassOrder::Memory));
    EXPECT_EQ(order_of(memory), (std::vector<std::string>{"scene", "scratch", "probe", "tint", "final"}));
    EXPECT_EQ(memory.summary.lower_bound_bytes, kBig + 2 * kSmall);
}

TEST(PassOrder, TheOrderIsPartOfThePlanCacheKey) {
    FrameGraph graph = Interleaved{}.build();
    auto declared = graph.plan(with_order(PassOrder::Declared));
    ASSERT_TRUE(declared.ok());
    auto memory = graph.plan(with_order(PassOrder::Memory));
    ASSERT_TRUE(memory.ok());
    EXPECT_EQ(graph.plans_built(), 2u);
    EXPECT_EQ((*memory)->summary.lower_bound_bytes, kBig + 2 * kSmall);
    EXPECT_EQ((*declared)->summary.lower_bound_bytes, 2 * kBig + kSmall);
}

TEST(PassOrder, ExportsNameTheMode) {
    const Plan memory = must_plan(Interleaved{}.build(), with_order(PassOrder::Memory));
    std::ostringstream table;
    write_plan_table(table, memory);
    EXPECT_EQ(table.str().rfind("plan: allocator heap, frame 1920x1080, sharing equal, order memory\n", 0), 0u)
        << table.str();
    std::ostringstream json;
    write_plan_json(json, memory);
    EXPECT_NE(json.str().find("\"pass_order\": \"memory\""), std::string::npos);
    EXPECT_EQ(pass_order_name(PassOrder::Declared), "declared");
    EXPECT_EQ(parse_pass_order("memory"), PassOrder::Memory);
    EXPECT_EQ(parse_pass_order("Memory"), std::nullopt);
}

// ---- the solver and the heuristic on the ordering problem itself ------------------------------

detail::OrderProblem problem_of(const FrameGraph& graph) {
    auto problem = detail::order_problem_of(graph, with_order(PassOrder::Declared));
    EXPECT_TRUE(problem.ok()) << problem.error().to_string();
    return problem.ok() ? std::move(*problem) : detail::OrderProblem{};
}

// The lowest peak over every order that respects the constraints, by enumeration.
uint64_t brute_force_peak(const detail::OrderProblem& problem) {
    std::vector<uint32_t> order(problem.pass_count());
    std::iota(order.begin(), order.end(), 0u);
    uint64_t best = UINT64_MAX;
    do {
        if (detail::respects_constraints(problem, order)) best = std::min(best, detail::order_cost(problem, order).peak);
    } while (std::next_permutation(order.begin(), order.end()));
    return best;
}

TEST(ExactOrder, MatchesBruteForceOnSmallGraphs) {
    uint32_t checked = 0;
    uint32_t improvable = 0;
    for (uint64_t seed = 1; seed <= 150; ++seed) {
        testing::RandomGraphOptions options;
        options.passes = 3 + static_cast<uint32_t>(seed % 6);
        options.window = 2 + static_cast<uint32_t>(seed % 4);
        const detail::OrderProblem problem = problem_of(testing::random_graph(seed, options));
        if (problem.pass_count() > 8) continue;
        const uint64_t expected = brute_force_peak(problem);
        auto exact = detail::exact_memory_order(problem, 1'000'000);
        ASSERT_TRUE(exact.has_value()) << "seed " << seed;
        EXPECT_EQ(exact->peak, expected) << "seed " << seed;
        EXPECT_TRUE(detail::respects_constraints(problem, exact->order)) << "seed " << seed;
        EXPECT_EQ(detail::order_cost(problem, exact->order).peak, exact->peak) << "seed " << seed;
        // With the optimum as the upper bound it finds it again; below it, nothing.
        auto bounded = detail::exact_memory_order(problem, 1'000'000, expected);
        ASSERT_TRUE(bounded.has_value()) << "seed " << seed;
        EXPECT_EQ(bounded->peak, expected);
        if (expected > 0) {
            EXPECT_FALSE(detail::exact_memory_order(problem, 1'000'000, expected - 1).has_value());
        }
        const std::vector<uint32_t> declared = [&] {
            std::vector<uint32_t> identity(problem.pass_count());
            std::iota(identity.begin(), identity.end(), 0u);
            return identity;
        }();
        improvable += detail::order_cost(problem, declared).peak > expected ? 1 : 0;
        ++checked;
    }
    EXPECT_GT(checked, 100u);
    EXPECT_GT(improvable, 5u);  // the corpus has graphs whose declared order is not the best
}

TEST(ExactOrder, GivesUpBeyondItsLimits) {
    const detail::OrderProblem problem = problem_of(Interleaved{}.build());
    EXPECT_FALSE(detail::exact_memory_order(problem, 3).has_value());
    auto exact = detail::exact_memory_order(problem, 1000);
    ASSERT_TRUE(exact.has_value());
    EXPECT_EQ(exact->peak, kBig + 2 * kSmall);
    testing::RandomGraphOptions options;
    options.passes = 200;
    options.side_effect_percent = 50;
    const detail::OrderProblem large = problem_of(testing::random_graph(3, options));
    ASSERT_GT(large.pass_count(), 64u);
    EXPECT_FALSE(detail::exact_memory_order(large, 1'000'000).has_value());
}

// Small random graphs: 6 to 25 passes before culling.
testing::RandomGraphOptions small_options(uint64_t seed) {
    testing::RandomGraphOptions options;
    options.passes = 6 + static_cast<uint32_t>(seed % 20);
    options.window = 2 + static_cast<uint32_t>(seed % 7);
    return options;
}

TEST(MemoryOrderCorpus, ReachesTheExactOptimumOnAtLeastNinetyPercentOfSmallGraphs) {
    constexpr uint64_t kGraphs = 600;
    uint32_t solved = 0;
    uint32_t optimal = 0;
    uint32_t improvable = 0;
    uint32_t improved = 0;
    double worst_gap = 0.0;
    uint64_t worst_seed = 0;
    double gap_sum = 0.0;
    for (uint64_t seed = 1; seed <= kGraphs; ++seed) {
        const detail::OrderProblem problem = problem_of(testing::random_graph(seed, small_options(seed)));
        const std::vector<uint32_t> order = detail::memory_order(problem);
        ASSERT_TRUE(detail::respects_constraints(problem, order)) << "seed " << seed;
        const uint64_t heuristic = detail::order_cost(problem, order).peak;
        std::vector<uint32_t> declared(problem.pass_count());
        std::iota(declared.begin(), declared.end(), 0u);
        const uint64_t declared_peak = detail::order_cost(problem, declared).peak;
        ASSERT_LE(heuristic, declared_peak) << "seed " << seed;
        auto exact = detail::exact_memory_order(problem, 2'000'000, heuristic);
        if (!exact) continue;
        ++solved;
        ASSERT_LE(exact->peak, heuristic) << "seed " << seed;
        optimal += exact->peak == heuristic ? 1 : 0;
        if (exact->peak < declared_peak) {
            ++improvable;
            improved += heuristic < declared_peak ? 1 : 0;
        }
        const double gap = static_cast<double>(heuristic) / static_cast<double>(exact->peak) - 1.0;
        gap_sum += gap;
        if (gap > worst_gap) {
            worst_gap = gap;
            worst_seed = seed;
        }
    }
    const double percent = 100.0 * optimal / solved;
    std::printf("memory order on %u small graphs (6-25 passes, %u solved exactly): optimal on %u (%.1f %%), "
                "mean gap %.3f %%, worst gap %.2f %% (seed %llu); declared order not optimal on %u, improved on %u\n",
                static_cast<unsigned>(kGraphs), solved, optimal, percent, 100.0 * gap_sum / solved, 100.0 * worst_gap,
                static_cast<unsigned long long>(worst_seed), improvable, improved);
    EXPECT_GE(solved, kGraphs * 95 / 100);
    EXPECT_GE(percent, 90.0);
    EXPECT_GT(improvable, 50u);  // the corpus tests something
}

// The corpus of property_test.cpp (2 to 40 passes, shuffled declarations): planned in memory
// order, never a higher peak than in declared order, every dependency and pin kept.
TEST(MemoryOrderCorpus, NeverWorseThanDeclaredAndEveryConstraintHolds) {
    uint32_t better = 0;
    constexpr uint64_t kGraphs = 1000;
    for (uint64_t seed = 1; seed <= kGraphs; ++seed) {
        testing::RandomGraphOptions options;
        options.passes = 2 + static_cast<uint32_t>(seed % 39);
        options.window = 2 + static_cast<uint32_t>(seed % 7);
        options.buffer_percent = seed % 2 == 0 ? 25 : 0;
        options.subresource_percent = seed % 3 == 0 ? 20 : 0;
        const FrameGraph graph = testing::random_graph(seed, options);
        const Plan declared = must_plan(graph, with_order(PassOrder::Declared, AllocatorKind::Interval));
        const Plan memory = must_plan(graph, with_order(PassOrder::Memory, AllocatorKind::Interval));
        ASSERT_LE(memory.summary.lower_bound_bytes, declared.summary.lower_bound_bytes) << "seed " << seed;
        better += memory.summary.lower_bound_bytes < declared.summary.lower_bound_bytes ? 1 : 0;
        // The interval allocator still needs exactly the peak count of each class.
        EXPECT_EQ(memory.summary.textures, memory.summary.lower_bound_textures) << "seed " << seed;
        ASSERT_EQ(memory.order.size(), declared.order.size());
        // Edges run forwards; lifetimes cover every use.
        for (const PlanEdge& e : memory.edges) ASSERT_LT(e.from_pass, e.to_pass) << "seed " << seed;
        for (uint32_t at = 0; at < memory.order.size(); ++at) {
            for (const PlanPort& port : memory.order[at].ports) {
                if (!port.resource) continue;
                const Lifetime& life = memory.resources[*port.resource].lifetime;
                ASSERT_LE(life.first, at) << "seed " << seed;
                ASSERT_GE(life.last, at) << "seed " << seed;
            }
        }
        // Readers of a texture's contents run before the pass that modifies it in place: the
        // inout's source position is before the inout, and every other reader of that source
        // is before the inout too.
        for (const PlanEdge& e : memory.edges) {
            if (memory.order[e.to_pass].ports[e.to_port].kind != PortKind::InOut) continue;
            for (const PlanEdge& other : memory.edges) {
                if (other.from_pass == e.from_pass && other.from_port == e.from_port && other.to_pass != e.to_pass) {
                    ASSERT_LT(other.to_pass, e.to_pass) << "seed " << seed;
                }
            }
        }
        // Side-effect passes run in the relative order the declared plan runs them.
        std::vector<std::string> declared_pinned;
        std::vector<std::string> memory_pinned;
        for (const PlanPass& pass : declared.order) {
            if (pass.side_effect) declared_pinned.push_back(pass.name);
        }
        for (const PlanPass& pass : memory.order) {
            if (pass.side_effect) memory_pinned.push_back(pass.name);
        }
        ASSERT_EQ(memory_pinned, declared_pinned) << "seed " << seed;
    }
    std::printf("memory order lowers the peak below the declared order's on %u of %u random graphs\n", better,
                static_cast<unsigned>(kGraphs));
    EXPECT_GT(better, kGraphs / 10);
}

// The allocation itself never grows: whatever the allocator, a plan in memory order needs at
// most the bytes of the same graph's plan in declared order (build_plan keeps the declared
// plan where the memory order's allocation would be bigger), on textures only, with buffers
// and subresources, and with async compute.
TEST(MemoryOrderCorpus, AllocatedBytesNeverAboveTheDeclaredOrders) {
    constexpr uint64_t kGraphs = 600;
    for (const AllocatorKind allocator : {AllocatorKind::Interval, AllocatorKind::Heap, AllocatorKind::Paper}) {
        uint32_t fewer = 0;
        uint32_t reordered = 0;
        for (uint64_t seed = 1; seed <= kGraphs; ++seed) {
            testing::RandomGraphOptions options;
            options.passes = 2 + static_cast<uint32_t>(seed % 39);
            options.window = 2 + static_cast<uint32_t>(seed % 7);
            options.buffer_percent = seed % 3 == 1 ? 25 : 0;
            options.subresource_percent = seed % 3 == 1 ? 20 : 0;
            // The paper allocator refuses async compute.
            options.async_percent = seed % 3 == 2 && allocator != AllocatorKind::Paper ? 30 : 0;
            const FrameGraph graph = testing::random_graph(seed, options);
            const Plan declared = must_plan(graph, with_order(PassOrder::Declared, allocator));
            const Plan memory = must_plan(graph, with_order(PassOrder::Memory, allocator));
            ASSERT_LE(memory.summary.bytes, declared.summary.bytes) << allocator_name(allocator) << " seed " << seed;
            ASSERT_LE(memory.summary.lower_bound_bytes, declared.summary.lower_bound_bytes) << "seed " << seed;
            fewer += memory.summary.bytes < declared.summary.bytes ? 1 : 0;
            const auto names = [](const Plan& plan) {
                std::vector<std::string> out;
                for (const PlanPass& pass : plan.order) out.push_back(pass.name);
                return out;
            };
            reordered += names(memory) != names(declared) ? 1 : 0;
        }
        std::printf("%s: memory order allocates fewer bytes than declared on %u of %u graphs, runs the passes "
                    "in another order on %u\n",
                    std::string(allocator_name(allocator)).c_str(), fewer, static_cast<unsigned>(kGraphs), reordered);
        EXPECT_GT(fewer, kGraphs / 10) << allocator_name(allocator);
    }
}

// The engine frames of samples/plan/graphs (docs/BENCHMARKS.md, "Pass order"): GTA V and Unreal
// reach the exact optimum in memory order; DOOM's peak is held by async compute and stays.
TEST(MemoryOrderEngineFrames, GtaAndUnrealReachTheOptimumDoomKeepsItsOrder) {
    struct Expected {
        const char* file;
        uint64_t declared;
        uint64_t memory;
        uint64_t exact;  // over lifetimes
    };
    for (const Expected& frame : {Expected{"gta5_frame.json", 86507520, 73662464, 73662464},
                                  Expected{"unreal_deferred_frame.json", 141962752, 119537664, 119537664},
                                  Expected{"doom2016_frame.json", 349462784, 349462784, 331768064}}) {
        SCOPED_TRACE(frame.file);
        auto file = load_graph_file(std::string(LOOM_SAMPLE_GRAPHS) + "/" + frame.file);
        ASSERT_TRUE(file.ok()) << file.error().to_string();
        PlanOptions options = with_order(PassOrder::Declared);
        options.frame = file->frame;
        const Plan declared = must_plan(file->graph, options);
        options.order = PassOrder::Memory;
        const Plan memory = must_plan(file->graph, options);
        EXPECT_EQ(declared.summary.lower_bound_bytes, frame.declared);
        EXPECT_EQ(memory.summary.lower_bound_bytes, frame.memory);
        auto problem = detail::order_problem_of(file->graph, options);
        ASSERT_TRUE(problem.ok());
        auto exact = detail::exact_memory_order(*problem, 1'000'000, frame.declared);
        ASSERT_TRUE(exact.has_value());
        EXPECT_EQ(exact->peak, frame.exact);
        EXPECT_EQ(detail::order_cost(*problem, detail::memory_order(*problem)).peak, frame.exact);
        // Every pass still runs, the graph output last.
        EXPECT_EQ(memory.order.size(), declared.order.size());
        EXPECT_EQ(memory.order.back().name, declared.order.back().name);
    }
}

}  // namespace
}  // namespace loom::fg

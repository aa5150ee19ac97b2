// Plans must not change when planning gets faster: the plan hashes of seeded random graphs,
// combined per way of planning, pinned to the values planning gave before the compile-speed
// work (issue 16). A change to what a plan says (order, resources, sharing, placement, syncs)
// changes a hash here; a deliberate change of plans updates the pinned values in the same
// commit, saying why. (The memory order's heap plans changed where the memory order's
// allocation needed more bytes than the declared order's: build_plan keeps the declared plan
// there, issue 17.)
#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "loom/framegraph/framegraph.hpp"
#include "random_graph.hpp"

namespace loom::fg {
namespace {

constexpr uint64_t kGraphs = 300;

// FNV-1a over the plan hashes in seed order, so that a changed plan anywhere changes the value.
struct Combined {
    uint64_t value = 1469598103934665603ull;
    void add(uint64_t hash) {
        for (int i = 0; i < 8; ++i) {
            value ^= (hash >> (8 * i)) & 0xff;
            value *= 1099511628211ull;
        }
    }
};

using testing::Corpus;

uint64_t corpus_hash(Corpus corpus, AllocatorKind allocator, SpecSharing sharing, PassOrder order) {
    PlanOptions options;
    options.frame = {1920, 1080};
    options.allocator = allocator;
    options.sharing = sharing;
    options.order = order;
    Combined combined;
    for (uint64_t seed = 1; seed <= kGraphs; ++seed) {
        const FrameGraph graph = testing::random_graph(seed, testing::corpus_options(seed, corpus));
        auto plan = build_plan(graph, options);
        if (!plan) {
            ADD_FAILURE() << "seed " << seed << " " << allocator_name(allocator) << ": " << plan.error().to_string();
            return 0;
        }
        combined.add(plan_hash(*plan));
    }
    return combined.value;
}

TEST(PlanHashCorpus, TexturePlansAreUnchanged) {
    EXPECT_EQ(corpus_hash(Corpus::Textures, AllocatorKind::Paper, SpecSharing::Equal, PassOrder::Declared), 0x3e33e217ef90d5c0ull);
    EXPECT_EQ(corpus_hash(Corpus::Textures, AllocatorKind::Interval, SpecSharing::Equal, PassOrder::Declared), 0xf6ec50e5ae468c34ull);
    EXPECT_EQ(corpus_hash(Corpus::Textures, AllocatorKind::Heap, SpecSharing::Equal, PassOrder::Declared), 0x8e8420041a855e4cull);
    EXPECT_EQ(corpus_hash(Corpus::Textures, AllocatorKind::Interval, SpecSharing::Joinable, PassOrder::Declared), 0x69adf352d14d2d42ull);
    EXPECT_EQ(corpus_hash(Corpus::Textures, AllocatorKind::Heap, SpecSharing::Joinable, PassOrder::Memory), 0x43a315b7ddc8cf59ull);
}

TEST(PlanHashCorpus, BufferAndSubresourcePlansAreUnchanged) {
    EXPECT_EQ(corpus_hash(Corpus::Mixed, AllocatorKind::Interval, SpecSharing::Equal, PassOrder::Declared), 0x6e82c040172e8fb0ull);
    EXPECT_EQ(corpus_hash(Corpus::Mixed, AllocatorKind::Heap, SpecSharing::Equal, PassOrder::Memory), 0x4163d895abcd0593ull);
}

TEST(PlanHashCorpus, AsyncComputePlansAreUnchanged) {
    EXPECT_EQ(corpus_hash(Corpus::Async, AllocatorKind::Interval, SpecSharing::Equal, PassOrder::Declared), 0x9d9e6355016bb9b5ull);
    EXPECT_EQ(corpus_hash(Corpus::Async, AllocatorKind::Heap, SpecSharing::Equal, PassOrder::Memory), 0x11f0b733af913089ull);
}

// One large graph (3,000 passes declared in frame order), where the heap allocator keeps many
// resources apart at once.
TEST(PlanHashCorpus, LargeGraphPlansAreUnchanged) {
    testing::RandomGraphOptions options;
    options.passes = 3000;
    options.window = 8;
    options.graph_output_percent = 0;
    options.side_effect_percent = 10;
    options.shuffle_declarations = false;
    const FrameGraph graph = testing::random_graph(7, options);
    for (AllocatorKind allocator : {AllocatorKind::Interval, AllocatorKind::Heap}) {
        PlanOptions plan_options;
        plan_options.allocator = allocator;
        plan_options.order = PassOrder::Declared;  // the hashes from before the memory order existed
        auto plan = build_plan(graph, plan_options);
        ASSERT_TRUE(plan) << plan.error().to_string();
        EXPECT_EQ(plan_hash(*plan), allocator == AllocatorKind::Heap ? 0xa9df76f6a8130fc9ull : 0xa3cfb5f8abd00c64ull) << allocator_name(allocator);
    }
}

}  // namespace
}  // namespace loom::fg

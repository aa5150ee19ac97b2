// Properties every plan must have, checked on thousands of seeded random DAGs: correctness of
// sharing (no two live resources in one texture or in overlapping heap bytes), optimality of
// the interval allocator, the lower bounds, and determinism.
#include <algorithm>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "loom/framegraph/framegraph.hpp"
#include "random_graph.hpp"

namespace loom::fg {
namespace {

// Two thousand graphs take about a second to plan in an optimised build; unoptimised
// (sanitizer) builds are ten to forty times slower and check half as many.
#ifdef NDEBUG
constexpr uint32_t kGraphs = 2000;
#else
constexpr uint32_t kGraphs = 1000;
#endif

testing::RandomGraphOptions options_for(uint64_t seed) {
    testing::RandomGraphOptions options;
    options.passes = 2 + static_cast<uint32_t>(seed % 39);  // 2..40 passes
    options.window = 2 + static_cast<uint32_t>(seed % 7);
    return options;
}

PlanOptions plan_options(AllocatorKind allocator, SpecSharing sharing = SpecSharing::Equal) {
    PlanOptions options;
    options.frame = {1920, 1080};
    options.allocator = allocator;
    options.sharing = sharing;
    return options;
}

// The plans of one way of planning (allocator and sharing) for every graph of the corpus.
using Plans = std::vector<Plan>;

// The corpus: graphs for seeds 1..kGraphs, each planned on first request per way of planning
// (ctest runs every test in its own process, so each test plans only what it checks).
class RandomGraphs : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        graphs_ = new std::vector<FrameGraph>();
        graphs_->reserve(kGraphs);
        for (uint64_t seed = 1; seed <= kGraphs; ++seed) graphs_->push_back(testing::random_graph(seed, options_for(seed)));
        plans_ = new std::map<std::pair<AllocatorKind, SpecSharing>, Plans>();
    }
    static void TearDownTestSuite() {
        delete graphs_;
        delete plans_;
        graphs_ = nullptr;
        plans_ = nullptr;
    }

    static uint64_t seed_of(std::size_t index) { return index + 1; }

    static const Plans& plans(AllocatorKind allocator, SpecSharing sharing = SpecSharing::Equal) {
        Plans& out = (*plans_)[{allocator, sharing}];
        if (!out.empty()) return out;
        out.reserve(graphs_->size());
        for (std::size_t i = 0; i < graphs_->size(); ++i) {
            auto plan = build_plan((*graphs_)[i], plan_options(allocator, sharing));
            if (!plan) {
                ADD_FAILURE() << "seed " << seed_of(i) << " " << allocator_name(allocator) << ": " << plan.error().to_string();
                out.emplace_back();
            } else {
                out.push_back(std::move(*plan));
            }
        }
        return out;
    }

private:
    static std::vector<FrameGraph>* graphs_;
    static std::map<std::pair<AllocatorKind, SpecSharing>, Plans>* plans_;
};

std::vector<FrameGraph>* RandomGraphs::graphs_ = nullptr;
std::map<std::pair<AllocatorKind, SpecSharing>, Plans>* RandomGraphs::plans_ = nullptr;

// No two resources alive at the same position share a texture (or a buffer).
void expect_no_shared_live_texture(const Plan& plan, uint64_t seed) {
    for (std::size_t a = 0; a < plan.resources.size(); ++a) {
        for (std::size_t b = a + 1; b < plan.resources.size(); ++b) {
            const PlanResource& ra = plan.resources[a];
            const PlanResource& rb = plan.resources[b];
            if (ra.type != rb.type) continue;
            if (ra.type == ResourceType::Buffer ? ra.buffer == rb.buffer : ra.texture == rb.texture) {
                ASSERT_FALSE(ra.lifetime.overlaps(rb.lifetime))
                    << "seed " << seed << " " << plan.allocator << ": " << ra.name << " and " << rb.name << " share t"
                    << ra.texture;
            }
        }
    }
}

// Each texture holds its resources: one shape in Equal sharing, and the union of their usage.
void expect_textures_fit_resources(const Plan& plan, uint64_t seed) {
    for (const PlanResource& r : plan.resources) {
        if (r.type == ResourceType::Buffer) {
            ASSERT_EQ(r.texture, kNoPhysical);
            const PlanBuffer& b = plan.buffers[r.buffer];
            ASSERT_NE(std::find(b.resources.begin(), b.resources.end(), &r - plan.resources.data()), b.resources.end());
            EXPECT_TRUE(rhi::has_all(b.spec.usage, r.buffer_spec.usage)) << "seed " << seed << " " << r.name;
            EXPECT_EQ(b.spec.size, r.buffer_spec.size) << "seed " << seed << " " << r.name;
            EXPECT_GE(b.bytes, r.bytes) << "seed " << seed << " " << r.name;
            continue;
        }
        ASSERT_EQ(r.buffer, kNoPhysical);
        const PlanTexture& t = plan.textures[r.texture];
        ASSERT_NE(std::find(t.resources.begin(), t.resources.end(), &r - plan.resources.data()), t.resources.end());
        EXPECT_TRUE(rhi::has_all(t.spec.usage, r.spec.usage)) << "seed " << seed << " " << r.name;
        EXPECT_EQ(t.spec.extent, r.spec.extent) << "seed " << seed << " " << r.name;
        EXPECT_GE(t.bytes, r.bytes) << "seed " << seed << " " << r.name;
        if (plan.sharing == SpecSharing::Equal) {
            EXPECT_TRUE(same_texture_shape(t.spec, r.spec)) << "seed " << seed << " " << r.name;
        }
    }
}

// Every texture and buffer is placed inside its heap, aligned, and no two resources alive at
// the same position overlap in heap bytes, whatever their types.
void expect_placements_disjoint(const Plan& plan, uint64_t seed) {
    ASSERT_EQ(plan.textures.size() + plan.buffers.size(), plan.resources.size()) << "seed " << seed;
    auto check = [&](const std::optional<HeapRange>& placement, uint64_t bytes, uint64_t alignment) {
        ASSERT_TRUE(placement.has_value()) << "seed " << seed;
        ASSERT_LT(placement->heap, plan.heaps.size());
        EXPECT_EQ(placement->offset % alignment, 0u) << "seed " << seed;
        EXPECT_LE(placement->offset + bytes, plan.heaps[placement->heap]) << "seed " << seed;
    };
    for (const PlanTexture& t : plan.textures) check(t.placement, t.bytes, t.alignment);
    for (const PlanBuffer& b : plan.buffers) check(b.placement, b.bytes, b.alignment);
    auto placement_of = [&](const PlanResource& r) {
        return r.type == ResourceType::Buffer ? *plan.buffers[r.buffer].placement : *plan.textures[r.texture].placement;
    };
    for (std::size_t a = 0; a < plan.resources.size(); ++a) {
        for (std::size_t b = a + 1; b < plan.resources.size(); ++b) {
            const PlanResource& ra = plan.resources[a];
            const PlanResource& rb = plan.resources[b];
            if (!ra.lifetime.overlaps(rb.lifetime)) continue;
            const HeapRange pa = placement_of(ra);
            const HeapRange pb = placement_of(rb);
            if (pa.heap != pb.heap) continue;
            const bool disjoint = pa.offset + ra.bytes <= pb.offset || pb.offset + rb.bytes <= pa.offset;
            ASSERT_TRUE(disjoint) << "seed " << seed << ": " << ra.name << " and " << rb.name;
        }
    }
}

TEST_F(RandomGraphs, CorpusIsVaried) {
    uint32_t culled = 0;
    uint32_t in_place = 0;
    uint32_t max_resources = 0;
    for (const Plan& plan : plans(AllocatorKind::Interval)) {
        culled += plan.culled.empty() ? 0 : 1;
        for (const PlanPass& pass : plan.order) {
            for (const PlanPort& port : pass.ports) in_place += port.kind == PortKind::InOut ? 1 : 0;
        }
        max_resources = std::max<uint32_t>(max_resources, static_cast<uint32_t>(plan.resources.size()));
    }
    EXPECT_GT(culled, kGraphs / 10);
    EXPECT_GT(in_place, kGraphs / 2);
    EXPECT_GE(max_resources, 50u);
}

TEST_F(RandomGraphs, NoTwoLiveResourcesShareATexture) {
    for (const auto& [allocator, sharing] : {std::pair{AllocatorKind::Paper, SpecSharing::Equal}, std::pair{AllocatorKind::Interval, SpecSharing::Equal},
                                             std::pair{AllocatorKind::Paper, SpecSharing::Joinable},
                                             std::pair{AllocatorKind::Interval, SpecSharing::Joinable}}) {
        const Plans& all = plans(allocator, sharing);
        for (std::size_t i = 0; i < all.size(); ++i) {
            expect_no_shared_live_texture(all[i], seed_of(i));
            expect_textures_fit_resources(all[i], seed_of(i));
        }
    }
}

TEST_F(RandomGraphs, NoTwoLiveResourcesOverlapInHeapBytes) {
    const Plans& all = plans(AllocatorKind::Heap);
    for (std::size_t i = 0; i < all.size(); ++i) {
        expect_placements_disjoint(all[i], seed_of(i));
    }
}

TEST_F(RandomGraphs, IntervalMeetsTheLowerBoundAndNeverLosesToPaper) {
    // In the memory order (the default) each allocator keeps the order it places in fewer
    // bytes, so the two are compared where both run the same order: most graphs.
    auto same_order = [](const Plan& a, const Plan& b) {
        return std::ranges::equal(a.order, b.order, [](const PlanPass& x, const PlanPass& y) { return x.name == y.name; });
    };
    for (SpecSharing sharing : {SpecSharing::Equal, SpecSharing::Joinable}) {
        const Plans& interval = plans(AllocatorKind::Interval, sharing);
        const Plans& paper = plans(AllocatorKind::Paper, sharing);
        std::size_t compared = 0;
        for (std::size_t i = 0; i < interval.size(); ++i) {
            EXPECT_EQ(interval[i].summary.textures, interval[i].summary.lower_bound_textures) << "seed " << seed_of(i);
            if (same_order(interval[i], paper[i])) {
                ++compared;
                EXPECT_LE(interval[i].summary.textures, paper[i].summary.textures) << "seed " << seed_of(i);
            }
            // The paper's reverse walk colours intervals by decreasing end and frees a colour
            // at the interval's start: the mirror image of the interval sweep, so it is optimal
            // too.
            EXPECT_EQ(paper[i].summary.textures, paper[i].summary.lower_bound_textures) << "seed " << seed_of(i);
        }
        EXPECT_GT(compared, interval.size() * 3 / 4) << spec_sharing_name(sharing);
    }
}

TEST_F(RandomGraphs, BytesRespectTheLowerBound) {
    for (const auto& [allocator, sharing] : {std::pair{AllocatorKind::Paper, SpecSharing::Equal}, std::pair{AllocatorKind::Interval, SpecSharing::Equal},
                                             std::pair{AllocatorKind::Heap, SpecSharing::Equal},
                                             std::pair{AllocatorKind::Interval, SpecSharing::Joinable}}) {
        const Plans& all = plans(allocator, sharing);
        for (std::size_t i = 0; i < all.size(); ++i) {
            const PlanSummary& summary = all[i].summary;
            EXPECT_GE(summary.bytes, summary.lower_bound_bytes) << "seed " << seed_of(i) << " " << allocator_name(allocator);
            EXPECT_LE(summary.lower_bound_bytes, summary.naive_bytes) << "seed " << seed_of(i);
            EXPECT_EQ(summary.naive_textures, all[i].resources.size());
            EXPECT_EQ(summary.textures, all[i].textures.size());
            if (allocator == AllocatorKind::Heap) {
                EXPECT_LE(summary.bytes, summary.naive_bytes) << "seed " << seed_of(i);
            }
        }
    }
}

TEST_F(RandomGraphs, OrderIsTopologicalAndLifetimesCoverEveryUse) {
    const Plans& all = plans(AllocatorKind::Interval);
    for (std::size_t i = 0; i < all.size(); ++i) {
        const Plan& plan = all[i];
        const uint64_t seed = seed_of(i);
        for (const PlanEdge& e : plan.edges) ASSERT_LT(e.from_pass, e.to_pass) << "seed " << seed;
        for (uint32_t at = 0; at < plan.order.size(); ++at) {
            for (const PlanPort& port : plan.order[at].ports) {
                if (!port.resource) {
                    EXPECT_TRUE(port.optional) << "seed " << seed << " " << plan.order[at].name << "." << port.name;
                    continue;
                }
                const Lifetime& life = plan.resources[*port.resource].lifetime;
                EXPECT_LE(life.first, at) << "seed " << seed;
                EXPECT_GE(life.last, at) << "seed " << seed;
                if (port.kind == PortKind::Output) {
                    EXPECT_EQ(life.first, at) << "seed " << seed;
                }
            }
        }
        for (const PlanResource& r : plan.resources) {
            if (r.graph_output) {
                EXPECT_EQ(r.lifetime.last, plan.order.size() - 1) << "seed " << seed;
            }
            // One queue: memory is held exactly while the resource lives.
            EXPECT_EQ(r.occupancy, r.lifetime) << "seed " << seed;
        }
        EXPECT_TRUE(plan.queue_syncs.empty()) << "seed " << seed;
    }
}

TEST_F(RandomGraphs, PlansAreDeterministic) {
    for (AllocatorKind allocator : allocator_kinds()) {
        const Plans& all = plans(allocator);
        for (std::size_t i = 0; i < all.size(); i += 4) {  // a quarter of the corpus, rebuilt from its seed
            const FrameGraph graph = testing::random_graph(seed_of(i), options_for(seed_of(i)));
            auto again = build_plan(graph, plan_options(allocator));
            ASSERT_TRUE(again.ok());
            EXPECT_EQ(*again, all[i]) << "seed " << seed_of(i) << " " << allocator_name(allocator);
            EXPECT_EQ(plan_hash(*again), plan_hash(all[i])) << "seed " << seed_of(i);
        }
    }
}

TEST(RandomGraph, GeneratorIsSeeded) {
    const FrameGraph a = testing::random_graph(42);
    const FrameGraph b = testing::random_graph(42);
    const FrameGraph c = testing::random_graph(43);
    ASSERT_EQ(a.pass_count(), b.pass_count());
    EXPECT_EQ(a.connections(), b.connections());
    for (uint32_t p = 0; p < a.pass_count(); ++p) {
        EXPECT_EQ(a.pass(PassId{p}).name(), b.pass(PassId{p}).name());
        EXPECT_EQ(a.pass(PassId{p}).ports(), b.pass(PassId{p}).ports());
    }
    EXPECT_NE(a.connections(), c.connections());
}


// ---- the same properties with buffers and subresource ranges --------------------------------

// A corpus where a quarter of the outputs after the first are buffers and a fifth of the
// textures are mip chains or layer arrays used one subresource at a time (a pass may read one
// mip and write another of the same texture).
testing::RandomGraphOptions mixed_options_for(uint64_t seed) {
    testing::RandomGraphOptions options = options_for(seed);
    options.buffer_percent = 25;
    options.subresource_percent = 20;
    return options;
}

class MixedRandomGraphs : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        graphs_ = new std::vector<FrameGraph>();
        for (uint64_t seed = 1; seed <= kGraphs / 2; ++seed) graphs_->push_back(testing::random_graph(seed, mixed_options_for(seed)));
    }
    static void TearDownTestSuite() {
        delete graphs_;
        graphs_ = nullptr;
    }
    static Plans plan_all(AllocatorKind allocator, SpecSharing sharing = SpecSharing::Equal) {
        Plans out;
        for (std::size_t i = 0; i < graphs_->size(); ++i) {
            auto plan = build_plan((*graphs_)[i], plan_options(allocator, sharing));
            if (!plan) {
                ADD_FAILURE() << "seed " << i + 1 << " " << allocator_name(allocator) << ": " << plan.error().to_string();
                out.emplace_back();
            } else {
                out.push_back(std::move(*plan));
            }
        }
        return out;
    }
    static std::vector<FrameGraph>* graphs_;
};

std::vector<FrameGraph>* MixedRandomGraphs::graphs_ = nullptr;

TEST_F(MixedRandomGraphs, CorpusHasBuffersAndSubresourceAccess) {
    uint32_t buffers = 0;
    uint32_t ranged_ports = 0;
    uint32_t read_and_modified = 0;  // a pass reading one subresource and writing another of one texture
    for (const Plan& plan : plan_all(AllocatorKind::Interval)) {
        buffers += plan.summary.naive_buffers;
        for (const PlanPass& pass : plan.order) {
            for (const PlanPort& port : pass.ports) {
                if (!port.resource || port.type != ResourceType::Texture) continue;
                const PlanResource& r = plan.resources[*port.resource];
                if (port.range.mip_count < r.spec.mips || port.range.layer_count < r.spec.layers) ++ranged_ports;
                if (port.kind != PortKind::InOut) continue;
                for (const PlanPort& other : pass.ports) {
                    if (&other != &port && other.kind == PortKind::Input && other.resource == port.resource) ++read_and_modified;
                }
            }
        }
    }
    EXPECT_GT(buffers, kGraphs);
    EXPECT_GT(ranged_ports, kGraphs);
    EXPECT_GT(read_and_modified, kGraphs / 20);
}

TEST_F(MixedRandomGraphs, NoTwoLiveResourcesShareAnObjectAndIntervalMeetsBothBounds) {
    for (SpecSharing sharing : {SpecSharing::Equal, SpecSharing::Joinable}) {
        const Plans interval = plan_all(AllocatorKind::Interval, sharing);
        const Plans paper = plan_all(AllocatorKind::Paper, sharing);
        for (std::size_t i = 0; i < interval.size(); ++i) {
            for (const Plan* plan : {&interval[i], &paper[i]}) {
                expect_no_shared_live_texture(*plan, i + 1);
                expect_textures_fit_resources(*plan, i + 1);
                EXPECT_EQ(plan->summary.textures, plan->summary.lower_bound_textures) << "seed " << i + 1 << " " << plan->allocator;
                EXPECT_EQ(plan->summary.buffers, plan->summary.lower_bound_buffers) << "seed " << i + 1 << " " << plan->allocator;
                EXPECT_EQ(plan->summary.naive_textures + plan->summary.naive_buffers, plan->resources.size());
                EXPECT_GE(plan->summary.bytes, plan->summary.lower_bound_bytes) << "seed " << i + 1;
            }
        }
    }
}

TEST_F(MixedRandomGraphs, HeapsPlaceBuffersAndTexturesWithoutOverlap) {
    const Plans heap = plan_all(AllocatorKind::Heap);
    for (std::size_t i = 0; i < heap.size(); ++i) {
        expect_placements_disjoint(heap[i], i + 1);
        EXPECT_GE(heap[i].summary.bytes, heap[i].summary.lower_bound_bytes) << "seed " << i + 1;
        EXPECT_LE(heap[i].summary.bytes, heap[i].summary.naive_bytes) << "seed " << i + 1;
    }
}

TEST_F(MixedRandomGraphs, EveryPortRangeIsInsideItsResourceAndSchedulesBuild) {
    const Plans plans = plan_all(AllocatorKind::Interval);
    for (std::size_t i = 0; i < plans.size(); ++i) {
        const Plan& plan = plans[i];
        for (const PlanPass& pass : plan.order) {
            for (const PlanPort& port : pass.ports) {
                if (!port.resource) continue;
                const PlanResource& r = plan.resources[*port.resource];
                if (port.type == ResourceType::Buffer) {
                    EXPECT_LE(port.bytes.offset + port.bytes.size, r.buffer_spec.size) << "seed " << i + 1;
                    EXPECT_GT(port.bytes.size, 0u) << "seed " << i + 1;
                } else {
                    EXPECT_LE(port.range.base_mip + port.range.mip_count, r.spec.mips) << "seed " << i + 1;
                    EXPECT_LE(port.range.base_layer + port.range.layer_count, r.spec.layers) << "seed " << i + 1;
                }
            }
        }
        auto schedule = build_execution_schedule(plan, {}, {});
        ASSERT_TRUE(schedule.ok()) << "seed " << i + 1 << ": " << schedule.error().to_string();
        EXPECT_EQ(schedule->buffer_needed, std::vector<bool>(plan.buffers.size(), true));
    }
}

TEST_F(MixedRandomGraphs, PlansAreDeterministic) {
    const Plans first = plan_all(AllocatorKind::Heap);
    for (std::size_t i = 0; i < first.size(); i += 8) {
        const FrameGraph graph = testing::random_graph(i + 1, mixed_options_for(i + 1));
        auto again = build_plan(graph, plan_options(AllocatorKind::Heap));
        ASSERT_TRUE(again.ok());
        EXPECT_EQ(*again, first[i]) << "seed " << i + 1;
        EXPECT_EQ(plan_hash(*again), plan_hash(first[i])) << "seed " << i + 1;
    }
}

}  // namespace
}  // namespace loom::fg

// Properties every plan must have, checked on thousands of seeded random DAGs: correctness of
// sharing (no two live resources in one texture or in overlapping heap bytes), optimality of
// the interval allocator, the lower bounds, and determinism.
#include <algorithm>

#include <gtest/gtest.h>

#include "loom/framegraph/framegraph.hpp"
#include "random_graph.hpp"

namespace loom::fg {
namespace {

constexpr uint32_t kGraphs = 2000;

testing::RandomGraphOptions options_for(uint64_t seed) {
    testing::RandomGraphOptions options;
    options.passes = 2 + static_cast<uint32_t>(seed % 39);  // 2..40 passes
    options.window = 2 + static_cast<uint32_t>(seed % 7);
    return options;
}

PlanOptions plan_options(const char* allocator, SpecSharing sharing = SpecSharing::Equal) {
    PlanOptions options;
    options.frame = {1920, 1080};
    options.allocator = allocator;
    options.sharing = sharing;
    return options;
}

struct Sample {
    uint64_t seed = 0;
    Plan paper;
    Plan interval;
    Plan heap;
    Plan paper_joinable;
    Plan interval_joinable;
};

// Plans every graph of the corpus once; the tests below check the plans.
class RandomGraphs : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        corpus_ = new std::vector<Sample>();
        corpus_->reserve(kGraphs);
        for (uint64_t seed = 1; seed <= kGraphs; ++seed) {
            const FrameGraph graph = testing::random_graph(seed, options_for(seed));
            Sample sample;
            sample.seed = seed;
            auto plan = [&](const PlanOptions& options) {
                auto result = build_plan(graph, options);
                if (!result) {
                    ADD_FAILURE() << "seed " << seed << " " << options.allocator << ": " << result.error().to_string();
                    return Plan{};
                }
                return std::move(*result);
            };
            sample.paper = plan(plan_options("paper"));
            sample.interval = plan(plan_options("interval"));
            sample.heap = plan(plan_options("heap"));
            sample.paper_joinable = plan(plan_options("paper", SpecSharing::Joinable));
            sample.interval_joinable = plan(plan_options("interval", SpecSharing::Joinable));
            corpus_->push_back(std::move(sample));
        }
    }
    static void TearDownTestSuite() {
        delete corpus_;
        corpus_ = nullptr;
    }
    static const std::vector<Sample>& corpus() { return *corpus_; }

private:
    static std::vector<Sample>* corpus_;
};

std::vector<Sample>* RandomGraphs::corpus_ = nullptr;

// No two resources alive at the same position share a texture.
void expect_no_shared_live_texture(const Plan& plan, uint64_t seed) {
    for (std::size_t a = 0; a < plan.resources.size(); ++a) {
        for (std::size_t b = a + 1; b < plan.resources.size(); ++b) {
            const PlanResource& ra = plan.resources[a];
            const PlanResource& rb = plan.resources[b];
            if (ra.texture == rb.texture) {
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

TEST_F(RandomGraphs, CorpusIsVaried) {
    uint32_t culled = 0;
    uint32_t in_place = 0;
    uint32_t max_resources = 0;
    for (const Sample& s : corpus()) {
        culled += s.interval.culled.empty() ? 0 : 1;
        for (const PlanPass& pass : s.interval.order) {
            for (const PlanPort& port : pass.ports) in_place += port.kind == PortKind::InOut ? 1 : 0;
        }
        max_resources = std::max<uint32_t>(max_resources, static_cast<uint32_t>(s.interval.resources.size()));
    }
    EXPECT_GT(culled, kGraphs / 10);
    EXPECT_GT(in_place, kGraphs / 2);
    EXPECT_GE(max_resources, 50u);
}

TEST_F(RandomGraphs, NoTwoLiveResourcesShareATexture) {
    for (const Sample& s : corpus()) {
        expect_no_shared_live_texture(s.paper, s.seed);
        expect_no_shared_live_texture(s.interval, s.seed);
        expect_no_shared_live_texture(s.paper_joinable, s.seed);
        expect_no_shared_live_texture(s.interval_joinable, s.seed);
        expect_textures_fit_resources(s.paper, s.seed);
        expect_textures_fit_resources(s.interval, s.seed);
        expect_textures_fit_resources(s.interval_joinable, s.seed);
    }
}

TEST_F(RandomGraphs, NoTwoLiveResourcesOverlapInHeapBytes) {
    for (const Sample& s : corpus()) {
        const Plan& plan = s.heap;
        ASSERT_EQ(plan.textures.size(), plan.resources.size());
        for (const PlanTexture& t : plan.textures) {
            ASSERT_TRUE(t.placement.has_value());
            ASSERT_LT(t.placement->heap, plan.heaps.size());
            EXPECT_EQ(t.placement->offset % t.alignment, 0u) << "seed " << s.seed;
            EXPECT_LE(t.placement->offset + t.bytes, plan.heaps[t.placement->heap]) << "seed " << s.seed;
        }
        for (std::size_t a = 0; a < plan.resources.size(); ++a) {
            for (std::size_t b = a + 1; b < plan.resources.size(); ++b) {
                const PlanResource& ra = plan.resources[a];
                const PlanResource& rb = plan.resources[b];
                if (!ra.lifetime.overlaps(rb.lifetime)) continue;
                const HeapRange& pa = *plan.textures[ra.texture].placement;
                const HeapRange& pb = *plan.textures[rb.texture].placement;
                if (pa.heap != pb.heap) continue;
                const bool disjoint = pa.offset + ra.bytes <= pb.offset || pb.offset + rb.bytes <= pa.offset;
                ASSERT_TRUE(disjoint) << "seed " << s.seed << ": " << ra.name << " and " << rb.name;
            }
        }
    }
}

TEST_F(RandomGraphs, IntervalMeetsTheLowerBoundAndNeverLosesToPaper) {
    uint32_t paper_worse = 0;
    for (const Sample& s : corpus()) {
        EXPECT_EQ(s.interval.summary.textures, s.interval.summary.lower_bound_textures) << "seed " << s.seed;
        EXPECT_EQ(s.interval_joinable.summary.textures, s.interval_joinable.summary.lower_bound_textures)
            << "seed " << s.seed;
        EXPECT_LE(s.interval.summary.textures, s.paper.summary.textures) << "seed " << s.seed;
        EXPECT_LE(s.interval_joinable.summary.textures, s.paper_joinable.summary.textures) << "seed " << s.seed;
        paper_worse += s.paper.summary.textures > s.interval.summary.textures ? 1 : 0;
        // The paper's reverse walk colours intervals by decreasing end and frees a colour at
        // the interval's start: the mirror image of the interval sweep, so it is optimal too.
        EXPECT_EQ(s.paper.summary.textures, s.paper.summary.lower_bound_textures) << "seed " << s.seed;
        EXPECT_EQ(s.paper_joinable.summary.textures, s.paper_joinable.summary.lower_bound_textures)
            << "seed " << s.seed;
    }
    EXPECT_EQ(paper_worse, 0u);
}

TEST_F(RandomGraphs, BytesRespectTheLowerBound) {
    for (const Sample& s : corpus()) {
        for (const Plan* plan : {&s.paper, &s.interval, &s.heap, &s.interval_joinable}) {
            const PlanSummary& summary = plan->summary;
            EXPECT_GE(summary.bytes, summary.lower_bound_bytes) << "seed " << s.seed << " " << plan->allocator;
            EXPECT_LE(summary.lower_bound_bytes, summary.naive_bytes) << "seed " << s.seed;
            EXPECT_EQ(summary.naive_textures, plan->resources.size());
            EXPECT_EQ(summary.textures, plan->textures.size());
        }
        EXPECT_LE(s.heap.summary.bytes, s.heap.summary.naive_bytes) << "seed " << s.seed;
    }
}

TEST_F(RandomGraphs, OrderIsTopologicalAndLifetimesCoverEveryUse) {
    for (const Sample& s : corpus()) {
        const Plan& plan = s.interval;
        for (const PlanEdge& e : plan.edges) ASSERT_LT(e.from_pass, e.to_pass) << "seed " << s.seed;
        for (uint32_t at = 0; at < plan.order.size(); ++at) {
            for (const PlanPort& port : plan.order[at].ports) {
                if (!port.resource) {
                    EXPECT_TRUE(port.optional) << "seed " << s.seed << " " << plan.order[at].name << "." << port.name;
                    continue;
                }
                const Lifetime& life = plan.resources[*port.resource].lifetime;
                EXPECT_LE(life.first, at) << "seed " << s.seed;
                EXPECT_GE(life.last, at) << "seed " << s.seed;
                if (port.kind == PortKind::Output) {
                    EXPECT_EQ(life.first, at) << "seed " << s.seed;
                }
            }
        }
        for (const PlanResource& r : plan.resources) {
            if (r.graph_output) {
                EXPECT_EQ(r.lifetime.last, plan.order.size() - 1) << "seed " << s.seed;
            }
        }
    }
}

TEST_F(RandomGraphs, PlansAreDeterministic) {
    for (const Sample& s : corpus()) {
        if (s.seed % 4 != 0) continue;  // a quarter of the corpus is enough to rebuild
        const FrameGraph graph = testing::random_graph(s.seed, options_for(s.seed));
        for (const Plan* expected : {&s.paper, &s.interval, &s.heap}) {
            auto again = build_plan(graph, plan_options(expected->allocator.c_str()));
            ASSERT_TRUE(again.ok());
            EXPECT_EQ(*again, *expected) << "seed " << s.seed << " " << expected->allocator;
            EXPECT_EQ(plan_hash(*again), plan_hash(*expected)) << "seed " << s.seed;
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

}  // namespace
}  // namespace loom::fg

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

PlanOptions plan_options(const std::string& allocator, SpecSharing sharing = SpecSharing::Equal) {
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
        plans_ = new std::map<std::pair<std::string, SpecSharing>, Plans>();
    }
    static void TearDownTestSuite() {
        delete graphs_;
        delete plans_;
        graphs_ = nullptr;
        plans_ = nullptr;
    }

    static uint64_t seed_of(std::size_t index) { return index + 1; }

    static const Plans& plans(const std::string& allocator, SpecSharing sharing = SpecSharing::Equal) {
        Plans& out = (*plans_)[{allocator, sharing}];
        if (!out.empty()) return out;
        out.reserve(graphs_->size());
        for (std::size_t i = 0; i < graphs_->size(); ++i) {
            auto plan = build_plan((*graphs_)[i], plan_options(allocator, sharing));
            if (!plan) {
                ADD_FAILURE() << "seed " << seed_of(i) << " " << allocator << ": " << plan.error().to_string();
                out.emplace_back();
            } else {
                out.push_back(std::move(*plan));
            }
        }
        return out;
    }

private:
    static std::vector<FrameGraph>* graphs_;
    static std::map<std::pair<std::string, SpecSharing>, Plans>* plans_;
};

std::vector<FrameGraph>* RandomGraphs::graphs_ = nullptr;
std::map<std::pair<std::string, SpecSharing>, Plans>* RandomGraphs::plans_ = nullptr;

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
    for (const Plan& plan : plans("interval")) {
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
    for (const auto& [allocator, sharing] : {std::pair{"paper", SpecSharing::Equal}, std::pair{"interval", SpecSharing::Equal},
                                             std::pair{"paper", SpecSharing::Joinable},
                                             std::pair{"interval", SpecSharing::Joinable}}) {
        const Plans& all = plans(allocator, sharing);
        for (std::size_t i = 0; i < all.size(); ++i) {
            expect_no_shared_live_texture(all[i], seed_of(i));
            expect_textures_fit_resources(all[i], seed_of(i));
        }
    }
}

TEST_F(RandomGraphs, NoTwoLiveResourcesOverlapInHeapBytes) {
    const Plans& all = plans("heap");
    for (std::size_t i = 0; i < all.size(); ++i) {
        const Plan& plan = all[i];
        const uint64_t seed = seed_of(i);
        ASSERT_EQ(plan.textures.size(), plan.resources.size());
        for (const PlanTexture& t : plan.textures) {
            ASSERT_TRUE(t.placement.has_value());
            ASSERT_LT(t.placement->heap, plan.heaps.size());
            EXPECT_EQ(t.placement->offset % t.alignment, 0u) << "seed " << seed;
            EXPECT_LE(t.placement->offset + t.bytes, plan.heaps[t.placement->heap]) << "seed " << seed;
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
                ASSERT_TRUE(disjoint) << "seed " << seed << ": " << ra.name << " and " << rb.name;
            }
        }
    }
}

TEST_F(RandomGraphs, IntervalMeetsTheLowerBoundAndNeverLosesToPaper) {
    for (SpecSharing sharing : {SpecSharing::Equal, SpecSharing::Joinable}) {
        const Plans& interval = plans("interval", sharing);
        const Plans& paper = plans("paper", sharing);
        for (std::size_t i = 0; i < interval.size(); ++i) {
            EXPECT_EQ(interval[i].summary.textures, interval[i].summary.lower_bound_textures) << "seed " << seed_of(i);
            EXPECT_LE(interval[i].summary.textures, paper[i].summary.textures) << "seed " << seed_of(i);
            // The paper's reverse walk colours intervals by decreasing end and frees a colour
            // at the interval's start: the mirror image of the interval sweep, so it is optimal
            // too.
            EXPECT_EQ(paper[i].summary.textures, paper[i].summary.lower_bound_textures) << "seed " << seed_of(i);
        }
    }
}

TEST_F(RandomGraphs, BytesRespectTheLowerBound) {
    for (const auto& [allocator, sharing] : {std::pair{"paper", SpecSharing::Equal}, std::pair{"interval", SpecSharing::Equal},
                                             std::pair{"heap", SpecSharing::Equal},
                                             std::pair{"interval", SpecSharing::Joinable}}) {
        const Plans& all = plans(allocator, sharing);
        for (std::size_t i = 0; i < all.size(); ++i) {
            const PlanSummary& summary = all[i].summary;
            EXPECT_GE(summary.bytes, summary.lower_bound_bytes) << "seed " << seed_of(i) << " " << allocator;
            EXPECT_LE(summary.lower_bound_bytes, summary.naive_bytes) << "seed " << seed_of(i);
            EXPECT_EQ(summary.naive_textures, all[i].resources.size());
            EXPECT_EQ(summary.textures, all[i].textures.size());
            if (std::string_view(allocator) == "heap") {
                EXPECT_LE(summary.bytes, summary.naive_bytes) << "seed " << seed_of(i);
            }
        }
    }
}

TEST_F(RandomGraphs, OrderIsTopologicalAndLifetimesCoverEveryUse) {
    const Plans& all = plans("interval");
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
        }
    }
}

TEST_F(RandomGraphs, PlansAreDeterministic) {
    for (const char* allocator : {"paper", "interval", "heap"}) {
        const Plans& all = plans(allocator);
        for (std::size_t i = 0; i < all.size(); i += 4) {  // a quarter of the corpus, rebuilt from its seed
            const FrameGraph graph = testing::random_graph(seed_of(i), options_for(seed_of(i)));
            auto again = build_plan(graph, plan_options(allocator));
            ASSERT_TRUE(again.ok());
            EXPECT_EQ(*again, all[i]) << "seed " << seed_of(i) << " " << allocator;
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

}  // namespace
}  // namespace loom::fg

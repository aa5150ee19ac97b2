// Re-planning a graph for another frame size, or after other texture specs (redeclared, or set by
// set_texture_spec) (FrameGraph::plan, plan_resize.hpp): in the declared order the plan is made
// from the previous one, and must equal what build_plan gives (every field, Plan::operator==), or
// fail with build_plan's error.
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "loom/framegraph/framegraph.hpp"
#include "random_graph.hpp"

namespace loom::fg {
namespace {

using rhi::Format;

PlanOptions declared_at(Extent2D frame, AllocatorKind allocator = AllocatorKind::Interval,
                        SpecSharing sharing = SpecSharing::Equal) {
    PlanOptions options;
    options.frame = frame;
    options.allocator = allocator;
    options.sharing = sharing;
    options.order = PassOrder::Declared;
    return options;
}

// Plans `graph` through FrameGraph::plan and checks the result against build_plan: the same plan,
// or the same error. Returns the plan (null on an error).
std::shared_ptr<const Plan> plan_as_build_plan_does(FrameGraph& graph, const PlanOptions& options) {
    auto planned = graph.plan(options);
    auto fresh = build_plan(graph, options);
    EXPECT_EQ(planned.ok(), fresh.ok());
    if (!fresh) {
        if (!planned) {
            EXPECT_EQ(planned.error().to_string(), fresh.error().to_string());
        }
        return nullptr;
    }
    if (!planned) {
        ADD_FAILURE() << planned.error().to_string();
        return nullptr;
    }
    EXPECT_TRUE(**planned == *fresh) << "at " << options.frame.width << "x" << options.frame.height;
    return *planned;
}

using testing::Corpus;

// Frame sizes a window goes through: smaller, larger, odd, tiny (where the mip chains of the
// corpus no longer fit: build_plan's error), and back.
const std::vector<Extent2D> kFrames{{1280, 720}, {3840, 2160}, {1001, 333}, {8, 8}, {1920, 1080}, {1280, 720}};

void check_corpus(Corpus corpus, AllocatorKind allocator, SpecSharing sharing) {
    uint64_t resized = 0;
    uint64_t expected_resized = 0;
    for (uint64_t seed = 1; seed <= 40; ++seed) {
        FrameGraph graph = testing::random_graph(seed, testing::corpus_options(seed, corpus));
        std::shared_ptr<const Plan> previous = plan_as_build_plan_does(graph, declared_at({1920, 1080}, allocator, sharing));
        ASSERT_NE(previous, nullptr) << "seed " << seed;
        for (std::size_t f = 0; f < kFrames.size(); ++f) {
            // Every other step holds the previous plan, as an executor does: it is copied, and
            // must stay as it was; else it is changed in place.
            std::shared_ptr<const Plan> held;
            Plan held_copy;
            if (f % 2 == 0 && previous) {
                held = previous;
                held_copy = *previous;
            }
            const bool could_resize = previous != nullptr;
            previous.reset();
            const uint64_t built = graph.plans_built();
            previous = plan_as_build_plan_does(graph, declared_at(kFrames[f], allocator, sharing));
            if (held) {
                EXPECT_TRUE(*held == held_copy) << "seed " << seed << ": a held plan changed";
            }
            // Every size build_plan plans is resized from a previous plan; after a size that
            // fails there is no previous plan, and the next size is planned anew.
            if (previous && could_resize) {
                ++expected_resized;
                EXPECT_EQ(graph.plans_built(), built) << "seed " << seed << ": planned anew";
            }
        }
        resized += graph.plans_resized();
    }
    EXPECT_EQ(resized, expected_resized);
    // Most graphs plan at every size (the tiny one fails where a mip chain no longer fits).
    EXPECT_GT(resized, 150u);
}

TEST(PlanResize, RandomTextureGraphsResizeAsTheyPlan) {
    for (AllocatorKind allocator : {AllocatorKind::Paper, AllocatorKind::Interval, AllocatorKind::Heap}) {
        for (SpecSharing sharing : {SpecSharing::Equal, SpecSharing::Joinable}) {
            SCOPED_TRACE(std::string(allocator_name(allocator)) + " " + std::string(spec_sharing_name(sharing)));
            check_corpus(Corpus::Textures, allocator, sharing);
        }
    }
}

TEST(PlanResize, RandomGraphsWithBuffersAndSubresourcesResizeAsTheyPlan) {
    for (AllocatorKind allocator : {AllocatorKind::Paper, AllocatorKind::Interval, AllocatorKind::Heap}) {
        SCOPED_TRACE(allocator_name(allocator));
        check_corpus(Corpus::Mixed, allocator, SpecSharing::Equal);
    }
}

TEST(PlanResize, RandomGraphsWithAsyncComputeResizeAsTheyPlan) {
    for (AllocatorKind allocator : {AllocatorKind::Interval, AllocatorKind::Heap}) {
        SCOPED_TRACE(allocator_name(allocator));
        check_corpus(Corpus::Async, allocator, SpecSharing::Equal);
    }
}

// How the graph is changed: declared again (redeclare) with the outputs of one pass in other
// specs, or given those specs in place (set_texture_spec on every texture port: most keep theirs).
enum class SpecChange { Redeclared, SetInPlace };

// Each corpus graph planned, then changed three times, the outputs of one pass in other specs
// each time (and the inputs that repeat them), the third time with `third_frame`: plan() makes
// the plan from the previous one when the passes that changed run, else plans anew; either way
// the plan (or the error) is build_plan's.
void check_respecified_corpus(Corpus corpus, AllocatorKind allocator, SpecSharing sharing, Extent2D third_frame,
                              SpecChange how) {
    uint64_t respecified = 0;
    uint64_t changes = 0;
    for (uint64_t seed = 1; seed <= 40; ++seed) {
        testing::RandomGraphOptions options = testing::corpus_options(seed, corpus);
        FrameGraph graph;
        testing::declare_random_graph(graph, seed, options);
        ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080}, allocator, sharing)), nullptr);
        for (uint32_t changed : {options.passes - 1, options.passes / 2, 0u}) {
            options.respecified_pass = changed;
            if (how == SpecChange::Redeclared) {
                graph.redeclare();
                testing::declare_random_graph(graph, seed, options);
            } else {
                const FrameGraph other = testing::random_graph(seed, options);
                const uint64_t revision = graph.revision();
                for (uint32_t pass = 0; pass < graph.pass_count(); ++pass) {
                    for (uint32_t port = 0; port < graph.pass(PassId{pass}).ports().size(); ++port) {
                        const PortAddress address{pass, port};
                        if (graph.port_at(address).type != ResourceType::Texture) continue;
                        ASSERT_TRUE(graph.set_texture_spec(address, other.port_at(address).spec).ok());
                    }
                }
                if (graph.revision() == revision) continue;  // a pass without palette outputs
            }
            const uint64_t built = graph.plans_built();
            const uint64_t resized = graph.plans_resized();
            const Extent2D frame = changed == 0 ? third_frame : Extent2D{1920, 1080};
            if (!plan_as_build_plan_does(graph, declared_at(frame, allocator, sharing))) break;
            ++changes;
            // Made from the previous plan or planned anew; a graph redeclared with the specs it
            // had (the changed pass draws no palette output) gets the previous plan itself.
            if (graph.plans_resized() == resized + 1) {
                ++respecified;
                EXPECT_EQ(graph.plans_built(), built);
            } else if (how == SpecChange::Redeclared) {
                EXPECT_LE(graph.plans_built(), built + 1);
            } else {
                EXPECT_EQ(graph.plans_built(), built + 1);
            }
        }
    }
    // Most changes are to passes that run.
    EXPECT_GT(respecified, changes / 2) << respecified << " of " << changes;
}

TEST(PlanResize, RandomGraphsRedeclaredWithOtherTextureSpecsPlanAsTheyPlan) {
    for (AllocatorKind allocator : {AllocatorKind::Paper, AllocatorKind::Interval, AllocatorKind::Heap}) {
        for (SpecSharing sharing : {SpecSharing::Equal, SpecSharing::Joinable}) {
            SCOPED_TRACE(std::string(allocator_name(allocator)) + " " + std::string(spec_sharing_name(sharing)));
            check_respecified_corpus(Corpus::Textures, allocator, sharing, {1920, 1080}, SpecChange::Redeclared);
            // With the frame size changing at once.
            check_respecified_corpus(Corpus::Textures, allocator, sharing, {1280, 720}, SpecChange::Redeclared);
        }
    }
    for (AllocatorKind allocator : {AllocatorKind::Interval, AllocatorKind::Heap}) {
        SCOPED_TRACE(allocator_name(allocator));
        check_respecified_corpus(Corpus::Mixed, allocator, SpecSharing::Equal, {1280, 720}, SpecChange::Redeclared);
        check_respecified_corpus(Corpus::Async, allocator, SpecSharing::Equal, {1280, 720}, SpecChange::Redeclared);
    }
}

TEST(PlanResize, RandomGraphsWithTextureSpecsSetInPlacePlanAsTheyPlan) {
    for (AllocatorKind allocator : {AllocatorKind::Paper, AllocatorKind::Interval, AllocatorKind::Heap}) {
        for (SpecSharing sharing : {SpecSharing::Equal, SpecSharing::Joinable}) {
            SCOPED_TRACE(std::string(allocator_name(allocator)) + " " + std::string(spec_sharing_name(sharing)));
            check_respecified_corpus(Corpus::Textures, allocator, sharing, {1280, 720}, SpecChange::SetInPlace);
        }
    }
    for (AllocatorKind allocator : {AllocatorKind::Interval, AllocatorKind::Heap}) {
        SCOPED_TRACE(allocator_name(allocator));
        check_respecified_corpus(Corpus::Mixed, allocator, SpecSharing::Equal, {1280, 720}, SpecChange::SetInPlace);
        check_respecified_corpus(Corpus::Async, allocator, SpecSharing::Equal, {1280, 720}, SpecChange::SetInPlace);
    }
}

// scene (full size, half size, absolute shadow map) -> post -> present.
FrameGraph small_graph() {
    FrameGraph graph;
    const PassId scene = *graph.add_pass(Pass("scene")
                                             .output("color", TextureSpec::of(Format::RGBA16Float))
                                             .output("half", TextureSpec::of(Format::RGBA16Float).with_scale(0.5f))
                                             .output("shadow", TextureSpec::of(Format::Depth32F).with_size(2048, 2048)));
    const PassId post = *graph.add_pass(Pass("post")
                                            .read(port_of(scene, 0))
                                            .read(port_of(scene, 1))
                                            .read(port_of(scene, 2))
                                            .output("out", TextureSpec::of(Format::RGBA8Unorm)));
    EXPECT_TRUE(graph.mark_output(port_of(post, 3)).ok());
    return graph;
}

TEST(PlanResize, APlanNobodyHoldsIsChangedInPlaceAndAHeldOneIsCopied) {
    FrameGraph graph = small_graph();
    const Plan* first = plan_as_build_plan_does(graph, declared_at({1920, 1080})).get();
    ASSERT_NE(first, nullptr);
    // Nothing holds the plan any more: the same object becomes the 1280x720 plan.
    std::shared_ptr<const Plan> resized = plan_as_build_plan_does(graph, declared_at({1280, 720}));
    ASSERT_NE(resized, nullptr);
    EXPECT_EQ(resized.get(), first);
    EXPECT_EQ(resized->frame, (Extent2D{1280, 720}));
    EXPECT_EQ(resized->resources[0].spec.extent, (Extent2D{1280, 720}));
    EXPECT_EQ(resized->resources[1].spec.extent, (Extent2D{640, 360}));
    EXPECT_EQ(resized->resources[2].spec.extent, (Extent2D{2048, 2048}));
    // Held: a new plan, the held one unchanged.
    std::shared_ptr<const Plan> larger = plan_as_build_plan_does(graph, declared_at({2560, 1440}));
    ASSERT_NE(larger, nullptr);
    EXPECT_NE(larger.get(), resized.get());
    EXPECT_EQ(resized->frame, (Extent2D{1280, 720}));
    EXPECT_EQ(resized->resources[1].spec.extent, (Extent2D{640, 360}));
    EXPECT_EQ(larger->resources[1].spec.extent, (Extent2D{1280, 720}));
    EXPECT_EQ(graph.plans_built(), 1u);
    EXPECT_EQ(graph.plans_resized(), 2u);
    // The same size again is the same plan, as ever.
    auto again = graph.plan(declared_at({2560, 1440}));
    ASSERT_TRUE(again.ok());
    EXPECT_EQ(again->get(), larger.get());
    EXPECT_EQ(graph.plans_resized(), 2u);
}

TEST(PlanResize, OtherOptionsAndTheMemoryOrderArePlannedAnew) {
    FrameGraph graph = small_graph();
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    // Another allocator and another size: planned anew.
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1280, 720}, AllocatorKind::Heap)), nullptr);
    EXPECT_EQ(graph.plans_built(), 2u);
    EXPECT_EQ(graph.plans_resized(), 0u);
    // The memory order weighs bytes, which a frame size changes: planned anew.
    PlanOptions memory = declared_at({1920, 1080});
    memory.order = PassOrder::Memory;
    ASSERT_NE(plan_as_build_plan_does(graph, memory), nullptr);
    memory.frame = {1280, 720};
    ASSERT_NE(plan_as_build_plan_does(graph, memory), nullptr);
    EXPECT_EQ(graph.plans_built(), 4u);
    EXPECT_EQ(graph.plans_resized(), 0u);
    // A changed graph: planned anew.
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    ASSERT_TRUE(graph.add_pass(Pass("debug").read(PortAddress{0, 0}).set_side_effect()).ok());
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1280, 720})), nullptr);
    EXPECT_EQ(graph.plans_built(), 6u);
    EXPECT_EQ(graph.plans_resized(), 0u);
}

TEST(PlanResize, ARedeclaredGraphIsResized) {
    FrameGraph graph;
    auto declare = [&] {
        const PassId scene = *graph.add_pass(Pass("scene").output("color", TextureSpec::of(Format::RGBA16Float)));
        const PassId post = *graph.add_pass(Pass("post").read(port_of(scene, 0)).output("out"));
        EXPECT_TRUE(graph.mark_output(port_of(post, 1)).ok());
    };
    declare();
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    graph.redeclare();
    declare();
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1280, 720})), nullptr);
    EXPECT_EQ(graph.plans_built(), 1u);
    EXPECT_EQ(graph.plans_resized(), 1u);
}

TEST(PlanResize, AJoinOnlyAFrameSizeComparesIsPlannedAnew) {
    // An absolute 960x540 and half the frame join at 1920x1080 only.
    FrameGraph graph;
    const PassId scene = *graph.add_pass(Pass("scene").output("color", TextureSpec::of(Format::RGBA8Unorm).with_size(960, 540)));
    const PassId post = *graph.add_pass(Pass("post").read(port_of(scene, 0), TextureSpec::any().with_scale(0.5f)).output("out"));
    ASSERT_TRUE(graph.mark_output(port_of(post, 1)).ok());
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    // At 1280x720 the join fails, as build_plan says.
    auto resized = graph.plan(declared_at({1280, 720}));
    ASSERT_FALSE(resized.ok());
    EXPECT_EQ(resized.error().code, ErrorCode::Join);
    EXPECT_EQ(plan_as_build_plan_does(graph, declared_at({1280, 720})), nullptr);
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    EXPECT_EQ(graph.plans_resized(), 0u);

    // A culled pass's join counts too (its groups are joined as well).
    FrameGraph culled;
    const PassId lit = *culled.add_pass(Pass("lit").output("color", TextureSpec::of(Format::RGBA8Unorm).with_size(960, 540)));
    ASSERT_TRUE(culled.add_pass(Pass("unused").read(port_of(lit, 0), TextureSpec::any().with_scale(0.5f)).output("out")).ok());
    ASSERT_TRUE(culled.add_pass(Pass("present").read(port_of(lit, 0)).set_side_effect()).ok());
    ASSERT_NE(plan_as_build_plan_does(culled, declared_at({1920, 1080})), nullptr);
    EXPECT_EQ(plan_as_build_plan_does(culled, declared_at({1280, 720})), nullptr);
    EXPECT_EQ(culled.plans_resized(), 0u);
}

TEST(PlanResize, ASizeThatNoLongerResolvesGivesBuildPlansError) {
    // Eleven mips fit 1920x1080 and 1024x1024, not 512x512.
    FrameGraph graph;
    const PassId pyramid = *graph.add_pass(Pass("pyramid").output("chain", TextureSpec::of(Format::RGBA16Float).with_mips(11)));
    ASSERT_TRUE(graph.add_pass(Pass("use").read(port_of(pyramid, 0), {}, mip(10)).set_side_effect()).ok());
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1024, 1024})), nullptr);
    EXPECT_EQ(graph.plans_resized(), 1u);
    auto small = graph.plan(declared_at({512, 512}));
    ASSERT_FALSE(small.ok());
    EXPECT_NE(small.error().message.find("mips 11"), std::string::npos) << small.error().to_string();
    EXPECT_EQ(plan_as_build_plan_does(graph, declared_at({512, 512})), nullptr);
    // After the error there is no plan to resize: the next size is planned anew.
    const uint64_t built = graph.plans_built();
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({2048, 2048})), nullptr);
    EXPECT_EQ(graph.plans_built(), built + 1);
}

TEST(PlanResize, TexturesThatShareAtOneSizeAndNotAtAnotherAreAllocatedAgain) {
    // Two textures one after the other, an absolute 960x540 and half the frame: one shape (and
    // one texture) at 1920x1080, two at 1280x720. The interval and paper allocators read no
    // bytes, so a resize keeps their allocation only while the classes stay as they are.
    FrameGraph graph;
    const PassId first = *graph.add_pass(Pass("first").output("a", TextureSpec::of(Format::RGBA8Unorm).with_size(960, 540)));
    const PassId use_a = *graph.add_pass(Pass("use_a").read(port_of(first, 0)).output("x"));
    const PassId second = *graph.add_pass(Pass("second").read(port_of(use_a, 1)).output("b", TextureSpec::of(Format::RGBA8Unorm).with_scale(0.5f)));
    ASSERT_TRUE(graph.add_pass(Pass("use_b").read(port_of(second, 1)).set_side_effect()).ok());
    for (AllocatorKind allocator : {AllocatorKind::Paper, AllocatorKind::Interval, AllocatorKind::Heap}) {
        SCOPED_TRACE(allocator_name(allocator));
        std::shared_ptr<const Plan> shared = plan_as_build_plan_does(graph, declared_at({1920, 1080}, allocator));
        ASSERT_NE(shared, nullptr);
        EXPECT_EQ(shared->spec_classes.size(), 2u);  // the 960x540s, the full-size "x"
        const uint32_t textures_at_1080p = shared->summary.textures;
        shared.reset();
        std::shared_ptr<const Plan> apart = plan_as_build_plan_does(graph, declared_at({1280, 720}, allocator));
        ASSERT_NE(apart, nullptr);
        EXPECT_EQ(apart->spec_classes.size(), 3u);
        if (allocator != AllocatorKind::Heap) {
            EXPECT_EQ(apart->summary.textures, textures_at_1080p + 1);
        }
        apart.reset();
        ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080}, allocator)), nullptr);
        // And a resize that keeps the classes, for the allocators whose answer is kept.
        ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1081}, allocator)), nullptr);
    }
    EXPECT_EQ(graph.plans_built(), 3u);
    EXPECT_EQ(graph.plans_resized(), 9u);
}

// scene -> post -> (culled) debug, with the scene's colour in `format` and `post` asking for
// `read` of it.
void declare_scene(FrameGraph& graph, TextureSpec color, TextureSpec read = {}, TextureSpec debug = {}) {
    const PassId scene = *graph.add_pass(Pass("scene").output("color", color).output("depth", TextureSpec::of(Format::Depth32F)));
    const PassId post = *graph.add_pass(Pass("post").read(port_of(scene, 0), read).read(port_of(scene, 1)).output("out"));
    EXPECT_TRUE(graph.add_pass(Pass("debug").read(port_of(scene, 0), debug).output("view")).ok());
    EXPECT_TRUE(graph.mark_output(port_of(post, 2)).ok());
}

TEST(PlanResize, ARedeclaredGraphWithOtherTextureSpecsIsPlannedFromThePreviousPlan) {
    FrameGraph graph;
    declare_scene(graph, TextureSpec::of(Format::RGBA16Float));
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    // Another format, then a depth format (the write becomes a depth attachment), then half size.
    graph.redeclare();
    declare_scene(graph, TextureSpec::of(Format::R11G11B10Float));
    std::shared_ptr<const Plan> other = plan_as_build_plan_does(graph, declared_at({1920, 1080}));
    ASSERT_NE(other, nullptr);
    EXPECT_EQ(other->resources[0].spec.format, Format::R11G11B10Float);
    graph.redeclare();
    declare_scene(graph, TextureSpec::of(Format::Depth24Stencil8));
    std::shared_ptr<const Plan> depth = plan_as_build_plan_does(graph, declared_at({1920, 1080}));
    ASSERT_NE(depth, nullptr);
    EXPECT_EQ(depth->order[0].ports[0].usage, rhi::TextureUsage::DepthStencilAttachment);
    other.reset();
    depth.reset();
    graph.redeclare();
    declare_scene(graph, TextureSpec::of(Format::RGBA16Float).with_scale(0.5f), TextureSpec::any().with_scale(0.5f));
    std::shared_ptr<const Plan> half = plan_as_build_plan_does(graph, declared_at({1920, 1080}));
    ASSERT_NE(half, nullptr);
    EXPECT_EQ(half->resources[0].spec.extent, (Extent2D{960, 540}));
    half.reset();
    // ... and its size follows a resize.
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1280, 720})), nullptr);
    EXPECT_EQ(graph.plans_built(), 1u);
    EXPECT_EQ(graph.plans_resized(), 4u);
    // The same specs again: the same plan.
    graph.redeclare();
    declare_scene(graph, TextureSpec::of(Format::RGBA16Float).with_scale(0.5f), TextureSpec::any().with_scale(0.5f));
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1280, 720})), nullptr);
    EXPECT_EQ(graph.plans_resized(), 4u);
}

TEST(PlanResize, ATextureSpecSetInPlaceIsPlannedFromThePreviousPlan) {
    FrameGraph graph;
    declare_scene(graph, TextureSpec::of(Format::RGBA16Float));
    std::shared_ptr<const Plan> first = plan_as_build_plan_does(graph, declared_at({1920, 1080}));
    ASSERT_NE(first, nullptr);
    const Plan before = *first;
    // Another format for the scene's colour, the post pass's read of it at half size: the held
    // plan is copied and stays as it was.
    ASSERT_TRUE(graph.set_texture_spec({0, 0}, TextureSpec::of(Format::R11G11B10Float).with_scale(0.5f)).ok());
    ASSERT_TRUE(graph.set_texture_spec({1, 0}, TextureSpec::any().with_scale(0.5f)).ok());
    std::shared_ptr<const Plan> other = plan_as_build_plan_does(graph, declared_at({1920, 1080}));
    ASSERT_NE(other, nullptr);
    EXPECT_EQ(other->resources[0].spec.format, Format::R11G11B10Float);
    EXPECT_EQ(other->resources[0].spec.extent, (Extent2D{960, 540}));
    EXPECT_TRUE(*first == before);
    EXPECT_EQ(graph.plans_built(), 1u);
    EXPECT_EQ(graph.plans_resized(), 1u);
    // Unchanged since: the same plan, the same object.
    {
        auto again = graph.plan(declared_at({1920, 1080}));
        ASSERT_TRUE(again.ok());
        EXPECT_EQ(*again, other);
    }
    // Back to the first specs (a spec equal to the port's changes nothing), and a resize.
    first.reset();
    other.reset();
    const uint64_t revision = graph.revision();
    ASSERT_TRUE(graph.set_texture_spec({1, 1}, {}).ok());
    EXPECT_EQ(graph.revision(), revision);
    ASSERT_TRUE(graph.set_texture_spec({0, 0}, TextureSpec::of(Format::RGBA16Float)).ok());
    ASSERT_TRUE(graph.set_texture_spec({1, 0}, {}).ok());
    std::shared_ptr<const Plan> back = plan_as_build_plan_does(graph, declared_at({1920, 1080}));
    ASSERT_NE(back, nullptr);
    EXPECT_TRUE(*back == before);
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1280, 720})), nullptr);
    EXPECT_EQ(graph.plans_built(), 1u);
    EXPECT_EQ(graph.plans_resized(), 3u);
}

TEST(PlanResize, ATextureSpecSetWithOtherChangesOrOnAPassThatDoesNotRunIsPlannedAnew) {
    FrameGraph graph;
    declare_scene(graph, TextureSpec::of(Format::RGBA16Float));
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    // The culled debug pass.
    ASSERT_TRUE(graph.set_texture_spec({2, 0}, TextureSpec::any().with_samples(1)).ok());
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    EXPECT_EQ(graph.plans_built(), 2u);
    // A spec set, then a graph output marked: planned anew...
    ASSERT_TRUE(graph.set_texture_spec({0, 0}, TextureSpec::of(Format::RGBA8Unorm)).ok());
    ASSERT_TRUE(graph.mark_output({2, 1}).ok());
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    EXPECT_EQ(graph.plans_built(), 3u);
    // ... and the other way round.
    ASSERT_TRUE(graph.require_order("debug", "post").ok());
    ASSERT_TRUE(graph.set_texture_spec({0, 0}, TextureSpec::of(Format::RGBA16Float)).ok());
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    EXPECT_EQ(graph.plans_built(), 4u);
    // Specs that no longer join: the join's error, as build_plan gives it.
    ASSERT_TRUE(graph.set_texture_spec({1, 0}, TextureSpec::of(Format::RGBA8Unorm)).ok());
    auto conflict = graph.plan(declared_at({1920, 1080}));
    ASSERT_FALSE(conflict.ok());
    EXPECT_EQ(conflict.error().code, ErrorCode::Join);
    EXPECT_EQ(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    EXPECT_EQ(graph.plans_resized(), 0u);
}

TEST(PlanResize, ATextureSpecSetWhileRedeclaringIsPlanned) {
    // A pass declared again as it was, so found the same as before, then given another spec.
    FrameGraph graph;
    declare_scene(graph, TextureSpec::of(Format::RGBA16Float));
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    graph.redeclare();
    declare_scene(graph, TextureSpec::of(Format::RGBA16Float));
    ASSERT_TRUE(graph.set_texture_spec({0, 0}, TextureSpec::of(Format::RGBA8Unorm)).ok());
    std::shared_ptr<const Plan> plan = plan_as_build_plan_does(graph, declared_at({1920, 1080}));
    ASSERT_NE(plan, nullptr);
    EXPECT_EQ(plan->resources[0].spec.format, Format::RGBA8Unorm);
    EXPECT_EQ(graph.plans_built(), 1u);
    EXPECT_EQ(graph.plans_resized(), 1u);
}

TEST(PlanResize, SetTextureSpecRefusesBufferPortsAndAddressesOutsideTheGraph) {
    FrameGraph graph;
    declare_scene(graph, TextureSpec::of(Format::RGBA16Float));
    ASSERT_TRUE(graph.add_pass(Pass("cull").set_kind(PassKind::Compute).buffer_output("lights", BufferSpec::of_size(64))).ok());
    const uint64_t revision = graph.revision();
    Status buffer = graph.set_texture_spec({3, 0}, TextureSpec::of(Format::RGBA8Unorm));
    ASSERT_FALSE(buffer.ok());
    EXPECT_EQ(buffer.error().code, ErrorCode::Graph);
    EXPECT_EQ(buffer.error().message, "set_texture_spec cull.lights: a buffer port; its spec is a BufferSpec");
    Status pass = graph.set_texture_spec({4, 0}, {});
    ASSERT_FALSE(pass.ok());
    EXPECT_EQ(pass.error().message, "set_texture_spec: no pass #4, which is not in the graph (it has 4 passes)");
    Status port = graph.set_texture_spec({0, 2}, {});
    ASSERT_FALSE(port.ok());
    EXPECT_EQ(port.error().message, "set_texture_spec: no port #2 of pass 'scene', which has 2 ports (color, depth)");
    EXPECT_EQ(graph.revision(), revision);
}

TEST(PlanResize, AnotherUsageKeepsTheClassesAndWidensTheirUsage) {
    // The post pass reads the colour as a storage image instead of sampling it: the same shapes,
    // the same classes and allocation, other usages for the resource, its class and its texture.
    FrameGraph graph;
    declare_scene(graph, TextureSpec::of(Format::RGBA16Float));
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    graph.redeclare();
    TextureSpec storage;
    storage.usage = rhi::TextureUsage::Storage;
    declare_scene(graph, TextureSpec::of(Format::RGBA16Float), storage);
    std::shared_ptr<const Plan> plan = plan_as_build_plan_does(graph, declared_at({1920, 1080}));
    ASSERT_NE(plan, nullptr);
    EXPECT_TRUE(rhi::has_all(plan->spec_classes[plan->resources[0].spec_class].spec.usage, rhi::TextureUsage::Storage));
    EXPECT_EQ(graph.plans_resized(), 1u);
}

TEST(PlanResize, OtherTextureSpecsThatDoNotJoinGiveBuildPlansError) {
    FrameGraph graph;
    declare_scene(graph, TextureSpec::of(Format::RGBA16Float), TextureSpec::of(Format::RGBA16Float));
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    graph.redeclare();
    declare_scene(graph, TextureSpec::of(Format::RGBA8Unorm), TextureSpec::of(Format::RGBA16Float));
    auto conflict = graph.plan(declared_at({1920, 1080}));
    ASSERT_FALSE(conflict.ok());
    EXPECT_EQ(conflict.error().code, ErrorCode::Join);
    EXPECT_EQ(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    EXPECT_EQ(graph.plans_resized(), 0u);
}

TEST(PlanResize, OtherSpecsOnPassesThatDoNotRunOrOtherPortsArePlannedAnew) {
    FrameGraph graph;
    declare_scene(graph, TextureSpec::of(Format::RGBA16Float));
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    // The culled debug pass asks for another spec (its group is joined all the same, and may no
    // longer join): planned anew.
    graph.redeclare();
    declare_scene(graph, TextureSpec::of(Format::RGBA16Float), {}, TextureSpec::any().with_samples(1));
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    EXPECT_EQ(graph.plans_resized(), 0u);
    // A port that differs in more than its spec (a range): planned anew.
    graph.redeclare();
    {
        const PassId scene = *graph.add_pass(Pass("scene").output("color", TextureSpec::of(Format::RGBA16Float)).output("depth", TextureSpec::of(Format::Depth32F)));
        const PassId post = *graph.add_pass(Pass("post").read(port_of(scene, 0), {}, mip(0)).read(port_of(scene, 1)).output("out"));
        ASSERT_TRUE(graph.add_pass(Pass("debug").read(port_of(scene, 0), TextureSpec::any().with_samples(1)).output("view")).ok());
        ASSERT_TRUE(graph.mark_output(port_of(post, 2)).ok());
    }
    ASSERT_NE(plan_as_build_plan_does(graph, declared_at({1920, 1080})), nullptr);
    EXPECT_EQ(graph.plans_built(), 3u);
    EXPECT_EQ(graph.plans_resized(), 0u);
}

TEST(PlanResize, BufferPortRangesFollowTheBufferSize) {
    // A per-pixel buffer; one reader uses all of it from an offset, which a small frame leaves
    // past the end.
    FrameGraph graph;
    const PassId cull = *graph.add_pass(
        Pass("cull").set_kind(PassKind::Compute).buffer_output("lights", BufferSpec::sized(BufferSize::per_pixel(4))));
    ASSERT_TRUE(graph.add_pass(Pass("shade")
                                   .set_kind(PassKind::Compute)
                                   .buffer_input("all")
                                   .buffer_input("tail", {}, BufferRange{1'000'000, 0})
                                   .set_side_effect())
                    .ok());
    ASSERT_TRUE(graph.connect(port_of(cull, 0), PortAddress{1, 0}).ok());
    ASSERT_TRUE(graph.connect(port_of(cull, 0), PortAddress{1, 1}).ok());
    std::shared_ptr<const Plan> full = plan_as_build_plan_does(graph, declared_at({1920, 1080}));
    ASSERT_NE(full, nullptr);
    EXPECT_EQ(full->order[1].ports[1].bytes, (BufferRange{1'000'000, 1920u * 1080u * 4u - 1'000'000}));
    std::shared_ptr<const Plan> smaller = plan_as_build_plan_does(graph, declared_at({1280, 720}));
    ASSERT_NE(smaller, nullptr);
    EXPECT_EQ(smaller->order[1].ports[0].bytes, (BufferRange{0, 1280u * 720u * 4u}));
    EXPECT_EQ(smaller->order[1].ports[1].bytes, (BufferRange{1'000'000, 1280u * 720u * 4u - 1'000'000}));
    EXPECT_EQ(graph.plans_resized(), 1u);
    // 320x240 holds 307200 bytes: the reader's offset is past the end.
    EXPECT_EQ(plan_as_build_plan_does(graph, declared_at({320, 240})), nullptr);
}

}  // namespace
}  // namespace loom::fg

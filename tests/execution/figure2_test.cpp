// The paper's Figure 2 graph shape (shadow map, G-buffer, deferred with three port sets, blur,
// composite) with simple test passes, run by the executor with every allocator: the final
// picture is exact, and the textures (and on Vulkan with `heap`, the heaps and their bytes) the
// backend really created are the plan's.
#include <iostream>

#include "execution_helpers.hpp"
#include "loom_test/render_fixture.hpp"

namespace loom::test {
namespace {

using rhi::Format;

const fg::TextureSpec kColor = fg::TextureSpec::of(Format::RGBA16Float).with_scale(1.0f);
const fg::TextureSpec kShadow = fg::TextureSpec::of(Format::Depth32F).with_size(64, 64);

// G-buffer: three constant maps.
const char* const kGeometryFrag = R"(#version 450
layout(location = 0) out vec4 position;
layout(location = 1) out vec4 normal;
layout(location = 2) out vec4 albedo;
void main() {
    position = vec4(0.125, 0.0, 0.0, 0.0);
    normal = vec4(0.0, 0.25, 0.0, 0.0);
    albedo = vec4(0.5, 0.5, 0.5, 1.0);
}
)";

// Deferred: color = position + normal + albedo * shadow, high_pass = albedo * (1 - shadow).
const char* const kDeferredFrag = R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D position;
layout(set = 0, binding = 1) uniform sampler2D normal;
layout(set = 0, binding = 2) uniform sampler2D albedo;
layout(set = 0, binding = 3) uniform sampler2D shadow_map;
layout(location = 0) out vec4 color;
layout(location = 1) out vec4 high_pass;
void main() {
    ivec2 at = ivec2(gl_FragCoord.xy);
    float s = texelFetch(shadow_map, min(at, textureSize(shadow_map, 0) - 1), 0).r;  // clamp: the map is 64x64
    vec4 a = texelFetch(albedo, at, 0);
    color = texelFetch(position, at, 0) + texelFetch(normal, at, 0) + a * s;
    high_pass = a * (1.0 - s);
}
)";

struct Figure2Programs {
    rhi::PipelineHandle shadow, geometry, deferred, blur, composite;
    rhi::SamplerHandle sampler;
};

// Declares the graph of figure 2 into `graph`.
void declare_figure2(fg::FrameGraph& graph, const Figure2Programs& p) {
    // The shadow map: depth 0.25 in columns 0..7, 0.75 beyond.
    EXPECT_TRUE(graph.add_pass(fg::Pass("shadow").output("shadow_map", kShadow).on_execute([p](fg::PassContext& ctx) {
        ctx.begin_depth_pass("shadow_map");
        ctx.commands().set_pipeline(p.shadow);
        ctx.commands().push_constants_of(FillConstants{{0.25f, 0, 0, 0}, {0.75f, 0, 0, 0}, 8.0f});
        ctx.commands().draw(3);
        ctx.end_render_pass();
        return Status{};
    })).ok());
    EXPECT_TRUE(graph.add_pass(fg::Pass("geometry")
                                   .output("position", kColor)
                                   .output("normal", kColor)
                                   .output("albedo", kColor)
                                   .on_execute([p](fg::PassContext& ctx) {
                                       ctx.begin_render_pass({"position", "normal", "albedo"});
                                       ctx.commands().set_pipeline(p.geometry);
                                       ctx.commands().draw(3);
                                       ctx.end_render_pass();
                                       return Status{};
                                   }))
                    .ok());
    const fg::PortSet deferred = fg::PortSet("deferred").input("position", kColor).input("normal", kColor).input("albedo", kColor).output("color", kColor);
    const fg::PortSet shadow_receiver = fg::PortSet("shadow-render").input("shadow_map", kShadow).output("color", kColor);
    const fg::PortSet high_pass = fg::PortSet("high-pass-render").output("high_pass", kColor);
    EXPECT_TRUE(graph.add_pass(fg::Pass("deferred").add(deferred).add(shadow_receiver).add(high_pass).on_execute([p](fg::PassContext& ctx) {
        ctx.begin_render_pass({"color", "high_pass"});
        ctx.commands().set_pipeline(p.deferred);
        ctx.commands().set_bind_group(0, rhi::BindGroup{}
                                             .texture(0, ctx.texture("position"), p.sampler)
                                             .texture(1, ctx.texture("normal"), p.sampler)
                                             .texture(2, ctx.texture("albedo"), p.sampler)
                                             .texture(3, ctx.texture("shadow_map"), p.sampler));
        ctx.commands().draw(3);
        ctx.end_render_pass();
        return Status{};
    })).ok());
    EXPECT_TRUE(graph.add_pass(filter_pass("blur", "previous_pass", "color", kColor, p.blur, p.sampler, {{0.5f, 0.5f, 0.5f, 0.5f}, {}})).ok());
    EXPECT_TRUE(graph.add_pass(combine_pass("composite", "color", "bloom", "final", kColor, p.composite, p.sampler, {})).ok());
    EXPECT_TRUE(graph.connect(fg::port("shadow", "shadow_map"), fg::port("deferred", "shadow_map")).ok());
    EXPECT_TRUE(graph.connect(fg::port("geometry", "position"), fg::port("deferred", "position")).ok());
    EXPECT_TRUE(graph.connect(fg::port("geometry", "normal"), fg::port("deferred", "normal")).ok());
    EXPECT_TRUE(graph.connect(fg::port("geometry", "albedo"), fg::port("deferred", "albedo")).ok());
    EXPECT_TRUE(graph.connect(fg::port("deferred", "high_pass"), fg::port("blur", "previous_pass")).ok());
    EXPECT_TRUE(graph.connect(fg::port("deferred", "color"), fg::port("composite", "color")).ok());
    EXPECT_TRUE(graph.connect(fg::port("blur", "color"), fg::port("composite", "bloom")).ok());
    EXPECT_TRUE(graph.mark_output(fg::port("composite", "final")).ok());
}

fg::FrameGraph figure2(const Figure2Programs& p) {
    fg::FrameGraph graph;
    declare_figure2(graph, p);
    return graph;
}

class Figure2Execution : public RenderTest {
protected:
    void SetUp() override {
        RenderTest::SetUp();
        programs_ = std::make_unique<TestPrograms>(device());
        LOOM_ASSIGN_OR_FAIL(p_.shadow, programs_->depth_only(Format::Depth32F));
        LOOM_ASSIGN_OR_FAIL(p_.geometry, programs_->make("geometry", kGeometryFrag,
                                                         {Format::RGBA16Float, Format::RGBA16Float, Format::RGBA16Float}));
        LOOM_ASSIGN_OR_FAIL(p_.deferred, programs_->make("deferred", kDeferredFrag, {Format::RGBA16Float, Format::RGBA16Float}));
        LOOM_ASSIGN_OR_FAIL(p_.blur, programs_->filter(Format::RGBA16Float));
        LOOM_ASSIGN_OR_FAIL(p_.composite, programs_->combine(Format::RGBA16Float));
        LOOM_ASSIGN_OR_FAIL(p_.sampler, programs_->sampler());
    }
    void TearDown() override {
        programs_.reset();
        RenderTest::TearDown();
    }

    // Left columns see shadow 0.25, the right ones 0.75 (values worked out in the shader comments).
    void expect_final_picture(rhi::TextureHandle final_texture, uint32_t width, uint32_t height, const std::string& what) {
        LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(final_texture));
        ASSERT_EQ(image.width, width) << what;
        ASSERT_EQ(image.height, height) << what;
        for (uint32_t y = 0; y < height; ++y) {
            for (uint32_t x = 0; x < width; ++x) {
                const std::array<double, 4> expected = x < 8 ? std::array<double, 4>{0.4375, 0.5625, 0.3125, 0.625}
                                                             : std::array<double, 4>{0.5625, 0.6875, 0.4375, 0.875};
                ASSERT_EQ(image.load(x, y), expected) << what << ": pixel " << x << "," << y;
            }
        }
    }

    std::unique_ptr<TestPrograms> programs_;
    Figure2Programs p_{};
};

TEST_P(Figure2Execution, EveryAllocatorGivesTheSamePictureAndCreatesThePlansTextures) {
    for (fg::AllocatorKind kind : fg::allocator_kinds()) {
        const std::string allocator(fg::allocator_name(kind));
        SCOPED_TRACE(allocator);
        fg::FrameGraph graph = figure2(p_);
        const rhi::ResourceStats before = device().resource_stats();
        {
            fg::Executor executor(device());
            fg::PlanOptions options;
            options.frame = {16, 8};
            options.allocator = kind;
            LOOM_ASSERT_OK(executor.run_frame(graph, options));
            expect_final_picture(executor.texture("composite", "final"), 16, 8, allocator);
            save_texture(device(), executor.texture("composite", "final"), "figure2_" + allocator + "_" + std::string(rhi::backend_name(backend())));

            const fg::Plan& plan = *executor.plan();
            const fg::ExecutionStats stats = executor.stats();
            const rhi::ResourceStats after = device().resource_stats();
            // Planned: 5 colour textures + the depth map for paper and interval (heap: its own count).
            if (allocator != "heap") {
                EXPECT_EQ(plan.textures.size(), 6u);
            }
            EXPECT_EQ(stats.plan_textures, plan.textures.size());
            EXPECT_EQ(stats.textures, plan.textures.size()) << describe(stats);
            EXPECT_EQ(after.textures - before.textures, plan.textures.size()) << describe(stats);
            const bool placed = allocator == "heap" && device().capabilities().placed_resources;
            if (placed) {
                uint64_t heap_bytes = 0;
                for (uint64_t h : plan.heaps) heap_bytes += h;
                EXPECT_FALSE(plan.heaps.empty());
                EXPECT_EQ(after.heaps - before.heaps, plan.heaps.size()) << describe(stats);
                EXPECT_EQ(after.heap_bytes - before.heap_bytes, heap_bytes) << describe(stats);
                EXPECT_EQ(plan.summary.bytes, heap_bytes);
                EXPECT_EQ(stats.placed_textures, plan.textures.size());
                // Placed textures count as textures, their bytes only in the heaps.
                EXPECT_EQ(after.texture_bytes, before.texture_bytes) << describe(stats);
            } else {
                EXPECT_EQ(after.heaps, before.heaps) << describe(stats);
                EXPECT_EQ(stats.placed_textures, 0u);
            }
        }
        // The executor released everything it created.
        const rhi::ResourceStats released = device().resource_stats();
        EXPECT_EQ(released.textures, before.textures);
        EXPECT_EQ(released.heaps, before.heaps);
        EXPECT_EQ(released.heap_bytes, before.heap_bytes);
        EXPECT_EQ(released.texture_bytes, before.texture_bytes);
    }
}

TEST_P(Figure2Execution, UnchangedPlanCreatesNothingNew) {
    fg::FrameGraph graph = figure2(p_);
    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {16, 8};
    options.allocator = device().capabilities().placed_resources ? fg::AllocatorKind::Heap : fg::AllocatorKind::Interval;
    LOOM_ASSERT_OK(executor.run_frame(graph, options));
    const rhi::ResourceStats first = device().resource_stats();
    const auto plan = executor.plan();
    std::vector<rhi::TextureHandle> handles;
    for (uint32_t t = 0; t < plan->textures.size(); ++t) handles.push_back(executor.plan_texture(t));
    for (int frame = 0; frame < 3; ++frame) {
        LOOM_ASSERT_OK(executor.run_frame(graph, options));
        expect_final_picture(executor.texture("composite", "final"), 16, 8, "frame " + std::to_string(frame + 1));
    }
    EXPECT_EQ(executor.plan(), plan) << "the graph planned again";
    EXPECT_EQ(graph.plans_built(), 1u);
    EXPECT_EQ(executor.stats().realisations, 1u);
    EXPECT_EQ(executor.frame_index(), 4u);
    const rhi::ResourceStats now = device().resource_stats();
    EXPECT_EQ(now.textures, first.textures);
    EXPECT_EQ(now.heaps, first.heaps);
    EXPECT_EQ(now.heap_bytes, first.heap_bytes);
    EXPECT_EQ(now.texture_bytes, first.texture_bytes);
    for (uint32_t t = 0; t < plan->textures.size(); ++t) EXPECT_EQ(executor.plan_texture(t), handles[t]) << "t" << t;
}


TEST_P(Figure2Execution, At720pWithFiguresAndTimings) {
    // A realistic frame size: the same exact picture, the plan's figures next to the device's,
    // and per-pass timings (printed for the record; not asserted).
    for (fg::AllocatorKind kind : {fg::AllocatorKind::Interval, fg::AllocatorKind::Heap}) {
        const std::string allocator(fg::allocator_name(kind));
        SCOPED_TRACE(allocator);
        fg::FrameGraph graph = figure2(p_);
        const rhi::ResourceStats before = device().resource_stats();
        fg::Executor executor(device());
        fg::PlanOptions options;
        options.frame = {1280, 720};
        options.allocator = kind;
        for (int frame = 0; frame < 3; ++frame) LOOM_ASSERT_OK(executor.run_frame(graph, options));
        LOOM_ASSERT_OK(device().wait_idle());
        expect_final_picture(executor.texture("composite", "final"), 1280, 720, allocator);
        const fg::Plan& plan = *executor.plan();
        const rhi::ResourceStats after = device().resource_stats();
        EXPECT_EQ(after.textures - before.textures, plan.textures.size());
        if (allocator == "heap" && device().capabilities().placed_resources) {
            EXPECT_EQ(after.heap_bytes - before.heap_bytes, plan.summary.bytes);
            EXPECT_GE(plan.summary.bytes, plan.summary.lower_bound_bytes);
        }
        const auto timings = executor.timings();
        EXPECT_EQ(timings.size(), plan.order.size());
        std::cout << "[figure2 " << rhi::backend_name(backend()) << " " << allocator << " 1280x720] textures "
                  << plan.summary.textures << " (naive " << plan.summary.naive_textures << ", lower bound "
                  << plan.summary.lower_bound_textures << "), bytes " << plan.summary.bytes << " (naive "
                  << plan.summary.naive_bytes << ", lower bound " << plan.summary.lower_bound_bytes << ")\n"
                  << fg::describe_stats(executor.stats()) << "\n"
                  << fg::describe_timings(timings);
    }
}

TEST_P(Figure2Execution, GraphRebuiltEveryFrameReusesTheResources) {
    // Some applications declare their graph anew every frame: an equal plan keeps the textures.
    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {16, 8};
    options.allocator = fg::AllocatorKind::Heap;
    std::vector<rhi::TextureHandle> first;
    for (int frame = 0; frame < 3; ++frame) {
        fg::FrameGraph graph = figure2(p_);
        LOOM_ASSERT_OK(executor.run_frame(graph, options));
        expect_final_picture(executor.texture("composite", "final"), 16, 8, "frame " + std::to_string(frame));
        std::vector<rhi::TextureHandle> handles;
        for (uint32_t t = 0; t < executor.plan()->textures.size(); ++t) handles.push_back(executor.plan_texture(t));
        if (frame == 0) first = handles;
        EXPECT_EQ(handles, first) << "frame " << frame;
    }
    EXPECT_EQ(executor.stats().realisations, 1u);
}

TEST_P(Figure2Execution, GraphRedeclaredEveryFrameIsPlannedOnceAndRunsEachFramesPasses) {
    // An engine's frame loop: one graph, redeclared every frame with new execute functions. The
    // graph is planned once, the executor keeps its plan and textures, and each frame runs the
    // passes declared for it.
    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {16, 8};
    fg::FrameGraph graph;
    std::vector<int> counted;
    const fg::Plan* first = nullptr;
    for (int frame = 0; frame < 3; ++frame) {
        graph.redeclare();
        declare_figure2(graph, p_);
        // A pass that records nothing, only which frame declared it.
        ASSERT_TRUE(graph.add_pass(fg::Pass("count").input("final").set_side_effect().on_execute([&counted, frame](fg::PassContext&) {
            counted.push_back(frame);
            return Status{};
        })).ok());
        ASSERT_TRUE(graph.connect(fg::port("composite", "final"), fg::port("count", "final")).ok());
        LOOM_ASSERT_OK(executor.run_frame(graph, options));
        expect_final_picture(executor.texture("composite", "final"), 16, 8, "frame " + std::to_string(frame));
        if (frame == 0) first = executor.plan().get();
        EXPECT_EQ(executor.plan().get(), first) << "frame " << frame;
    }
    EXPECT_EQ(counted, (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(graph.plans_built(), 1u);
    EXPECT_EQ(executor.stats().realisations, 1u);
}

// The executor's latest plan is the one build_plan makes of `graph` now.
void expect_plan_of_build_plan(const fg::Executor& executor, const fg::FrameGraph& graph, const fg::PlanOptions& options) {
    auto fresh = fg::build_plan(graph, executor.effective_options(options));
    ASSERT_TRUE(fresh.ok()) << fresh.error().to_string();
    EXPECT_TRUE(*executor.plan() == *fresh);
}

TEST_P(Figure2Execution, ResizesInTheDeclaredOrderArePlannedFromThePreviousPlan) {
    // A window resized frame after frame, planned in the declared order: the graph plans once and
    // makes each new size's plan from the previous one (which the executor holds, so it is
    // copied); the executor realises each plan, and every picture is the one a fresh plan draws.
    fg::FrameGraph graph = figure2(p_);
    fg::Executor executor(device());
    fg::PlanOptions options;
    options.order = fg::PassOrder::Declared;
    options.allocator = fg::AllocatorKind::Interval;
    const std::vector<fg::Extent2D> frames{{16, 8}, {40, 24}, {12, 30}, {16, 8}};
    for (const fg::Extent2D frame : frames) {
        const std::string what = std::to_string(frame.width) + "x" + std::to_string(frame.height);
        SCOPED_TRACE(what);
        options.frame = frame;
        LOOM_ASSERT_OK(executor.run_frame(graph, options));
        expect_final_picture(executor.texture("composite", "final"), frame.width, frame.height, what);
        LOOM_ASSIGN_OR_FAIL(rhi::TextureDesc final_desc, device().texture_desc(executor.texture("composite", "final")));
        EXPECT_EQ(final_desc.width, frame.width);
        EXPECT_EQ(final_desc.height, frame.height);
        expect_plan_of_build_plan(executor, graph, options);
    }
    EXPECT_EQ(graph.plans_built(), 1u);
    EXPECT_EQ(graph.plans_resized(), frames.size() - 1);
    EXPECT_EQ(executor.stats().realisations, frames.size());
}

TEST_P(Figure2Execution, TextureSpecsSetBetweenFramesArePlannedFromThePreviousPlan) {
    // A setting changed between frames, nothing declared again: the shadow map at 32x32, then
    // at 48x48, set on its write and its read, which must join (a format would need other
    // pipelines, a usage other bindings). In the declared order each plan is made from the
    // previous one, which the executor holds; each is realised, draws the same picture and is
    // the plan build_plan makes.
    fg::FrameGraph graph = figure2(p_);
    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {16, 8};
    options.order = fg::PassOrder::Declared;
    options.allocator = fg::AllocatorKind::Interval;
    auto address = [&](const char* pass, const char* port) {
        auto found = graph.resolve(fg::port(pass, port));
        EXPECT_TRUE(found.ok()) << found.error().to_string();
        return found.ok() ? *found : fg::PortAddress{};
    };
    const std::vector<uint32_t> shadow_sizes{64, 32, 48};
    for (std::size_t frame = 0; frame < shadow_sizes.size(); ++frame) {
        SCOPED_TRACE("frame " + std::to_string(frame));
        const uint32_t size = shadow_sizes[frame];
        if (frame > 0) {
            const fg::TextureSpec shadow = fg::TextureSpec::of(Format::Depth32F).with_size(size, size);
            LOOM_ASSERT_OK(graph.set_texture_spec(address("shadow", "shadow_map"), shadow));
            LOOM_ASSERT_OK(graph.set_texture_spec(address("deferred", "shadow_map"), shadow));
        }
        LOOM_ASSERT_OK(executor.run_frame(graph, options));
        expect_final_picture(executor.texture("composite", "final"), 16, 8, "frame " + std::to_string(frame));
        LOOM_ASSIGN_OR_FAIL(rhi::TextureDesc shadow_desc, device().texture_desc(executor.texture("shadow", "shadow_map")));
        EXPECT_EQ(shadow_desc.width, size);
        EXPECT_EQ(shadow_desc.height, size);
        expect_plan_of_build_plan(executor, graph, options);
    }
    EXPECT_EQ(graph.plans_built(), 1u);
    EXPECT_EQ(graph.plans_resized(), 2u);
    EXPECT_EQ(executor.stats().realisations, 3u);
}

TEST_P(Figure2Execution, ResizeRebuildsTexturesWithoutLeaks) {
    fg::FrameGraph graph = figure2(p_);
    const rhi::ResourceStats before = device().resource_stats();
    fg::Executor executor(device());
    fg::PlanOptions options;
    options.allocator = device().capabilities().placed_resources ? fg::AllocatorKind::Heap : fg::AllocatorKind::Interval;
    for (const fg::Extent2D frame : {fg::Extent2D{16, 8}, fg::Extent2D{40, 24}, fg::Extent2D{12, 30}, fg::Extent2D{16, 8}}) {
        const std::string what = std::to_string(frame.width) + "x" + std::to_string(frame.height);
        SCOPED_TRACE(what);
        options.frame = frame;
        LOOM_ASSERT_OK(executor.run_frame(graph, options));
        LOOM_ASSERT_OK(executor.run_frame(graph, options));
        expect_final_picture(executor.texture("composite", "final"), frame.width, frame.height, what);

        // Relative sizes follow the frame; the shadow map keeps its absolute size.
        LOOM_ASSIGN_OR_FAIL(rhi::TextureDesc final_desc, device().texture_desc(executor.texture("composite", "final")));
        EXPECT_EQ(final_desc.width, frame.width);
        EXPECT_EQ(final_desc.height, frame.height);
        LOOM_ASSIGN_OR_FAIL(rhi::TextureDesc shadow_desc, device().texture_desc(executor.texture("shadow", "shadow_map")));
        EXPECT_EQ(shadow_desc.width, 64u);
        EXPECT_EQ(shadow_desc.height, 64u);

        // The old resources are gone: what is alive is exactly the new plan's.
        const fg::Plan& plan = *executor.plan();
        const rhi::ResourceStats now = device().resource_stats();
        EXPECT_EQ(plan.frame, frame);
        EXPECT_EQ(now.textures - before.textures, plan.textures.size()) << describe(executor.stats());
        EXPECT_EQ(now.heaps - before.heaps, executor.stats().heaps) << describe(executor.stats());
        uint64_t heap_bytes = 0;
        if (device().capabilities().placed_resources) {
            for (uint64_t h : plan.heaps) heap_bytes += h;
            EXPECT_EQ(now.heaps - before.heaps, plan.heaps.size());
        }
        EXPECT_EQ(now.heap_bytes - before.heap_bytes, heap_bytes);
    }
    // Each size was realised once (two frames each); going back to 16x8 realises again.
    EXPECT_EQ(executor.stats().realisations, 4u);
    LOOM_ASSERT_OK(executor.release());
    const rhi::ResourceStats released = device().resource_stats();
    EXPECT_EQ(released.textures, before.textures);
    EXPECT_EQ(released.heaps, before.heaps);
    EXPECT_EQ(released.texture_bytes, before.texture_bytes);
    EXPECT_EQ(released.heap_bytes, before.heap_bytes);
}

// The heap plan gives textures whose lifetimes do not overlap the same bytes. Both tenants'
// results must be right every frame (the hand-over runs again at the start of each frame).
TEST_P(Figure2Execution, HeapAliasingKeepsBothTenantsResults) {
    fg::FrameGraph graph = figure2(p_);
    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {16, 8};
    options.allocator = fg::AllocatorKind::Heap;
    LOOM_ASSERT_OK(executor.run_frame(graph, options));
    const fg::Plan& plan = *executor.plan();

    // Pairs of textures sharing heap bytes, with the resources they hold.
    std::vector<std::pair<uint32_t, uint32_t>> shared;
    for (uint32_t a = 0; a < plan.textures.size(); ++a) {
        for (uint32_t b = a + 1; b < plan.textures.size(); ++b) {
            const auto& pa = plan.textures[a].placement;
            const auto& pb = plan.textures[b].placement;
            if (!pa || !pb || pa->heap != pb->heap) continue;
            if (pa->offset < pb->offset + plan.textures[b].bytes && pb->offset < pa->offset + plan.textures[a].bytes) {
                shared.emplace_back(a, b);
            }
        }
    }
    ASSERT_FALSE(shared.empty()) << "the heap plan shares no bytes";
    const bool placed = device().capabilities().placed_resources;
    EXPECT_EQ(executor.stats().placed_textures, placed ? plan.textures.size() : 0u);

    // blur.color takes bytes an earlier tenant (one of shadow map, G-buffer maps, high-pass) held.
    const uint32_t bloom_texture = *plan.texture_of("blur", "color");
    bool bloom_shares = false;
    for (auto [a, b] : shared) bloom_shares = bloom_shares || a == bloom_texture || b == bloom_texture;
    EXPECT_TRUE(bloom_shares) << "blur.color shares no bytes";

    for (int frame = 0; frame < 3; ++frame) {
        if (frame > 0) LOOM_ASSERT_OK(executor.run_frame(graph, options));
        // The final picture needs the earlier tenants (shadow map, G-buffer) intact when read;
        // the bloom, written into shared bytes, must be intact when composite reads it.
        expect_final_picture(executor.texture("composite", "final"), 16, 8, "frame " + std::to_string(frame));
        LOOM_ASSIGN_OR_FAIL(rhi::Image bloom, device().read_texture(executor.texture("blur", "color")));
        EXPECT_EQ(bloom.load(3, 3), (std::array<double, 4>{0.1875, 0.1875, 0.1875, 0.375}));
        EXPECT_EQ(bloom.load(12, 5), (std::array<double, 4>{0.0625, 0.0625, 0.0625, 0.125}));
    }
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(Figure2Execution);

}  // namespace loom::test

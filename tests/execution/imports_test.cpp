// Textures the application owns bound into the graph (an output written in place of a plan
// texture, an input read from outside), and history: a port reading what another port held at
// the end of the previous frame.
#include <cstring>

#include "execution_helpers.hpp"
#include "loom_test/render_fixture.hpp"
#include "loom_test/test_support.hpp"

namespace loom::test {
namespace {

using rhi::Format;

const fg::TextureSpec kColor = fg::TextureSpec::of(Format::RGBA16Float);

class ImportTest : public RenderTest {
protected:
    void SetUp() override {
        RenderTest::SetUp();
        programs_ = std::make_unique<TestPrograms>(device());
        LOOM_ASSIGN_OR_FAIL(fill_, programs_->fill(Format::RGBA16Float));
        LOOM_ASSIGN_OR_FAIL(filter_, programs_->filter(Format::RGBA16Float));
        LOOM_ASSIGN_OR_FAIL(combine_, programs_->combine(Format::RGBA16Float));
        LOOM_ASSIGN_OR_FAIL(sampler_, programs_->sampler());
    }
    void TearDown() override {
        for (rhi::TextureHandle t : textures_) (void)device().destroy(t);
        programs_.reset();
        RenderTest::TearDown();
    }

    rhi::TextureHandle app_texture(const std::string& name, Format format, uint32_t width, uint32_t height) {
        rhi::TextureDesc desc;
        desc.name = name;
        desc.format = format;
        desc.width = width;
        desc.height = height;
        desc.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::ColorAttachment | rhi::TextureUsage::CopySrc |
                     rhi::TextureUsage::CopyDst;
        auto texture = device().create_texture(desc);
        EXPECT_TRUE(texture.ok()) << texture.error().to_string();
        if (!texture) return {};
        textures_.push_back(*texture);
        return *texture;
    }

    // fill (left (0.25, 0.5, 0, 1) | right (0.75, 0.125, 0.5, 1)) → invert (1 - rgb) → out.
    fg::FrameGraph fill_invert() {
        fg::FrameGraph graph;
        EXPECT_TRUE(graph.add_pass(fill_pass("fill", "color", kColor, fill_, {{0.25f, 0.5f, 0, 1}, {0.75f, 0.125f, 0.5f, 1}, 8.0f})).ok());
        EXPECT_TRUE(graph.add_pass(filter_pass("invert", "in", "out", kColor, filter_, sampler_, {{-1, -1, -1, 1}, {1, 1, 1, 0}})).ok());
        EXPECT_TRUE(graph.connect(fg::port("fill", "color"), fg::port("invert", "in")).ok());
        EXPECT_TRUE(graph.mark_output(fg::port("invert", "out")).ok());
        return graph;
    }

    // A pass with an optional input `previous` and an output `out` = previous * mul + add.
    fg::Pass reader_pass(const std::string& name, FilterConstants constants, std::vector<bool>* valid = nullptr) {
        fg::Pass pass(name);
        pass.optional_input("previous", kColor).output("out", kColor);
        pass.on_execute([this, constants, valid](fg::PassContext& ctx) {
            if (valid) valid->push_back(ctx.history_valid("previous"));
            ctx.begin_render_pass({"out"});
            ctx.commands().set_pipeline(filter_);
            ctx.commands().set_bind_group(0, rhi::BindGroup{}.texture(0, ctx.texture("previous"), sampler_));
            ctx.commands().push_constants_of(constants);
            ctx.commands().draw(3);
            ctx.end_render_pass();
            return Status{};
        });
        return pass;
    }

    std::unique_ptr<TestPrograms> programs_;
    rhi::PipelineHandle fill_, filter_, combine_;
    rhi::SamplerHandle sampler_;
    std::vector<rhi::TextureHandle> textures_;
};

TEST_P(ImportTest, GraphOutputWritesIntoTheApplicationsTexture) {
    fg::FrameGraph graph = fill_invert();
    const rhi::TextureHandle target = app_texture("app target", Format::RGBA16Float, 16, 8);
    const rhi::ResourceStats before = device().resource_stats();
    fg::Executor executor(device());
    executor.import_texture(fg::port("invert", "out"), target, rhi::ResourceState::ShaderRead);
    fg::PlanOptions options;
    options.frame = {16, 8};
    LOOM_ASSERT_OK(executor.run_frame(graph, options));

    EXPECT_EQ(executor.texture("invert", "out"), target);
    EXPECT_EQ(texel(device(), target, 2, 3), (std::array<double, 4>{0.75, 0.5, 1.0, 1.0}));
    EXPECT_EQ(texel(device(), target, 13, 6), (std::array<double, 4>{0.25, 0.875, 0.5, 1.0}));
    // The plan has two textures (fill.color, invert.out live together); the import stands in
    // for invert.out's, which holds nothing else, so only one is created.
    EXPECT_EQ(executor.plan()->textures.size(), 2u);
    EXPECT_EQ(executor.stats().textures, 1u) << describe(executor.stats());
    EXPECT_EQ(device().resource_stats().textures - before.textures, 1u);

    // The texture was left in ShaderRead: the application samples it without a transition
    // (both backends reject sampling a texture in another state).
    const rhi::TextureHandle copy = app_texture("app copy", Format::RGBA16Float, 16, 8);
    rhi::CommandList& list = device().begin_frame();
    rhi::RenderPassDesc pass;
    pass.label = "app samples the graph's output";
    pass.colors.push_back(rhi::ColorAttachment{copy, 0, 0, rhi::LoadOp::Clear, rhi::StoreOp::Store, {0, 0, 0, 0}});
    list.begin_render_pass(pass);
    list.set_pipeline(filter_);
    list.set_bind_group(0, rhi::BindGroup{}.texture(0, target, sampler_));
    list.push_constants_of(FilterConstants{});
    list.draw(3);
    list.end_render_pass();
    LOOM_ASSERT_OK(device().end_frame());
    EXPECT_EQ(texel(device(), copy, 2, 3), (std::array<double, 4>{0.75, 0.5, 1.0, 1.0}));

    // Another texture bound to the same port (as a window's back buffer changes every frame)
    // is used in place, without rebuilding anything.
    const rhi::TextureHandle second = app_texture("app target 2", Format::RGBA16Float, 16, 8);
    executor.import_texture(fg::port("invert", "out"), second, rhi::ResourceState::CopySrc);
    LOOM_ASSERT_OK(executor.run_frame(graph, options));
    EXPECT_EQ(texel(device(), second, 13, 6), (std::array<double, 4>{0.25, 0.875, 0.5, 1.0}));
    EXPECT_EQ(executor.stats().realisations, 1u);

    // Without the import the plan's own texture comes back.
    EXPECT_TRUE(executor.remove_import(fg::port("invert", "out")));
    LOOM_ASSERT_OK(executor.run_frame(graph, options));
    EXPECT_EQ(executor.stats().textures, 2u);
    EXPECT_NE(executor.texture("invert", "out"), second);
    EXPECT_EQ(texel(device(), executor.texture("invert", "out"), 13, 6), (std::array<double, 4>{0.25, 0.875, 0.5, 1.0}));
}

TEST_P(ImportTest, MismatchingImportIsAnErrorNamingThePort) {
    fg::FrameGraph graph = fill_invert();
    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {16, 8};
    executor.import_texture(fg::port("invert", "out"), app_texture("too small", Format::RGBA16Float, 8, 8));
    Status wrong_size = executor.run_frame(graph, options);
    ASSERT_FALSE(wrong_size.ok());
    EXPECT_EQ(wrong_size.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(wrong_size.error().message.find("import invert.out"), std::string::npos) << wrong_size.error().message;
    EXPECT_NE(wrong_size.error().message.find("'too small'"), std::string::npos) << wrong_size.error().message;

    executor.import_texture(fg::port("invert", "out"), app_texture("wrong format", Format::RGBA8Unorm, 16, 8));
    Status wrong_format = executor.run_frame(graph, options);
    ASSERT_FALSE(wrong_format.ok());
    EXPECT_NE(wrong_format.error().message.find("RGBA8Unorm"), std::string::npos) << wrong_format.error().message;

    executor.import_texture(fg::port("invert", "nope"), app_texture("ok", Format::RGBA16Float, 16, 8));
    Status unknown = executor.run_frame(graph, options);
    ASSERT_FALSE(unknown.ok());
    EXPECT_EQ(unknown.error().code, ErrorCode::Graph);
    EXPECT_NE(unknown.error().message.find("import invert.nope"), std::string::npos) << unknown.error().message;

    // Fixed, the same executor runs.
    EXPECT_TRUE(executor.remove_import(fg::port("invert", "nope")));
    executor.import_texture(fg::port("invert", "out"), app_texture("right", Format::RGBA16Float, 16, 8));
    LOOM_ASSERT_OK(executor.run_frame(graph, options));
}

TEST_P(ImportTest, UnconnectedInputReadsTheApplicationsTexture) {
    // A texture the application filled: column x holds (x / 16, 0.5, 0, 1).
    const rhi::TextureHandle source = app_texture("app source", Format::RGBA32Float, 16, 8);
    std::vector<float> texels;
    for (uint32_t y = 0; y < 8; ++y) {
        for (uint32_t x = 0; x < 16; ++x) texels.insert(texels.end(), {static_cast<float>(x) / 16.0f, 0.5f, 0.0f, 1.0f});
    }
    LOOM_ASSERT_OK(device().write_texture(source, rhi::TextureRegion{}, std::as_bytes(std::span<const float>(texels))));

    fg::FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(reader_pass("double", {{2, 2, 2, 1}, {0, 0, 0, 0}})).ok());
    LOOM_ASSERT_OK(graph.mark_output(fg::port("double", "out")));
    fg::Executor executor(device());
    executor.import_texture(fg::port("double", "previous"), source);
    fg::PlanOptions options;
    options.frame = {16, 8};
    LOOM_ASSERT_OK(executor.run_frame(graph, options));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(executor.texture("double", "out")));
    for (uint32_t x = 0; x < 16; ++x) {
        ASSERT_EQ(image.load(x, 4), (std::array<double, 4>{x / 8.0, 1.0, 0.0, 1.0})) << "column " << x;
    }
}

TEST_P(ImportTest, HistoryAccumulatesOverFrames) {
    fg::FrameGraph graph;
    std::vector<bool> valid;
    // out = previous frame's out + 0.25 (red) / 0.125 (green).
    ASSERT_TRUE(graph.add_pass(reader_pass("accumulate", {{1, 1, 1, 1}, {0.25f, 0.125f, 0, 0.25f}}, &valid)).ok());
    LOOM_ASSERT_OK(graph.mark_output(fg::port("accumulate", "out")));
    fg::Executor executor(device());
    executor.bind_history(fg::port("accumulate", "previous"), fg::port("accumulate", "out"));
    fg::PlanOptions options;
    options.frame = {16, 8};
    for (int frame = 0; frame < 3; ++frame) {
        LOOM_ASSERT_OK(executor.run_frame(graph, options));
        const double n = frame + 1;
        EXPECT_EQ(texel(device(), executor.texture("accumulate", "out"), 5, 5),
                  (std::array<double, 4>{0.25 * n, 0.125 * n, 0.0, 0.25 * n}))
            << "frame " << frame;
        // What the history port will read next frame: this frame's output.
        EXPECT_EQ(texel(device(), executor.texture("accumulate", "previous"), 5, 5),
                  (std::array<double, 4>{0.25 * n, 0.125 * n, 0.0, 0.25 * n}))
            << "frame " << frame;
    }
    EXPECT_EQ(valid, (std::vector<bool>{false, true, true}));
    EXPECT_EQ(executor.stats().history_textures, 1u);
    EXPECT_EQ(executor.stats().realisations, 1u);

    // A new frame size recreates the history: it starts again from zeros.
    options.frame = {8, 8};
    LOOM_ASSERT_OK(executor.run_frame(graph, options));
    EXPECT_EQ(texel(device(), executor.texture("accumulate", "out"), 5, 5), (std::array<double, 4>{0.25, 0.125, 0.0, 0.25}));
    EXPECT_EQ(valid.back(), false);
    LOOM_ASSERT_OK(executor.run_frame(graph, options));
    EXPECT_EQ(texel(device(), executor.texture("accumulate", "out"), 5, 5), (std::array<double, 4>{0.5, 0.25, 0.0, 0.5}));
}

TEST_P(ImportTest, HistoryReadAfterTheSourceIsRewrittenUsesTwoTextures) {
    // source.color (frame-dependent) → mid; late runs after source.color was copied and reads
    // its history: it must see the previous frame's value, not this frame's.
    fg::FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(fg::Pass("source").output("color", kColor).on_execute([this](fg::PassContext& ctx) {
        const float v = 0.125f * static_cast<float>(ctx.frame_index() + 1);
        ctx.begin_render_pass({"color"});
        ctx.commands().set_pipeline(fill_);
        ctx.commands().push_constants_of(FillConstants{{v, v, v, 1}, {v, v, v, 1}, 0.0f});
        ctx.commands().draw(3);
        ctx.end_render_pass();
        return Status{};
    })).ok());
    ASSERT_TRUE(graph.add_pass(filter_pass("mid", "in", "out", kColor, filter_, sampler_, {})).ok());
    fg::Pass late("late");
    late.input("color", kColor).optional_input("previous", kColor).output("out", kColor);
    late.on_execute([this](fg::PassContext& ctx) {
        ctx.begin_render_pass({"out"});
        ctx.commands().set_pipeline(combine_);
        ctx.commands().set_bind_group(0, rhi::BindGroup{}.texture(0, ctx.texture("color"), sampler_).texture(1, ctx.texture("previous"), sampler_));
        // out = previous (the current colour is only there to order the pass after mid).
        ctx.commands().push_constants_of(CombineConstants{{0, 0, 0, 0}, {1, 1, 1, 1}});
        ctx.commands().draw(3);
        ctx.end_render_pass();
        return Status{};
    });
    ASSERT_TRUE(graph.add_pass(std::move(late)).ok());
    LOOM_ASSERT_OK(graph.connect(fg::port("source", "color"), fg::port("mid", "in")));
    LOOM_ASSERT_OK(graph.connect(fg::port("mid", "out"), fg::port("late", "color")));
    LOOM_ASSERT_OK(graph.mark_output(fg::port("late", "out")));

    fg::Executor executor(device());
    executor.bind_history(fg::port("late", "previous"), fg::port("source", "color"));
    fg::PlanOptions options;
    options.frame = {16, 8};
    for (int frame = 0; frame < 3; ++frame) {
        LOOM_ASSERT_OK(executor.run_frame(graph, options));
        const double previous = frame == 0 ? 0.0 : 0.125 * frame;
        EXPECT_EQ(texel(device(), executor.texture("late", "out"), 7, 2),
                  (std::array<double, 4>{previous, previous, previous, frame == 0 ? 0.0 : 1.0}))
            << "frame " << frame;
    }
    EXPECT_EQ(executor.stats().history_textures, 2u);
}

TEST_P(ImportTest, HistoryOnAConnectedPortIsAnError) {
    fg::FrameGraph graph = fill_invert();
    fg::Executor executor(device());
    executor.bind_history(fg::port("invert", "in"), fg::port("invert", "out"));
    fg::PlanOptions options;
    options.frame = {16, 8};
    Status status = executor.run_frame(graph, options);
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().code, ErrorCode::Graph);
    EXPECT_NE(status.error().message.find("history reader invert.in is connected"), std::string::npos) << status.error().message;
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(ImportTest);

}  // namespace loom::test

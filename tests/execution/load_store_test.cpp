// Load and store actions from the plan, as passes see them through PassContext: a first write
// clears (with the pass's clear value), an inout keeps what the previous pass wrote, contents
// nobody reads later are not stored.
#include "execution_helpers.hpp"
#include "loom_test/render_fixture.hpp"

namespace loom::test {
namespace {

using rhi::Format;

const fg::TextureSpec kColor = fg::TextureSpec::of(Format::RGBA16Float);

class LoadStoreTest : public RenderTest {
protected:
    void SetUp() override {
        RenderTest::SetUp();
        programs_ = std::make_unique<TestPrograms>(device());
        LOOM_ASSIGN_OR_FAIL(fill_, programs_->fill(Format::RGBA16Float));
    }
    void TearDown() override {
        programs_.reset();
        RenderTest::TearDown();
    }
    std::unique_ptr<TestPrograms> programs_;
    rhi::PipelineHandle fill_;
};

TEST_P(LoadStoreTest, InOutKeepsWhatThePreviousPassWrote) {
    fg::FrameGraph graph;
    // base: red left, green right.
    ASSERT_TRUE(graph.add_pass(fill_pass("base", "color", kColor, fill_, {{1, 0, 0, 1}, {0, 1, 0, 1}, 8.0f})).ok());
    // tint: draws blue into columns 0..3 only (scissor); the rest must survive.
    std::vector<rhi::RenderPassDesc> seen;
    ASSERT_TRUE(graph.add_pass(fg::Pass("tint").inout("color", kColor).on_execute([&](fg::PassContext& ctx) {
        seen.push_back(ctx.render_pass(std::vector<fg::ColorPort>{{"color", {0.5, 0.5, 0.5, 0.5}}}));
        ctx.begin_render_pass({{"color", {0.5, 0.5, 0.5, 0.5}}});
        ctx.commands().set_pipeline(fill_);
        ctx.commands().set_scissor(rhi::Rect{0, 0, 4, 8});
        ctx.commands().push_constants_of(FillConstants{{0, 0, 1, 1}, {0, 0, 1, 1}, 0.0f});
        ctx.commands().draw(3);
        ctx.end_render_pass();
        return Status{};
    })).ok());
    LOOM_ASSERT_OK(graph.connect(fg::port("base", "color"), fg::port("tint", "color")));
    LOOM_ASSERT_OK(graph.mark_output(fg::port("tint", "color")));

    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {16, 8};
    for (int frame = 0; frame < 2; ++frame) {
        LOOM_ASSERT_OK(executor.run_frame(graph, options));
        LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(executor.texture("tint", "color")));
        for (uint32_t x = 0; x < 16; ++x) {
            const std::array<double, 4> expected = x < 4 ? std::array<double, 4>{0, 0, 1, 1}
                                                 : x < 8 ? std::array<double, 4>{1, 0, 0, 1}
                                                         : std::array<double, 4>{0, 1, 0, 1};
            ASSERT_EQ(image.load(x, 6), expected) << "column " << x << ", frame " << frame;
        }
    }
    ASSERT_EQ(seen.size(), 2u);
    ASSERT_EQ(seen[0].colors.size(), 1u);
    EXPECT_EQ(seen[0].label, "tint");
    EXPECT_EQ(seen[0].colors[0].load, rhi::LoadOp::Load);
    EXPECT_EQ(seen[0].colors[0].store, rhi::StoreOp::Store);
    EXPECT_EQ(seen[0].colors[0].texture, executor.texture("base", "color"));
}

TEST_P(LoadStoreTest, FirstWriteClearsWithThePassesValueAndUnreadContentsAreNotStored) {
    fg::FrameGraph graph;
    std::vector<rhi::RenderPassDesc> seen;
    // "clear" only begins and ends its render pass: the texture holds its clear value.
    ASSERT_TRUE(graph.add_pass(fg::Pass("clear")
                                   .output("color", kColor)
                                   .output("scratch", kColor)
                                   .output("depth", fg::TextureSpec::of(Format::Depth32F))
                                   .on_execute([&](fg::PassContext& ctx) {
                                       const std::vector<fg::ColorPort> colors{{"color", {0.25, 0.5, 0.75, 1.0}}, "scratch"};
                                       seen.push_back(ctx.render_pass(colors, fg::DepthPort{"depth", 0.5f}));
                                       ctx.begin_render_pass(colors, fg::DepthPort{"depth", 0.5f});
                                       ctx.end_render_pass();
                                       return Status{};
                                   }))
                    .ok());
    ASSERT_TRUE(graph.add_pass(fg::Pass("overwrite").output("full", kColor).on_execute([&](fg::PassContext& ctx) {
        fg::ColorPort full("full");
        full.writes_every_texel = true;
        seen.push_back(ctx.render_pass(std::vector<fg::ColorPort>{full}));
        ctx.begin_render_pass({full});
        ctx.commands().set_pipeline(fill_);
        ctx.commands().push_constants_of(FillConstants{{0, 0, 0.5f, 1}, {0, 0, 0.5f, 1}, 0.0f});
        ctx.commands().draw(3);
        ctx.end_render_pass();
        return Status{};
    })).ok());
    LOOM_ASSERT_OK(graph.mark_output(fg::port("clear", "color")));
    LOOM_ASSERT_OK(graph.mark_output(fg::port("clear", "depth")));
    LOOM_ASSERT_OK(graph.mark_output(fg::port("overwrite", "full")));
    LOOM_ASSERT_OK(graph.set_side_effect("clear"));

    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {16, 8};
    LOOM_ASSERT_OK(executor.run_frame(graph, options));
    EXPECT_EQ(texel(device(), executor.texture("clear", "color"), 9, 2), (std::array<double, 4>{0.25, 0.5, 0.75, 1.0}));
    EXPECT_EQ(texel(device(), executor.texture("clear", "depth"), 9, 2)[0], 0.5);
    EXPECT_EQ(texel(device(), executor.texture("overwrite", "full"), 9, 2), (std::array<double, 4>{0, 0, 0.5, 1}));

    ASSERT_EQ(seen.size(), 2u);
    const rhi::RenderPassDesc& clear = seen[0];
    ASSERT_EQ(clear.colors.size(), 2u);
    EXPECT_EQ(clear.colors[0].load, rhi::LoadOp::Clear);
    EXPECT_EQ(clear.colors[0].clear, (std::array<double, 4>{0.25, 0.5, 0.75, 1.0}));
    EXPECT_EQ(clear.colors[0].store, rhi::StoreOp::Store);  // graph output
    EXPECT_EQ(clear.colors[1].load, rhi::LoadOp::Clear);
    EXPECT_EQ(clear.colors[1].store, rhi::StoreOp::DontCare);  // nobody reads scratch
    ASSERT_TRUE(clear.depth.has_value());
    EXPECT_EQ(clear.depth->depth_load, rhi::LoadOp::Clear);
    EXPECT_EQ(clear.depth->clear_depth, 0.5f);
    EXPECT_EQ(clear.depth->depth_store, rhi::StoreOp::Store);
    const rhi::RenderPassDesc& overwrite = seen[1];
    ASSERT_EQ(overwrite.colors.size(), 1u);
    EXPECT_EQ(overwrite.colors[0].load, rhi::LoadOp::DontCare);
    EXPECT_EQ(overwrite.colors[0].store, rhi::StoreOp::Store);
}

TEST_P(LoadStoreTest, PassCopyingItsOutputLeavesItReadableForTheNext) {
    // A pass that copies its output (e.g. to capture it) leaves it in CopySrc; the executor's
    // transition before the reading pass must still bring it to ShaderRead.
    TestPrograms& programs = *programs_;
    LOOM_ASSIGN_OR_FAIL(auto filter, programs.filter(Format::RGBA16Float));
    LOOM_ASSIGN_OR_FAIL(auto sampler, programs.sampler());
    rhi::TextureDesc desc;
    desc.name = "capture";
    desc.format = Format::RGBA16Float;
    desc.width = 16;
    desc.height = 8;
    desc.usage = rhi::TextureUsage::CopyDst | rhi::TextureUsage::CopySrc;
    LOOM_ASSIGN_OR_FAIL(rhi::TextureHandle capture, device().create_texture(desc));
    fg::FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(fg::Pass("draw").output("color", kColor.with_usage(rhi::TextureUsage::CopySrc)).on_execute([&](fg::PassContext& ctx) {
        ctx.begin_render_pass({"color"});
        ctx.commands().set_pipeline(fill_);
        ctx.commands().push_constants_of(FillConstants{{0.25f, 0.5f, 0.75f, 1}, {0.25f, 0.5f, 0.75f, 1}, 0.0f});
        ctx.commands().draw(3);
        ctx.end_render_pass();
        rhi::TextureCopy copy;
        copy.src = ctx.texture("color");
        copy.dst = capture;
        ctx.commands().copy_texture(copy);
        return Status{};
    })).ok());
    ASSERT_TRUE(graph.add_pass(filter_pass("read", "in", "out", kColor, filter, sampler, {{2, 2, 2, 1}, {}})).ok());
    LOOM_ASSERT_OK(graph.connect(fg::port("draw", "color"), fg::port("read", "in")));
    LOOM_ASSERT_OK(graph.mark_output(fg::port("read", "out")));
    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {16, 8};
    for (int frame = 0; frame < 2; ++frame) {
        LOOM_ASSERT_OK(executor.run_frame(graph, options));
        EXPECT_EQ(texel(device(), executor.texture("read", "out"), 4, 4), (std::array<double, 4>{0.5, 1.0, 1.5, 1.0}));
        EXPECT_EQ(texel(device(), capture, 4, 4), (std::array<double, 4>{0.25, 0.5, 0.75, 1.0}));
    }
    (void)device().destroy(capture);
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(LoadStoreTest);

}  // namespace loom::test

// A chain of passes run by the executor on every backend: the final picture is checked pixel
// by pixel, and what each pass read is what the previous one wrote.
#include "execution_helpers.hpp"
#include "loom_test/render_fixture.hpp"

namespace loom::test {
namespace {

using rhi::Format;

class ChainTest : public RenderTest {};

TEST_P(ChainTest, ThreePassChainGivesExactPixels) {
    TestPrograms programs(device());
    const fg::TextureSpec spec = fg::TextureSpec::of(Format::RGBA16Float);
    LOOM_ASSIGN_OR_FAIL(auto fill, programs.fill(Format::RGBA16Float));
    LOOM_ASSIGN_OR_FAIL(auto filter, programs.filter(Format::RGBA16Float));
    LOOM_ASSIGN_OR_FAIL(auto sampler, programs.sampler());

    fg::FrameGraph graph;
    // Columns 0..7: (0.25, 0.5, 0, 1); columns 8..: (0.75, 0.125, 0.5, 1).
    ASSERT_TRUE(graph.add_pass(fill_pass("fill", "color", spec, fill, {{0.25f, 0.5f, 0.0f, 1.0f}, {0.75f, 0.125f, 0.5f, 1.0f}, 8.0f})).ok());
    // x * 2 + (0, 0, 0.25, 0)
    ASSERT_TRUE(graph.add_pass(filter_pass("double", "in", "out", spec, filter, sampler, {{2, 2, 2, 1}, {0, 0, 0.25f, 0}})).ok());
    // 1 - x for rgb
    ASSERT_TRUE(graph.add_pass(filter_pass("invert", "in", "out", spec, filter, sampler, {{-1, -1, -1, 1}, {1, 1, 1, 0}})).ok());
    LOOM_ASSERT_OK(graph.connect(fg::port("fill", "color"), fg::port("double", "in")));
    LOOM_ASSERT_OK(graph.connect(fg::port("double", "out"), fg::port("invert", "in")));
    LOOM_ASSERT_OK(graph.mark_output(fg::port("invert", "out")));

    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {16, 8};
    LOOM_ASSERT_OK(executor.run_frame(graph, options));

    const rhi::TextureHandle final_texture = executor.texture("invert", "out");
    ASSERT_FALSE(final_texture.is_null());
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(final_texture));
    ASSERT_EQ(image.width, 16u);
    ASSERT_EQ(image.height, 8u);
    for (uint32_t y = 0; y < 8; ++y) {
        for (uint32_t x = 0; x < 16; ++x) {
            const std::array<double, 4> expected =
                x < 8 ? std::array<double, 4>{0.5, 0.0, 0.75, 1.0} : std::array<double, 4>{-0.5, 0.75, -0.25, 1.0};
            ASSERT_EQ(image.load(x, y), expected) << "pixel " << x << "," << y;
        }
    }
    // The interval allocator gives the three outputs two textures (fill's is free after
    // "double" read it); "invert" reads what "double" wrote through a different texture.
    EXPECT_EQ(executor.plan()->textures.size(), 2u);
    EXPECT_NE(executor.texture("double", "out"), executor.texture("invert", "out"));
    EXPECT_EQ(executor.texture("double", "out"), executor.texture("invert", "in"));
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(ChainTest);

}  // namespace loom::test

// A triangle's coverage: known pixels inside carry its exact colour, known pixels outside keep
// the clear colour.
#include "loom_test/render_fixture.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

class TriangleTest : public RenderTest {};

TEST_P(TriangleTest, CoversExpectedPixels) {
    constexpr uint32_t kSize = 64;
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "triangle target", rhi::Format::RGBA8Unorm, kSize, kSize));
    LOOM_ASSIGN_OR_FAIL(auto pipeline, make_solid_pipeline(device(), rhi::Format::RGBA8Unorm));
    // A triangle counter-clockwise in NDC: bottom-left, bottom-right, top-centre.
    const std::vector<float> vertices = {-0.5f, -0.5f, 0.0f, 0.5f, -0.5f, 0.0f, 0.0f, 0.5f, 0.0f};
    LOOM_ASSIGN_OR_FAIL(auto vb, make_buffer_of(device(), "triangle vertices", rhi::BufferUsage::Vertex, vertices));
    const std::array<float, 4> color{1.0f, 0.5f, 0.0f, 1.0f};
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("triangle", target, {0.0, 0.0, 0.2, 1.0}));
        list.set_pipeline(pipeline);
        list.set_vertex_buffer(0, vb);
        list.push_constants_of(color);
        list.draw(3);
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    save_picture(image, "triangle_coverage_" + std::string(rhi::backend_name(backend())));

    // 0.5 * 255 = 127.5: GL and Vulkan let a float -> unorm conversion give either of the two
    // nearest values (Mesa gives 128, NVIDIA 127), but the same one for every texel.
    const std::array<int, 4> centre = rgba8_at(image, 32, 32);
    ASSERT_TRUE(centre == (std::array<int, 4>{255, 128, 0, 255}) || centre == (std::array<int, 4>{255, 127, 0, 255}))
        << centre[0] << " " << centre[1] << " " << centre[2] << " " << centre[3];
    const std::array<int, 4> inside = centre;
    const std::array<int, 4> clear{0, 0, 51, 255};
    // The triangle spans x in [16, 48] at the bottom (y = 48) and narrows to x = 32 at y = 16.
    EXPECT_EQ(rgba8_at(image, 18, 46), inside);  // near the bottom-left corner
    EXPECT_EQ(rgba8_at(image, 45, 46), inside);  // near the bottom-right corner
    EXPECT_EQ(rgba8_at(image, 32, 18), inside);  // near the apex
    EXPECT_EQ(rgba8_at(image, 0, 0), clear);
    EXPECT_EQ(rgba8_at(image, kSize - 1, kSize - 1), clear);
    EXPECT_EQ(rgba8_at(image, 32, 14), clear);  // above the apex
    EXPECT_EQ(rgba8_at(image, 32, 50), clear);  // below the base
    EXPECT_EQ(rgba8_at(image, 20, 20), clear);  // left of the left edge
    EXPECT_EQ(rgba8_at(image, 44, 20), clear);  // right of the right edge
    // Exactly one half of the 32x32 box is covered (rasterisation rules give each edge pixel
    // to exactly one side): 32 * 32 / 2 = 512 pixels.
    int covered = 0;
    for (uint32_t y = 0; y < kSize; ++y) {
        for (uint32_t x = 0; x < kSize; ++x) covered += rgba8_at(image, x, y) == inside ? 1 : 0;
    }
    EXPECT_EQ(covered, 512);
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(TriangleTest);

}  // namespace loom::test

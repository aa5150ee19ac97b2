// Depth testing and the 0..1 depth range: a triangle at z = 0.25 hides one at z = 0.75 with
// Less, and the depth read back is the z that was written.
#include "loom_test/render_fixture.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

class DepthTest : public RenderTest {};

TEST_P(DepthTest, NearerTriangleHidesFartherOneAndDepthReadsBack) {
    constexpr uint32_t kSize = 16;
    LOOM_ASSIGN_OR_FAIL(auto color, make_target(device(), "depth colour", rhi::Format::RGBA8Unorm, kSize, kSize));
    LOOM_ASSIGN_OR_FAIL(auto depth, make_target(device(), "depth buffer", rhi::Format::Depth32F, kSize, kSize));
    SolidPipelineOptions options;
    options.depth = rhi::DepthState{true, true, rhi::CompareOp::Less};
    options.depth_format = rhi::Format::Depth32F;
    LOOM_ASSIGN_OR_FAIL(auto pipeline, make_solid_pipeline(device(), rhi::Format::RGBA8Unorm, options));
    // Both triangles cover the left three quarters of the target; the near one is drawn first,
    // so only the depth test can keep the far one out. A third, far-only triangle on the right
    // checks that z = 0.75 is written where nothing is in front.
    const std::vector<float> vertices = {
        -1.0f, -1.0f, 0.25f, 0.5f, -1.0f, 0.25f, -1.0f, 3.0f, 0.25f,  // near, z = 0.25
        -1.0f, -1.0f, 0.75f, 0.5f, -1.0f, 0.75f, -1.0f, 3.0f, 0.75f,  // far, z = 0.75
        0.5f,  -1.0f, 0.75f, 1.0f, -1.0f, 0.75f, 1.0f,  1.0f, 0.75f,  // far only, right strip
    };
    LOOM_ASSIGN_OR_FAIL(auto vb, make_buffer_of(device(), "depth vertices", rhi::BufferUsage::Vertex, vertices));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("depth", color, {0, 0, 0, 1}, depth));
        list.set_pipeline(pipeline);
        list.set_vertex_buffer(0, vb);
        list.push_constants_of(std::array<float, 4>{1, 0, 0, 1});
        list.draw(3, 1, 0);
        list.push_constants_of(std::array<float, 4>{0, 1, 0, 1});
        list.draw(6, 1, 3);
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(color));
    LOOM_ASSIGN_OR_FAIL(rhi::Image depth_image, device().read_texture(depth));
    save_picture(image, "depth_color_" + std::string(rhi::backend_name(backend())));
    EXPECT_EQ(rgba8_at(image, 2, 8), (std::array<int, 4>{255, 0, 0, 255})) << "the far triangle was drawn over the near one";
    EXPECT_EQ(rgba8_at(image, 15, 14), (std::array<int, 4>{0, 255, 0, 255}));
    // Depth is exactly the z of the vertices: 0..1 depth range, no [-1,1] remapping.
    EXPECT_EQ(depth_image.load(2, 8)[0], 0.25);
    EXPECT_EQ(depth_image.load(15, 14)[0], 0.75);
    EXPECT_EQ(depth_image.load(15, 0)[0], 1.0);  // above the right strip's diagonal: cleared
}

TEST_P(DepthTest, ViewportDepthRangeMapsZ) {
    constexpr uint32_t kSize = 8;
    LOOM_ASSIGN_OR_FAIL(auto color, make_target(device(), "range colour", rhi::Format::RGBA8Unorm, kSize, kSize));
    LOOM_ASSIGN_OR_FAIL(auto depth, make_target(device(), "range depth", rhi::Format::Depth32F, kSize, kSize));
    SolidPipelineOptions options;
    options.depth = rhi::DepthState{true, true, rhi::CompareOp::Always};
    options.depth_format = rhi::Format::Depth32F;
    LOOM_ASSIGN_OR_FAIL(auto pipeline, make_solid_pipeline(device(), rhi::Format::RGBA8Unorm, options));
    const std::vector<float> vertices = {-1, -1, 0.5f, 3, -1, 0.5f, -1, 3, 0.5f};
    LOOM_ASSIGN_OR_FAIL(auto vb, make_buffer_of(device(), "range vertices", rhi::BufferUsage::Vertex, vertices));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("range", color, {0, 0, 0, 1}, depth));
        list.set_pipeline(pipeline);
        // Depth range 0.5..1: z maps to 0.5 + z * 0.5.
        list.set_viewport(rhi::Viewport{0, 0, kSize, kSize, 0.5f, 1.0f});
        list.set_vertex_buffer(0, vb);
        list.push_constants_of(std::array<float, 4>{1, 1, 1, 1});
        list.draw(3);
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image depth_image, device().read_texture(depth));
    // 0.5 + 0.5 * (1.0 - 0.5) = 0.75, exact in binary.
    EXPECT_EQ(depth_image.load(4, 4)[0], 0.75);
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(DepthTest);

}  // namespace loom::test

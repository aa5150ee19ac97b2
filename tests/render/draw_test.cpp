// Instanced draws (per-instance attributes, gl_InstanceIndex, first instance) and indexed
// draws with a base vertex and a first index.
#include "loom_test/render_fixture.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

class DrawTest : public RenderTest {
protected:
    static constexpr uint32_t kSize = 32;
};

TEST_P(DrawTest, InstancedDrawPlacesEachInstance) {
    // A quad (two triangles) in the top-left 8x8 pixels of NDC, moved by a per-instance offset;
    // its red channel is the instance index / 8 (gl_InstanceIndex counts from first_instance).
    LOOM_ASSIGN_OR_FAIL(auto vs, make_shader(device(), rhi::ShaderStage::Vertex, "instanced.vert", R"(#version 450
layout(location = 0) in vec2 corner;
layout(location = 1) in vec2 offset;
layout(location = 0) out vec4 v_color;
void main() {
    v_color = vec4(float(gl_InstanceIndex) / 8.0, 1.0, 0.0, 1.0);
    gl_Position = vec4(corner + offset, 0.0, 1.0);
})"));
    LOOM_ASSIGN_OR_FAIL(auto fs, make_shader(device(), rhi::ShaderStage::Fragment, "color.frag", R"(#version 450
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 frag_color;
void main() { frag_color = v_color; }
)"));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "instanced";
    pd.vertex = vs;
    pd.fragment = fs;
    pd.vertex_buffers = {
        rhi::VertexBufferLayout{8, rhi::VertexStepMode::PerVertex, {{0, rhi::VertexFormat::Float2, 0}}},
        rhi::VertexBufferLayout{8, rhi::VertexStepMode::PerInstance, {{1, rhi::VertexFormat::Float2, 0}}},
    };
    pd.color_formats = {rhi::Format::RGBA32Float};
    LOOM_ASSIGN_OR_FAIL(auto pipeline, device().create_graphics_pipeline(pd));
    // The quad covers NDC x, y in [-1, -0.5] x [0.5, 1]: pixels 0..7 of the top-left corner.
    const std::vector<float> corners = {-1, 0.5f, -0.5f, 0.5f, -0.5f, 1, -1, 0.5f, -0.5f, 1, -1, 1};
    // Instance i moves right by i * 0.5 (8 pixels); instances 0..3 fill the top row of cells.
    const std::vector<float> offsets = {0, 0, 0.5f, 0, 1.0f, 0, 1.5f, 0, 0, -0.5f, 0.5f, -0.5f};
    LOOM_ASSIGN_OR_FAIL(auto corner_vb, make_buffer_of(device(), "corners", rhi::BufferUsage::Vertex, corners));
    LOOM_ASSIGN_OR_FAIL(auto offset_vb, make_buffer_of(device(), "offsets", rhi::BufferUsage::Vertex, offsets));
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "instances", rhi::Format::RGBA32Float, kSize, kSize));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("instanced", target, {-1, 0, 0, 0}));
        list.set_pipeline(pipeline);
        list.set_vertex_buffer(0, corner_vb);
        list.set_vertex_buffer(1, offset_vb);
        list.draw(6, 4);      // instances 0..3: top row
        list.draw(6, 2, 0, 4);  // instances 4 and 5 (first_instance 4): second row, left
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    for (uint32_t i = 0; i < 4; ++i) {
        EXPECT_EQ(image.load(i * 8 + 4, 4), (std::array<double, 4>{i / 8.0, 1, 0, 1})) << "instance " << i;
    }
    EXPECT_EQ(image.load(4, 12), (std::array<double, 4>{4 / 8.0, 1, 0, 1})) << "instance 4";
    EXPECT_EQ(image.load(12, 12), (std::array<double, 4>{5 / 8.0, 1, 0, 1})) << "instance 5";
    EXPECT_EQ(image.load(20, 12), (std::array<double, 4>{-1, 0, 0, 0})) << "no instance 6 was drawn";
}

TEST_P(DrawTest, IndexedDrawWithBaseVertexAndFirstIndex) {
    LOOM_ASSIGN_OR_FAIL(auto pipeline, make_solid_pipeline(device(), rhi::Format::RGBA8Unorm));
    // Vertices 0..3: a quad on the left half; vertices 4..7: a quad on the right half.
    const std::vector<float> vertices = {
        -1, -1, 0, 0, -1, 0, -1, 1, 0, 0, 1, 0,  // left
        0,  -1, 0, 1, -1, 0, 0,  1, 0, 1, 1, 0,  // right
    };
    // Indices of one quad, preceded by three indices that must be skipped (first_index = 3).
    const std::vector<uint16_t> indices = {7, 7, 7, 0, 1, 2, 2, 1, 3};
    LOOM_ASSIGN_OR_FAIL(auto vb, make_buffer_of(device(), "two quads", rhi::BufferUsage::Vertex, vertices));
    LOOM_ASSIGN_OR_FAIL(auto ib, make_buffer_of(device(), "quad indices", rhi::BufferUsage::Index, indices));
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "indexed", rhi::Format::RGBA8Unorm, kSize, kSize));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("indexed", target, {0, 0, 0, 1}));
        list.set_pipeline(pipeline);
        list.set_vertex_buffer(0, vb);
        list.set_index_buffer(ib, rhi::IndexType::Uint16);
        list.push_constants_of(std::array<float, 4>{0, 0, 1, 1});
        list.draw_indexed(6, 1, 3, 4);  // base vertex 4: the right quad
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    for (uint32_t y = 0; y < kSize; y += 3) {
        for (uint32_t x = 0; x < kSize; x += 3) {
            const std::array<int, 4> expected = x >= kSize / 2 ? std::array<int, 4>{0, 0, 255, 255} : std::array<int, 4>{0, 0, 0, 255};
            ASSERT_EQ(rgba8_at(image, x, y), expected) << "pixel " << x << "," << y;
        }
    }
}

TEST_P(DrawTest, BuffersBoundBetweenDrawsTakeEffectAtTheNextDraw) {
    // Vertex and index buffers rebound between draws with nothing else recorded between them
    // (the path GL records as per-draw changes instead of a new vertex state): rebinding twice,
    // a slot the pipeline does not read, an empty draw between, 16- and 32-bit indices at an
    // offset, and a change made before a pipeline switch.
    LOOM_ASSIGN_OR_FAIL(auto pipeline, make_solid_pipeline(device(), rhi::Format::RGBA8Unorm));
    LOOM_ASSIGN_OR_FAIL(auto other_pipeline, make_solid_pipeline(device(), rhi::Format::RGBA8Unorm));
    // Four quads, one per quadrant (4 vertices of 12 bytes each): 0 x,y in [-1,0]; 1 x in
    // [0,1]; 2 y in [0,1]; 3 both.
    std::vector<float> quads;
    for (const auto& [x, y] : std::array<std::pair<float, float>, 4>{{{-1, -1}, {0, -1}, {-1, 0}, {0, 0}}}) {
        for (const auto& [dx, dy] : std::array<std::pair<float, float>, 4>{{{0, 0}, {1, 0}, {0, 1}, {1, 1}}}) {
            quads.insert(quads.end(), {x + dx, y + dy, 0});
        }
    }
    constexpr uint64_t kQuadBytes = 4 * 12;
    const std::vector<uint16_t> indices16 = {7, 7, 7, 0, 1, 2, 2, 1, 3};  // the quad from byte 6
    const std::vector<uint32_t> indices32 = {0, 1, 2, 2, 1, 3};
    const std::vector<float> unused = {0, 0, 0, 0};
    LOOM_ASSIGN_OR_FAIL(auto vb, make_buffer_of(device(), "quads", rhi::BufferUsage::Vertex, quads));
    LOOM_ASSIGN_OR_FAIL(auto unused_vb, make_buffer_of(device(), "unused", rhi::BufferUsage::Vertex, unused));
    LOOM_ASSIGN_OR_FAIL(auto ib16, make_buffer_of(device(), "indices16", rhi::BufferUsage::Index, indices16));
    LOOM_ASSIGN_OR_FAIL(auto ib32, make_buffer_of(device(), "indices32", rhi::BufferUsage::Index, indices32));
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "rebound", rhi::Format::RGBA8Unorm, kSize, kSize));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("rebound", target, {0, 0, 0, 1}));
        list.set_pipeline(pipeline);
        list.set_vertex_buffer(0, vb, 0 * kQuadBytes);
        list.set_index_buffer(ib16, rhi::IndexType::Uint16, 6);
        list.push_constants_of(std::array<float, 4>{1, 0, 0, 1});
        list.draw_indexed(6);  // quad 0, red
        list.set_vertex_buffer(0, vb, 1 * kQuadBytes);
        list.set_vertex_buffer(0, vb, 3 * kQuadBytes);  // the last binding counts
        list.set_index_buffer(ib32, rhi::IndexType::Uint32);
        list.push_constants_of(std::array<float, 4>{0, 1, 0, 1});
        list.draw_indexed(6);  // quad 3, green
        list.set_vertex_buffer(1, unused_vb);  // the pipeline reads slot 0 only
        list.set_vertex_buffer(0, vb, 1 * kQuadBytes);
        list.draw_indexed(0);  // draws nothing; the buffers stay bound for the next draw
        list.set_index_buffer(ib16, rhi::IndexType::Uint16, 6);
        list.push_constants_of(std::array<float, 4>{0, 0, 1, 1});
        list.draw_indexed(6);  // quad 1, blue
        list.set_vertex_buffer(0, vb, 2 * kQuadBytes);
        list.set_pipeline(other_pipeline);
        list.push_constants_of(std::array<float, 4>{1, 1, 1, 1});
        list.draw_indexed(6);  // quad 2, white, with the other pipeline
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    // Quad 0 covers NDC y in [-1, 0], the bottom half of the image (NDC y points up).
    const std::array<std::array<int, 4>, 4> expected = {{{255, 0, 0, 255}, {0, 0, 255, 255}, {255, 255, 255, 255}, {0, 255, 0, 255}}};
    for (uint32_t y = 1; y < kSize; y += 3) {
        for (uint32_t x = 1; x < kSize; x += 3) {
            const uint32_t quad = (x >= kSize / 2 ? 1 : 0) + (y < kSize / 2 ? 2 : 0);
            ASSERT_EQ(rgba8_at(image, x, y), expected[quad]) << "pixel " << x << "," << y << " (quad " << quad << ")";
        }
    }
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(DrawTest);

}  // namespace loom::test

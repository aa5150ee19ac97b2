#include "triangle_renderer.hpp"

#include <array>

#include "loom/shaders/builtin.hpp"

namespace loom::samples {

Result<TriangleRenderer> TriangleRenderer::create(rhi::Device& device, rhi::Format format) {
    TriangleRenderer renderer(device);
    auto vs_module = shaders::builtin("triangle.vert");
    if (!vs_module.ok()) return vs_module.take_error();
    auto fs_module = shaders::builtin("triangle.frag");
    if (!fs_module.ok()) return fs_module.take_error();
    auto vs = device.create_shader(*vs_module);
    if (!vs.ok()) return vs.take_error();
    auto fs = device.create_shader(*fs_module);
    if (!fs.ok()) {
        (void)device.destroy(*vs);
        return fs.take_error();
    }
    rhi::GraphicsPipelineDesc desc;
    desc.name = "triangle";
    desc.vertex = *vs;
    desc.fragment = *fs;
    // Interleaved: position (vec2) then colour (vec3), 20 bytes per vertex.
    desc.vertex_buffers = {rhi::VertexBufferLayout{
        20, rhi::VertexStepMode::PerVertex, {{0, rhi::VertexFormat::Float2, 0}, {1, rhi::VertexFormat::Float3, 8}}}};
    desc.color_formats = {format};
    auto pipeline = device.create_graphics_pipeline(desc);
    // The pipeline keeps what it needs from its shaders.
    (void)device.destroy(*vs);
    (void)device.destroy(*fs);
    if (!pipeline.ok()) return pipeline.take_error();
    renderer.pipeline_ = *pipeline;

    const std::array<float, 15> vertices = {
        -0.5f, -0.5f, 1.0f, 0.0f, 0.0f,  // bottom-left, red
        0.5f,  -0.5f, 0.0f, 1.0f, 0.0f,  // bottom-right, green
        0.0f,  0.5f,  0.0f, 0.0f, 1.0f,  // top, blue
    };
    const auto bytes = std::as_bytes(std::span(vertices));
    auto buffer = device.create_buffer(rhi::BufferDesc{"triangle vertices", bytes.size(), rhi::BufferUsage::Vertex});
    if (!buffer.ok()) return buffer.take_error();
    renderer.vertices_ = *buffer;
    LOOM_TRY(device.write_buffer(*buffer, 0, bytes));
    return renderer;
}

TriangleRenderer::TriangleRenderer(TriangleRenderer&& other) noexcept
    : device_(other.device_), pipeline_(other.pipeline_), vertices_(other.vertices_) {
    other.pipeline_ = {};
    other.vertices_ = {};
}

TriangleRenderer::~TriangleRenderer() {
    if (!pipeline_.is_null()) (void)device_->destroy(pipeline_);
    if (!vertices_.is_null()) (void)device_->destroy(vertices_);
}

void TriangleRenderer::record(rhi::CommandList& list, rhi::TextureHandle target) const {
    rhi::RenderPassDesc pass;
    pass.label = "triangle";
    rhi::ColorAttachment color;
    color.texture = target;
    color.clear = kTriangleBackground;
    pass.colors.push_back(color);
    list.begin_render_pass(pass);
    list.set_pipeline(pipeline_);
    list.set_vertex_buffer(0, vertices_);
    list.draw(3);
    list.end_render_pass();
}

}  // namespace loom::samples

#include "render_helpers.hpp"

#include "loom_test/test_support.hpp"

#include "loom/image_io/image_io.hpp"

namespace loom::test {

const char* const kPositionVert = R"(#version 450
layout(location = 0) in vec3 position;
void main() { gl_Position = vec4(position, 1.0); }
)";

const char* const kPushColorFrag = R"(#version 450
layout(push_constant) uniform Push { vec4 color; } pc;
layout(location = 0) out vec4 frag_color;
void main() { frag_color = pc.color; }
)";

Result<rhi::ShaderHandle> make_shader(rhi::Device& device, rhi::ShaderStage stage, const std::string& name,
                                      const std::string& code) {
    return shader_compiler::ShaderCompiler().create_shader(device, {name, stage, code, {}});
}

Result<rhi::BufferHandle> make_buffer(rhi::Device& device, const std::string& name, rhi::BufferUsage usage,
                                      std::span<const std::byte> data) {
    auto buffer = device.create_buffer(rhi::BufferDesc{name, data.size(), usage});
    if (!buffer.ok()) return buffer;
    LOOM_TRY(device.write_buffer(*buffer, 0, data));
    return buffer;
}

Result<rhi::TextureHandle> make_target(rhi::Device& device, const std::string& name, rhi::Format format, uint32_t width,
                                       uint32_t height, rhi::TextureUsage extra) {
    rhi::TextureDesc desc;
    desc.name = name;
    desc.format = format;
    desc.width = width;
    desc.height = height;
    const bool depth = rhi::format_info(format).is_depth_stencil();
    desc.usage = (depth ? rhi::TextureUsage::DepthStencilAttachment : rhi::TextureUsage::ColorAttachment) |
                 rhi::TextureUsage::CopySrc | rhi::TextureUsage::CopyDst | extra;
    return device.create_texture(desc);
}

Result<rhi::PipelineHandle> make_solid_pipeline(rhi::Device& device, rhi::Format color_format,
                                                const SolidPipelineOptions& options) {
    auto vs = make_shader(device, rhi::ShaderStage::Vertex, "position.vert", kPositionVert);
    if (!vs.ok()) return vs.take_error();
    auto fs = make_shader(device, rhi::ShaderStage::Fragment, "push_color.frag", kPushColorFrag);
    if (!fs.ok()) return fs.take_error();
    rhi::GraphicsPipelineDesc desc;
    desc.name = "solid";
    desc.vertex = *vs;
    desc.fragment = *fs;
    desc.vertex_buffers = {rhi::VertexBufferLayout{12, rhi::VertexStepMode::PerVertex, {{0, rhi::VertexFormat::Float3, 0}}}};
    desc.topology = options.topology;
    desc.raster.cull = options.cull;
    desc.depth = options.depth;
    desc.depth_format = options.depth_format;
    desc.color_formats = {color_format};
    auto pipeline = device.create_graphics_pipeline(desc);
    // The pipeline keeps what it needs; the shaders can go.
    (void)device.destroy(*vs);
    (void)device.destroy(*fs);
    return pipeline;
}

Status run_frame(rhi::Device& device, const std::function<void(rhi::CommandList&)>& record) {
    rhi::CommandList& list = device.begin_frame();
    record(list);
    return device.end_frame();
}

rhi::RenderPassDesc clear_pass(const std::string& label, rhi::TextureHandle color, std::array<double, 4> clear,
                               rhi::TextureHandle depth) {
    rhi::RenderPassDesc pass;
    pass.label = label;
    rhi::ColorAttachment attachment;
    attachment.texture = color;
    attachment.clear = clear;
    pass.colors.push_back(attachment);
    if (!depth.is_null()) {
        rhi::DepthAttachment d;
        d.texture = depth;
        d.clear_depth = 1.0f;
        pass.depth = d;
    }
    return pass;
}

std::array<int, 4> rgba8_at(const rhi::Image& image, uint32_t x, uint32_t y) {
    auto texel = image.texel(x, y);
    return {static_cast<int>(texel[0]), static_cast<int>(texel[1]), static_cast<int>(texel[2]), static_cast<int>(texel[3])};
}

void save_picture(const rhi::Image& image, const std::string& name) {
    const auto path = output_dir() / "render" / (name + ".png");
    auto status = image_io::write_png(image, path);
    EXPECT_TRUE(status.ok()) << status.error().to_string();
}

}  // namespace loom::test

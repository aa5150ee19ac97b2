#include "vulkan_test_support.hpp"

#include "loom/vulkan/vulkan_device.hpp"

namespace loom::test {

std::unique_ptr<rhi::Device> make_vulkan_device() {
    rhi::DeviceDesc desc;
    desc.backend = rhi::Backend::Vulkan;
    desc.headless = true;
    desc.debug = true;
    auto device = vulkan::create_vulkan_device(desc);
    EXPECT_TRUE(device.ok()) << device.error().to_string();
    return device.ok() ? std::move(*device) : nullptr;
}

Result<rhi::PipelineHandle> make_fill_pipeline(rhi::Device& device, rhi::Format format) {
    shader_compiler::ShaderCompiler compiler;
    auto vs = compiler.compile({"fill.vert", rhi::ShaderStage::Vertex, R"(#version 450
void main() {
    vec2 p = vec2(gl_VertexIndex == 1 ? 3.0 : -1.0, gl_VertexIndex == 2 ? 3.0 : -1.0);
    gl_Position = vec4(p, 0.5, 1.0);
})", {}});
    if (!vs.ok()) return vs.take_error();
    auto fs = compiler.compile({"fill.frag", rhi::ShaderStage::Fragment, R"(#version 450
layout(push_constant) uniform Push { vec4 color; } pc;
layout(location = 0) out vec4 frag_color;
void main() { frag_color = pc.color; })", {}});
    if (!fs.ok()) return fs.take_error();
    auto v = device.create_shader(*vs);
    if (!v.ok()) return v.take_error();
    auto f = device.create_shader(*fs);
    if (!f.ok()) return f.take_error();
    rhi::GraphicsPipelineDesc desc;
    desc.name = "fill";
    desc.vertex = *v;
    desc.fragment = *f;
    desc.color_formats = {format};
    auto pipeline = device.create_graphics_pipeline(desc);
    (void)device.destroy(*v);
    (void)device.destroy(*f);
    return pipeline;
}

Status record_frame(rhi::Device& device, const std::function<void(rhi::CommandList&)>& record) {
    rhi::CommandList& list = device.begin_frame();
    record(list);
    return device.end_frame();
}

void clear_and_fill(rhi::CommandList& list, rhi::TextureHandle target, rhi::PipelineHandle pipeline,
                    std::array<double, 4> clear, std::array<float, 4> fill, rhi::Rect rect) {
    rhi::RenderPassDesc pass;
    pass.label = "clear and fill";
    rhi::ColorAttachment color;
    color.texture = target;
    color.clear = clear;
    pass.colors.push_back(color);
    list.begin_render_pass(pass);
    list.set_pipeline(pipeline);
    list.set_scissor(rect);
    list.push_constants_of(fill);
    list.draw(3);
    list.end_render_pass();
}

}  // namespace loom::test

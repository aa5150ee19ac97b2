// docs/getting-started.md: the first graph, two passes of your own.
#include <array>

#include "snippets.hpp"

// [docs:includes]
#include "loom/framegraph/framegraph.hpp"   // FrameGraph, Pass, Executor, ...
#include "loom/rhi/device.hpp"              // rhi::Device, rhi::create_device
#include "loom/shader_compiler/shader_compiler.hpp"     // GLSL 450 -> SPIR-V (Vulkan) and GL GLSL
// [/docs:includes]

namespace loom::docs {

// [docs:shaders]
// A triangle that covers the whole target, without vertex buffers.
constexpr const char* kFullscreenVert = R"(#version 450
void main() {
    vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
})";

// Red grows with the column: x / 255 (exact in 8 bits), scaled by a push constant.
constexpr const char* kGradientFrag = R"(#version 450
layout(push_constant) uniform Params { vec4 scale; };
layout(location = 0) out vec4 color;
void main() { color = vec4(floor(gl_FragCoord.x) / 255.0, 0.0, 0.0, 1.0) * scale; })";

// 1 - the texel of the input at the same position.
constexpr const char* kInvertFrag = R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D source;
layout(location = 0) out vec4 color;
void main() { color = vec4(1.0 - texelFetch(source, ivec2(gl_FragCoord.xy), 0).rgb, 1.0); })";
// [/docs:shaders]

// [docs:pipeline]
/// A pipeline drawing a fullscreen triangle with `fragment` into one RGBA8 target.
Result<rhi::PipelineHandle> make_pipeline(rhi::Device& device, const char* name, const char* fragment) {
    shader_compiler::ShaderCompiler compiler;
    auto vs = compiler.compile({"fullscreen.vert", rhi::ShaderStage::Vertex, kFullscreenVert, {}});
    if (!vs) return vs.take_error();  // a ShaderCompile error with "file:line: message"
    auto fs = compiler.compile({name, rhi::ShaderStage::Fragment, fragment, {}});
    if (!fs) return fs.take_error();
    auto vertex = device.create_shader(*vs);
    if (!vertex) return vertex.take_error();
    auto pixel = device.create_shader(*fs);
    if (!pixel) return pixel.take_error();
    rhi::GraphicsPipelineDesc desc;
    desc.name = name;
    desc.vertex = *vertex;
    desc.fragment = *pixel;
    desc.color_formats = {rhi::Format::RGBA8Unorm};
    return device.create_graphics_pipeline(desc);
}
// [/docs:pipeline]

// [docs:pass-class]
/// A pass of your own: its ports are declared in the constructor, its work in execute().
class GradientPass : public fg::Pass {
public:
    explicit GradientPass(rhi::PipelineHandle pipeline) : Pass("gradient"), pipeline_(pipeline) {
        output("color", fg::TextureSpec::of(rhi::Format::RGBA8Unorm));  // frame-sized by default
    }

    Status execute(fg::PassContext& ctx) override {
        ctx.begin_render_pass({"color"});  // clears "color" (its first write in the frame)
        ctx.commands().set_pipeline(pipeline_);
        ctx.commands().push_constants_of(std::array<float, 4>{1.0f, 1.0f, 1.0f, 1.0f});
        ctx.commands().draw(3);
        ctx.end_render_pass();
        return {};
    }

private:
    rhi::PipelineHandle pipeline_;
};
// [/docs:pass-class]

// [docs:run]
Result<rhi::Image> render_first_graph(rhi::Device& device) {
    auto gradient = make_pipeline(device, "gradient.frag", kGradientFrag);
    if (!gradient) return gradient.take_error();
    auto invert = make_pipeline(device, "invert.frag", kInvertFrag);
    if (!invert) return invert.take_error();
    auto sampler = device.create_sampler({});
    if (!sampler) return sampler.take_error();

    fg::FrameGraph graph;
    LOOM_TRY(graph.add_pass(GradientPass(*gradient)));
    // A pass without a class: ports and a callback.
    LOOM_TRY(graph.add_pass(fg::Pass("invert")
                                .input("source")
                                .output("color", fg::TextureSpec::of(rhi::Format::RGBA8Unorm))
                                .on_execute([&](fg::PassContext& ctx) {
                                    ctx.begin_render_pass({"color"});
                                    ctx.commands().set_pipeline(*invert);
                                    // "source" is in ShaderRead already: the executor moved it.
                                    ctx.commands().set_bind_group(0, rhi::BindGroup{}.texture(0, ctx.texture("source"), *sampler));
                                    ctx.commands().draw(3);
                                    ctx.end_render_pass();
                                    return Status{};
                                })));
    LOOM_TRY(graph.connect(fg::port("gradient", "color"), fg::port("invert", "source")));
    LOOM_TRY(graph.mark_output(fg::port("invert", "color")));  // read after the frame

    fg::Executor executor(device);
    fg::PlanOptions options;
    options.frame = {256, 64};
    LOOM_TRY(executor.run_frame(graph, options));  // plan, create textures, record, submit
    return device.read_texture(executor.texture("invert", "color"));
}
// [/docs:run]

}  // namespace loom::docs

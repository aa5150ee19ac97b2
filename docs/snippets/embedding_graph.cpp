// The small graph the embedding snippets run (not shown in the guide): one pass drawing red
// into the top-left quadrant of the application's texture, bound to "ui"."target".
#include "embedding_graph.hpp"

#include "loom/shader_compiler/shader_compiler.hpp"

namespace loom::docs {
namespace {

constexpr const char* kFullscreenVert = R"(#version 450
void main() {
    vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
})";
constexpr const char* kRedFrag = R"(#version 450
layout(location = 0) out vec4 color;
void main() { color = vec4(1.0, 0.0, 0.0, 1.0); })";

}  // namespace

Result<std::unique_ptr<EmbeddingGraph>> EmbeddingGraph::create(rhi::Device& device, rhi::Format target_format) {
    auto out = std::make_unique<EmbeddingGraph>();
    shader_compiler::ShaderCompiler compiler;
    auto vs = compiler.compile({"fullscreen.vert", rhi::ShaderStage::Vertex, kFullscreenVert, {}});
    if (!vs) return vs.take_error();
    auto fs = compiler.compile({"red.frag", rhi::ShaderStage::Fragment, kRedFrag, {}});
    if (!fs) return fs.take_error();
    auto vertex = device.create_shader(*vs);
    if (!vertex) return vertex.take_error();
    auto pixel = device.create_shader(*fs);
    if (!pixel) return pixel.take_error();
    rhi::GraphicsPipelineDesc desc;
    desc.name = "red";
    desc.vertex = *vertex;
    desc.fragment = *pixel;
    desc.color_formats = {target_format};
    auto pipeline = device.create_graphics_pipeline(desc);
    if (!pipeline) return pipeline.take_error();
    const rhi::PipelineHandle red = *pipeline;
    fg::Pass ui("ui");
    ui.declare("target", fg::PortKind::InOut, fg::TextureSpec::of(target_format), /*optional=*/true);
    ui.on_execute([red](fg::PassContext& ctx) {
        const fg::Extent2D size = ctx.extent("target");
        ctx.begin_render_pass({"target"});  // an imported optional inout: loads the application's picture
        ctx.commands().set_pipeline(red);
        ctx.commands().set_viewport({0.0f, 0.0f, static_cast<float>(size.width / 2), static_cast<float>(size.height / 2)});
        ctx.commands().set_scissor({0, 0, size.width / 2, size.height / 2});
        ctx.commands().draw(3);
        ctx.end_render_pass();
        return Status{};
    });
    LOOM_TRY(out->graph.add_pass(std::move(ui)));
    LOOM_TRY(out->graph.mark_output(fg::port("ui", "target")));
    return out;
}

}  // namespace loom::docs

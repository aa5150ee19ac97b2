#include "overlay_graph.hpp"

#include "loom/shader_compiler/shader_compiler.hpp"

namespace loom::samples {
namespace {

// A triangle covering the viewport, without vertex buffers.
constexpr const char* kFullscreenVert = R"(#version 450
void main() {
    vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

constexpr const char* kPatternFrag = R"(#version 450
layout(location = 0) out vec4 color;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    color = vec4(float(p.x % 16) / 15.0, float(p.y % 16) / 15.0, float((p.x / 16 + p.y / 16) % 2), 1.0);
}
)";

constexpr const char* kOverlayFrag = R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D pattern;
layout(location = 0) out vec4 color;
void main() {
    color = texelFetch(pattern, ivec2(gl_FragCoord.xy), 0);
}
)";

}  // namespace

Result<std::unique_ptr<OverlayGraph>> OverlayGraph::create(rhi::Device& device, rhi::Format target_format) {
    std::unique_ptr<OverlayGraph> overlay(new OverlayGraph(device));
    LOOM_TRY(overlay->build(target_format));
    return overlay;
}

Status OverlayGraph::build(rhi::Format target_format) {
    shader_compiler::ShaderCompiler compiler;
    auto vs = compiler.create_shader(device_, {"fullscreen.vert", rhi::ShaderStage::Vertex, kFullscreenVert, {}});
    if (!vs) return vs.take_error();
    vertex_ = *vs;
    auto pattern_fs = compiler.create_shader(device_, {"pattern.frag", rhi::ShaderStage::Fragment, kPatternFrag, {}});
    if (!pattern_fs) return pattern_fs.take_error();
    pattern_fragment_ = *pattern_fs;
    auto overlay_fs = compiler.create_shader(device_, {"overlay.frag", rhi::ShaderStage::Fragment, kOverlayFrag, {}});
    if (!overlay_fs) return overlay_fs.take_error();
    overlay_fragment_ = *overlay_fs;

    rhi::GraphicsPipelineDesc desc;
    desc.name = "pattern";
    desc.vertex = vertex_;
    desc.fragment = pattern_fragment_;
    desc.color_formats = {rhi::Format::RGBA8Unorm};
    auto pattern = device_.create_graphics_pipeline(desc);
    if (!pattern) return pattern.take_error();
    pattern_ = *pattern;
    desc.name = "overlay";
    desc.fragment = overlay_fragment_;
    desc.color_formats = {target_format};
    auto overlay = device_.create_graphics_pipeline(desc);
    if (!overlay) return overlay.take_error();
    overlay_ = *overlay;
    rhi::SamplerDesc nearest;
    nearest.name = "nearest";
    nearest.min_filter = nearest.mag_filter = rhi::Filter::Nearest;
    auto sampler = device_.create_sampler(nearest);
    if (!sampler) return sampler.take_error();
    sampler_ = *sampler;

    const rhi::PipelineHandle pattern_pipeline = pattern_, overlay_pipeline = overlay_;
    const rhi::SamplerHandle sampler_handle = sampler_;
    LOOM_TRY(graph_.add_pass(fg::Pass("pattern")
                                 .output("color", fg::TextureSpec::of(rhi::Format::RGBA8Unorm))
                                 .on_execute([pattern_pipeline](fg::PassContext& ctx) {
                                     // Every texel is written: no clear needed first.
                                     fg::ColorPort color("color");
                                     color.writes_every_texel = true;
                                     ctx.begin_render_pass({color});
                                     ctx.commands().set_pipeline(pattern_pipeline);
                                     ctx.commands().draw(3);
                                     ctx.end_render_pass();
                                     return Status{};
                                 })));
    fg::Pass overlay_pass("overlay");
    overlay_pass.input("pattern", fg::TextureSpec::of(rhi::Format::RGBA8Unorm))
        .declare("target", fg::PortKind::InOut, fg::TextureSpec::of(target_format), /*optional=*/true)
        .on_execute([overlay_pipeline, sampler_handle](fg::PassContext& ctx) {
            // The target is the engine's: its contents are loaded, and only the quadrant is drawn.
            const fg::Extent2D size = ctx.extent("target");
            ctx.begin_render_pass({"target"});
            auto& cmd = ctx.commands();
            cmd.set_pipeline(overlay_pipeline);
            cmd.set_viewport({0.0f, 0.0f, static_cast<float>(size.width / 2), static_cast<float>(size.height / 2)});
            cmd.set_scissor({0, 0, size.width / 2, size.height / 2});
            cmd.set_bind_group(0, rhi::BindGroup{}.texture(0, ctx.texture("pattern"), sampler_handle));
            cmd.draw(3);
            ctx.end_render_pass();
            return Status{};
        });
    LOOM_TRY(graph_.add_pass(std::move(overlay_pass)));
    LOOM_TRY(graph_.connect(fg::port("pattern", "color"), fg::port("overlay", "pattern")));
    LOOM_TRY(graph_.mark_output(target_port()));
    return {};
}

OverlayGraph::~OverlayGraph() {
    for (rhi::PipelineHandle p : {overlay_, pattern_}) {
        if (p) (void)device_.destroy(p);
    }
    if (sampler_) (void)device_.destroy(sampler_);
    for (rhi::ShaderHandle s : {overlay_fragment_, pattern_fragment_, vertex_}) {
        if (s) (void)device_.destroy(s);
    }
}

}  // namespace loom::samples

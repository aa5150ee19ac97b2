#include "loom/passes/parts.hpp"

namespace loom::passes {
namespace {

constexpr rhi::ShaderStage kVertex = rhi::ShaderStage::Vertex;
constexpr rhi::ShaderStage kFragment = rhi::ShaderStage::Fragment;

}  // namespace

fg::TextureSpec depth_spec(const PassConfig& config) {
    fg::TextureSpec spec = fg::TextureSpec::of(rhi::Format::Depth32F);
    if (config.capturable) spec = spec.with_usage(rhi::TextureUsage::CopySrc);
    return spec;
}

PassPart fullscreen_part() {
    PassPart part("fullscreen");
    part.shader.stage_file(kVertex, "loom/parts/fullscreen.vert.glsl");
    return part;
}

PassPart camera_part() {
    PassPart part("camera", 1);
    part.shader.stage_file(kVertex, "loom/parts/camera.vert.glsl").stage_file(kFragment, "loom/parts/camera.frag.glsl");
    return part;
}

PassPart gbuffer_part(const PassConfig& config) {
    PassPart part("g-buffer");
    const fg::TextureSpec color = color_spec(config);
    part.ports.output("position", color).output("normal", color).output("albedo", color);
    part.ports.output("depth", depth_spec(config).with_scale(1.0f));
    part.shader.stage_file(kFragment, "loom/parts/gbuffer.frag.glsl");
    return part;
}

PassPart shadow_caster_part(const PassConfig& config, uint32_t map_size) {
    PassPart part("shadow-caster", 1);
    part.ports.output("shadow_map", depth_spec(config).with_size(map_size, map_size));
    part.shader.stage_file(kVertex, "loom/parts/shadow_caster.vert.glsl")
        .stage_file(kFragment, "loom/parts/shadow_caster.frag.glsl");
    return part;
}

PassPart deferred_render_part(const PassConfig& config) {
    PassPart part("deferred-render", 4);
    const fg::TextureSpec color = color_spec(config);
    part.ports.input("position", color).input("normal", color).input("albedo", color).output("color", color);
    part.shader.stage_file(kFragment, "loom/parts/deferred_render.frag.glsl");
    return part;
}

PassPart shadow_render_part(const PassConfig& config) {
    PassPart part("shadow-render", 2);
    // The receiver asks for a depth map of any size: the shadow-map pass decides it.
    part.ports.input("shadow_map", fg::TextureSpec::of(rhi::Format::Depth32F)).output("color", color_spec(config));
    part.shader.stage_file(kFragment, "loom/parts/shadow_render.frag.glsl");
    return part;
}

PassPart high_pass_render_part(const PassConfig& config) {
    PassPart part("high-pass-render", 1);
    part.ports.output("high_pass", color_spec(config));
    part.shader.stage_file(kFragment, "loom/parts/high_pass_render.frag.glsl");
    return part;
}

PassPart forward_render_part(const PassConfig& config) {
    PassPart part("forward-render", 1);
    part.ports.output("color", color_spec(config)).output("depth", depth_spec(config).with_scale(1.0f));
    part.shader.stage_file(kFragment, "loom/parts/forward_render.frag.glsl");
    return part;
}

PassPart gaussian_blur_part(const PassConfig& config) {
    PassPart part("gaussian-blur", 2);
    const fg::TextureSpec color = color_spec(config);
    part.ports.input("previous_pass", color).output("color", color);
    part.shader.stage_file(kFragment, "loom/parts/gaussian_blur.frag.glsl");
    return part;
}

PassPart composite_part(const PassConfig& config) {
    PassPart part("composite", 3);
    const fg::TextureSpec color = color_spec(config);
    part.ports.input("color", color).input("bloom", color).output("final", color);
    part.shader.stage_file(kFragment, "loom/parts/composite.frag.glsl");
    return part;
}

PassPart blit_part(const PassConfig& config, const fg::TextureSpec& target_spec) {
    PassPart part("blit", 1);
    part.ports.input("source", color_spec(config)).output("target", target_spec);
    part.shader.stage_file(kFragment, "loom/parts/blit.frag.glsl");
    return part;
}

PassPart color_source_part(const PassConfig& config) {
    PassPart part("color-source", 1);
    part.ports.input("source", color_spec(config));
    part.shader.stage_file(kFragment, "loom/parts/color_source.frag.glsl");
    return part;
}

}  // namespace loom::passes

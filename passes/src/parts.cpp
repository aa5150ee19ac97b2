#include "loom/passes/parts.hpp"

#include <string>

namespace loom::passes {
namespace {

constexpr rhi::ShaderStage kVertex = rhi::ShaderStage::Vertex;
constexpr rhi::ShaderStage kFragment = rhi::ShaderStage::Fragment;

using Options = PartOptions;

// The part table. A row: name, resources, vertex file, fragment file, ports. The ports keep the
// order in which each part declared them before the table (a pass's ports are in that order).
constexpr PartDesc kParts[] = {
    // ---- pass parts ----
    {"fullscreen", 0, "loom/parts/fullscreen.vert.glsl", {}, nullptr},
    {"camera", 1, "loom/parts/camera.vert.glsl", "loom/parts/camera.frag.glsl", nullptr},
    {"g-buffer", 0, {}, "loom/parts/gbuffer.frag.glsl",
     [](fg::PortSet& ports, const Options& o) {
         const fg::TextureSpec color = color_spec(o.config);
         ports.output("position", color).output("normal", color).output("albedo", color).output("emission", color);
         ports.output("depth", depth_spec(o.config).with_scale(1.0f));
     }},
    {"shadow-caster", 1, "loom/parts/shadow_caster.vert.glsl", "loom/parts/shadow_caster.frag.glsl",
     [](fg::PortSet& ports, const Options& o) {
         ports.output("shadow_map", depth_spec(o.config).with_size(o.shadow_map_size, o.shadow_map_size));
     }},
    {"deferred-render", 5, {}, "loom/parts/deferred_render.frag.glsl",
     [](fg::PortSet& ports, const Options& o) {
         const fg::TextureSpec color = color_spec(o.config);
         ports.input("position", color).input("normal", color).input("albedo", color).input("emission", color).output("color", color);
     }},
    // The receiver asks for a depth map of any size: the shadow-map pass decides it.
    {"shadow-render", 2, {}, "loom/parts/shadow_render.frag.glsl",
     [](fg::PortSet& ports, const Options& o) {
         ports.input("shadow_map", fg::TextureSpec::of(rhi::Format::Depth32F)).output("color", color_spec(o.config));
     }},
    {"high-pass-render", 1, {}, "loom/parts/high_pass_render.frag.glsl",
     [](fg::PortSet& ports, const Options& o) { ports.output("high_pass", color_spec(o.config)); }},
    // No ports: the pass that draws the sky owns the attachments.
    {"sky-render", 2, {}, "loom/parts/sky_render.frag.glsl", nullptr},
    {"forward-render", 1, {}, "loom/parts/forward_render.frag.glsl",
     [](fg::PortSet& ports, const Options& o) {
         ports.output("color", color_spec(o.config)).output("depth", depth_spec(o.config).with_scale(1.0f));
     }},
    {"gaussian-blur", 2, {}, "loom/parts/gaussian_blur.frag.glsl",
     [](fg::PortSet& ports, const Options& o) {
         const fg::TextureSpec color = color_spec(o.config);
         ports.input("previous_pass", color).output("color", color);
     }},
    {"composite", 3, {}, "loom/parts/composite.frag.glsl",
     [](fg::PortSet& ports, const Options& o) {
         const fg::TextureSpec color = color_spec(o.config);
         ports.input("color", color).input("bloom", color).output("final", color);
     }},
    {"blit", 1, {}, "loom/parts/blit.frag.glsl",
     [](fg::PortSet& ports, const Options& o) {
         ports.input("source", color_spec(o.config)).output("target", o.blit_target);
     }},
    {"color-source", 1, {}, "loom/parts/color_source.frag.glsl",
     [](fg::PortSet& ports, const Options& o) { ports.input("source", color_spec(o.config)); }},
    // loom::renderer's transparent pass: blends onto the lit frame (lighting uniforms).
    {"blend-render", 1, {}, "loom/parts/blend_render.frag.glsl",
     [](fg::PortSet& ports, const Options& o) {
         ports.inout("color", color_spec(o.config)).inout("depth", depth_spec(o.config).with_scale(1.0f));
     }},
    // loom::renderer's masked shadow pass: the shadow map of any size, drawn onto in place.
    {"masked-shadow-caster", 0, {}, "loom/parts/masked_shadow_caster.frag.glsl",
     [](fg::PortSet& ports, const Options& o) { ports.inout("shadow_map", depth_spec(o.config)); }},

    // ---- object parts (no ports) ----
    {"mesh-geometry", 1, "loom/parts/mesh_geometry.vert.glsl", "loom/parts/mesh_geometry.frag.glsl", nullptr},
    {"pbr-material", 0, {}, "loom/parts/pbr_material.frag.glsl", nullptr},
    {"checker-material", 0, {}, "loom/parts/checker_material.frag.glsl", nullptr},
    {"retained-mesh", 2, "loom/parts/retained_mesh.vert.glsl", "loom/parts/retained_mesh.frag.glsl", nullptr},
    {"gltf-geometry", 1, "loom/parts/gltf_geometry.vert.glsl", "loom/parts/gltf_geometry.frag.glsl", nullptr},
    // "gltf-geometry" for a RetainedScene: the record buffer and the material's set.
    {"retained-gltf-geometry", 2, "loom/parts/retained_gltf_geometry.vert.glsl",
     "loom/parts/retained_gltf_geometry.frag.glsl", nullptr},
    // The skinned variants: the joint palette besides (gltf_skinning.glsl).
    {"gltf-skinned-geometry", 2, "loom/parts/gltf_skinned_geometry.vert.glsl",
     "loom/parts/gltf_skinned_geometry.frag.glsl", nullptr},
    {"retained-gltf-skinned-geometry", 3, "loom/parts/retained_gltf_skinned_geometry.vert.glsl",
     "loom/parts/retained_gltf_skinned_geometry.frag.glsl", nullptr},
    // One sampler per glTF texture (kSamplers in renderer/src/gltf_object.cpp).
    {"gltf-material", 5, {}, "loom/parts/gltf_material.frag.glsl", nullptr},
};

std::string standard_part_names() {
    std::string out;
    for (const PartDesc& desc : kParts) {
        if (!out.empty()) out += ", ";
        out += desc.name;
    }
    return out;
}

}  // namespace

std::span<const PartDesc> standard_parts() { return kParts; }

PassPart make_part(const PartDesc& desc, const PartOptions& options) {
    PassPart part(std::string(desc.name), desc.bindings);
    if (desc.declare_ports) desc.declare_ports(part.ports, options);
    if (!desc.vertex_file.empty()) part.shader.stage_file(kVertex, desc.vertex_file);
    if (!desc.fragment_file.empty()) part.shader.stage_file(kFragment, desc.fragment_file);
    return part;
}

PassPart standard_part(std::string_view name, const PartOptions& options) {
    for (const PartDesc& desc : kParts) {
        if (desc.name == name) return make_part(desc, options);
    }
    // Reported when a program is composed with it, as a file that is not embedded is
    // (ShaderPart::stage_file): callers such as pass constructors have no error path.
    PassPart part{std::string(name)};
    part.shader.set_problem("no row of the part table has this name (its rows: " + standard_part_names() + ")");
    return part;
}

fg::TextureSpec depth_spec(const PassConfig& config) {
    fg::TextureSpec spec = fg::TextureSpec::of(rhi::Format::Depth32F);
    if (config.capturable) spec = spec.with_usage(rhi::TextureUsage::CopySrc);
    return spec;
}

PassPart fullscreen_part() { return standard_part("fullscreen"); }

PassPart camera_part() { return standard_part("camera"); }

PassPart gbuffer_part(const PassConfig& config) { return standard_part("g-buffer", {.config = config}); }

PassPart shadow_caster_part(const PassConfig& config, uint32_t map_size) {
    return standard_part("shadow-caster", {.config = config, .shadow_map_size = map_size});
}

PassPart deferred_render_part(const PassConfig& config) { return standard_part("deferred-render", {.config = config}); }

PassPart shadow_render_part(const PassConfig& config) { return standard_part("shadow-render", {.config = config}); }

PassPart high_pass_render_part(const PassConfig& config) {
    return standard_part("high-pass-render", {.config = config});
}

PassPart forward_render_part(const PassConfig& config) { return standard_part("forward-render", {.config = config}); }

PassPart sky_render_part() { return standard_part("sky-render"); }

PassPart gaussian_blur_part(const PassConfig& config) { return standard_part("gaussian-blur", {.config = config}); }

PassPart composite_part(const PassConfig& config) { return standard_part("composite", {.config = config}); }

PassPart blit_part(const PassConfig& config, const fg::TextureSpec& target_spec) {
    return standard_part("blit", {.config = config, .blit_target = target_spec});
}

PassPart color_source_part(const PassConfig& config) { return standard_part("color-source", {.config = config}); }

}  // namespace loom::passes

#pragma once
// The standard parts: every part whose code is a file under shaders/include/loom/parts/, in one
// table (the rows of standard_parts(), written in passes/src/parts.cpp): each part's name, the
// number of resources it declares, its code file per stage, and the ports it declares. Pass
// parts declare ports; object parts (the code of object kinds) declare none.
//
// Adding a part is two files: its .glsl file under shaders/include/loom/parts/ (embedded by a
// glob in shaders/CMakeLists.txt) and its row in the table. It is then standard_part("name").
//
// The paper's Listings 3-5 are "deferred-render", "shadow-render" and "high-pass-render": a pass
// built from all three has the union of their ports and a program composed of their code.

#include <cstdint>
#include <span>
#include <string_view>

#include "loom/framegraph/pass.hpp"
#include "loom/framegraph/texture_spec.hpp"
#include "loom/passes/shader_part.hpp"
#include "loom/passes/shader_pass.hpp"

namespace loom::passes {

/// What the ports of a standard part may depend on.
struct PartOptions {
    PassConfig config;
    /// "shadow-caster": its shadow_map is shadow_map_size x shadow_map_size.
    uint32_t shadow_map_size = 2048;
    /// "blit": the spec of its target (RGBA8Unorm at the frame size).
    fg::TextureSpec blit_target = fg::TextureSpec::of(rhi::Format::RGBA8Unorm).with_scale(1.0f);
};

/// One row of the part table: how to make a part.
struct PartDesc {
    std::string_view name;
    /// The resources the part declares: LOOM_BINDING(0) to LOOM_BINDING(bindings - 1).
    uint32_t bindings = 0;
    /// The embedded files (shaders::include_files() names, "loom/parts/...") of its vertex and
    /// fragment code; empty where the part has no code for the stage.
    std::string_view vertex_file;
    std::string_view fragment_file;
    /// Declares the part's ports; null for a part that declares none.
    void (*declare_ports)(fg::PortSet& ports, const PartOptions& options) = nullptr;
};

/// The part table: pass parts first, then object parts.
std::span<const PartDesc> standard_parts();

/// The part `desc` describes, with its ports for `options`. A file that is not embedded is the
/// part's problem (ShaderPart::stage_file): composing a program with the part fails with an
/// InvalidArgument error naming the part and the file.
PassPart make_part(const PartDesc& desc, const PartOptions& options = {});

/// The standard part called `name`: make_part() of its row. A name that is not in the table
/// gives a part without ports or code whose problem names it and lists the table's names, so
/// that the first program composed with it fails (InvalidArgument) saying so. It returns no
/// error itself, so that pass constructors and object kinds can call it.
PassPart standard_part(std::string_view name, const PartOptions& options = {});

/// The spec of depth ports: Depth32F (the scene depth is frame-sized; the shadow map sets its
/// own absolute size). CopySrc when capturable.
fg::TextureSpec depth_spec(const PassConfig& config);

// Shortcuts for the rows the standard passes use (each is standard_part() of its name); a new
// part needs none.

/// "fullscreen": the vertex stage of post-process passes (no ports, no resources).
PassPart fullscreen_part();
/// "camera": places object vertices in front of the camera (CameraUniforms) and interpolates
/// the surface for the fragment stage; no ports.
PassPart camera_part();
/// "g-buffer": outputs position, normal, albedo, emission (colour spec) and depth.
PassPart gbuffer_part(const PassConfig& config);
/// "shadow-caster": depth of objects seen from the light (ShadowCasterUniforms); output
/// shadow_map (Depth32F, map_size x map_size).
PassPart shadow_caster_part(const PassConfig& config, uint32_t map_size);
/// "deferred-render" (Listing 3): inputs position, normal, albedo, emission; output color.
/// Lights the G-buffer (LightingUniforms, gbuffer_position/normal/albedo/emission).
PassPart deferred_render_part(const PassConfig& config);
/// "shadow-render" (Listing 4): input shadow_map, output color. Provides shadow_visibility()
/// (ShadowUniforms, shadow_map).
PassPart shadow_render_part(const PassConfig& config);
/// "high-pass-render" (Listing 5): output high_pass. Provides emit_high_pass()
/// (HighPassUniforms).
PassPart high_pass_render_part(const PassConfig& config);
/// "forward-render": lights objects as they are drawn (LightingUniforms); outputs color and
/// depth.
PassPart forward_render_part(const PassConfig& config);
/// "sky-render": the deferred pass's sky, full screen (LightingUniforms, SkyUniforms: the
/// target's size); no ports. The forward pass draws it behind its objects.
PassPart sky_render_part();
/// "gaussian-blur": input previous_pass, output color (BlurUniforms, source).
PassPart gaussian_blur_part(const PassConfig& config);
/// "composite": inputs color and bloom, output final (CompositeUniforms, color, bloom).
PassPart composite_part(const PassConfig& config);
/// "blit": input source, output target with `target_spec` (source).
PassPart blit_part(const PassConfig& config, const fg::TextureSpec& target_spec);
/// "color-source": input source; hands every texel to the high-pass part (source).
PassPart color_source_part(const PassConfig& config);

}  // namespace loom::passes

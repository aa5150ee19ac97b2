#pragma once
// The standard pass parts: ports (fg::PortSet) and shader code (shaders/include/loom/parts/) under
// one name. The paper's Listings 3-5 are deferred_render_part, shadow_render_part and
// high_pass_render_part; a pass built from all three has the union of their ports and a program
// composed of their code.

#include "loom/framegraph/texture_spec.hpp"
#include "loom/passes/shader_part.hpp"
#include "loom/passes/shader_pass.hpp"

namespace loom::passes {

/// The spec of depth ports: Depth32F (the scene depth is frame-sized; the shadow map sets its
/// own absolute size). CopySrc when capturable.
fg::TextureSpec depth_spec(const PassConfig& config);

/// "fullscreen": the vertex stage of post-process passes (no ports, no resources).
PassPart fullscreen_part();
/// "camera": places object vertices in front of the camera (CameraUniforms) and interpolates
/// the surface for the fragment stage; no ports.
PassPart camera_part();
/// "g-buffer": outputs position, normal, albedo (colour spec) and depth.
PassPart gbuffer_part(const PassConfig& config);
/// "shadow-caster": depth of objects seen from the light (ShadowCasterUniforms); output
/// shadow_map (Depth32F, map_size x map_size).
PassPart shadow_caster_part(const PassConfig& config, uint32_t map_size);
/// "deferred-render" (Listing 3): inputs position, normal, albedo; output color. Lights the
/// G-buffer (LightingUniforms, gbuffer_position/normal/albedo).
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
/// "gaussian-blur": input previous_pass, output color (BlurUniforms, source).
PassPart gaussian_blur_part(const PassConfig& config);
/// "composite": inputs color and bloom, output final (CompositeUniforms, color, bloom).
PassPart composite_part(const PassConfig& config);
/// "blit": input source, output target with `target_spec` (source).
PassPart blit_part(const PassConfig& config, const fg::TextureSpec& target_spec);
/// "color-source": input source; hands every texel to the high-pass part (source).
PassPart color_source_part(const PassConfig& config);

}  // namespace loom::passes

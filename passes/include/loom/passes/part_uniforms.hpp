#pragma once
// C++ mirrors of the std140 uniform blocks that the standard shader parts declare
// (shaders/include/loom/parts/ and loom/passes/lighting.glsl), how they are filled from a
// SceneView, and the sampler the shadow-receiving part expects. Public so that passes built
// outside loom::passes from the same parts (a glTF transparent pass, a masked shadow pass) bind
// exactly what the standard passes bind. Sizes are checked against reflection whenever a block
// is bound (Bindings::uniforms).

#include <cstdint>

#include <glm/glm.hpp>

#include "loom/passes/view.hpp"
#include "loom/rhi/descriptions.hpp"

namespace loom::passes {

/// "camera" part: places vertices in front of the camera.
struct CameraUniforms {
    glm::mat4 view_projection;
    glm::vec4 camera_position;
};

/// "shadow-caster" part: depth as seen from the light.
struct ShadowCasterUniforms {
    glm::mat4 light_view_projection;
};

/// "deferred-render" and "forward-render" parts: the sun, the sky and the fog.
struct LightingUniforms {
    glm::mat4 inverse_view_projection;
    glm::vec4 camera_position;
    glm::vec4 light_direction;
    glm::vec4 light_radiance;
    glm::vec4 sky_radiance;
    glm::vec4 horizon_radiance;
    glm::vec4 ground_radiance;
    glm::vec4 fog;  // density, start distance
};

/// "shadow-render" part: how the shadow map is read.
struct ShadowUniforms {
    glm::mat4 light_view_projection;
    glm::vec4 params;  // 1 / map size, normal offset, depth bias, PCF radius
};

/// "high-pass" part.
struct HighPassUniforms {
    glm::vec4 params;  // threshold
};

static_assert(sizeof(CameraUniforms) == 80 && sizeof(ShadowCasterUniforms) == 64 && sizeof(LightingUniforms) == 176 &&
              sizeof(ShadowUniforms) == 80 && sizeof(HighPassUniforms) == 16);

/// The camera block for `camera`.
CameraUniforms camera_uniforms(const scene::CameraMatrices& camera);
/// The lighting block for `view` (its camera, light and environment).
LightingUniforms lighting_uniforms(const SceneView& view);
/// The shadow-receiving block for `settings` and a square shadow map of `map_size` texels.
ShadowUniforms shadow_uniforms(const ShadowSettings& settings, uint32_t map_size);
/// The sampler the "shadow-render" part reads the shadow map with: bilinear depth comparison
/// (LessEqual), clamped.
rhi::SamplerDesc shadow_comparison_sampler_desc();

}  // namespace loom::passes

#pragma once
// C++ mirrors of the std140 uniform blocks of the standard pass parts (shaders/include/loom/
// parts/ and loom/passes/lighting.glsl), and how they are filled from a SceneView. Sizes are
// checked against reflection whenever a block is bound (Bindings::uniforms).

#include <cstdint>

#include <glm/glm.hpp>

#include "loom/passes/shader_pass.hpp"
#include "loom/passes/view.hpp"

namespace loom::passes::detail {

struct CameraUniforms {
    glm::mat4 view_projection;
    glm::vec4 camera_position;
};

struct ShadowCasterUniforms {
    glm::mat4 light_view_projection;
};

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

struct ShadowUniforms {
    glm::mat4 light_view_projection;
    glm::vec4 params;  // 1 / map size, normal offset, depth bias, PCF radius
};

struct HighPassUniforms {
    glm::vec4 params;  // threshold
};

inline constexpr uint32_t kMaxBlurWeights = 64;

struct BlurUniforms {
    int32_t params[4];  // radius, direction x, direction y, unused
    float weights[kMaxBlurWeights];  // as vec4[16]: weight i at [i / 4][i % 4]
};

struct CompositeUniforms {
    glm::vec4 params;  // exposure, bloom strength, encode sRGB
};

static_assert(sizeof(CameraUniforms) == 80 && sizeof(ShadowCasterUniforms) == 64 && sizeof(LightingUniforms) == 176 &&
              sizeof(ShadowUniforms) == 80 && sizeof(HighPassUniforms) == 16 && sizeof(BlurUniforms) == 272 &&
              sizeof(CompositeUniforms) == 16);

CameraUniforms camera_uniforms(const Camera& camera);
LightingUniforms lighting_uniforms(const SceneView& view);

/// Binds what the "shadow-render" part declares: ShadowUniforms and the shadow map with a
/// comparison sampler.
Status bind_shadow_receiver(Bindings& set, const ShadowSettings& settings, rhi::TextureHandle shadow_map,
                            uint32_t map_size, rhi::SamplerHandle comparison_sampler);

/// The sampler the "shadow-render" part reads the shadow map with: bilinear depth comparison
/// (LessEqual), clamped.
rhi::SamplerDesc shadow_comparison_sampler_desc();

}  // namespace loom::passes::detail

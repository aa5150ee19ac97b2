#pragma once
// C++ mirrors of the std140 uniform blocks of the standard pass parts the transparent pass is
// composed of ("camera", loom/passes/lighting.glsl, "shadow-render", "high-pass-render"), filled
// as the standard passes fill them. loom::passes keeps its own mirrors private
// (passes/src/uniforms.hpp); Bindings checks every size against reflection when binding, so a
// block that changes there fails loudly here instead of drawing garbage.

#include <glm/glm.hpp>

#include "loom/passes/view.hpp"

namespace loom::scene_objects::detail {

struct CameraUniforms {
    glm::mat4 view_projection;
    glm::vec4 camera_position;
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

static_assert(sizeof(CameraUniforms) == 80 && sizeof(LightingUniforms) == 176 && sizeof(ShadowUniforms) == 80 &&
              sizeof(HighPassUniforms) == 16);

inline CameraUniforms camera_uniforms(const passes::Camera& camera) {
    return CameraUniforms{camera.view_projection(), glm::vec4(camera.position, 1.0f)};
}

inline LightingUniforms lighting_uniforms(const passes::SceneView& view) {
    LightingUniforms u;
    u.inverse_view_projection = glm::inverse(view.camera.view_projection());
    u.camera_position = glm::vec4(view.camera.position, 1.0f);
    u.light_direction = glm::vec4(glm::normalize(view.light.direction), 0.0f);
    u.light_radiance = glm::vec4(view.light.color * view.light.intensity, 0.0f);
    u.sky_radiance = glm::vec4(view.environment.sky, 0.0f);
    u.horizon_radiance = glm::vec4(view.environment.horizon, 0.0f);
    u.ground_radiance = glm::vec4(view.environment.ground, 0.0f);
    u.fog = glm::vec4(view.environment.fog_density, view.environment.fog_start, 0.0f, 0.0f);
    return u;
}

inline ShadowUniforms shadow_uniforms(const passes::ShadowSettings& settings, uint32_t map_size) {
    return ShadowUniforms{settings.light_view_projection,
                          glm::vec4(1.0f / static_cast<float>(map_size == 0 ? 1 : map_size), settings.normal_offset,
                                    settings.depth_bias, static_cast<float>(settings.pcf_radius))};
}

}  // namespace loom::scene_objects::detail

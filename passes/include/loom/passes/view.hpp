#pragma once
// What the standard passes need to know about the frame besides their textures: the camera,
// the directional light, the sky, and the light's view for shadow mapping.

#include <cstdint>

#include <glm/glm.hpp>

#include "loom/scene/bounds.hpp"
#include "loom/scene/camera.hpp"

namespace loom::passes {

/// A light infinitely far away (the sun).
struct DirectionalLight {
    glm::vec3 direction{0.0f, 1.0f, 0.0f};  ///< unit vector from the scene towards the light
    glm::vec3 color{1.0f};                  ///< linear RGB
    float intensity = 3.0f;                 ///< radiance scale of `color`
};

/// Ambient light, the sky seen behind the scene, and fog.
struct Environment {
    glm::vec3 sky{0.16f, 0.30f, 0.62f};      ///< zenith; ambient light from above
    glm::vec3 horizon{0.62f, 0.66f, 0.72f};  ///< horizon, and the colour of fog
    glm::vec3 ground{0.42f, 0.40f, 0.36f};   ///< light bounced up from the (sunlit) ground
    /// Fog: a surface d world units from the eye fades to the horizon by
    /// 1 - exp(-((d - fog_start) * fog_density)^2) (nothing nearer than fog_start).
    float fog_density = 0.0f;
    float fog_start = 0.0f;
};

/// How shadows are received (the "shadow-render" part).
struct ShadowSettings {
    /// World to the light's clip space, as the shadow map was drawn (fit_directional_shadow).
    glm::mat4 light_view_projection{1.0f};
    uint32_t map_size = 2048;   ///< texels per side of the shadow map
    float normal_offset = 0.02f;///< world units a receiver point moves along its normal
    float depth_bias = 0.0005f; ///< subtracted from the receiver's depth (0..1)
    uint32_t pcf_radius = 1;    ///< (2r+1)^2 comparison taps
};

/// Everything the lit passes need per frame.
struct SceneView {
    scene::CameraMatrices camera;
    DirectionalLight light;
    Environment environment;
    ShadowSettings shadow;
};

/// An orthographic view-projection of the light that encloses `bounds` tightly: looking along
/// -towards_light at the centre of the box, x and y fit to the projected corners, depth 0..1
/// spanning the box (nearest corner at 0). `towards_light` need not be unit length.
glm::mat4 fit_directional_shadow(const glm::vec3& towards_light, const scene::Bounds& bounds);

}  // namespace loom::passes

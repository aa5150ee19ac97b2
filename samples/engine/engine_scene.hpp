#pragma once
// The scene of loom-engine: a courtyard (ground, a ring of pillars, spheres and crates) lit by a
// low sun and many coloured point lights, with a glTF model in the middle when one is given.
// Everything is one loom::scene::Scene (the model's meshes, materials and textures appended to
// the courtyard's), so one GpuScene holds all geometry and textures.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "loom/renderer/gpu_scene.hpp"
#include "loom/rhi/result.hpp"

namespace loom::engine {

/// A point light as the light buffer stores it (std430, mirrors PointLight in
/// shaders/engine/frame.glsl).
struct PointLight {
    glm::vec4 position_radius{0.0f};  ///< world position, radius of influence
    glm::vec4 color{0.0f};            ///< linear rgb (intensity included), 0
};
static_assert(sizeof(PointLight) == 32);

/// What make_engine_scene builds.
struct SceneSettings {
    /// A glTF 2.0 file placed in the middle of the courtyard (scaled to about 2.5 units, standing
    /// on the ground); empty: the courtyard alone, with a torus and crates in the middle.
    std::filesystem::path model;
    /// Point lights scattered over the courtyard (at least 1, at most kMaxLights).
    uint32_t lights = 128;
};

/// The most point lights a scene may have.
inline constexpr uint32_t kMaxLights = 4096;

/// A scene ready to upload, with its lights, sun, sky and camera.
struct EngineScene {
    std::shared_ptr<const renderer::PreparedScene> prepared;
    std::vector<PointLight> lights;
    glm::vec3 towards_sun{0.0f, 1.0f, 0.0f};  ///< unit vector
    glm::vec3 sun_color{1.0f};                ///< linear radiance
    glm::vec3 sky_zenith{0.0f};
    glm::vec3 sky_horizon{0.0f};
    glm::vec3 ground_color{0.0f};
    glm::vec3 eye{0.0f};
    glm::vec3 target{0.0f};
    float yfov = 0.87f;   ///< radians
    float znear = 0.1f;
    float zfar = 60.0f;
    /// The view distances the shadow cascades split between: where the nearest visible
    /// geometry begins (nothing nearer needs a shadow texel) and how far shadows reach.
    float shadow_start = 6.0f;
    float shadow_end = 30.0f;
    /// One line: what the scene holds (draw items, lights, the model and its warnings).
    std::string description;
};

/// Builds the scene. Errors: the glTF importer's (naming the file), or `lights` out of range.
Result<EngineScene> make_engine_scene(const SceneSettings& settings);

}  // namespace loom::engine

#pragma once
// The built-in scene of loom-deferred: a checkered ground fading into the haze, a pillar, two
// cubes, a chrome and a glossy blue sphere, a gold torus, and two glowing objects bright enough
// to bloom, under a low sun that casts long shadows across the ground.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "loom/passes/mesh_object.hpp"
#include "loom/passes/view.hpp"
#include "loom/renderer/deferred_pipeline.hpp"
#include "loom/rhi/device.hpp"

namespace loom::deferred {

/// Geometry on the CPU: MeshVertex (the layout of loom::scene::Vertex) and a u32 triangle list
/// whose triangles are counter-clockwise seen from the side their normals point to.
struct MeshData {
    std::vector<passes::MeshVertex> vertices;
    std::vector<uint32_t> indices;
};

/// One object of the scene.
struct SceneItem {
    std::string name;
    MeshData mesh;
    passes::MeshSurface surface;
    glm::mat4 model{1.0f};
    bool checker = false;  ///< the "checker-mesh" kind instead of "pbr-mesh"
    bool casts_shadow = true;  ///< drawn into the shadow map
};

/// A scene: objects, light, sky and how to look at it.
struct SceneContent {
    std::vector<SceneItem> items;
    passes::DirectionalLight light;
    passes::Environment environment;
    glm::vec3 eye{0.0f};
    glm::vec3 target{0.0f};
    float yfov = 0.7853982f;
    /// World bounds of every item.
    scene::Bounds bounds;
    /// What the shadow map covers: the shadow casters and where their shadows fall on the
    /// ground (the ground reaches far beyond; outside this box it is lit).
    scene::Bounds shadow_bounds;
};

// Mesh generators (unit-sized, centred on the origin; normals point outwards).
/// A plane facing +y, cells x cells quads (small triangles are clipped less against the view).
MeshData make_plane(float size_x, float size_z, uint32_t cells = 1);
MeshData make_box(const glm::vec3& size);
MeshData make_sphere(float radius, uint32_t segments, uint32_t rings);
MeshData make_torus(float major_radius, float minor_radius, uint32_t segments, uint32_t sides);

/// World bounds of the items' transformed vertices (of those with `casts_shadow` set, when
/// `only_casters`).
scene::Bounds scene_bounds(const std::vector<SceneItem>& items, bool only_casters = false);

/// `casters` and their shadows on the plane y = 0 under a light from `towards_light`.
scene::Bounds shadow_region(const scene::Bounds& casters, const glm::vec3& towards_light);

/// The default scene.
SceneContent procedural_scene();

/// Uploads the scene's meshes (one GpuMesh per item) and makes its objects ("pbr-mesh" or
/// "checker-mesh"), camera, light, sky and bounds.
Result<renderer::PipelineScene> procedural_pipeline_scene(rhi::Device& device, const SceneContent& content);

/// The Figure 2 pipeline drawing `content` (procedural_pipeline_scene, then
/// renderer::DeferredPipeline::create).
Result<std::unique_ptr<renderer::DeferredPipeline>> create_procedural_pipeline(
    rhi::Device& device, const SceneContent& content, const renderer::PipelineSettings& settings = {});

}  // namespace loom::deferred

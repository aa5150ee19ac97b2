#pragma once
// The many-object scene of the retained-layer tests and benchmark (tests/bench/retained_bench):
// a grid of small procedural meshes (a few hundred distinct low-poly ellipsoids), tens of
// materials (some double-sided, some checkered), some mirrored transforms, in a random
// submission order, seen from above. The same description builds both the naive objects
// (MeshObject, registered with a pass, drawn one by one) and the retained shapes (submitted to
// a RetainedScene), so the two paths draw exactly the same thing.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "loom/passes/mesh_object.hpp"
#include "loom/passes/param.hpp"
#include "loom/passes/retained_scene.hpp"
#include "loom/passes/shape.hpp"
#include "loom/passes/view.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

namespace loom::test {

struct ObjectSceneSpec {
    uint32_t objects = 10000;
    uint32_t meshes = 300;
    uint32_t materials = 30;
    uint32_t seed = 1;
};

struct SceneMesh {
    std::string name;
    std::vector<passes::MeshVertex> vertices;
    std::vector<uint32_t> indices;
};

/// A plain white dielectric surface (metallic 0, roughness 0.5) for tests that need one.
passes::MeshSurface plain_surface();

struct SceneMaterial {
    passes::MeshSurface value;
    bool checker = false;  ///< drawn with the checker kind
};

struct SceneObject {
    uint32_t mesh = 0;
    uint32_t material = 0;
    glm::mat4 model{1.0f};
};

struct ObjectScene {
    std::vector<SceneMesh> meshes;
    std::vector<SceneMaterial> materials;
    std::vector<SceneObject> objects;  ///< in submission order (shuffled)
    scene::CameraMatrices camera;             ///< sees the whole grid, for a square frame
};

/// The scene for `spec` (deterministic for a seed). Objects sit in the cells of a square grid,
/// rotated about y and scaled to stay inside their cell; every 20th is mirrored in x.
ObjectScene make_object_scene(const ObjectSceneSpec& spec);

/// The number of distinct state keys of the scene in a pass that reads materials: (kind,
/// culling, winding, material) — what a sorted queue binds once each.
uint64_t distinct_state_keys(const ObjectScene& scene);
/// Distinct (state key, mesh) pairs: the indirect commands of a sorted queue.
uint64_t distinct_key_mesh_pairs(const ObjectScene& scene);

/// The scene as MeshObjects (the naive path): one GpuMesh per mesh on `device`.
struct NaiveObjects {
    std::vector<std::shared_ptr<passes::GpuMesh>> meshes;
    std::vector<std::shared_ptr<passes::MeshObject>> objects;
};
Result<NaiveObjects> make_naive_objects(rhi::Device& device, const ObjectScene& scene);

/// The scene as retained shapes: one Geometry per mesh, one Material per material, one shape
/// per object with its own model parameter (set it to move the object).
struct RetainedObjects {
    std::vector<std::shared_ptr<const passes::Geometry>> geometries;
    std::vector<std::shared_ptr<passes::GpuMaterial>> materials;
    std::vector<std::shared_ptr<passes::InputParam<glm::mat4>>> models;
    std::vector<std::shared_ptr<passes::Shape>> shapes;
};
Result<RetainedObjects> make_retained_objects(const ObjectScene& scene);

}  // namespace loom::test

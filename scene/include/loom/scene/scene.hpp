#pragma once
// The CPU scene: everything a renderer needs to draw a glTF file, already validated and
// resolved — meshes in one vertex layout, materials, decoded images, samplers, cameras, and a
// flat list of draw items (primitive + world matrix + material) with their bounds.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "loom/scene/bounds.hpp"
#include "loom/scene/camera.hpp"
#include "loom/scene/glm.hpp"
#include "loom/scene/material.hpp"
#include "loom/scene/mesh.hpp"

namespace loom::scene {

/// A node of the file's hierarchy (all nodes of the file, in file order).
struct Node {
    std::string name;
    std::optional<uint32_t> parent;
    std::vector<uint32_t> children;
    glm::mat4 local{1.0f};  ///< from `matrix` or translation * rotation * scale
    glm::mat4 world{1.0f};  ///< product of the ancestors' local matrices and this one
    std::optional<uint32_t> mesh;    ///< index into Scene::meshes
    std::optional<uint32_t> camera;  ///< index of the glTF camera (not of Scene::cameras)
};

/// One thing to draw: a mesh primitive placed in the world with its material.
struct DrawItem {
    uint32_t node = 0;       ///< index into Scene::nodes
    uint32_t mesh = 0;       ///< index into Scene::meshes
    uint32_t primitive = 0;  ///< index into Scene::meshes[mesh].primitives
    uint32_t material = 0;   ///< index into Scene::materials (same as the primitive's)
    glm::mat4 world{1.0f};
    /// Transforms normals to world space: the cofactor matrix of world's upper 3x3, scaled by
    /// the sign of its determinant (the inverse transpose up to a positive factor, defined even
    /// for singular matrices). Normalise after transforming.
    glm::mat3 normal_matrix{1.0f};
    /// The world matrix mirrors (negative determinant): counter-clockwise front faces become
    /// clockwise, so the renderer must flip its front-face winding for this item.
    bool flips_winding = false;
    Bounds world_bounds;  ///< exact bounds of the transformed vertex positions
};

/// A loaded scene. Indices between the vectors are always valid.
struct Scene {
    std::string source;  ///< the file it was loaded from
    std::vector<Node> nodes;
    std::vector<Mesh> meshes;          ///< one per glTF mesh, in file order
    std::vector<Material> materials;   ///< glTF materials in file order, then the default one if used
    std::vector<Texture> textures;     ///< textures the materials use
    std::vector<TextureImage> images;  ///< decoded images the textures use
    std::vector<DrawItem> draw_items;  ///< the displayed glTF scene, flattened, in traversal order
    std::vector<Camera> cameras;       ///< camera instances of the displayed scene (node order)
    Bounds bounds;                       ///< world bounds of all draw items
    /// Non-fatal problems found while importing (also logged through loom::log at Warning).
    std::vector<std::string> warnings;

    /// Total vertex / index count over every primitive of every mesh.
    [[nodiscard]] uint64_t vertex_count() const;
    [[nodiscard]] uint64_t index_count() const;
};

}  // namespace loom::scene

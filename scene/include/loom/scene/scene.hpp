#pragma once
// The CPU scene: everything a renderer needs to draw a glTF file, already validated and
// resolved — meshes in one vertex layout, materials, decoded images, samplers, cameras, and a
// flat list of draw items (primitive + world matrix + material) with their bounds.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "loom/scene/animation.hpp"
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
    /// The node's transform as glTF gives it, which animations drive: `local` is
    /// trs_matrix(translation, rotation, scale) unless the file gives a matrix (`has_matrix`;
    /// such a node is not animated).
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 scale{1.0f};
    bool has_matrix = false;
    std::optional<uint32_t> mesh;    ///< index into Scene::meshes
    std::optional<uint32_t> camera;  ///< index of the glTF camera (not of Scene::cameras)
    std::optional<uint32_t> skin;    ///< index into Scene::skins: the skin that deforms `mesh`
};

/// A glTF skin: the nodes that act as its joints and, per joint, the inverse bind matrix that
/// takes the mesh's bind-pose vertices into the joint's space.
struct Skin {
    std::string name;
    std::vector<uint32_t> joints;  ///< indices into Scene::nodes
    /// One per joint (the identity where the file gives none).
    std::vector<glm::mat4> inverse_bind_matrices;
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
    /// Index into Scene::skins when the primitive is skinned (its node has a skin and the
    /// primitive has influences): its vertices are placed by joint_matrices(), not by a node, so
    /// `world` and `normal_matrix` are the identity (glTF ignores the skinned mesh's node
    /// transform) and `world_bounds` are the bounds of the skinned positions.
    std::optional<uint32_t> skin;
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
    /// The file's animations, in file order, with the channels that drive a node's translation,
    /// rotation or scale (pose() plays them); channels the importer cannot play are left out
    /// with a warning.
    std::vector<Animation> animations;
    std::vector<Skin> skins;  ///< the file's skins, in file order
    /// Non-fatal problems found while importing (also logged through loom::log at Warning).
    std::vector<std::string> warnings;

    /// Total vertex / index count over every primitive of every mesh.
    [[nodiscard]] uint64_t vertex_count() const;
    [[nodiscard]] uint64_t index_count() const;
};

/// A copy of `scene` without its decoded images (a renderer that has them on the device poses
/// this copy: nodes, meshes, materials, draw items and animations are all there).
Scene copy_without_images(const Scene& scene);

/// translation * rotation * scale, as glTF composes a node's local matrix.
glm::mat4 trs_matrix(const glm::vec3& translation, const glm::quat& rotation, const glm::vec3& scale);

/// Transforms normals by `world`: the cofactor matrix of its upper 3x3 times the sign of its
/// determinant (proportional to the inverse transpose by a positive factor, and defined for
/// singular matrices too). `flips_winding`: the determinant is negative.
glm::mat3 normal_matrix(const glm::mat4& world, bool& flips_winding);

/// World matrices top-down from the roots (parent's world times local): of the nodes `moved`
/// marks and of their descendants, which it marks too (all true: every node). Returns how many
/// nodes the roots reach: fewer than nodes.size() when the hierarchy has a cycle.
std::size_t update_world_matrices(std::vector<Node>& nodes, std::vector<bool>& moved);

/// Places `item` at its node's world matrix: its world and normal matrices, winding and the
/// exact bounds of its transformed vertex positions.
void place_draw_item(DrawItem& item, const Node& node, const Primitive& primitive);

/// The skinning matrix of every joint of skin `skin` as the nodes are posed now: the joint's
/// world matrix times its inverse bind matrix. A skinned vertex is placed at the weighted sum of
/// its joints' matrices applied to its position.
std::vector<glm::mat4> joint_matrices(const Scene& scene, uint32_t skin);

/// Where `vertex` of a skinned primitive lies, given its influences and the skin's
/// joint_matrices() (joints past their end are ignored).
glm::vec3 skinned_position(const glm::vec3& position, const SkinInfluences& influences,
                           std::span<const glm::mat4> joint_matrices);

/// Places a skinned draw item (DrawItem::skin set) at its skin's current pose: identity world
/// and normal matrices, and the exact bounds of its skinned vertex positions.
void place_skinned_draw_item(DrawItem& item, const Scene& scene, const Primitive& primitive);

/// Sets the translations, rotations and scales `animation` drives to their values at `time`
/// (seconds; before the first keyframe the first value, after the last the last), then the
/// local and world matrices of the nodes, the draw items whose node moved and the scene's
/// bounds. Returns the indices of the draw items that moved, in order: what a renderer must
/// upload again (skinned items move when a joint of their skin does). Channels must name nodes of `scene` without a matrix (the importer's are).
std::vector<uint32_t> pose(Scene& scene, const Animation& animation, float time);

}  // namespace loom::scene

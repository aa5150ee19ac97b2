#include "loom/scene/scene.hpp"

#include <array>
#include <span>

namespace loom::scene {

uint64_t Scene::vertex_count() const {
    uint64_t count = 0;
    for (const Mesh& mesh : meshes) {
        for (const Primitive& primitive : mesh.primitives) count += primitive.vertices.size();
    }
    return count;
}

uint64_t Scene::index_count() const {
    uint64_t count = 0;
    for (const Mesh& mesh : meshes) {
        for (const Primitive& primitive : mesh.primitives) count += primitive.indices.size();
    }
    return count;
}

}  // namespace loom::scene

namespace loom::scene {

glm::mat4 trs_matrix(const glm::vec3& translation, const glm::quat& rotation, const glm::vec3& scale) {
    glm::mat4 matrix = glm::mat4_cast(rotation);
    matrix[0] *= scale.x;
    matrix[1] *= scale.y;
    matrix[2] *= scale.z;
    matrix[3] = glm::vec4(translation, 1.0f);
    return matrix;
}

Scene copy_without_images(const Scene& source) {
    Scene copy;
    copy.source = source.source;
    copy.nodes = source.nodes;
    copy.meshes = source.meshes;
    copy.materials = source.materials;
    copy.textures = source.textures;
    copy.draw_items = source.draw_items;
    copy.cameras = source.cameras;
    copy.bounds = source.bounds;
    copy.animations = source.animations;
    copy.skins = source.skins;
    copy.warnings = source.warnings;
    return copy;
}

glm::mat3 normal_matrix(const glm::mat4& world, bool& flips_winding) {
    const glm::vec3 c0(world[0]);
    const glm::vec3 c1(world[1]);
    const glm::vec3 c2(world[2]);
    glm::mat3 cofactor(glm::cross(c1, c2), glm::cross(c2, c0), glm::cross(c0, c1));
    const float determinant = glm::dot(c0, glm::cross(c1, c2));
    flips_winding = determinant < 0.0f;
    if (flips_winding) cofactor = -cofactor;
    return cofactor;
}

std::size_t update_world_matrices(std::vector<Node>& nodes, std::vector<bool>& moved) {
    // Without recursion: hierarchies can be deep.
    std::vector<uint32_t> stack;
    for (uint32_t n = 0; n < nodes.size(); ++n) {
        if (!nodes[n].parent) stack.push_back(n);
    }
    std::size_t reached = 0;
    while (!stack.empty()) {
        const uint32_t n = stack.back();
        stack.pop_back();
        ++reached;
        Node& node = nodes[n];
        if (node.parent && moved[*node.parent]) moved[n] = true;
        if (moved[n]) node.world = node.parent ? nodes[*node.parent].world * node.local : node.local;
        for (const uint32_t child : node.children) stack.push_back(child);
    }
    return reached;
}

void place_draw_item(DrawItem& item, const Node& node, const Primitive& primitive) {
    item.world = node.world;
    item.normal_matrix = normal_matrix(node.world, item.flips_winding);
    item.world_bounds = Bounds{};
    for (const Vertex& vertex : primitive.vertices) {
        item.world_bounds.extend(glm::vec3(node.world * glm::vec4(vertex.position, 1.0f)));
    }
}

std::vector<glm::mat4> joint_matrices(const Scene& scene, uint32_t skin) {
    const Skin& s = scene.skins[skin];
    std::vector<glm::mat4> matrices(s.joints.size());
    for (std::size_t j = 0; j < s.joints.size(); ++j) matrices[j] = scene.nodes[s.joints[j]].world * s.inverse_bind_matrices[j];
    return matrices;
}

glm::vec3 skinned_position(const glm::vec3& position, const SkinInfluences& influences,
                           std::span<const glm::mat4> joint_matrices) {
    const glm::vec4 p(position, 1.0f);
    glm::vec3 sum(0.0f);
    for (int c = 0; c < 4; ++c) {
        const float weight = influences.weights[c];
        if (weight == 0.0f || influences.joints[c] >= joint_matrices.size()) continue;
        sum += weight * glm::vec3(joint_matrices[influences.joints[c]] * p);
    }
    return sum;
}

void place_skinned_draw_item(DrawItem& item, const Scene& scene, const Primitive& primitive) {
    item.world = glm::mat4(1.0f);
    item.normal_matrix = glm::mat3(1.0f);
    item.flips_winding = false;
    item.world_bounds = Bounds{};
    const std::vector<glm::mat4> joints = joint_matrices(scene, *item.skin);
    for (std::size_t v = 0; v < primitive.vertices.size(); ++v) {
        item.world_bounds.extend(skinned_position(primitive.vertices[v].position, primitive.skin[v], joints));
    }
}

std::vector<uint32_t> pose(Scene& scene, const Animation& animation, float time) {
    std::vector<bool> moved(scene.nodes.size(), false);
    std::array<float, 4> value{};
    for (const AnimationChannel& channel : animation.channels) {
        const AnimationSampler& sampler = animation.samplers[channel.sampler];
        // Morph target weights change no node (and loom draws no morph targets).
        if (channel.property == AnimatedProperty::Weights || sampler.components > value.size()) continue;
        const bool rotation = channel.property == AnimatedProperty::Rotation;
        sample(sampler, time, rotation, std::span<float>(value.data(), sampler.components));
        Node& node = scene.nodes[channel.node];
        if (channel.property == AnimatedProperty::Translation) {
            node.translation = glm::vec3(value[0], value[1], value[2]);
        } else if (rotation) {
            node.rotation = glm::quat(value[3], value[0], value[1], value[2]);  // glTF's (x, y, z, w)
        } else {
            node.scale = glm::vec3(value[0], value[1], value[2]);
        }
        moved[channel.node] = true;
    }
    for (uint32_t n = 0; n < scene.nodes.size(); ++n) {
        Node& node = scene.nodes[n];
        if (moved[n] && !node.has_matrix) node.local = trs_matrix(node.translation, node.rotation, node.scale);
    }
    update_world_matrices(scene.nodes, moved);  // a node moves when it or an ancestor does
    // A skin moves when one of its joints does.
    std::vector<bool> moved_skins(scene.skins.size(), false);
    for (std::size_t s = 0; s < scene.skins.size(); ++s) {
        for (const uint32_t joint : scene.skins[s].joints) moved_skins[s] = moved_skins[s] || moved[joint];
    }
    std::vector<uint32_t> moved_items;
    for (uint32_t i = 0; i < scene.draw_items.size(); ++i) {
        DrawItem& item = scene.draw_items[i];
        const Primitive& primitive = scene.meshes[item.mesh].primitives[item.primitive];
        if (item.skin) {
            if (!moved_skins[*item.skin]) continue;
            place_skinned_draw_item(item, scene, primitive);
        } else {
            if (!moved[item.node]) continue;
            place_draw_item(item, scene.nodes[item.node], primitive);
        }
        moved_items.push_back(i);
    }
    if (!moved_items.empty()) {
        scene.bounds = Bounds{};
        for (const DrawItem& item : scene.draw_items) scene.bounds.extend(item.world_bounds);
    }
    return moved_items;
}

}  // namespace loom::scene

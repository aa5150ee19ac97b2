#include "loom/scene/scene.hpp"

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

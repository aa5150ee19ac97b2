#include "loom/scene/packed_geometry.hpp"

#include <cassert>
#include <limits>

namespace loom::scene {

PackedGeometry pack_geometry(const Scene& scene) {
    PackedGeometry packed;
    packed.vertices.reserve(static_cast<std::size_t>(scene.vertex_count()));
    packed.indices.reserve(static_cast<std::size_t>(scene.index_count()));
    assert(scene.vertex_count() <= static_cast<uint64_t>(std::numeric_limits<int32_t>::max()));
    assert(scene.index_count() <= std::numeric_limits<uint32_t>::max());
    packed.ranges.resize(scene.meshes.size());
    bool skinned = false;
    for (const Mesh& mesh : scene.meshes) {
        for (const Primitive& primitive : mesh.primitives) skinned = skinned || !primitive.skin.empty();
    }
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        for (const Primitive& primitive : scene.meshes[m].primitives) {
            if (skinned) {
                if (primitive.skin.empty()) {
                    packed.skin.resize(packed.skin.size() + primitive.vertices.size());
                } else {
                    packed.skin.insert(packed.skin.end(), primitive.skin.begin(), primitive.skin.end());
                }
            }
            PrimitiveRange range;
            range.first_index = static_cast<uint32_t>(packed.indices.size());
            range.index_count = static_cast<uint32_t>(primitive.indices.size());
            range.base_vertex = static_cast<int32_t>(packed.vertices.size());
            packed.vertices.insert(packed.vertices.end(), primitive.vertices.begin(), primitive.vertices.end());
            packed.indices.insert(packed.indices.end(), primitive.indices.begin(), primitive.indices.end());
            packed.ranges[m].push_back(range);
        }
    }
    return packed;
}

}  // namespace loom::scene

#pragma once
// All of a scene's geometry in one vertex array and one index array, ready for one vertex
// buffer and one index buffer: each primitive becomes a range that draw_indexed() takes as is
// (first_index, index_count, base_vertex).

#include <cstdint>
#include <vector>

#include "loom/scene/mesh.hpp"
#include "loom/scene/scene.hpp"

namespace loom::scene {

/// Where one primitive lies in PackedGeometry: its indices are
/// indices[first_index .. first_index + index_count), relative to base_vertex.
struct PrimitiveRange {
    uint32_t first_index = 0;
    uint32_t index_count = 0;
    int32_t base_vertex = 0;

    friend bool operator==(const PrimitiveRange&, const PrimitiveRange&) = default;
};

/// The concatenated geometry of every primitive of every mesh, in mesh and primitive order.
struct PackedGeometry {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;  ///< as in the primitives (not offset by base_vertex)
    /// Parallel to `vertices` when any primitive is skinned (zeros for the others), else empty:
    /// the primitives' skin influences, with joint indices into their skin's joint list.
    std::vector<SkinInfluences> skin;
    /// ranges[mesh][primitive], parallel to Scene::meshes[mesh].primitives.
    std::vector<std::vector<PrimitiveRange>> ranges;

    /// The range of a draw item's primitive.
    [[nodiscard]] const PrimitiveRange& range(const DrawItem& item) const { return ranges[item.mesh][item.primitive]; }
};

/// Packs the scene's meshes (copies; the scene is unchanged). Scenes too large for 32-bit
/// index offsets (more than 2^31 vertices or 2^32 indices in total) are a programming error.
PackedGeometry pack_geometry(const Scene& scene);

}  // namespace loom::scene

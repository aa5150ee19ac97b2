#pragma once
// Geometry processing the glTF importer (loom::gltf) applies to primitives, public so that it
// can be reused and tested on its own: primitive topologies to triangle lists, normal and
// tangent generation.
// The generators require valid primitives (every index < vertices.size()), which the importer
// guarantees.

#include <cstdint>
#include <span>
#include <vector>

#include "loom/scene/mesh.hpp"

namespace loom::scene {

/// glTF primitive topologies (the `mode` values 0..6).
enum class Topology : uint8_t { Points, Lines, LineLoop, LineStrip, Triangles, TriangleStrip, TriangleFan };

/// Converts a vertex sequence of a triangle topology into a triangle list, keeping the winding
/// of every triangle as glTF defines it: strip triangle i is (i, i+1, i+2) for even i and
/// (i+1, i, i+2) for odd i; fan triangle i is (i+1, i+2, 0). Incomplete trailing triangles of
/// a list are dropped. Point and line topologies give an empty list.
std::vector<uint32_t> triangle_list(Topology topology, std::span<const uint32_t> sequence);

/// Flat normals (what glTF requires when a file has none): every triangle gets its own three
/// vertices carrying the triangle's face normal, so the primitive becomes non-indexed
/// (indices 0, 1, 2, ...), and its skin influences (when it has them) follow its vertices.
/// Degenerate triangles get (0, 0, 1).
void generate_flat_normals(Primitive& primitive);

/// Smooth normals: each vertex gets the normalised sum of the unnormalised face normals (the
/// cross products, hence area-weighted) of the triangles that use its index. Vertices that
/// share a position but not an index are not welded. Vertices whose sum is zero (only used by
/// degenerate triangles, or by none) get (0, 0, 1).
void generate_smooth_normals(Primitive& primitive);

/// Per-vertex tangents from the UV derivatives of UV set `uv_set` (0 or 1), for normal mapping.
/// Method (not MikkTSpace): for every triangle, the object-space directions of increasing u
/// (T = dP/du) and increasing v (B = dP/dv) are solved from its edges and UV deltas; each vertex
/// sums the unnormalised T and B of its triangles (Lengyel's method). Per vertex, the
/// summed T is orthogonalised against the normal (Gram-Schmidt) and normalised; w is the
/// handedness such that cross(normal, tangent) * w points towards decreasing v, which is "up"
/// in a glTF image and the +Y of a glTF normal map. Vertices whose triangles have no usable UV
/// derivatives get an arbitrary unit tangent perpendicular to the normal and w = +1.
/// Uses the vertices' current normals, so generate normals first.
void generate_tangents(Primitive& primitive, uint32_t uv_set);

}  // namespace loom::scene

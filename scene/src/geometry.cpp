#include "loom/scene/geometry.hpp"

#include <cmath>

namespace loom::scene {
namespace {

// Normalises `v`, or returns `fallback` when v has no usable length (zero, denormal, overflow).
glm::vec3 normalize_or(const glm::vec3& v, const glm::vec3& fallback) {
    const float length = glm::length(v);
    if (!(length > 1e-30f) || !std::isfinite(length)) return fallback;
    return v / length;
}

glm::vec3 face_normal(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) {
    return glm::cross(p1 - p0, p2 - p0);
}

constexpr glm::vec3 kDefaultNormal{0.0f, 0.0f, 1.0f};

// Some unit vector perpendicular to `normal` (for vertices without usable UV derivatives).
glm::vec3 any_perpendicular(const glm::vec3& normal) {
    const glm::vec3 axis = std::abs(normal.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    return normalize_or(axis - normal * glm::dot(normal, axis), glm::vec3(1.0f, 0.0f, 0.0f));
}

}  // namespace

std::vector<uint32_t> triangle_list(Topology topology, std::span<const uint32_t> sequence) {
    std::vector<uint32_t> list;
    const std::size_t n = sequence.size();
    switch (topology) {
        case Topology::Triangles:
            list.assign(sequence.begin(), sequence.begin() + static_cast<std::ptrdiff_t>(n - n % 3));
            break;
        case Topology::TriangleStrip:
            if (n < 3) break;
            list.reserve((n - 2) * 3);
            for (std::size_t i = 0; i + 2 < n; ++i) {
                if (i % 2 == 0) {
                    list.insert(list.end(), {sequence[i], sequence[i + 1], sequence[i + 2]});
                } else {
                    list.insert(list.end(), {sequence[i + 1], sequence[i], sequence[i + 2]});
                }
            }
            break;
        case Topology::TriangleFan:
            if (n < 3) break;
            list.reserve((n - 2) * 3);
            for (std::size_t i = 0; i + 2 < n; ++i) list.insert(list.end(), {sequence[i + 1], sequence[i + 2], sequence[0]});
            break;
        case Topology::Points:
        case Topology::Lines:
        case Topology::LineLoop:
        case Topology::LineStrip:
            break;
    }
    return list;
}

void generate_flat_normals(Primitive& primitive) {
    std::vector<Vertex> vertices;
    vertices.reserve(primitive.indices.size() - primitive.indices.size() % 3);
    // The skin follows the vertices: one entry per corner.
    std::vector<SkinInfluences> skin;
    for (std::size_t i = 0; i + 2 < primitive.indices.size(); i += 3) {
        if (!primitive.skin.empty()) {
            for (std::size_t c = 0; c < 3; ++c) skin.push_back(primitive.skin[primitive.indices[i + c]]);
        }
        Vertex corners[3] = {primitive.vertices[primitive.indices[i]], primitive.vertices[primitive.indices[i + 1]],
                             primitive.vertices[primitive.indices[i + 2]]};
        const glm::vec3 normal =
            normalize_or(face_normal(corners[0].position, corners[1].position, corners[2].position), kDefaultNormal);
        for (Vertex& corner : corners) {
            corner.normal = normal;
            vertices.push_back(corner);
        }
    }
    primitive.vertices = std::move(vertices);
    primitive.skin = std::move(skin);
    primitive.indices.resize(primitive.vertices.size());
    for (std::size_t i = 0; i < primitive.indices.size(); ++i) primitive.indices[i] = static_cast<uint32_t>(i);
    primitive.generated |= kAttributeNormal;
}

void generate_smooth_normals(Primitive& primitive) {
    std::vector<glm::vec3> sums(primitive.vertices.size(), glm::vec3(0.0f));
    const auto& idx = primitive.indices;
    for (std::size_t i = 0; i + 2 < idx.size(); i += 3) {
        const glm::vec3 normal = face_normal(primitive.vertices[idx[i]].position, primitive.vertices[idx[i + 1]].position,
                                             primitive.vertices[idx[i + 2]].position);
        if (!std::isfinite(normal.x) || !std::isfinite(normal.y) || !std::isfinite(normal.z)) continue;
        for (std::size_t k = 0; k < 3; ++k) sums[idx[i + k]] += normal;
    }
    for (std::size_t v = 0; v < sums.size(); ++v) primitive.vertices[v].normal = normalize_or(sums[v], kDefaultNormal);
    primitive.generated |= kAttributeNormal;
}

void generate_tangents(Primitive& primitive, uint32_t uv_set) {
    auto uv_of = [uv_set](const Vertex& v) { return uv_set == 1 ? v.uv1 : v.uv0; };
    std::vector<glm::vec3> u_directions(primitive.vertices.size(), glm::vec3(0.0f));
    std::vector<glm::vec3> v_directions(primitive.vertices.size(), glm::vec3(0.0f));
    const auto& idx = primitive.indices;
    for (std::size_t i = 0; i + 2 < idx.size(); i += 3) {
        const Vertex& a = primitive.vertices[idx[i]];
        const Vertex& b = primitive.vertices[idx[i + 1]];
        const Vertex& c = primitive.vertices[idx[i + 2]];
        const glm::vec3 e1 = b.position - a.position;
        const glm::vec3 e2 = c.position - a.position;
        const glm::vec2 d1 = uv_of(b) - uv_of(a);
        const glm::vec2 d2 = uv_of(c) - uv_of(a);
        const float det = d1.x * d2.y - d2.x * d1.y;
        if (!(std::abs(det) > 1e-20f) || !std::isfinite(det)) continue;  // no UV parametrisation
        // Solve e1 = d1.x T + d1.y B, e2 = d2.x T + d2.y B for T = dP/du and B = dP/dv.
        const glm::vec3 t = (e1 * d2.y - e2 * d1.y) / det;
        const glm::vec3 bt = (e2 * d1.x - e1 * d2.x) / det;
        if (!std::isfinite(glm::dot(t, t)) || !std::isfinite(glm::dot(bt, bt))) continue;
        for (std::size_t k = 0; k < 3; ++k) {
            u_directions[idx[i + k]] += t;
            v_directions[idx[i + k]] += bt;
        }
    }
    for (std::size_t v = 0; v < primitive.vertices.size(); ++v) {
        Vertex& vertex = primitive.vertices[v];
        const glm::vec3 normal = normalize_or(vertex.normal, kDefaultNormal);
        const glm::vec3 projected = u_directions[v] - normal * glm::dot(normal, u_directions[v]);
        const float length = glm::length(projected);
        if (!(length > 1e-20f) || !std::isfinite(length)) {
            vertex.tangent = glm::vec4(any_perpendicular(normal), 1.0f);
            continue;
        }
        const glm::vec3 tangent = projected / length;
        // glTF: bitangent = cross(normal, tangent) * w must point to decreasing v (image up).
        const float w = glm::dot(glm::cross(normal, tangent), v_directions[v]) > 0.0f ? -1.0f : 1.0f;
        vertex.tangent = glm::vec4(tangent, w);
    }
    primitive.generated |= kAttributeTangent;
}

}  // namespace loom::scene

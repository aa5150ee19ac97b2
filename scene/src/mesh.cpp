#include "loom/scene/mesh.hpp"

#include <cstddef>

namespace loom::scene {

// The layout below is what shaders and pipelines rely on; keep Vertex tightly packed.
static_assert(sizeof(Vertex) == 72, "Vertex must be tightly packed (72 bytes)");
static_assert(offsetof(Vertex, position) == 0);
static_assert(offsetof(Vertex, normal) == 12);
static_assert(offsetof(Vertex, tangent) == 24);
static_assert(offsetof(Vertex, uv0) == 40);
static_assert(offsetof(Vertex, uv1) == 48);
static_assert(offsetof(Vertex, color) == 56);

rhi::VertexBufferLayout vertex_buffer_layout() {
    rhi::VertexBufferLayout layout;
    layout.stride = sizeof(Vertex);
    layout.step = rhi::VertexStepMode::PerVertex;
    layout.attributes = {
        {vertex_location::kPosition, rhi::VertexFormat::Float3, offsetof(Vertex, position)},
        {vertex_location::kNormal, rhi::VertexFormat::Float3, offsetof(Vertex, normal)},
        {vertex_location::kTangent, rhi::VertexFormat::Float4, offsetof(Vertex, tangent)},
        {vertex_location::kUv0, rhi::VertexFormat::Float2, offsetof(Vertex, uv0)},
        {vertex_location::kUv1, rhi::VertexFormat::Float2, offsetof(Vertex, uv1)},
        {vertex_location::kColor, rhi::VertexFormat::Float4, offsetof(Vertex, color)},
    };
    return layout;
}

static_assert(sizeof(SkinInfluences) == 32, "two vec4s, as skin_buffer_layout() reads them");

rhi::VertexBufferLayout skin_buffer_layout() {
    rhi::VertexBufferLayout layout;
    layout.stride = sizeof(SkinInfluences);
    layout.step = rhi::VertexStepMode::PerVertex;
    layout.attributes = {
        {vertex_location::kJoints, rhi::VertexFormat::Uint4, offsetof(SkinInfluences, joints)},
        {vertex_location::kWeights, rhi::VertexFormat::Float4, offsetof(SkinInfluences, weights)},
    };
    return layout;
}

}  // namespace loom::scene

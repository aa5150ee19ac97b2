// Geometry processing on its own: topology conversion, flat and smooth normals, tangents (on
// known quads, and against the exported tangents of a real model), the vertex layout.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "loom/gltf/gltf.hpp"
#include "loom/scene/geometry.hpp"
#include "loom_test/test_support.hpp"
#include "scene_test_util.hpp"

namespace loom::test {
namespace {

using scene::Primitive;
using scene::Topology;
using scene::Vertex;

Primitive make_primitive(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices,
                         const std::vector<glm::vec2>& uvs = {}) {
    Primitive primitive;
    for (std::size_t i = 0; i < positions.size(); ++i) {
        Vertex vertex;
        vertex.position = positions[i];
        if (i < uvs.size()) vertex.uv0 = uvs[i];
        primitive.vertices.push_back(vertex);
    }
    primitive.indices = indices;
    return primitive;
}

void expect_near(const glm::vec3& actual, const glm::vec3& expected, float tolerance = 1e-6f) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

TEST(SceneGeometry, TriangleListsFromEveryTopology) {
    const std::vector<uint32_t> sequence = {10, 11, 12, 13, 14, 15, 16};
    EXPECT_EQ(scene::triangle_list(Topology::Triangles, sequence), (std::vector<uint32_t>{10, 11, 12, 13, 14, 15}));
    EXPECT_EQ(scene::triangle_list(Topology::TriangleStrip, std::vector<uint32_t>{10, 11, 12, 13}),
              (std::vector<uint32_t>{10, 11, 12, 12, 11, 13}));
    EXPECT_EQ(scene::triangle_list(Topology::TriangleFan, std::vector<uint32_t>{10, 11, 12, 13}),
              (std::vector<uint32_t>{11, 12, 10, 12, 13, 10}));
    EXPECT_TRUE(scene::triangle_list(Topology::TriangleStrip, std::vector<uint32_t>{1, 2}).empty());
    EXPECT_TRUE(scene::triangle_list(Topology::Points, sequence).empty());
    EXPECT_TRUE(scene::triangle_list(Topology::LineStrip, sequence).empty());
}

TEST(SceneGeometry, FlatNormalOfASlantedTriangle) {
    // Edges (1,0,0) and (0,1,1): normal (0,-1,1)/sqrt(2).
    Primitive primitive = make_primitive({{0, 0, 0}, {1, 0, 0}, {0, 1, 1}, {5, 5, 5}}, {0, 1, 2, 2, 1, 0});
    scene::generate_flat_normals(primitive);
    ASSERT_EQ(primitive.vertices.size(), 6u);
    EXPECT_EQ(primitive.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
    const float s = 1.0f / std::sqrt(2.0f);
    for (int i = 0; i < 3; ++i) expect_near(primitive.vertices[i].normal, glm::vec3(0.0f, -s, s));
    for (int i = 3; i < 6; ++i) expect_near(primitive.vertices[i].normal, glm::vec3(0.0f, s, -s));  // reversed winding
    EXPECT_EQ(primitive.vertices[2].position, glm::vec3(0, 1, 1));
    EXPECT_EQ(primitive.vertices[3].position, glm::vec3(0, 1, 1));
    EXPECT_EQ(primitive.generated, scene::kAttributeNormal);
}

TEST(SceneGeometry, FlatNormalOfADegenerateTriangleIsAFallback) {
    Primitive primitive = make_primitive({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}, {0, 1, 2});
    scene::generate_flat_normals(primitive);
    for (const Vertex& vertex : primitive.vertices) EXPECT_EQ(vertex.normal, glm::vec3(0.0f, 0.0f, 1.0f));
}

TEST(SceneGeometry, SmoothNormalsAreAreaWeighted) {
    // A roof: a big triangle in the z = 0 plane and a small one standing up at x = 0, sharing
    // the edge from (0,0,0) to (0,1,0). The shared vertices lean towards the big face.
    Primitive primitive = make_primitive({{0, 0, 0}, {0, 1, 0}, {-4, 0, 0}, {0, 0, 1}}, {0, 1, 2, 0, 3, 1});
    scene::generate_smooth_normals(primitive);
    ASSERT_EQ(primitive.vertices.size(), 4u);
    // Big face: cross((0,1,0), (-4,0,0)) = (0,0,4). Small face: cross((0,0,1), (0,1,0)) = (-1,0,0).
    const glm::vec3 shared = glm::normalize(glm::vec3(-1.0f, 0.0f, 4.0f));
    expect_near(primitive.vertices[0].normal, shared);
    expect_near(primitive.vertices[1].normal, shared);
    expect_near(primitive.vertices[2].normal, glm::vec3(0, 0, 1));
    expect_near(primitive.vertices[3].normal, glm::vec3(-1, 0, 0));
    EXPECT_EQ(primitive.indices, (std::vector<uint32_t>{0, 1, 2, 0, 3, 1}));
}

TEST(SceneGeometry, TangentsOfAKnownQuad) {
    // The quad of glTF's convention: u right, v down the image (v = 0 at the top, y = 1).
    const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3};
    Primitive primitive = make_primitive(positions, indices, {{0, 1}, {1, 1}, {1, 0}, {0, 0}});
    for (Vertex& vertex : primitive.vertices) vertex.normal = glm::vec3(0, 0, 1);
    scene::generate_tangents(primitive, 0);
    for (const Vertex& vertex : primitive.vertices) EXPECT_EQ(vertex.tangent, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
    EXPECT_EQ(primitive.generated, scene::kAttributeTangent);

    // Mirrored texture (u runs right to left): tangent -X, handedness -1, so that
    // cross(normal, tangent) * w = +Y still points to decreasing v.
    Primitive mirrored = make_primitive(positions, indices, {{1, 1}, {0, 1}, {0, 0}, {1, 0}});
    for (Vertex& vertex : mirrored.vertices) vertex.normal = glm::vec3(0, 0, 1);
    scene::generate_tangents(mirrored, 0);
    for (const Vertex& vertex : mirrored.vertices) EXPECT_EQ(vertex.tangent, glm::vec4(-1.0f, 0.0f, 0.0f, -1.0f));

    // V running up the image instead (v = 0 at the bottom): tangent +X, handedness -1.
    Primitive flipped = make_primitive(positions, indices, {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    for (Vertex& vertex : flipped.vertices) vertex.normal = glm::vec3(0, 0, 1);
    scene::generate_tangents(flipped, 0);
    for (const Vertex& vertex : flipped.vertices) EXPECT_EQ(vertex.tangent, glm::vec4(1.0f, 0.0f, 0.0f, -1.0f));

    // UV set 1, rotated by 90 degrees: u runs up the quad (+Y).
    Primitive second = make_primitive(positions, indices);
    const std::vector<glm::vec2> uv1 = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    for (std::size_t i = 0; i < 4; ++i) {
        second.vertices[i].uv1 = uv1[i];
        second.vertices[i].normal = glm::vec3(0, 0, 1);
    }
    scene::generate_tangents(second, 1);
    for (const Vertex& vertex : second.vertices) {
        expect_near(glm::vec3(vertex.tangent), glm::vec3(0.0f, 1.0f, 0.0f));
        // v increases along +X here, so decreasing v is -X = cross(+Z, +Y) * w with w = +1.
        EXPECT_EQ(vertex.tangent.w, 1.0f);
    }
}

TEST(SceneGeometry, TangentsWithoutUvsFallBackToAPerpendicular) {
    Primitive primitive = make_primitive({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
    for (Vertex& vertex : primitive.vertices) vertex.normal = glm::vec3(1, 0, 0);
    scene::generate_tangents(primitive, 0);  // all UVs (0,0)
    for (const Vertex& vertex : primitive.vertices) {
        EXPECT_NEAR(glm::dot(glm::vec3(vertex.tangent), glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::length(glm::vec3(vertex.tangent)), 1.0f, 1e-6f);
        EXPECT_EQ(vertex.tangent.w, 1.0f);
    }
}

// AlphaBlendModeTest was exported with MikkTSpace tangents; on its flat quads and the bed the
// generated ones must agree in direction and handedness.
TEST(SceneGeometry, GeneratedTangentsMatchTheExportedOnes) {
    LOOM_REQUIRE_DATA_DIR(data);
    const scene::Scene* scene = load_cached(gltf_models(data) / "AlphaBlendModeTest" / "glTF" / "AlphaBlendModeTest.gltf");
    ASSERT_NE(scene, nullptr);
    std::size_t compared = 0;
    for (const scene::Mesh& mesh : scene->meshes) {
        for (const Primitive& original : mesh.primitives) {
            Primitive regenerated = original;
            scene::generate_tangents(regenerated, 0);
            for (std::size_t v = 0; v < original.vertices.size(); ++v) {
                const glm::vec4 expected = original.vertices[v].tangent;
                const glm::vec4 actual = regenerated.vertices[v].tangent;
                EXPECT_GT(glm::dot(glm::vec3(expected), glm::vec3(actual)), 0.999f) << mesh.name << " vertex " << v;
                EXPECT_EQ(expected.w, actual.w) << mesh.name << " vertex " << v;
                ++compared;
            }
        }
    }
    EXPECT_EQ(compared, 137u);
}

TEST(SceneGeometry, VertexBufferLayoutMatchesTheVertexStruct) {
    const rhi::VertexBufferLayout layout = scene::vertex_buffer_layout();
    EXPECT_EQ(layout.stride, 72u);
    EXPECT_EQ(layout.step, rhi::VertexStepMode::PerVertex);
    ASSERT_EQ(layout.attributes.size(), 6u);
    const std::vector<std::pair<rhi::VertexFormat, uint32_t>> expected = {
        {rhi::VertexFormat::Float3, 0},  {rhi::VertexFormat::Float3, 12}, {rhi::VertexFormat::Float4, 24},
        {rhi::VertexFormat::Float2, 40}, {rhi::VertexFormat::Float2, 48}, {rhi::VertexFormat::Float4, 56},
    };
    for (uint32_t i = 0; i < 6; ++i) {
        EXPECT_EQ(layout.attributes[i].location, i);
        EXPECT_EQ(layout.attributes[i].format, expected[i].first);
        EXPECT_EQ(layout.attributes[i].offset, expected[i].second);
    }
}

TEST(SceneGeometry, BoundsOperations) {
    scene::Bounds box;
    EXPECT_TRUE(box.empty());
    EXPECT_TRUE(box.transformed(glm::mat4(1.0f)).empty());
    box.extend(glm::vec3(1, 2, 3));
    EXPECT_FALSE(box.empty());
    box.extend(glm::vec3(-1, 0, 5));
    EXPECT_EQ(box.min, glm::vec3(-1, 0, 3));
    EXPECT_EQ(box.max, glm::vec3(1, 2, 5));
    EXPECT_EQ(box.center(), glm::vec3(0, 1, 4));
    EXPECT_EQ(box.corners()[5], glm::vec3(1, 0, 5));
    scene::Bounds other;
    box.extend(other);  // empty: no change
    EXPECT_EQ(box.max, glm::vec3(1, 2, 5));
    glm::mat4 shift(1.0f);
    shift[3] = glm::vec4(10, 0, 0, 1);
    EXPECT_EQ(box.transformed(shift).min, glm::vec3(9, 0, 3));
}

// Flat normals give every triangle its own corners; a skinned primitive's influences follow them.
TEST(Geometry, FlatNormalsKeepEachCornersSkinInfluences) {
    scene::Primitive primitive;
    for (const glm::vec3& p : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(1, 1, 0)}) {
        primitive.vertices.push_back(scene::Vertex{p});
    }
    primitive.indices = {0, 1, 2, 2, 1, 3};
    for (uint32_t v = 0; v < 4; ++v) primitive.skin.push_back({glm::uvec4(v, 0, 0, 0), glm::vec4(1, 0, 0, 0)});
    scene::generate_flat_normals(primitive);
    ASSERT_EQ(primitive.vertices.size(), 6u);
    ASSERT_EQ(primitive.skin.size(), 6u);
    const uint32_t corners[6] = {0, 1, 2, 2, 1, 3};
    for (std::size_t c = 0; c < 6; ++c) EXPECT_EQ(primitive.skin[c].joints.x, corners[c]) << c;
}

}  // namespace
}  // namespace loom::test

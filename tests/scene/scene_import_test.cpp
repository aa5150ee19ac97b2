// Import features on synthetic files with known content: index types, topologies, normalised
// and quantised attributes, interleaved views, sparse accessors without a buffer view,
// hierarchies, samplers, materials, cameras, skipped primitives and buffer layouts.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "loom/image_io/image_io.hpp"
#include "loom/gltf/gltf.hpp"
#include "loom_test/test_support.hpp"
#include "scene_test_util.hpp"

namespace loom::test {
namespace {

using Layout = GltfBuilder::Layout;
using scene::Scene;

Scene load_ok(const std::filesystem::path& path, const gltf::LoadOptions& options = {}) {
    auto scene = gltf::load(path, options);
    EXPECT_TRUE(scene) << scene.error().to_string();
    return scene ? std::move(*scene) : Scene{};
}

std::string current_test() {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    return std::string(info->test_suite_name()) + "." + info->name();
}

TEST(SceneImport, EveryIndexTypeAndNoIndicesGiveTheSameTriangles) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    std::vector<Scene> scenes;
    for (const int type : {kUnsignedByte, kUnsignedShort, kUnsignedInt, 0}) {
        GltfBuilder builder;
        // Two triangles, unshared vertices, so that a non-indexed primitive can express them.
        const int positions = builder.add_floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
        const int normals = builder.add_floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
        nlohmann::json primitive = {{"attributes", {{"POSITION", positions}, {"NORMAL", normals}}}};
        if (type != 0) primitive["indices"] = builder.add_indices({0, 1, 2, 3, 4, 5}, type);
        builder.set_scene({builder.add_node({{"mesh", builder.add_mesh(nlohmann::json::array({primitive}))}})});
        scenes.push_back(load_ok(builder.write(dir, "indices" + std::to_string(type), Layout::External)));
    }
    ASSERT_EQ(scenes.front().meshes.at(0).primitives.at(0).indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
    for (std::size_t i = 1; i < scenes.size(); ++i) expect_same_scene(scenes.front(), scenes[i]);
}

TEST(SceneImport, StripsAndFansBecomeListsWithTheirWinding) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    GltfBuilder builder;
    const int positions = builder.add_floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0}, "VEC3");
    const int strip = builder.add_indices({0, 1, 2, 3, 4});
    const nlohmann::json primitives = {
        {{"attributes", {{"POSITION", positions}}}, {"indices", strip}, {"mode", 5}},
        {{"attributes", {{"POSITION", positions}}}, {"indices", strip}, {"mode", 6}},
        {{"attributes", {{"POSITION", positions}}}, {"mode", 5}},  // non-indexed strip
    };
    builder.set_scene({builder.add_node({{"mesh", builder.add_mesh(primitives)}})});
    gltf::LoadOptions options;
    options.normals = gltf::NormalGeneration::Smooth;  // keeps the indices as they are
    const Scene scene = load_ok(builder.write(dir, "topologies", Layout::Embedded), options);
    ASSERT_EQ(scene.meshes.at(0).primitives.size(), 3u);
    const std::vector<uint32_t> strip_list = {0, 1, 2, 2, 1, 3, 2, 3, 4};
    EXPECT_EQ(scene.meshes[0].primitives[0].indices, strip_list);
    EXPECT_EQ(scene.meshes[0].primitives[1].indices, (std::vector<uint32_t>{1, 2, 0, 2, 3, 0, 3, 4, 0}));
    EXPECT_EQ(scene.meshes[0].primitives[2].indices, strip_list);
    // Every strip triangle faces +Z (counter-clockwise): the smooth normals say so.
    for (const scene::Vertex& vertex : scene.meshes[0].primitives[0].vertices) {
        EXPECT_EQ(vertex.normal, glm::vec3(0.0f, 0.0f, 1.0f));
    }
    EXPECT_EQ(scene.draw_items.size(), 3u);
}

TEST(SceneImport, PointsAndLinesAreSkippedWithAWarning) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    GltfBuilder builder;
    const int positions = builder.add_floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const nlohmann::json primitives = {
        {{"attributes", {{"POSITION", positions}}}, {"mode", 0}},
        {{"attributes", {{"POSITION", positions}}}, {"mode", 1}},
        {{"attributes", {{"POSITION", positions}}}, {"mode", 4}},
        {{"attributes", {{"TEXCOORD_0", builder.add_floats({0, 0, 1, 0, 0, 1}, "VEC2")}}}},  // no POSITION
    };
    builder.set_scene({builder.add_node({{"mesh", builder.add_mesh(primitives)}})});
    ScopedLogCapture capture;
    const Scene scene = load_ok(builder.write(dir, "points", Layout::External));
    ASSERT_EQ(scene.meshes.at(0).primitives.size(), 1u);
    EXPECT_EQ(scene.draw_items.size(), 1u);
    ASSERT_EQ(scene.warnings.size(), 3u);
    EXPECT_NE(scene.warnings[0].find("/meshes/0/primitives/0/mode: mode 0 (points) is not supported"), std::string::npos)
        << scene.warnings[0];
    EXPECT_NE(scene.warnings[1].find("/meshes/0/primitives/1/mode: mode 1 (lines)"), std::string::npos) << scene.warnings[1];
    EXPECT_NE(scene.warnings[2].find("/meshes/0/primitives/3/attributes: primitive has no POSITION"), std::string::npos);
    // The warnings were logged too.
    EXPECT_EQ(capture.messages().size(), 3u);
}

TEST(SceneImport, NormalisedIntegerAttributesAndColours) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    GltfBuilder builder;
    const int positions = builder.add_floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    // TEXCOORD_0: normalised u8, padded to 4 bytes per element (vertex attribute alignment).
    const int uv0_view = builder.add_view(std::vector<uint8_t>{0, 255, 0, 0, 255, 0, 0, 0, 51, 102, 0, 0}, 4);
    const int uv0 = builder.add_accessor(uv0_view, kUnsignedByte, 3, "VEC2", 0, true);
    // TEXCOORD_1: normalised u16.
    const int uv1 = builder.add_accessor(builder.add_view(std::vector<uint16_t>{0, 65535, 65535, 0, 13107, 26214}), kUnsignedShort,
                                         3, "VEC2", 0, true);
    // COLOR_0: normalised u16 VEC3 (alpha becomes 1).
    const int color = builder.add_accessor(
        builder.add_view(std::vector<uint16_t>{65535, 0, 0, 0, 0, 65535, 0, 0, 0, 0, 65535, 0}, 8), kUnsignedShort, 3, "VEC3", 0,
        true);
    const nlohmann::json primitive = {
        {"attributes", {{"POSITION", positions}, {"TEXCOORD_0", uv0}, {"TEXCOORD_1", uv1}, {"COLOR_0", color}}}};
    builder.set_scene({builder.add_node({{"mesh", builder.add_mesh(nlohmann::json::array({primitive}))}})});
    const Scene scene = load_ok(builder.write(dir, "normalized", Layout::Binary));
    const auto& vertices = scene.meshes.at(0).primitives.at(0).vertices;
    ASSERT_EQ(vertices.size(), 3u);
    EXPECT_EQ(vertices[0].uv0, glm::vec2(0.0f, 1.0f));
    EXPECT_EQ(vertices[1].uv0, glm::vec2(1.0f, 0.0f));
    EXPECT_EQ(vertices[2].uv0, glm::vec2(0.2f, 0.4f));
    EXPECT_EQ(vertices[2].uv1, glm::vec2(0.2f, 0.4f));
    EXPECT_EQ(vertices[0].uv1, glm::vec2(0.0f, 1.0f));
    EXPECT_EQ(vertices[0].color, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
    EXPECT_EQ(vertices[2].color, glm::vec4(0.0f, 0.0f, 1.0f, 1.0f));
    EXPECT_EQ(scene.meshes[0].primitives[0].from_file,
              scene::kAttributeUv0 | scene::kAttributeUv1 | scene::kAttributeColor);
}

TEST(SceneImport, FloatVec4ColoursAndInterleavedViews) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    GltfBuilder builder;
    // One interleaved view: position (12 bytes) + colour (16 bytes) per vertex, stride 28.
    const std::vector<float> interleaved = {0, 0, 0, 1, 0, 0, 0.5f,   //
                                            1, 0, 0, 0, 1, 0, 0.25f,  //
                                            0, 1, 0, 0, 0, 1, 1};
    const int view = builder.add_view(interleaved, 28);
    const int positions = builder.add_accessor(view, kFloat, 3, "VEC3");
    builder.json()["accessors"][positions]["min"] = {0, 0, 0};  // glTF requires POSITION bounds
    builder.json()["accessors"][positions]["max"] = {1, 1, 0};
    const int colors = builder.add_accessor(view, kFloat, 3, "VEC4", 12);
    const nlohmann::json primitive = {{"attributes", {{"POSITION", positions}, {"COLOR_0", colors}}}};
    builder.set_scene({builder.add_node({{"mesh", builder.add_mesh(nlohmann::json::array({primitive}))}})});
    const Scene scene = load_ok(builder.write(dir, "interleaved", Layout::External));
    // Flat normals de-index: the vertices keep their order for a non-indexed triangle.
    const auto& vertices = scene.meshes.at(0).primitives.at(0).vertices;
    ASSERT_EQ(vertices.size(), 3u);
    EXPECT_EQ(vertices[1].position, glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(vertices[1].color, glm::vec4(0.0f, 1.0f, 0.0f, 0.25f));
    EXPECT_EQ(vertices[2].color, glm::vec4(0.0f, 0.0f, 1.0f, 1.0f));
}

TEST(SceneImport, MeshQuantizationAttributes) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    GltfBuilder builder;
    builder.json()["extensionsUsed"] = {"KHR_mesh_quantization"};
    builder.json()["extensionsRequired"] = {"KHR_mesh_quantization"};
    // Positions as plain shorts (padded to 8 bytes), normals as normalised bytes, texture
    // coordinates as plain unsigned bytes.
    const int positions = builder.add_accessor(builder.add_view(std::vector<int16_t>{0, 0, 0, 0, 100, 0, 0, 0, 0, -100, 0, 0}, 8),
                                               kShort, 3, "VEC3");
    builder.json()["accessors"][positions]["min"] = {0, -100, 0};  // glTF requires POSITION bounds
    builder.json()["accessors"][positions]["max"] = {100, 0, 0};
    const int normals = builder.add_accessor(builder.add_view(std::vector<int8_t>{0, 0, 127, 0, 0, 0, -128, 0, 0, -127, 0, 0}, 4),
                                             kByte, 3, "VEC3", 0, true);
    const int uvs = builder.add_accessor(builder.add_view(std::vector<uint8_t>{0, 0, 0, 0, 2, 0, 0, 0, 0, 3, 0, 0}, 4),
                                         kUnsignedByte, 3, "VEC2");
    const nlohmann::json primitive = {{"attributes", {{"POSITION", positions}, {"NORMAL", normals}, {"TEXCOORD_0", uvs}}}};
    // The node scales the quantised positions back.
    builder.set_scene({builder.add_node({{"mesh", builder.add_mesh(nlohmann::json::array({primitive}))}, {"scale", {0.01, 0.01, 0.01}}})});
    const Scene scene = load_ok(builder.write(dir, "quantized", Layout::Embedded));
    const auto& vertices = scene.meshes.at(0).primitives.at(0).vertices;
    EXPECT_EQ(vertices[1].position, glm::vec3(100.0f, 0.0f, 0.0f));
    EXPECT_EQ(vertices[2].position, glm::vec3(0.0f, -100.0f, 0.0f));
    EXPECT_EQ(vertices[0].normal, glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(vertices[1].normal, glm::vec3(0.0f, 0.0f, -1.0f));  // -128 clamps to -1
    EXPECT_EQ(vertices[2].normal, glm::vec3(0.0f, -1.0f, 0.0f));
    EXPECT_EQ(vertices[1].uv0, glm::vec2(2.0f, 0.0f));
    EXPECT_NEAR(scene.bounds.max.x, 1.0f, 1e-6f);
    EXPECT_NEAR(scene.bounds.min.y, -1.0f, 1e-6f);

    // Without the extension the same attributes are errors.
    const std::filesystem::path without = builder.write(dir, "unquantized", Layout::Embedded, [](nlohmann::json& doc) {
        doc.erase("extensionsUsed");
        doc.erase("extensionsRequired");
    });
    auto result = gltf::load(without);
    ASSERT_FALSE(result);
    EXPECT_NE(result.error().message.find("/meshes/0/primitives/0/attributes/NORMAL: accessor 1 is VEC3 BYTE normalized"),
              std::string::npos)
        << result.error().message;
}

TEST(SceneImport, SparseAccessorWithoutABufferView) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    GltfBuilder builder;
    // All-zero positions, three of which a sparse substitution (u16 indices) moves.
    const int indices = builder.add_view(std::vector<uint16_t>{0, 2, 3, 0});
    const int values = builder.add_view(std::vector<float>{1, 0, 0, 0, 1, 0, 1, 1, 0});
    builder.json()["accessors"].push_back({{"componentType", kFloat},
                                           {"count", 4},
                                           {"type", "VEC3"},
                                           {"min", {0, 0, 0}},  // glTF requires POSITION bounds
                                           {"max", {1, 1, 0}},
                                           {"sparse",
                                            {{"count", 3},
                                             {"indices", {{"bufferView", indices}, {"componentType", kUnsignedShort}}},
                                             {"values", {{"bufferView", values}}}}}});
    const nlohmann::json primitive = {{"attributes", {{"POSITION", 0}}}, {"indices", builder.add_indices({1, 0, 2, 0, 3, 2})}};
    builder.set_scene({builder.add_node({{"mesh", builder.add_mesh(nlohmann::json::array({primitive}))}})});
    gltf::LoadOptions options;
    options.normals = gltf::NormalGeneration::Smooth;
    const Scene scene = load_ok(builder.write(dir, "sparse", Layout::External), options);
    const auto& vertices = scene.meshes.at(0).primitives.at(0).vertices;
    ASSERT_EQ(vertices.size(), 4u);
    EXPECT_EQ(vertices[0].position, glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(vertices[1].position, glm::vec3(0.0f));
    EXPECT_EQ(vertices[2].position, glm::vec3(0.0f, 1.0f, 0.0f));
    EXPECT_EQ(vertices[3].position, glm::vec3(1.0f, 1.0f, 0.0f));
}

TEST(SceneImport, NodeHierarchyWorldMatricesAndMirroring) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    GltfBuilder builder;
    const int mesh = builder.add_quad(true);  // node 0 holds it
    builder.json()["nodes"][0] = {{"translation", {1, 2, 3}}, {"children", {1}}};
    builder.add_node({{"rotation", {0, 0.7071067811865476, 0, 0.7071067811865476}}, {"children", {2}}});  // 90 deg about Y
    builder.add_node({{"scale", {-2, 1, 1}}, {"mesh", mesh}});
    const Scene scene = load_ok(builder.write(dir, "hierarchy", Layout::External));
    ASSERT_EQ(scene.draw_items.size(), 1u);
    const scene::DrawItem& item = scene.draw_items[0];
    EXPECT_EQ(item.node, 2u);
    EXPECT_EQ(scene.nodes[2].parent, std::optional<uint32_t>(1));
    EXPECT_EQ(scene.nodes[1].parent, std::optional<uint32_t>(0));
    // Local (1,0,0) -> scale (-2,0,0) -> rotate about Y (0,0,2) -> translate (1,2,5).
    const glm::vec4 moved = item.world * glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
    EXPECT_NEAR(moved.x, 1.0f, 1e-6f);
    EXPECT_NEAR(moved.y, 2.0f, 1e-6f);
    EXPECT_NEAR(moved.z, 5.0f, 1e-6f);
    EXPECT_TRUE(item.flips_winding);  // the negative scale mirrors
    // The quad's +Z normal: mirrored in x does not change it, the rotation turns it to +X.
    const glm::vec3 normal = glm::normalize(item.normal_matrix * glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_NEAR(normal.x, 1.0f, 1e-6f);
    EXPECT_NEAR(normal.z, 0.0f, 1e-6f);
    // Exact world bounds of the quad (0..1 in x and y): x -> z in [3, 5], y in [2, 3].
    EXPECT_NEAR(item.world_bounds.min.z, 3.0f, 1e-6f);
    EXPECT_NEAR(item.world_bounds.max.z, 5.0f, 1e-6f);
    EXPECT_NEAR(item.world_bounds.min.y, 2.0f, 1e-6f);
    EXPECT_NEAR(item.world_bounds.max.y, 3.0f, 1e-6f);
    EXPECT_EQ(scene.bounds, item.world_bounds);
}

TEST(SceneImport, FilesWithoutScenesShowEveryRoot) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    GltfBuilder builder;
    const int mesh = builder.add_quad(true);
    builder.json().erase("scenes");
    builder.json().erase("scene");
    builder.add_node({{"mesh", mesh}, {"translation", {5, 0, 0}}});
    const Scene scene = load_ok(builder.write(dir, "no_scenes", Layout::External));
    EXPECT_EQ(scene.draw_items.size(), 2u);
    EXPECT_EQ(scene.bounds.max.x, 6.0f);

    // LoadOptions::scene picks a scene; one that does not exist is an InvalidArgument error.
    builder.json()["scenes"] = nlohmann::json::array({{{"nodes", {0}}}, {{"nodes", {1}}}});
    gltf::LoadOptions options;
    options.scene = 1;
    const Scene second = load_ok(builder.write(dir, "two_scenes", Layout::External), options);
    ASSERT_EQ(second.draw_items.size(), 1u);
    EXPECT_EQ(second.draw_items[0].node, 1u);
    options.scene = 2;
    auto missing = gltf::load(dir / "two_scenes.gltf", options);
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().code, ErrorCode::InvalidArgument);
}

TEST(SceneImport, UnsupportedUsedExtensionsAreIgnoredWithAWarning) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    GltfBuilder builder;
    builder.add_quad(true);
    builder.json()["extensionsUsed"] = {"KHR_mesh_quantization", "KHR_materials_clearcoat"};
    ScopedLogCapture capture;
    const Scene scene = load_ok(builder.write(dir, "extensions", Layout::External));
    ASSERT_EQ(scene.warnings.size(), 1u);
    EXPECT_NE(scene.warnings[0].find("/extensionsUsed/1: extension 'KHR_materials_clearcoat' is not supported"),
              std::string::npos)
        << scene.warnings[0];
    EXPECT_EQ(scene.draw_items.size(), 1u);
}

// EXT_texture_webp, used but not required: its WebP images (a data URI, a buffer view) are
// allowed and never decoded; every texture draws with its PNG fallback `source`. Without the
// extension declared, a WebP image is an error.
TEST(SceneImport, WebpTexturesDrawTheirPngFallback) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    rhi::Image pixel(1, 1, rhi::Format::RGBA8Unorm);
    pixel.pixels = {std::byte{200}, std::byte{10}, std::byte{20}, std::byte{255}};
    ASSERT_TRUE(image_io::write_png(pixel, dir / "pixel.png").ok());
    const std::vector<unsigned char> webp = {'R', 'I', 'F', 'F', 4, 0, 0, 0, 'W', 'E', 'B', 'P'};
    const auto build = [&](bool declared) {
        GltfBuilder builder;
        builder.add_quad(true, 0);
        const int webp_view = builder.add_view(webp.data(), webp.size());
        builder.json()["images"] = nlohmann::json::array({{{"uri", "pixel.png"}},
                                                          {{"uri", "data:image/webp;base64,UklGRgQAAABXRUJQ"}},
                                                          {{"bufferView", webp_view}, {"mimeType", "image/webp"}}});
        builder.json()["textures"] = nlohmann::json::array(
            {{{"source", 0}, {"extensions", {{"EXT_texture_webp", {{"source", 1}}}}}},
             {{"source", 0}, {"extensions", {{"EXT_texture_webp", {{"source", 2}}}}}}});
        builder.json()["materials"] = nlohmann::json::array(
            {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}},
             {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 1}}}}}}});
        if (declared) builder.json()["extensionsUsed"] = {"EXT_texture_webp"};
        return builder.write(dir, declared ? "webp" : "webp_undeclared", Layout::External);
    };
    ScopedLogCapture capture;
    const Scene scene = load_ok(build(true));
    ASSERT_EQ(scene.textures.size(), 2u);
    ASSERT_EQ(scene.images.size(), 1u);  // the PNG, shared; the WebP images are not decoded
    EXPECT_EQ(scene.images[0].image.pixels[0], std::byte{200});
    ASSERT_EQ(scene.warnings.size(), 1u);
    EXPECT_NE(scene.warnings[0].find("/extensionsUsed/0: extension 'EXT_texture_webp' is not supported"), std::string::npos)
        << scene.warnings[0];

    auto undeclared = gltf::load(build(false));
    ASSERT_FALSE(undeclared.ok());
    EXPECT_NE(undeclared.error().message.find("/images/1/uri: data URI media type 'image/webp' is not supported"),
              std::string::npos)
        << undeclared.error().message;
}

TEST(SceneImport, SamplersMapToRhiSamplerDescriptions) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    struct Case {
        nlohmann::json sampler;
        rhi::Filter min, mag, mip;
        float max_lod;
        rhi::AddressMode u, v;
    };
    using F = rhi::Filter;
    using A = rhi::AddressMode;
    const std::vector<Case> cases = {
        {nlohmann::json::object(), F::Linear, F::Linear, F::Linear, 1000.0f, A::Repeat, A::Repeat},
        {{{"magFilter", 9728}, {"minFilter", 9728}}, F::Nearest, F::Nearest, F::Nearest, 0.0f, A::Repeat, A::Repeat},
        {{{"minFilter", 9729}, {"wrapS", 33071}, {"wrapT", 33648}}, F::Linear, F::Linear, F::Nearest, 0.0f, A::ClampToEdge,
         A::MirroredRepeat},
        {{{"minFilter", 9984}}, F::Nearest, F::Linear, F::Nearest, 1000.0f, A::Repeat, A::Repeat},
        {{{"minFilter", 9985}}, F::Linear, F::Linear, F::Nearest, 1000.0f, A::Repeat, A::Repeat},
        {{{"minFilter", 9986}, {"magFilter", 9728}}, F::Nearest, F::Nearest, F::Linear, 1000.0f, A::Repeat, A::Repeat},
        {{{"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 33071}}, F::Linear, F::Linear, F::Linear, 1000.0f, A::Repeat,
         A::ClampToEdge},
    };
    GltfBuilder builder;
    builder.add_quad(true, 0);
    rhi::Image pixel(1, 1, rhi::Format::RGBA8Unorm);
    ASSERT_TRUE(image_io::write_png(pixel, dir / "pixel.png").ok());
    builder.json()["images"] = nlohmann::json::array({{{"uri", "pixel.png"}}});
    for (std::size_t i = 0; i < cases.size(); ++i) {
        builder.json()["samplers"].push_back(cases[i].sampler);
        builder.json()["textures"].push_back({{"source", 0}, {"sampler", i}});
    }
    builder.json()["textures"].push_back({{"source", 0}});  // no sampler at all: glTF defaults
    // One material per texture, so that every texture is used.
    for (std::size_t i = 0; i <= cases.size(); ++i) {
        builder.json()["materials"].push_back({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", i}}}}}});
    }
    const Scene scene = load_ok(builder.write(dir, "samplers", Layout::External));
    ASSERT_EQ(scene.textures.size(), cases.size() + 1);
    ASSERT_EQ(scene.images.size(), 1u);  // one decoded image shared by all
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const rhi::SamplerDesc& desc = scene.textures[i].sampler;
        SCOPED_TRACE(cases[i].sampler.dump());
        EXPECT_EQ(desc.min_filter, cases[i].min);
        EXPECT_EQ(desc.mag_filter, cases[i].mag);
        EXPECT_EQ(desc.mipmap_filter, cases[i].mip);
        EXPECT_EQ(desc.max_lod, cases[i].max_lod);
        EXPECT_EQ(desc.address_u, cases[i].u);
        EXPECT_EQ(desc.address_v, cases[i].v);
    }
    const rhi::SamplerDesc& fallback = scene.textures.back().sampler;
    EXPECT_EQ(fallback.min_filter, rhi::Filter::Linear);
    EXPECT_EQ(fallback.mipmap_filter, rhi::Filter::Linear);
    EXPECT_EQ(fallback.address_u, rhi::AddressMode::Repeat);
}

// KHR_texture_transform on a texture reference: offset, rotation, scale, and a texCoord that
// replaces the reference's own.
TEST(SceneImport, TextureTransformIsRead) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    GltfBuilder builder;
    builder.add_quad(true, 0);
    builder.json()["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = builder.add_floats({0, 0, 1, 0, 1, 1, 0, 1}, "VEC2");
    rhi::Image pixel(1, 1, rhi::Format::RGBA8Unorm);
    ASSERT_TRUE(image_io::write_png(pixel, dir / "pixel.png").ok());
    builder.json()["images"] = nlohmann::json::array({{{"uri", "pixel.png"}}});
    builder.json()["textures"] = nlohmann::json::array({{{"source", 0}}});
    builder.json()["extensionsUsed"] = {"KHR_texture_transform"};
    nlohmann::json transform = {{"offset", {0.25, 0.5}}, {"rotation", 0.5}, {"scale", {2.0, 4.0}}, {"texCoord", 1}};
    nlohmann::json material_json;
    material_json["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}, {"extensions", {{"KHR_texture_transform", transform}}}};
    material_json["emissiveTexture"] = {{"index", 0}};
    builder.json()["materials"] = nlohmann::json::array({material_json});
    ScopedLogCapture capture;
    const Scene scene = load_ok(builder.write(dir, "transform", Layout::Embedded));
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
    const scene::Material& material = scene.materials.at(0);
    ASSERT_TRUE(material.base_color_texture.has_value());
    EXPECT_EQ(material.base_color_texture->uv_set, 1u);
    ASSERT_TRUE(material.base_color_texture->transform.has_value());
    EXPECT_EQ(*material.base_color_texture->transform, (scene::TextureTransform{{0.25f, 0.5f}, 0.5f, {2.0f, 4.0f}}));
    const auto rows = material.base_color_texture->transform->rows();
    EXPECT_NEAR(rows[0].x, 2.0 * std::cos(0.5), 1e-6);
    EXPECT_NEAR(rows[0].y, 4.0 * std::sin(0.5), 1e-6);
    EXPECT_EQ(rows[0].z, 0.25f);
    EXPECT_NEAR(rows[1].x, -2.0 * std::sin(0.5), 1e-6);
    EXPECT_NEAR(rows[1].y, 4.0 * std::cos(0.5), 1e-6);
    EXPECT_EQ(rows[1].z, 0.5f);
    ASSERT_TRUE(material.emissive_texture.has_value());
    EXPECT_FALSE(material.emissive_texture->transform.has_value());
}

// KHR_materials_emissive_strength multiplies the emissive factor (HDR emission); without the
// extension the factor stays as it is.
TEST(SceneImport, EmissiveStrengthScalesTheEmissiveFactor) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    GltfBuilder builder;
    builder.add_quad(true, 0);
    builder.json()["extensionsUsed"] = {"KHR_materials_emissive_strength"};
    builder.json()["materials"] = nlohmann::json::array(
        {{{"emissiveFactor", {1.0, 0.5, 0.0}}, {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 6.0}}}}}},
         {{"emissiveFactor", {1.0, 0.5, 0.0}}}});
    ScopedLogCapture capture;
    const Scene scene = load_ok(builder.write(dir, "strength", Layout::Embedded));
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
    EXPECT_EQ(scene.materials.at(0).emissive_factor, glm::vec3(6.0f, 3.0f, 0.0f));
    EXPECT_EQ(scene.materials.at(1).emissive_factor, glm::vec3(1.0f, 0.5f, 0.0f));
}

TEST(SceneImport, MaterialFactorsTexturesAndUvSets) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    GltfBuilder builder;
    builder.add_quad(true, 0);
    // A second UV set for the occlusion texture.
    builder.json()["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = builder.add_floats({0, 0, 1, 0, 1, 1, 0, 1}, "VEC2");
    rhi::Image pixel(2, 1, rhi::Format::RGBA8Unorm);
    pixel.store(1, 0, {0.0, 1.0, 0.0, 1.0});
    ASSERT_TRUE(image_io::write_png(pixel, dir / "two pixels.png").ok());
    builder.json()["images"] = nlohmann::json::array({{{"uri", "two%20pixels.png"}, {"name", "pixels"}}});
    builder.json()["textures"] = nlohmann::json::array({{{"source", 0}}, {{"source", 0}, {"name", "orm"}}});
    builder.json()["materials"] = nlohmann::json::array({{
        {"name", "everything"},
        {"pbrMetallicRoughness",
         {{"baseColorFactor", {0.5, 0.25, 1.0, 0.75}},
          {"baseColorTexture", {{"index", 0}}},
          {"metallicFactor", 0.5},
          {"roughnessFactor", 0.125},
          {"metallicRoughnessTexture", {{"index", 1}}}}},
        {"normalTexture", {{"index", 1}, {"scale", 0.5}}},
        {"occlusionTexture", {{"index", 1}, {"texCoord", 1}, {"strength", 0.25}}},
        {"emissiveTexture", {{"index", 0}}},
        {"emissiveFactor", {1.0, 0.5, 0.0}},
        {"alphaMode", "MASK"},
        {"alphaCutoff", 0.3},
        {"doubleSided", true},
    }});
    const Scene scene = load_ok(builder.write(dir, "material", Layout::Binary));
    const scene::Material& material = scene.materials.at(0);
    EXPECT_EQ(material.name, "everything");
    EXPECT_EQ(material.base_color_factor, glm::vec4(0.5f, 0.25f, 1.0f, 0.75f));
    EXPECT_EQ(material.metallic_factor, 0.5f);
    EXPECT_EQ(material.roughness_factor, 0.125f);
    EXPECT_EQ(material.emissive_factor, glm::vec3(1.0f, 0.5f, 0.0f));
    EXPECT_EQ(material.normal_scale, 0.5f);
    EXPECT_EQ(material.occlusion_strength, 0.25f);
    EXPECT_EQ(material.alpha_mode, scene::AlphaMode::Mask);
    EXPECT_EQ(material.alpha_cutoff, 0.3f);
    EXPECT_TRUE(material.double_sided);
    ASSERT_TRUE(material.base_color_texture && material.emissive_texture && material.metallic_roughness_texture &&
                material.normal_texture && material.occlusion_texture);
    // glTF texture 0 in sRGB (base colour, emissive) and glTF texture 1 in linear (the rest).
    EXPECT_EQ(material.base_color_texture->texture, material.emissive_texture->texture);
    EXPECT_EQ(material.metallic_roughness_texture->texture, material.normal_texture->texture);
    EXPECT_EQ(material.normal_texture->texture, material.occlusion_texture->texture);
    EXPECT_NE(material.base_color_texture->texture, material.normal_texture->texture);
    EXPECT_EQ(material.occlusion_texture->uv_set, 1u);
    EXPECT_EQ(material.normal_texture->uv_set, 0u);
    ASSERT_EQ(scene.textures.size(), 2u);
    ASSERT_EQ(scene.images.size(), 2u);  // the same image decoded once per colour space
    const scene::TextureImage& srgb = scene.images[scene.textures[material.base_color_texture->texture].image];
    const scene::TextureImage& linear = scene.images[scene.textures[material.normal_texture->texture].image];
    EXPECT_EQ(srgb.image.format, rhi::Format::RGBA8Srgb);
    EXPECT_EQ(linear.image.format, rhi::Format::RGBA8Unorm);
    EXPECT_EQ(srgb.name, "pixels");
    EXPECT_EQ(scene.textures[material.normal_texture->texture].name, "orm");
    EXPECT_EQ(srgb.image.pixels, linear.image.pixels);
    // Row 0, pixel 1 is green, as written.
    EXPECT_EQ(linear.image.load(1, 0), (std::array<double, 4>{0.0, 1.0, 0.0, 1.0}));
    // The quad has NORMAL but no TANGENT and a normal map: tangents are generated from UV set 0.
    const scene::Primitive& primitive = scene.meshes.at(0).primitives.at(0);
    EXPECT_EQ(primitive.generated, scene::kAttributeTangent);
    EXPECT_EQ(primitive.vertices[0].tangent, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
}

TEST(SceneImport, PerspectiveCameraWithoutAspectOrFarPlane) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    GltfBuilder builder;
    builder.add_quad(true);
    builder.json()["cameras"] = nlohmann::json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.5}}}}});
    builder.json()["nodes"].push_back({{"camera", 0}, {"translation", {0, 0, 4}}, {"name", "eye"}});
    builder.json()["scenes"][0]["nodes"].push_back(1);
    const Scene scene = load_ok(builder.write(dir, "camera", Layout::External));
    ASSERT_EQ(scene.cameras.size(), 1u);
    const scene::Camera& camera = scene.cameras[0];
    EXPECT_EQ(camera.name, "eye");
    const auto& perspective = std::get<scene::PerspectiveProjection>(camera.projection);
    EXPECT_FALSE(perspective.aspect_ratio.has_value());
    EXPECT_FALSE(perspective.zfar.has_value());
    // The viewport's aspect is used; depth is 0 at the near plane and approaches 1 far away.
    const glm::mat4 projection = camera.projection_matrix(2.0f);
    EXPECT_FLOAT_EQ(projection[0][0], 1.0f / std::tan(0.5f) / 2.0f);
    EXPECT_FLOAT_EQ(projection[1][1], 1.0f / std::tan(0.5f));
    const glm::vec4 near_point = projection * glm::vec4(0.0f, 0.0f, -0.5f, 1.0f);
    EXPECT_NEAR(near_point.z / near_point.w, 0.0f, 1e-6f);
    const glm::vec4 far_point = projection * glm::vec4(0.0f, 0.0f, -1e6f, 1.0f);
    EXPECT_GT(far_point.z / far_point.w, 0.999f);
    EXPECT_LT(far_point.z / far_point.w, 1.0f);
    // The origin (the quad's corner) lies straight ahead of the camera at (0, 0, 4).
    const glm::vec4 clip = camera.view_projection(2.0f) * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    EXPECT_NEAR(clip.x / clip.w, 0.0f, 1e-6f);
    EXPECT_NEAR(clip.y / clip.w, 0.0f, 1e-6f);
}

TEST(SceneImport, LayoutsGiveIdenticalScenes) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    GltfBuilder builder;
    builder.add_quad(false, 0);
    rhi::Image pixel(1, 1, rhi::Format::RGBA8Unorm);
    ASSERT_TRUE(image_io::write_png(pixel, dir / "pixel.png").ok());
    const std::vector<unsigned char> png_bytes = read_bytes(dir / "pixel.png");
    builder.json()["images"] = nlohmann::json::array({{{"bufferView", builder.add_view(png_bytes)}, {"mimeType", "image/png"}}});
    builder.json()["textures"] = nlohmann::json::array({{{"source", 0}}});
    builder.json()["materials"] = nlohmann::json::array({{{"normalTexture", {{"index", 0}}}}});
    const Scene external = load_ok(builder.write(dir, "external", Layout::External));
    const Scene embedded = load_ok(builder.write(dir, "embedded", Layout::Embedded));
    const Scene binary = load_ok(builder.write(dir, "binary", Layout::Binary));
    // RFC 2397 data URIs without ";base64": the bytes percent-encoded (every one, so that the
    // URI holds no raw binary), the PNG as an image of its own.
    const auto percent_encoded = [](const std::vector<unsigned char>& bytes, const std::string& media) {
        static constexpr char kHex[] = "0123456789ABCDEF";
        std::string uri = "data:" + media + ",";
        for (const unsigned char b : bytes) uri += {'%', kHex[b >> 4], kHex[b & 15]};
        return uri;
    };
    const Scene percent = load_ok(builder.write(dir, "percent", Layout::Embedded, [&](nlohmann::json& doc) {
        doc["buffers"][0]["uri"] = percent_encoded(builder.bin(), "application/octet-stream");
        doc["images"][0] = {{"uri", percent_encoded(png_bytes, "image/png")}};
    }));
    EXPECT_EQ(external.vertex_count(), 6u);  // flat normals for the quad without them
    EXPECT_EQ(external.meshes.at(0).primitives.at(0).generated, scene::kAttributeNormal | scene::kAttributeTangent);
    expect_same_scene(external, embedded);
    expect_same_scene(external, binary);
    expect_same_scene(external, percent);
}

// Animations: the channels on a node's translation, rotation and scale are imported with their
// samplers; a channel the file may not have (on a node with a matrix, a second one on the same
// target, a sampler whose times decrease or whose rotations are not unit quaternions) is left
// out with a warning naming it, one without a node is ignored, as the specification says.
TEST(SceneImport, AnimationsKeepTheChannelsThatMayDriveANodeAndPoseTheScene) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    GltfBuilder builder;
    const int positions = builder.add_floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int mesh = builder.add_mesh(nlohmann::json::array({{{"attributes", {{"POSITION", positions}}}}}));
    const int moving = builder.add_node({{"mesh", mesh}});
    const int fixed = builder.add_node({{"mesh", mesh}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 7, 1}}});
    const int turning = builder.add_node({{"mesh", mesh}, {"translation", {0, 3, 0}}});
    builder.set_scene({moving, fixed, turning});
    const int times = builder.add_floats({0, 1}, "SCALAR");
    const int decreasing = builder.add_floats({1, 0.5f}, "SCALAR");
    const int slide = builder.add_floats({0, 0, 0, 4, 0, 0}, "VEC3");
    const int half_turn = builder.add_floats({0, 0, 0, 1, 0, 0, 1, 0}, "VEC4");
    const int not_unit = builder.add_floats({0, 0, 0, 2, 0, 0, 0, 1}, "VEC4");
    auto channel = [](int sampler, std::optional<int> node, const char* path) {
        nlohmann::json target = {{"path", path}};
        if (node) target["node"] = *node;
        return nlohmann::json{{"sampler", sampler}, {"target", target}};
    };
    builder.json()["animations"] = nlohmann::json::array({{
        {"name", "move"},
        {"samplers",
         {{{"input", times}, {"output", slide}},
          {{"input", times}, {"output", half_turn}, {"interpolation", "STEP"}},
          {{"input", decreasing}, {"output", slide}},
          {{"input", times}, {"output", not_unit}}}},
        {"channels",
         {channel(0, moving, "translation"), channel(1, turning, "rotation"), channel(0, fixed, "translation"),
          channel(2, turning, "translation"), channel(0, moving, "translation"), channel(3, moving, "rotation"),
          channel(0, std::nullopt, "translation")}},
    }});
    Scene scene = load_ok(builder.write(dir, "animated", Layout::Embedded));

    ASSERT_EQ(scene.animations.size(), 1u);
    const scene::Animation& animation = scene.animations[0];
    EXPECT_EQ(animation.name, "move");
    ASSERT_EQ(animation.channels.size(), 2u);
    EXPECT_EQ(animation.channels[0].node, static_cast<uint32_t>(moving));
    EXPECT_EQ(animation.channels[0].property, scene::AnimatedProperty::Translation);
    EXPECT_EQ(animation.channels[1].node, static_cast<uint32_t>(turning));
    EXPECT_EQ(animation.channels[1].property, scene::AnimatedProperty::Rotation);
    ASSERT_EQ(animation.samplers.size(), 2u);
    EXPECT_EQ(animation.samplers[animation.channels[0].sampler].values, (std::vector<float>{0, 0, 0, 4, 0, 0}));
    EXPECT_EQ(animation.samplers[animation.channels[1].sampler].interpolation, scene::Interpolation::Step);
    EXPECT_EQ(animation.duration(), 1.0f);
    EXPECT_TRUE(scene.nodes[static_cast<std::size_t>(fixed)].has_matrix);
    EXPECT_EQ(scene.nodes[static_cast<std::size_t>(turning)].translation, glm::vec3(0, 3, 0));
    auto warned = [&](const std::string& pointer) {
        return std::any_of(scene.warnings.begin(), scene.warnings.end(),
                           [&](const std::string& w) { return w.find(": " + pointer + ":") != std::string::npos; });
    };
    EXPECT_TRUE(warned("/animations/0/channels/2/target")) << ::testing::PrintToString(scene.warnings);
    EXPECT_TRUE(warned("/animations/0/samplers/2/input")) << ::testing::PrintToString(scene.warnings);
    EXPECT_TRUE(warned("/animations/0/channels/0/target")) << ::testing::PrintToString(scene.warnings);  // channel 4's twin
    EXPECT_TRUE(warned("/animations/0/channels/5/sampler")) << ::testing::PrintToString(scene.warnings);

    // Halfway: the slide is at x = 2; the step rotation still at its first keyframe.
    const std::vector<uint32_t> moved = scene::pose(scene, animation, 0.5f);
    ASSERT_EQ(scene.draw_items.size(), 3u);
    EXPECT_EQ(moved, (std::vector<uint32_t>{0, 2}));
    EXPECT_EQ(scene.draw_items[0].world[3], glm::vec4(2, 0, 0, 1));
    EXPECT_EQ(scene.draw_items[1].world[3], glm::vec4(0, 0, 7, 1));
    EXPECT_EQ(scene.draw_items[2].world, glm::translate(glm::mat4(1.0f), glm::vec3(0, 3, 0)));
    // At the end the half turn about z: the turning node's x axis points along -x.
    scene::pose(scene, animation, 1.0f);
    const glm::vec4 x_axis = scene.draw_items[2].world * glm::vec4(1, 0, 0, 0);
    EXPECT_NEAR(x_axis.x, -1.0f, 1e-6f);
    EXPECT_NEAR(x_axis.y, 0.0f, 1e-6f);
    EXPECT_EQ(scene.draw_items[2].world[3], glm::vec4(0, 3, 0, 1));
}

// Skins: the joints and inverse bind matrices, the skinned node's skin and the primitive's
// JOINTS_0 / WEIGHTS_0 per vertex are imported, and the draw item is placed by its joints (the
// mesh node's own translation is ignored, as glTF says); JOINTS_1 / WEIGHTS_1 are left out with a
// warning.
TEST(SceneImport, SkinsTheirJointsAndEachVertexsInfluencesAreImported) {
    const std::filesystem::path dir = synthetic_dir(current_test());
    GltfBuilder builder;
    const int positions = builder.add_floats({0, 0, 0, 0, 2, 0, 1, 1, 0}, "VEC3");
    const std::vector<uint8_t> joints = {0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0};
    const int joints_0 = builder.add_accessor(builder.add_view(joints), kUnsignedByte, 3, "VEC4");
    const int weights_0 = builder.add_floats({1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0}, "VEC4");
    const int weights_1 = builder.add_floats(std::vector<float>(12, 0.0f), "VEC4");
    const int mesh = builder.add_mesh(nlohmann::json::array({{{"attributes",
                                                               {{"POSITION", positions},
                                                                {"JOINTS_0", joints_0},
                                                                {"WEIGHTS_0", weights_0},
                                                                {"JOINTS_1", joints_0},
                                                                {"WEIGHTS_1", weights_1}}}}}));
    const int elbow = builder.add_node({{"translation", {0, 1, 0}}});
    const int shoulder = builder.add_node({{"children", {elbow}}});
    const int body = builder.add_node({{"mesh", mesh}, {"skin", 0}, {"translation", {10, 0, 0}}});
    const std::vector<float> inverse_binds = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
                                              1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
    const int matrices = builder.add_accessor(builder.add_view(inverse_binds), kFloat, 2, "MAT4");
    builder.json()["skins"] = nlohmann::json::array(
        {{{"name", "arm"}, {"joints", {shoulder, elbow}}, {"inverseBindMatrices", matrices}, {"skeleton", shoulder}}});
    builder.set_scene({shoulder, body});
    const Scene scene = load_ok(builder.write(dir, "skinned", Layout::Embedded));

    ASSERT_EQ(scene.skins.size(), 1u);
    EXPECT_EQ(scene.skins[0].name, "arm");
    EXPECT_EQ(scene.skins[0].joints, (std::vector<uint32_t>{static_cast<uint32_t>(shoulder), static_cast<uint32_t>(elbow)}));
    ASSERT_EQ(scene.skins[0].inverse_bind_matrices.size(), 2u);
    EXPECT_EQ(scene.skins[0].inverse_bind_matrices[0], glm::mat4(1.0f));
    EXPECT_EQ(scene.skins[0].inverse_bind_matrices[1][3], glm::vec4(0, -1, 0, 1));
    EXPECT_EQ(scene.nodes[static_cast<std::size_t>(body)].skin, std::optional<uint32_t>(0));
    EXPECT_FALSE(scene.nodes[static_cast<std::size_t>(shoulder)].skin.has_value());
    const scene::Primitive& primitive = scene.meshes[0].primitives[0];
    ASSERT_EQ(primitive.skin.size(), primitive.vertices.size());
    // Flat normals (the file has none) made one vertex per corner: find the half-and-half one.
    bool found = false;
    for (std::size_t v = 0; v < primitive.vertices.size(); ++v) {
        if (primitive.vertices[v].position != glm::vec3(1, 1, 0)) continue;
        found = true;
        EXPECT_EQ(primitive.skin[v].joints, glm::uvec4(0, 1, 0, 0));
        EXPECT_EQ(primitive.skin[v].weights, glm::vec4(0.5f, 0.5f, 0, 0));
    }
    EXPECT_TRUE(found);
    ASSERT_EQ(scene.draw_items.size(), 1u);
    EXPECT_EQ(scene.draw_items[0].skin, std::optional<uint32_t>(0));
    EXPECT_EQ(scene.draw_items[0].world, glm::mat4(1.0f));
    EXPECT_EQ(scene.draw_items[0].world_bounds.min, glm::vec3(0, 0, 0));
    EXPECT_EQ(scene.draw_items[0].world_bounds.max, glm::vec3(1, 2, 0));
    auto warned = [&](const std::string& text) {
        return std::any_of(scene.warnings.begin(), scene.warnings.end(),
                           [&](const std::string& w) { return w.find(text) != std::string::npos; });
    };
    EXPECT_TRUE(warned("/meshes/0/primitives/0/attributes/JOINTS_1: JOINTS_1 is not imported")) << ::testing::PrintToString(scene.warnings);
    EXPECT_TRUE(warned("/meshes/0/primitives/0/attributes/WEIGHTS_1: WEIGHTS_1 is not imported")) << ::testing::PrintToString(scene.warnings);
    EXPECT_FALSE(warned("/skins")) << ::testing::PrintToString(scene.warnings);
    EXPECT_FALSE(warned("attributes/JOINTS_0:")) << ::testing::PrintToString(scene.warnings);
    // The skeleton and the mesh are both roots of the scene: no warning that the joints are not in it.
    EXPECT_FALSE(warned("is skinned, but no joint")) << ::testing::PrintToString(scene.warnings);
}

}  // namespace
}  // namespace loom::test

// The real glTF sample models (<data>/gltf/<Model>/<variant>/): every variant loads with the
// exact counts the files define, the variants of a model give identical scenes, and values at
// checkpoints match the files.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "loom/gltf/gltf.hpp"
#include "loom/scene/packed_geometry.hpp"
#include "loom_test/test_support.hpp"
#include "scene_test_util.hpp"

namespace loom::test {
namespace {

using scene::AlphaMode;
using scene::Scene;

// What each model's file defines (and, for vertices, what flat normal generation makes of
// primitives without normals: three vertices per triangle).
struct ModelExpectation {
    std::string name;
    std::vector<std::string> variants;  // folders holding <name>.gltf / <name>.glb
    std::size_t nodes, meshes, draw_items, vertices, indices, materials, textures, images, cameras;
};

const std::vector<ModelExpectation>& models() {
    static const std::vector<ModelExpectation> list = {
        // name, variants, nodes, meshes, draws, vertices, indices, materials, textures, images, cameras
        {"Box", {"glTF", "glTF-Embedded", "glTF-Binary"}, 2, 1, 1, 24, 36, 1, 0, 0, 0},
        {"BoxTextured", {"glTF", "glTF-Embedded", "glTF-Binary"}, 2, 1, 1, 24, 36, 1, 1, 1, 0},
        // The square has no normals: 2 triangles become 6 vertices; one default material.
        {"Cameras", {"glTF", "glTF-Embedded"}, 3, 1, 1, 6, 6, 1, 0, 0, 2},
        {"CesiumMilkTruck", {"glTF", "glTF-Binary"}, 5, 2, 5, 1856 + 72 + 464 + 586, 5232 + 168 + 864 + 2304, 4, 2, 1, 0},
        {"DamagedHelmet", {"glTF", "glTF-Binary"}, 1, 1, 1, 14556, 46356, 1, 5, 5, 0},
        {"Duck", {"glTF", "glTF-Embedded", "glTF-Binary"}, 3, 1, 1, 2399, 12636, 1, 1, 1, 1},
        // 36 indices without normals: 36 vertices.
        {"SimpleSparseAccessor", {"glTF", "glTF-Embedded"}, 1, 1, 1, 36, 36, 1, 0, 0, 0},
        {"TextureCoordinateTest", {"glTF", "glTF-Embedded"}, 5, 5, 5, 20, 30, 5, 1, 1, 0},
        {"TriangleWithoutIndices", {"glTF", "glTF-Embedded"}, 1, 1, 1, 3, 3, 1, 0, 0, 0},
        {"AlphaBlendModeTest", {"glTF", "glTF-Binary"}, 9, 9, 9, 137, 183, 6, 4, 4, 0},
    };
    return list;
}

std::filesystem::path model_file(const std::filesystem::path& data, const std::string& name, const std::string& variant) {
    const std::string extension = variant == "glTF-Binary" ? ".glb" : ".gltf";
    return gltf_models(data) / name / variant / (name + extension);
}

const Scene* load_model(const std::filesystem::path& data, const std::string& name, const std::string& variant = "glTF") {
    return load_cached(model_file(data, name, variant));
}

void expect_vec_near(const glm::vec3& actual, const glm::vec3& expected, float tolerance, const std::string& what) {
    EXPECT_NEAR(actual.x, expected.x, tolerance) << what;
    EXPECT_NEAR(actual.y, expected.y, tolerance) << what;
    EXPECT_NEAR(actual.z, expected.z, tolerance) << what;
}

struct ModelVariant {
    std::string name;
    std::string variant;
};

std::vector<ModelVariant> all_variants() {
    std::vector<ModelVariant> list;
    for (const ModelExpectation& model : models()) {
        for (const std::string& variant : model.variants) list.push_back({model.name, variant});
    }
    return list;
}

std::string variant_name(const ::testing::TestParamInfo<ModelVariant>& param_info) {
    std::string name = param_info.param.name + "_" + param_info.param.variant;
    for (char& c : name) {
        if (c == '-') c = '_';
    }
    return name;
}

class ValidModel : public ::testing::TestWithParam<ModelVariant> {};

TEST_P(ValidModel, LoadsWithTheFilesCounts) {
    LOOM_REQUIRE_DATA_DIR(data);
    const ModelVariant& param = GetParam();
    const ModelExpectation* expected = nullptr;
    for (const ModelExpectation& model : models()) {
        if (model.name == param.name) expected = &model;
    }
    ASSERT_NE(expected, nullptr);
    const Scene* scene = load_model(data, param.name, param.variant);
    ASSERT_NE(scene, nullptr);
    EXPECT_EQ(scene->nodes.size(), expected->nodes);
    EXPECT_EQ(scene->meshes.size(), expected->meshes);
    EXPECT_EQ(scene->draw_items.size(), expected->draw_items);
    EXPECT_EQ(scene->vertex_count(), expected->vertices);
    EXPECT_EQ(scene->index_count(), expected->indices);
    EXPECT_EQ(scene->materials.size(), expected->materials);
    EXPECT_EQ(scene->textures.size(), expected->textures);
    EXPECT_EQ(scene->images.size(), expected->images);
    EXPECT_EQ(scene->cameras.size(), expected->cameras);
    EXPECT_FALSE(scene->bounds.empty());
    // Every index refers to a vertex and every reference between the vectors holds.
    for (const scene::Mesh& mesh : scene->meshes) {
        for (const scene::Primitive& primitive : mesh.primitives) {
            EXPECT_EQ(primitive.indices.size() % 3, 0u);
            for (const uint32_t index : primitive.indices) ASSERT_LT(index, primitive.vertices.size());
            EXPECT_LT(primitive.material, scene->materials.size());
        }
    }
    for (const scene::Texture& texture : scene->textures) EXPECT_LT(texture.image, scene->images.size());
}

INSTANTIATE_TEST_SUITE_P(SampleModels, ValidModel, ::testing::ValuesIn(all_variants()), variant_name);

// Every variant other than glTF/ (external files) against that one.
class ModelVariantMatchesReference : public ::testing::TestWithParam<ModelVariant> {};

TEST_P(ModelVariantMatchesReference, IdenticalScenes) {
    LOOM_REQUIRE_DATA_DIR(data);
    const ModelVariant& param = GetParam();
    const Scene* reference = load_model(data, param.name, "glTF");
    const Scene* variant = load_model(data, param.name, param.variant);
    ASSERT_NE(reference, nullptr);
    ASSERT_NE(variant, nullptr);
    expect_same_scene(*reference, *variant);
}

std::vector<ModelVariant> other_variants() {
    std::vector<ModelVariant> list = all_variants();
    std::erase_if(list, [](const ModelVariant& v) { return v.variant == "glTF"; });
    return list;
}

INSTANTIATE_TEST_SUITE_P(SampleModels, ModelVariantMatchesReference, ::testing::ValuesIn(other_variants()), variant_name);

TEST(SceneModels, BoxVerticesIndicesMaterialAndBounds) {
    LOOM_REQUIRE_DATA_DIR(data);
    const Scene* scene = load_model(data, "Box");
    ASSERT_NE(scene, nullptr);
    const scene::Primitive& primitive = scene->meshes.at(0).primitives.at(0);
    // The file's first vertices (POSITION accessor 2, NORMAL accessor 1).
    EXPECT_EQ(primitive.vertices[0].position, glm::vec3(-0.5f, -0.5f, 0.5f));
    EXPECT_EQ(primitive.vertices[1].position, glm::vec3(0.5f, -0.5f, 0.5f));
    EXPECT_EQ(primitive.vertices[2].position, glm::vec3(-0.5f, 0.5f, 0.5f));
    EXPECT_EQ(primitive.vertices[23].position, glm::vec3(0.5f, 0.5f, -0.5f));
    EXPECT_EQ(primitive.vertices[0].normal, glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(std::vector<uint32_t>(primitive.indices.begin(), primitive.indices.begin() + 9),
              (std::vector<uint32_t>{0, 1, 2, 3, 2, 1, 4, 5, 6}));
    EXPECT_EQ(primitive.from_file, scene::kAttributeNormal);
    EXPECT_EQ(primitive.generated, 0u);
    EXPECT_EQ(primitive.bounds.min, glm::vec3(-0.5f));
    EXPECT_EQ(primitive.bounds.max, glm::vec3(0.5f));

    const scene::Material& material = scene->materials.at(0);
    EXPECT_EQ(material.name, "Red");
    EXPECT_EQ(material.base_color_factor, glm::vec4(0.800000011920929f, 0.0f, 0.0f, 1.0f));
    EXPECT_EQ(material.metallic_factor, 0.0f);
    EXPECT_EQ(material.roughness_factor, 1.0f);
    EXPECT_EQ(material.alpha_mode, AlphaMode::Opaque);
    EXPECT_FALSE(material.double_sided);
    EXPECT_FALSE(material.base_color_texture.has_value());

    // Node 0's matrix turns +Y into -Z and +Z into +Y (a Y-up fix-up); node 1 adds nothing.
    const scene::DrawItem& item = scene->draw_items.at(0);
    EXPECT_EQ(item.node, 1u);
    const glm::mat4 expected_world(glm::vec4(1, 0, 0, 0), glm::vec4(0, 0, -1, 0), glm::vec4(0, 1, 0, 0), glm::vec4(0, 0, 0, 1));
    EXPECT_EQ(item.world, expected_world);
    EXPECT_EQ(item.normal_matrix, glm::mat3(expected_world));
    EXPECT_FALSE(item.flips_winding);
    EXPECT_EQ(scene->nodes[1].parent, std::optional<uint32_t>(0));
    EXPECT_EQ(scene->bounds.min, glm::vec3(-0.5f));
    EXPECT_EQ(scene->bounds.max, glm::vec3(0.5f));
    EXPECT_TRUE(scene->warnings.empty());
}

TEST(SceneModels, BoxTexturedTextureSamplerAndUvs) {
    LOOM_REQUIRE_DATA_DIR(data);
    const Scene* scene = load_model(data, "BoxTextured");
    ASSERT_NE(scene, nullptr);
    const scene::Primitive& primitive = scene->meshes.at(0).primitives.at(0);
    EXPECT_EQ(primitive.vertices[0].uv0, glm::vec2(6.0f, 0.0f));
    EXPECT_EQ(primitive.vertices[3].uv0, glm::vec2(5.0f, 0.9999998807907104f));
    EXPECT_EQ(primitive.from_file, scene::kAttributeNormal | scene::kAttributeUv0);

    const scene::Material& material = scene->materials.at(0);
    ASSERT_TRUE(material.base_color_texture.has_value());
    EXPECT_EQ(material.base_color_texture->texture, 0u);
    EXPECT_EQ(material.base_color_texture->uv_set, 0u);
    EXPECT_EQ(material.base_color_factor, glm::vec4(1.0f));

    const scene::Texture& texture = scene->textures.at(0);
    // minFilter NEAREST_MIPMAP_LINEAR, magFilter LINEAR, REPEAT both ways.
    EXPECT_EQ(texture.sampler.min_filter, rhi::Filter::Nearest);
    EXPECT_EQ(texture.sampler.mipmap_filter, rhi::Filter::Linear);
    EXPECT_EQ(texture.sampler.mag_filter, rhi::Filter::Linear);
    EXPECT_EQ(texture.sampler.address_u, rhi::AddressMode::Repeat);
    EXPECT_EQ(texture.sampler.address_v, rhi::AddressMode::Repeat);
    const scene::TextureImage& image = scene->images.at(texture.image);
    EXPECT_EQ(image.name, "CesiumLogoFlat.png");
    EXPECT_EQ(image.image.width, 256u);
    EXPECT_EQ(image.image.height, 256u);
    EXPECT_EQ(image.image.format, rhi::Format::RGBA8Srgb);  // base colour is sRGB
    EXPECT_EQ(image.image.pixels.size(), 256u * 256u * 4u);
}

TEST(SceneModels, CamerasParametersPlacementAndFlatNormals) {
    LOOM_REQUIRE_DATA_DIR(data);
    const Scene* scene = load_model(data, "Cameras");
    ASSERT_NE(scene, nullptr);
    ASSERT_EQ(scene->cameras.size(), 2u);

    const auto* perspective = std::get_if<scene::PerspectiveProjection>(&scene->cameras[0].projection);
    ASSERT_NE(perspective, nullptr);
    EXPECT_EQ(perspective->yfov, 0.7f);
    EXPECT_EQ(perspective->aspect_ratio, std::optional<float>(1.0f));
    EXPECT_EQ(perspective->znear, 0.01f);
    EXPECT_EQ(perspective->zfar, std::optional<float>(100.0f));
    EXPECT_EQ(scene->cameras[0].position(), glm::vec3(0.5f, 0.5f, 3.0f));
    EXPECT_EQ(scene->cameras[0].forward(), glm::vec3(0.0f, 0.0f, -1.0f));
    // The file's own aspect ratio wins over the viewport's.
    EXPECT_FLOAT_EQ(scene->cameras[0].projection_matrix(2.0f)[0][0], 1.0f / std::tan(0.35f));

    const auto* ortho = std::get_if<scene::OrthographicProjection>(&scene->cameras[1].projection);
    ASSERT_NE(ortho, nullptr);
    EXPECT_EQ(ortho->xmag, 1.0f);
    EXPECT_EQ(ortho->ymag, 1.0f);
    EXPECT_EQ(ortho->znear, 0.01f);
    EXPECT_EQ(ortho->zfar, 100.0f);
    EXPECT_EQ(scene->cameras[1].position(), glm::vec3(0.5f, 0.5f, 3.0f));

    // The square (z = 0, counter-clockwise from +Z) has no normals: flat ones are generated.
    const scene::Primitive& primitive = scene->meshes.at(0).primitives.at(0);
    EXPECT_EQ(primitive.generated, scene::kAttributeNormal);
    EXPECT_EQ(primitive.from_file, 0u);
    ASSERT_EQ(primitive.vertices.size(), 6u);
    for (const scene::Vertex& vertex : primitive.vertices) EXPECT_EQ(vertex.normal, glm::vec3(0.0f, 0.0f, 1.0f));
    // Triangles (0,1,2) and (1,3,2) of the file, unshared.
    EXPECT_EQ(primitive.vertices[3].position, glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(primitive.vertices[4].position, glm::vec3(1.0f, 1.0f, 0.0f));
    EXPECT_EQ(primitive.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
    // No material: the glTF default one.
    EXPECT_EQ(scene->materials.at(0).name, "default");
    EXPECT_EQ(scene->materials.at(0).base_color_factor, glm::vec4(1.0f));
    EXPECT_EQ(scene->materials.at(0).metallic_factor, 1.0f);
}

TEST(SceneModels, SimpleSparseAccessorSubstitutesValues) {
    LOOM_REQUIRE_DATA_DIR(data);
    gltf::LoadOptions options;
    options.normals = gltf::NormalGeneration::Smooth;  // keeps the 14 shared vertices
    auto scene = gltf::load(model_file(data, "SimpleSparseAccessor", "glTF"), options);
    ASSERT_TRUE(scene) << scene.error().to_string();
    const scene::Primitive& primitive = scene->meshes.at(0).primitives.at(0);
    ASSERT_EQ(primitive.vertices.size(), 14u);
    // Base grid: (i % 7, i / 7, 0); sparse indices 8, 10, 12 get (1,2,0), (3,3,0), (5,4,0).
    EXPECT_EQ(primitive.vertices[8].position, glm::vec3(1.0f, 2.0f, 0.0f));
    EXPECT_EQ(primitive.vertices[10].position, glm::vec3(3.0f, 3.0f, 0.0f));
    EXPECT_EQ(primitive.vertices[12].position, glm::vec3(5.0f, 4.0f, 0.0f));
    EXPECT_EQ(primitive.vertices[7].position, glm::vec3(0.0f, 1.0f, 0.0f));
    EXPECT_EQ(primitive.vertices[9].position, glm::vec3(2.0f, 1.0f, 0.0f));
    EXPECT_EQ(primitive.vertices[13].position, glm::vec3(6.0f, 1.0f, 0.0f));
    EXPECT_EQ(primitive.bounds.max, glm::vec3(6.0f, 4.0f, 0.0f));  // the accessor's max
    // Every triangle of the flat grid faces +Z.
    for (const scene::Vertex& vertex : primitive.vertices) EXPECT_EQ(vertex.normal, glm::vec3(0.0f, 0.0f, 1.0f));

    // With flat normals, vertex 1 is the second corner of the first triangle (index 8).
    const Scene* flat = load_model(data, "SimpleSparseAccessor");
    ASSERT_NE(flat, nullptr);
    EXPECT_EQ(flat->meshes.at(0).primitives.at(0).vertices[1].position, glm::vec3(1.0f, 2.0f, 0.0f));
}

TEST(SceneModels, TriangleWithoutIndicesGetsImplicitIndicesAndANormal) {
    LOOM_REQUIRE_DATA_DIR(data);
    const Scene* scene = load_model(data, "TriangleWithoutIndices");
    ASSERT_NE(scene, nullptr);
    const scene::Primitive& primitive = scene->meshes.at(0).primitives.at(0);
    EXPECT_EQ(primitive.indices, (std::vector<uint32_t>{0, 1, 2}));
    ASSERT_EQ(primitive.vertices.size(), 3u);
    EXPECT_EQ(primitive.vertices[1].position, glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(primitive.vertices[2].position, glm::vec3(0.0f, 1.0f, 0.0f));
    for (const scene::Vertex& vertex : primitive.vertices) EXPECT_EQ(vertex.normal, glm::vec3(0.0f, 0.0f, 1.0f));
}

TEST(SceneModels, DuckCameraAndBounds) {
    LOOM_REQUIRE_DATA_DIR(data);
    const Scene* scene = load_model(data, "Duck");
    ASSERT_NE(scene, nullptr);
    ASSERT_EQ(scene->cameras.size(), 1u);
    const auto* perspective = std::get_if<scene::PerspectiveProjection>(&scene->cameras[0].projection);
    ASSERT_NE(perspective, nullptr);
    EXPECT_EQ(perspective->aspect_ratio, std::optional<float>(1.5f));
    EXPECT_EQ(perspective->yfov, 0.6605925559997559f);
    EXPECT_EQ(perspective->znear, 1.0f);
    EXPECT_EQ(perspective->zfar, std::optional<float>(10000.0f));
    // The camera node's translation, scaled by its parent's 0.01.
    expect_vec_near(scene->cameras[0].position(), glm::vec3(4.001130065917969f, 4.632640075683594f, -4.310780334472656f),
                    1e-5f, "camera position");
    const scene::Primitive& primitive = scene->meshes.at(0).primitives.at(0);
    EXPECT_EQ(primitive.bounds.min, glm::vec3(-69.29850006103516f, 9.929369926452637f, -61.32819747924805f));
    EXPECT_EQ(primitive.bounds.max, glm::vec3(96.17990112304688f, 163.97000122070312f, 53.92519760131836f));
    expect_vec_near(scene->bounds.min, primitive.bounds.min * 0.01f, 1e-5f, "scene bounds min");
    expect_vec_near(scene->bounds.max, primitive.bounds.max * 0.01f, 1e-5f, "scene bounds max");
    // The duck has the file's normals and UVs.
    EXPECT_EQ(primitive.from_file, scene::kAttributeNormal | scene::kAttributeUv0);
}

TEST(SceneModels, DamagedHelmetTexturesColourSpacesAndGeneratedTangents) {
    LOOM_REQUIRE_DATA_DIR(data);
    const Scene* scene = load_model(data, "DamagedHelmet");
    ASSERT_NE(scene, nullptr);
    const scene::Material& material = scene->materials.at(0);
    ASSERT_TRUE(material.base_color_texture && material.metallic_roughness_texture && material.normal_texture &&
                material.occlusion_texture && material.emissive_texture);
    auto format_of = [&](const std::optional<scene::TextureRef>& ref) {
        return scene->images.at(scene->textures.at(ref->texture).image).image.format;
    };
    EXPECT_EQ(format_of(material.base_color_texture), rhi::Format::RGBA8Srgb);
    EXPECT_EQ(format_of(material.emissive_texture), rhi::Format::RGBA8Srgb);
    EXPECT_EQ(format_of(material.metallic_roughness_texture), rhi::Format::RGBA8Unorm);
    EXPECT_EQ(format_of(material.normal_texture), rhi::Format::RGBA8Unorm);
    EXPECT_EQ(format_of(material.occlusion_texture), rhi::Format::RGBA8Unorm);
    EXPECT_EQ(scene->images.at(scene->textures.at(material.normal_texture->texture).image).name, "Default_normal.jpg");
    for (const scene::TextureImage& image : scene->images) {
        EXPECT_EQ(image.image.width, 2048u);
        EXPECT_EQ(image.image.height, 2048u);
    }
    EXPECT_EQ(material.emissive_factor, glm::vec3(1.0f));
    // A sampler object without properties: trilinear, repeat.
    EXPECT_EQ(scene->textures.at(0).sampler.min_filter, rhi::Filter::Linear);
    EXPECT_EQ(scene->textures.at(0).sampler.mipmap_filter, rhi::Filter::Linear);
    EXPECT_EQ(scene->textures.at(0).sampler.address_u, rhi::AddressMode::Repeat);

    // Normal-mapped without TANGENT: tangents are generated, unit length, perpendicular to
    // the normal, with handedness +-1.
    const scene::Primitive& primitive = scene->meshes.at(0).primitives.at(0);
    EXPECT_EQ(primitive.generated, scene::kAttributeTangent);
    for (const scene::Vertex& vertex : primitive.vertices) {
        const glm::vec3 tangent(vertex.tangent);
        ASSERT_NEAR(glm::length(tangent), 1.0f, 1e-4f);
        ASSERT_NEAR(glm::dot(tangent, glm::normalize(vertex.normal)), 0.0f, 1e-3f);
        ASSERT_TRUE(vertex.tangent.w == 1.0f || vertex.tangent.w == -1.0f);
    }
    // Rotated 90 degrees about X: y' = -z, z' = y.
    EXPECT_NEAR(scene->bounds.min.y, -0.900973916053772f, 1e-5f);
    EXPECT_NEAR(scene->bounds.max.z, 0.8128451108932495f, 1e-5f);
    EXPECT_NEAR(scene->bounds.min.z, -1.18715500831604f, 1e-5f);
}

TEST(SceneModels, CesiumMilkTruckHierarchyAndSharedImage) {
    LOOM_REQUIRE_DATA_DIR(data);
    const Scene* scene = load_model(data, "CesiumMilkTruck");
    ASSERT_NE(scene, nullptr);
    // Depth-first in file order: node 0 (3 primitives), then child 3 -> 4, then child 1 -> 2.
    ASSERT_EQ(scene->draw_items.size(), 5u);
    const std::vector<uint32_t> nodes = {0, 0, 0, 4, 2};
    const std::vector<uint32_t> meshes = {0, 0, 0, 1, 1};
    const std::vector<uint32_t> primitives = {0, 1, 2, 0, 0};
    for (std::size_t i = 0; i < 5; ++i) {
        EXPECT_EQ(scene->draw_items[i].node, nodes[i]) << i;
        EXPECT_EQ(scene->draw_items[i].mesh, meshes[i]) << i;
        EXPECT_EQ(scene->draw_items[i].primitive, primitives[i]) << i;
    }
    // The wheels: their parents' translations (x = 1.43267 and -1.35233).
    EXPECT_NEAR(scene->draw_items[3].world[3].x, 1.432669997215271f, 1e-6f);
    EXPECT_NEAR(scene->draw_items[4].world[3].x, -1.352329969406128f, 1e-6f);
    EXPECT_EQ(scene->draw_items[1].material, 1u);
    EXPECT_EQ(scene->materials.at(1).name, "glass");
    // Two glTF textures of one image: two textures sharing one decoded image.
    ASSERT_EQ(scene->textures.size(), 2u);
    EXPECT_EQ(scene->textures[0].image, 0u);
    EXPECT_EQ(scene->textures[1].image, 0u);
    // The wheels' animation: each wheel turns about its axle (z), 31 linear keyframes over 1.25 s.
    for (const std::string& warning : scene->warnings) EXPECT_EQ(warning.find("/animations"), std::string::npos) << warning;
    ASSERT_EQ(scene->animations.size(), 1u);
    const scene::Animation& wheels = scene->animations[0];
    ASSERT_EQ(wheels.channels.size(), 2u);
    EXPECT_EQ(wheels.channels[0].node, 4u);
    EXPECT_EQ(wheels.channels[1].node, 2u);
    for (const scene::AnimationChannel& channel : wheels.channels) {
        EXPECT_EQ(channel.property, scene::AnimatedProperty::Rotation);
        const scene::AnimationSampler& sampler = wheels.samplers.at(channel.sampler);
        EXPECT_EQ(sampler.times.size(), 31u);
        EXPECT_EQ(sampler.values.size(), 31u * 4u);
        EXPECT_EQ(sampler.interpolation, scene::Interpolation::Linear);
    }
    EXPECT_EQ(wheels.duration(), 1.25f);
    // Posed halfway, the wheels (draw items 3 and 4) turn in place; the body does not move.
    Scene posed = *scene;
    EXPECT_EQ(scene::pose(posed, wheels, 0.625f), (std::vector<uint32_t>{3, 4}));
    for (std::size_t i = 0; i < 5; ++i) {
        EXPECT_EQ(posed.draw_items[i].world[3], scene->draw_items[i].world[3]) << i;
        if (i < 3) {
            EXPECT_EQ(posed.draw_items[i].world, scene->draw_items[i].world) << i;
        }
    }
    // Half of the keyframes' turn: far from the file's static pose, about z only.
    EXPECT_GT(glm::length(posed.draw_items[3].world[0] - scene->draw_items[3].world[0]), 0.5f);
    EXPECT_EQ(posed.draw_items[3].world[2], scene->draw_items[3].world[2]);
}

TEST(SceneModels, PackedGeometryReproducesEveryDrawItem) {
    LOOM_REQUIRE_DATA_DIR(data);
    const Scene* scene = load_model(data, "CesiumMilkTruck");
    ASSERT_NE(scene, nullptr);
    const scene::PackedGeometry packed = scene::pack_geometry(*scene);
    EXPECT_EQ(packed.vertices.size(), scene->vertex_count());
    EXPECT_EQ(packed.indices.size(), scene->index_count());
    // Mesh 0's three primitives, then mesh 1's one, back to back.
    ASSERT_EQ(packed.ranges.size(), 2u);
    EXPECT_EQ(packed.ranges[0][1], (scene::PrimitiveRange{5232, 168, 1856}));
    EXPECT_EQ(packed.ranges[1][0], (scene::PrimitiveRange{5232 + 168 + 864, 2304, 1856 + 72 + 464}));
    for (const scene::DrawItem& item : scene->draw_items) {
        const scene::Primitive& primitive = scene->meshes[item.mesh].primitives[item.primitive];
        const scene::PrimitiveRange& range = packed.range(item);
        ASSERT_EQ(range.index_count, primitive.indices.size());
        for (uint32_t i = 0; i < range.index_count; ++i) {
            const uint32_t index = packed.indices[range.first_index + i];
            ASSERT_EQ(packed.vertices[static_cast<std::size_t>(range.base_vertex) + index],
                      primitive.vertices[primitive.indices[i]]);
        }
    }
}

TEST(SceneModels, AlphaBlendModeTestAlphaModesAndDoubleSided) {
    LOOM_REQUIRE_DATA_DIR(data);
    const Scene* scene = load_model(data, "AlphaBlendModeTest");
    ASSERT_NE(scene, nullptr);
    const auto& materials = scene->materials;
    ASSERT_EQ(materials.size(), 6u);
    EXPECT_EQ(materials[0].alpha_mode, AlphaMode::Opaque);
    EXPECT_FALSE(materials[0].double_sided);
    EXPECT_EQ(materials[1].alpha_mode, AlphaMode::Blend);
    EXPECT_TRUE(materials[1].double_sided);
    EXPECT_EQ(materials[2].alpha_mode, AlphaMode::Mask);
    EXPECT_EQ(materials[2].alpha_cutoff, 0.25f);
    EXPECT_EQ(materials[3].alpha_cutoff, 0.75f);
    EXPECT_EQ(materials[4].alpha_mode, AlphaMode::Mask);
    EXPECT_EQ(materials[4].alpha_cutoff, 0.5f);  // the default
    EXPECT_EQ(materials[5].alpha_mode, AlphaMode::Opaque);
    EXPECT_EQ(materials[1].roughness_factor, 0.800000011920929f);
    // Occlusion and metallic-roughness share glTF texture 1 (linear): one scene texture.
    ASSERT_TRUE(materials[0].occlusion_texture && materials[0].metallic_roughness_texture);
    EXPECT_EQ(materials[0].occlusion_texture->texture, materials[0].metallic_roughness_texture->texture);
    // Tangents come from the file, none are generated.
    for (const scene::Mesh& mesh : scene->meshes) {
        for (const scene::Primitive& primitive : mesh.primitives) {
            EXPECT_TRUE(primitive.from_file & scene::kAttributeTangent);
            EXPECT_EQ(primitive.generated, 0u);
        }
    }
}

TEST(SceneModels, TextureCoordinateTestSharesOneTexture) {
    LOOM_REQUIRE_DATA_DIR(data);
    const Scene* scene = load_model(data, "TextureCoordinateTest");
    ASSERT_NE(scene, nullptr);
    for (std::size_t m = 1; m < 5; ++m) {
        ASSERT_TRUE(scene->materials[m].base_color_texture) << m;
        EXPECT_EQ(scene->materials[m].base_color_texture->texture, 0u);
        EXPECT_TRUE(scene->materials[m].double_sided);
    }
    EXPECT_FALSE(scene->materials[0].base_color_texture);
    EXPECT_EQ(scene->materials[2].base_color_factor, glm::vec4(0.0f, 0.800000011920929f, 0.0f, 1.0f));
    EXPECT_EQ(scene->images.at(0).image.width, 512u);
    // The mesh without TEXCOORD_0 (the back plane) is the one whose material has no texture.
    EXPECT_EQ(scene->meshes.at(3).primitives.at(0).from_file, scene::kAttributeNormal);
}

TEST(SceneModels, FramingFitsEveryModelInTheViewport) {
    LOOM_REQUIRE_DATA_DIR(data);
    for (const ModelExpectation& model : models()) {
        const Scene* scene = load_model(data, model.name);
        ASSERT_NE(scene, nullptr);
        for (const float aspect : {0.5f, 1.0f, 16.0f / 9.0f}) {
            const scene::Camera camera = scene::frame_bounds(scene->bounds, aspect);
            const glm::mat4 view_projection = camera.view_projection(aspect);
            float largest = 0.0f;
            for (const glm::vec3& corner : scene->bounds.corners()) {
                const glm::vec4 clip = view_projection * glm::vec4(corner, 1.0f);
                ASSERT_GT(clip.w, 0.0f) << model.name;
                const glm::vec3 ndc = glm::vec3(clip) / clip.w;
                EXPECT_LE(std::abs(ndc.x), 1.0f) << model.name << " aspect " << aspect;
                EXPECT_LE(std::abs(ndc.y), 1.0f) << model.name << " aspect " << aspect;
                EXPECT_GE(ndc.z, 0.0f) << model.name;
                EXPECT_LE(ndc.z, 1.0f) << model.name;
                largest = std::max({largest, std::abs(ndc.x), std::abs(ndc.y)});
            }
            // Framed tightly: the outermost corner reaches 1 / margin of the half-viewport.
            EXPECT_NEAR(largest, 1.0f / scene::FramingOptions{}.margin, 1e-3f) << model.name << " aspect " << aspect;
        }
    }
}

}  // namespace
}  // namespace loom::test

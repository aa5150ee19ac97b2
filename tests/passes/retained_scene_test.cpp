// The retained object layer on both backends: submitted shapes render exactly like the naive
// MeshObjects they replace; sorted queues bind every state key once and batch bundles into
// indirect commands (or one draw per command without indirect draws); only changed uniform
// sets are uploaded; lazy transforms follow their parents; retracting releases what only that
// shape used; separate vertex streams work; errors name the shape.
#include <algorithm>
#include <cstring>
#include <memory>
#include <set>
#include <tuple>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "gbuffer_graph.hpp"
#include "loom/image_io/image_io.hpp"
#include "loom/passes/retained_mesh.hpp"
#include "loom/passes/retained_scene.hpp"
#include "loom/passes/shadow_map_pass.hpp"
#include "loom_test/render_fixture.hpp"
#include "object_scene.hpp"

namespace loom::test {
namespace {

using passes::InputParam;
using passes::RetainedScene;
using passes::Shape;

constexpr uint64_t kRecordBytes = sizeof(passes::ObjectRecord);
constexpr uint64_t kMaterialBytes = sizeof(passes::MeshSurfaceUniforms);

class RetainedSceneTest : public RenderTest {
protected:
    /// Renders `scene` through the naive path (MeshObjects registered with the pass).
    void render_naive(const ObjectScene& scene, uint32_t size, std::vector<rhi::Image>& maps) {
        auto objects = make_naive_objects(device(), scene);
        ASSERT_TRUE(objects.ok()) << objects.error().to_string();
        GBufferGraph graph(device(), size, scene.camera);
        for (const auto& object : objects->objects) ASSERT_TRUE(passes::register_object(graph.pass(), object).ok());
        auto status = graph.frame();
        ASSERT_TRUE(status.ok()) << status.error().to_string();
        read_maps(graph, maps);
    }

    static void read_maps(GBufferGraph& graph, std::vector<rhi::Image>& maps) {
        maps.clear();
        for (const char* port : {"position", "normal", "albedo"}) {
            auto image = graph.read(port);
            ASSERT_TRUE(image.ok()) << image.error().to_string();
            maps.push_back(std::move(*image));
        }
    }

    /// Compares G-buffer maps exactly, writing a report when they differ.
    void expect_same_maps(const std::vector<rhi::Image>& a, const std::vector<rhi::Image>& b, const std::string& stem) {
        ASSERT_EQ(a.size(), 3u);
        ASSERT_EQ(b.size(), 3u);
        const char* names[] = {"position", "normal", "albedo"};
        for (int i = 0; i < 3; ++i) {
            auto comparison = image_io::compare_and_report(a[i], b[i], output_dir(),
                                                      stem + "." + std::string(rhi::backend_name(backend())) + "." + names[i]);
            ASSERT_TRUE(comparison.ok()) << comparison.error().to_string();
            EXPECT_TRUE(comparison->equal()) << names[i] << ": " << comparison->summary();
        }
    }

    /// Texels with a non-zero normal (something was drawn there).
    static uint64_t covered(const rhi::Image& normal) {
        uint64_t count = 0;
        for (uint32_t y = 0; y < normal.height; ++y) {
            for (uint32_t x = 0; x < normal.width; ++x) {
                const auto n = normal.load(x, y);
                if (n[0] != 0.0 || n[1] != 0.0 || n[2] != 0.0) ++count;
            }
        }
        return count;
    }
};

ObjectSceneSpec small_spec() {
    ObjectSceneSpec spec;
    spec.objects = 144;
    spec.meshes = 12;
    spec.materials = 12;
    spec.seed = 3;
    return spec;
}

TEST_P(RetainedSceneTest, SubmittedShapesRenderExactlyLikeMeshObjects) {
    const ObjectScene scene = make_object_scene(small_spec());
    std::vector<rhi::Image> naive;
    render_naive(scene, 96, naive);

    auto objects = make_retained_objects(scene);
    ASSERT_TRUE(objects.ok()) << objects.error().to_string();
    RetainedScene retained;
    GBufferGraph graph(device(), 96, scene.camera);
    ASSERT_TRUE(retained.attach(graph.pass()).ok());
    for (const auto& shape : objects->shapes) ASSERT_TRUE(retained.submit(shape).ok());
    ASSERT_TRUE(graph.frame().ok());
    std::vector<rhi::Image> maps;
    read_maps(graph, maps);
    EXPECT_GT(covered(maps[1]), 96u * 96u / 10) << "the scene should cover a good part of the frame";
    expect_same_maps(naive, maps, "retained_small");
    // The same again a frame later, with nothing uploaded in between.
    ASSERT_TRUE(graph.frame().ok());
    read_maps(graph, maps);
    expect_same_maps(naive, maps, "retained_small_second_frame");
}

TEST_P(RetainedSceneTest, TenThousandObjectsMatchTheNaiveLoopWithMinimalStateAndUploads) {
    // The benchmark's scene (loom_retained_bench): 10,000 objects, 300 meshes, 30 materials.
    const ObjectScene scene = make_object_scene(ObjectSceneSpec{});
    ASSERT_EQ(scene.objects.size(), 10000u);
    const uint32_t size = 64;
    const uint64_t keys = distinct_state_keys(scene);
    // 1% of the objects move in the third frame (lifted; rotation and scale kept).
    std::vector<uint32_t> moving;
    for (uint32_t i = 0; i < 10000; i += 100) moving.push_back(i + (i / 100) % 100);
    auto lifted = [&](uint32_t i) { return glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.2f, 0.0f)) * scene.objects[i].model; };

    std::vector<rhi::Image> naive_maps;
    {
        auto objects = make_naive_objects(device(), scene);
        ASSERT_TRUE(objects.ok());
        GBufferGraph graph(device(), size, scene.camera);
        for (const auto& object : objects->objects) ASSERT_TRUE(passes::register_object(graph.pass(), object).ok());
        ASSERT_TRUE(graph.frame().ok());
        for (uint32_t i : moving) objects->objects[i]->set_model(lifted(i));
        ASSERT_TRUE(graph.frame().ok());
        // The naive loop uploads every object's uniforms every frame and draws one by one.
        EXPECT_EQ(device().last_frame_stats().bytes_uploaded, 10000u * 192u);
        EXPECT_EQ(device().last_frame_stats().draw_calls, 10000u);
        read_maps(graph, naive_maps);
    }

    auto objects = make_retained_objects(scene);
    ASSERT_TRUE(objects.ok());
    RetainedScene retained;
    GBufferGraph graph(device(), size, scene.camera);
    ASSERT_TRUE(retained.attach(graph.pass()).ok());
    for (const auto& shape : objects->shapes) ASSERT_TRUE(retained.submit(shape).ok());
    ASSERT_TRUE(graph.frame().ok());
    retained.reset_stats();
    ASSERT_TRUE(graph.frame().ok());  // nothing changed
    EXPECT_EQ(device().last_frame_stats().bytes_uploaded, 0u);
    EXPECT_EQ(retained.stats().uploaded_bytes(), 0u);

    retained.reset_stats();
    for (uint32_t i : moving) objects->models[i]->set(lifted(i));
    ASSERT_TRUE(graph.frame().ok());
    // Uploads: the 100 records that changed, nothing else.
    EXPECT_EQ(retained.stats().object_uploads.sets, moving.size());
    EXPECT_EQ(device().last_frame_stats().bytes_uploaded, moving.size() * kRecordBytes);
    // State: every distinct key bound once, one draw per key (indirect) or per command.
    EXPECT_EQ(retained.stats().state_changes, keys);
    EXPECT_EQ(retained.stats().distinct_keys, keys);
    EXPECT_EQ(retained.stats().commands_drawn, distinct_key_mesh_pairs(scene));
    const bool indirect = device().capabilities().draw_indirect;
    EXPECT_EQ(device().last_frame_stats().draw_calls, indirect ? keys : distinct_key_mesh_pairs(scene));
    EXPECT_LT(device().last_frame_stats().api_calls, 20 * keys);

    std::vector<rhi::Image> maps;
    read_maps(graph, maps);
    // 10,000 objects of about half a texel each: they cover about 14% of the frame (texels:
    // 575 on GL, 576 on Vulkan when this was written); a tenth shows the scene was drawn.
    EXPECT_GT(covered(maps[1]), size * size / 10);
    expect_same_maps(naive_maps, maps, "retained_10k");
}

TEST_P(RetainedSceneTest, SortedQueueBindsEveryStateKeyOnceAndBatchesByMesh) {
    const ObjectScene scene = make_object_scene(small_spec());
    auto objects = make_retained_objects(scene);
    ASSERT_TRUE(objects.ok());
    RetainedScene retained;
    GBufferGraph graph(device(), 32, scene.camera);
    ASSERT_TRUE(retained.attach(graph.pass()).ok());
    for (const auto& shape : objects->shapes) ASSERT_TRUE(retained.submit(shape).ok());
    ASSERT_TRUE(graph.frame().ok());

    const uint64_t keys = distinct_state_keys(scene);
    const uint64_t pairs = distinct_key_mesh_pairs(scene);
    const auto batches = retained.batches(graph.pass());
    const auto commands = retained.commands(graph.pass());
    const auto instances = retained.instances(graph.pass());
    EXPECT_EQ(batches.size(), keys);
    EXPECT_EQ(commands.size(), pairs);
    ASSERT_EQ(instances.size(), scene.objects.size());
    const passes::RetainedStats& stats = retained.stats();
    EXPECT_EQ(stats.state_changes, keys);  // the minimum: every key bound once
    EXPECT_EQ(stats.distinct_keys, keys);
    EXPECT_EQ(stats.batches_drawn, keys);
    EXPECT_EQ(stats.bundles_drawn, scene.objects.size());
    EXPECT_EQ(stats.commands_drawn, pairs);
    const bool indirect = device().capabilities().draw_indirect;
    EXPECT_EQ(stats.draw_calls, indirect ? keys : pairs);
    EXPECT_EQ(device().last_frame_stats().draw_calls, indirect ? keys : pairs);

    // Commands cover the instance list in order, each instance once, and every object's slot is
    // in it once.
    uint32_t next_instance = 0;
    uint32_t command = 0;
    for (const passes::DrawBatch& batch : batches) {
        EXPECT_EQ(batch.first_command, command);
        uint32_t bundles = 0;
        for (uint32_t c = 0; c < batch.command_count; ++c, ++command) {
            EXPECT_EQ(commands[command].first_instance, next_instance);
            next_instance += commands[command].instance_count;
            bundles += commands[command].instance_count;
        }
        EXPECT_EQ(bundles, batch.bundles);
    }
    EXPECT_EQ(next_instance, instances.size());
    std::set<uint32_t> slots(instances.begin(), instances.end());
    EXPECT_EQ(slots.size(), scene.objects.size());
    for (const auto& shape : objects->shapes) EXPECT_TRUE(slots.count(*retained.object_slot(*shape)));
}

TEST_P(RetainedSceneTest, WithoutIndirectDrawsEveryCommandIsOneDrawOfTheSamePicture) {
    // RetainedConfig::indirect = false: what a device without indirect draws gets.
    const ObjectScene scene = make_object_scene(small_spec());
    std::vector<rhi::Image> naive;
    render_naive(scene, 48, naive);
    auto objects = make_retained_objects(scene);
    ASSERT_TRUE(objects.ok());
    passes::RetainedConfig config;
    config.indirect = false;
    RetainedScene retained(config);
    GBufferGraph graph(device(), 48, scene.camera);
    ASSERT_TRUE(retained.attach(graph.pass()).ok());
    for (const auto& shape : objects->shapes) ASSERT_TRUE(retained.submit(shape).ok());
    ASSERT_TRUE(graph.frame().ok());
    const uint64_t keys = distinct_state_keys(scene);
    const uint64_t pairs = distinct_key_mesh_pairs(scene);
    ASSERT_GT(pairs, keys) << "the scene must tell one draw per batch from one per command";
    EXPECT_EQ(retained.stats().state_changes, keys);
    EXPECT_EQ(retained.stats().draw_calls, pairs);
    EXPECT_EQ(device().last_frame_stats().draw_calls, pairs);
    std::vector<rhi::Image> maps;
    read_maps(graph, maps);
    expect_same_maps(naive, maps, "retained_direct");
}

TEST_P(RetainedSceneTest, SubmissionOrderQueueBindsAgainWheneverTheKeyChanges) {
    const ObjectScene scene = make_object_scene(small_spec());
    auto objects = make_retained_objects(scene);
    ASSERT_TRUE(objects.ok());
    RetainedScene retained;
    GBufferGraph graph(device(), 32, scene.camera);
    ASSERT_TRUE(retained.attach(graph.pass(), passes::QueueOrder::Submission).ok());
    for (const auto& shape : objects->shapes) ASSERT_TRUE(retained.submit(shape).ok());
    ASSERT_TRUE(graph.frame().ok());

    // In submission order a batch ends wherever the key changes from one object to the next.
    uint64_t runs = 0;
    std::tuple<bool, bool, bool, uint32_t> previous{};
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& object = scene.objects[i];
        const SceneMaterial& material = scene.materials[object.material];
        const std::tuple<bool, bool, bool, uint32_t> key{material.checker, material.value.material.double_sided,
                                                         glm::determinant(glm::mat3(object.model)) < 0.0f, object.material};
        if (i == 0 || key != previous) ++runs;
        previous = key;
    }
    const auto batches = retained.batches(graph.pass());
    EXPECT_EQ(batches.size(), runs);
    EXPECT_EQ(retained.stats().state_changes, runs);
    EXPECT_EQ(retained.stats().distinct_keys, distinct_state_keys(scene));
    EXPECT_GT(runs, distinct_state_keys(scene));
    // Instances follow submission order.
    const auto instances = retained.instances(graph.pass());
    ASSERT_EQ(instances.size(), objects->shapes.size());
    for (std::size_t i = 0; i < objects->shapes.size(); ++i) {
        EXPECT_EQ(instances[i], *retained.object_slot(*objects->shapes[i]));
    }
}

TEST_P(RetainedSceneTest, UploadsOnlyTheSetsThatChanged) {
    const ObjectScene scene = make_object_scene(small_spec());
    auto objects = make_retained_objects(scene);
    ASSERT_TRUE(objects.ok());
    RetainedScene retained;
    GBufferGraph graph(device(), 32, scene.camera);
    ASSERT_TRUE(retained.attach(graph.pass()).ok());
    for (const auto& shape : objects->shapes) ASSERT_TRUE(retained.submit(shape).ok());
    ASSERT_TRUE(graph.frame().ok());
    // The first frame placed every mesh used and wrote every set once.
    std::set<uint32_t> meshes_used, materials_used;
    for (const SceneObject& object : scene.objects) {
        meshes_used.insert(object.mesh);
        materials_used.insert(object.material);
    }
    EXPECT_EQ(retained.stats().geometries_placed, meshes_used.size());
    EXPECT_EQ(retained.stats().object_uploads.sets, scene.objects.size());
    EXPECT_EQ(retained.stats().material_uploads.sets, materials_used.size());

    // Nothing changed: nothing uploaded, by the scene or by anyone else in the frame.
    retained.reset_stats();
    ASSERT_TRUE(graph.frame().ok());
    EXPECT_EQ(retained.stats().uploaded_bytes(), 0u);
    EXPECT_EQ(device().last_frame_stats().bytes_uploaded, 0u);
    EXPECT_EQ(retained.stats().queue_rebuilds, 0u);

    // Five objects move: five records, 128 bytes each, nothing else.
    retained.reset_stats();
    for (std::size_t i : {3u, 17u, 18u, 60u, 143u}) {
        objects->models[i]->set(glm::translate(scene.objects[i].model, glm::vec3(0.0f, 0.25f, 0.0f)));
    }
    ASSERT_TRUE(graph.frame().ok());
    EXPECT_EQ(retained.stats().object_uploads.sets, 5u);
    EXPECT_EQ(retained.stats().object_uploads.bytes, 5 * kRecordBytes);
    EXPECT_EQ(retained.stats().uploaded_bytes(), 5 * kRecordBytes);
    EXPECT_EQ(device().last_frame_stats().bytes_uploaded, 5 * kRecordBytes);
    EXPECT_EQ(retained.stats().queue_rebuilds, 0u);  // moving changes no state key

    // An object set to the transform it has: recomputed, but the same bytes are not uploaded.
    retained.reset_stats();
    objects->models[3]->set(objects->models[3]->value());
    ASSERT_TRUE(graph.frame().ok());
    EXPECT_EQ(retained.stats().object_sets_refreshed, 1u);
    EXPECT_EQ(retained.stats().uploaded_bytes(), 0u);

    // A material changes: its set alone.
    retained.reset_stats();
    auto material_values = std::make_shared<InputParam<passes::MeshSurface>>(scene.materials[0].value);
    auto material = passes::make_mesh_material("changing", material_values);
    auto model = std::make_shared<InputParam<glm::mat4>>(glm::mat4(1.0f));
    auto extra = std::make_shared<Shape>("extra", passes::retained_pbr_mesh_kind(), objects->geometries[0], material, model);
    ASSERT_TRUE(retained.submit(extra).ok());
    ASSERT_TRUE(graph.frame().ok());
    retained.reset_stats();
    passes::MeshSurface changed = scene.materials[0].value;
    changed.material.roughness_factor = 0.25f;
    material_values->set(changed);
    ASSERT_TRUE(graph.frame().ok());
    EXPECT_EQ(retained.stats().material_uploads.sets, 1u);
    EXPECT_EQ(retained.stats().uploaded_bytes(), kMaterialBytes);
    EXPECT_EQ(device().last_frame_stats().bytes_uploaded, kMaterialBytes);

    // The camera moves: the pass's own set (80 bytes), nothing of the scene.
    retained.reset_stats();
    scene::CameraMatrices camera = scene.camera;
    camera.position += glm::vec3(0.5f, 0.0f, 0.0f);
    camera.view = glm::translate(camera.view, glm::vec3(-0.5f, 0.0f, 0.0f));
    graph.pass().set_camera(camera);
    ASSERT_TRUE(graph.frame().ok());
    EXPECT_EQ(retained.stats().uploaded_bytes(), 0u);
    EXPECT_EQ(device().last_frame_stats().bytes_uploaded, 80u);
}

TEST_P(RetainedSceneTest, LazyTransformsFollowTheirParent) {
    // A ring of children placed relative to one parent transform.
    std::vector<passes::MeshVertex> vertices;
    std::vector<uint32_t> indices;
    {
        ObjectSceneSpec spec;
        spec.objects = 1;
        spec.meshes = 1;
        spec.materials = 1;
        const ObjectScene one = make_object_scene(spec);
        vertices = one.meshes[0].vertices;
        indices = one.meshes[0].indices;
    }
    auto geometry = passes::make_mesh_geometry("ball", vertices, indices);
    ASSERT_TRUE(geometry.ok());
    const passes::MeshSurface white = plain_surface();
    auto material = passes::make_mesh_material("white", white);
    auto parent = std::make_shared<InputParam<glm::mat4>>(glm::mat4(1.0f));
    std::vector<std::shared_ptr<passes::ComputedParam<glm::mat4, glm::mat4>>> children;
    RetainedScene retained;
    scene::CameraMatrices camera;
    camera.position = glm::vec3(0.0f, 10.0f, 0.01f);
    camera.view = glm::lookAtRH(camera.position, glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f));
    camera.projection = glm::orthoRH_ZO(-4.0f, 4.0f, -4.0f, 4.0f, 0.1f, 20.0f);
    GBufferGraph graph(device(), 64, camera);
    ASSERT_TRUE(retained.attach(graph.pass()).ok());
    for (int i = 0; i < 4; ++i) {
        const glm::mat4 local = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(-1.5f + static_cast<float>(i), 0.0f, 0.0f)),
                                           glm::vec3(0.3f));
        auto child = passes::compute<glm::mat4>([local](const glm::mat4& p) { return p * local; }, parent);
        children.push_back(child);
        ASSERT_TRUE(retained.submit(std::make_shared<Shape>("child " + std::to_string(i), passes::retained_pbr_mesh_kind(),
                                                            *geometry, material, child))
                        .ok());
    }
    ASSERT_TRUE(graph.frame().ok());
    auto lowest_x = [&]() {
        auto position = graph.read("position");
        auto normal = graph.read("normal");
        EXPECT_TRUE(position.ok() && normal.ok());
        double lowest = 1e9;
        for (uint32_t y = 0; y < position->height; ++y) {
            for (uint32_t x = 0; x < position->width; ++x) {
                const auto n = normal->load(x, y);
                if (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0) continue;
                lowest = std::min(lowest, position->load(x, y)[0]);
            }
        }
        return lowest;
    };
    float leftmost = 0.0f;
    for (const passes::MeshVertex& v : vertices) leftmost = std::min(leftmost, -1.5f + 0.3f * v.position.x);
    const double before = lowest_x();
    EXPECT_NEAR(before, leftmost, 0.125);  // the leftmost child's left edge, within a texel
    for (const auto& child : children) EXPECT_EQ(child->computations(), 1u);

    // Moving the parent invalidates every child; they are recomputed once, when uploaded.
    retained.reset_stats();
    parent->set(glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 0.0f)));
    for (const auto& child : children) EXPECT_FALSE(child->valid());
    ASSERT_TRUE(graph.frame().ok());
    for (const auto& child : children) EXPECT_EQ(child->computations(), 2u);
    EXPECT_EQ(retained.stats().object_uploads.sets, 4u);
    EXPECT_EQ(retained.stats().object_uploads.bytes, 4 * kRecordBytes);
    EXPECT_NEAR(lowest_x(), before + 1.0, 1e-3);  // one unit is 8 texels: the same texels, moved
}

TEST_P(RetainedSceneTest, RetractingReleasesWhatOnlyThatShapeUsed) {
    ObjectSceneSpec spec;
    spec.objects = 1;
    spec.meshes = 3;
    spec.materials = 1;
    const ObjectScene source = make_object_scene(spec);
    std::vector<std::shared_ptr<const passes::Geometry>> geometries;
    for (const SceneMesh& mesh : source.meshes) {
        auto geometry = passes::make_mesh_geometry(mesh.name, mesh.vertices, mesh.indices);
        ASSERT_TRUE(geometry.ok());
        geometries.push_back(*geometry);
    }
    // A second geometry of mesh 1's size, to take the ranges mesh 1 leaves.
    auto copy = passes::make_mesh_geometry("copy", source.meshes[1].vertices, source.meshes[1].indices);
    ASSERT_TRUE(copy.ok());
    auto shared_material = passes::make_mesh_material("shared", plain_surface());
    auto own_material = passes::make_mesh_material("own", plain_surface());
    auto model = [](float x) { return std::make_shared<InputParam<glm::mat4>>(glm::translate(glm::mat4(1.0f), glm::vec3(x, 0, 0))); };
    const auto kind = passes::retained_pbr_mesh_kind();
    auto a = std::make_shared<Shape>("a", kind, geometries[0], shared_material, model(0));
    auto b = std::make_shared<Shape>("b", kind, geometries[0], shared_material, model(2));
    auto c = std::make_shared<Shape>("c", kind, geometries[1], own_material, model(4));

    RetainedScene retained;
    GBufferGraph graph(device(), 16, source.camera);
    ASSERT_TRUE(retained.attach(graph.pass()).ok());
    for (const auto& shape : {a, b, c}) ASSERT_TRUE(retained.submit(shape).ok());
    ASSERT_TRUE(graph.frame().ok());
    EXPECT_EQ(retained.geometry_count(), 2u);
    EXPECT_EQ(retained.material_count(), 2u);
    const auto commands = retained.commands(graph.pass());
    ASSERT_EQ(commands.size(), 2u);  // a and b share geometry and material: one instanced command
    EXPECT_EQ(commands[0].instance_count, 2u);
    const uint32_t c_first_index = commands[1].first_index;
    const uint32_t b_slot = *retained.object_slot(*b);
    const uint64_t indices_before = retained.geometry_buffers().indices_used();

    // b goes: its geometry and material stay (a uses them).
    ASSERT_TRUE(retained.retract(*b).ok());
    EXPECT_EQ(retained.geometry_count(), 2u);
    EXPECT_EQ(retained.material_count(), 2u);
    // c goes: its geometry's ranges and its material are released.
    ASSERT_TRUE(retained.retract(*c).ok());
    EXPECT_EQ(retained.geometry_count(), 1u);
    EXPECT_EQ(retained.material_count(), 1u);
    EXPECT_EQ(retained.geometry_buffers().indices_used(), indices_before - geometries[1]->indices().size());
    EXPECT_FALSE(retained.submitted(*c));
    ASSERT_TRUE(graph.frame().ok());
    EXPECT_EQ(retained.instances(graph.pass()).size(), 1u);

    // A new shape reuses the lowest freed record slot (b's), and a geometry of c's size c's ranges.
    auto d = std::make_shared<Shape>("d", kind, *copy, own_material, model(4));
    ASSERT_TRUE(retained.submit(d).ok());
    ASSERT_TRUE(graph.frame().ok());
    EXPECT_EQ(*retained.object_slot(*d), b_slot);
    const auto after = retained.commands(graph.pass());
    ASSERT_EQ(after.size(), 2u);
    EXPECT_EQ(after[1].first_index, c_first_index);
    EXPECT_EQ(retained.geometry_buffers().indices_used(), indices_before);

    ScopedLogCapture capture;
    auto again = retained.retract(*c);
    ASSERT_FALSE(again.ok());
    EXPECT_EQ(again.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(again.error().message.find("'c'"), std::string::npos) << again.error().message;
}

TEST_P(RetainedSceneTest, SeparateVertexStreamsShareTheirOwnPool) {
    // A kind reading positions from slot 0 and colours from slot 1 (two buffers per vertex
    // pool), the object index from slot 2; albedo = vertex colour.
    const char* records =
        "struct StreamRecord { mat4 model; mat4 normal_matrix; };\n"
        "layout(std430, set = LOOM_SET, binding = LOOM_BINDING(0)) readonly buffer ObjectRecords {\n"
        "    StreamRecord records[];\n"
        "} object_records;\n";
    passes::ShaderPart part("stream-mesh", 1);
    part.stage(rhi::ShaderStage::Vertex, std::string(records) +
                                             "layout(location = 0) in vec3 in_position;\n"
                                             "layout(location = 5) in vec4 in_color;\n"
                                             "layout(location = 15) in uint in_object_index;\n"
                                             "ObjectVertex object_vertex() {\n"
                                             "    ObjectVertex v;\n"
                                             "    v.world_position = transform_point(object_records.records[in_object_index].model, in_position).xyz;\n"
                                             "    v.world_normal = vec3(0.0, 1.0, 0.0);\n"
                                             "    v.uv = vec2(0.0);\n"
                                             "    v.color = in_color;\n"
                                             "    return v;\n"
                                             "}\n");
    part.stage(rhi::ShaderStage::Fragment,
               "MaterialSample object_material(SurfaceInput s) {\n"
               "    MaterialSample m;\n"
               "    m.albedo = s.color.rgb;\n"
               "    m.metallic = 0.0;\n"
               "    m.roughness = 1.0;\n"
               "    m.emissive = vec3(0.0);\n"
               "    return m;\n"
               "}\n");
    rhi::VertexBufferLayout positions{12, rhi::VertexStepMode::PerVertex, {{0, rhi::VertexFormat::Float3, 0}}};
    rhi::VertexBufferLayout colors{16, rhi::VertexStepMode::PerVertex, {{5, rhi::VertexFormat::Float4, 0}}};
    auto kind = std::make_shared<passes::ObjectKind>(
        "stream-mesh", std::vector<passes::ShaderPart>{part},
        std::vector<rhi::VertexBufferLayout>{positions, colors, passes::object_index_layout()});

    // A quad in the xz plane (seen from above: counter-clockwise), one colour per quad.
    auto quad = [&](const std::string& name, glm::vec3 color) {
        const float p[] = {-1, 0, 1, 1, 0, 1, 1, 0, -1, -1, 0, -1};
        std::vector<std::byte> position_bytes(sizeof(p));
        std::memcpy(position_bytes.data(), p, sizeof(p));
        std::vector<float> c;
        for (int i = 0; i < 4; ++i) c.insert(c.end(), {color.r, color.g, color.b, 1.0f});
        std::vector<std::byte> color_bytes(c.size() * sizeof(float));
        std::memcpy(color_bytes.data(), c.data(), color_bytes.size());
        return passes::Geometry::create(name, {positions, colors}, {position_bytes, color_bytes}, 4, {0, 1, 2, 0, 2, 3});
    };
    auto red = quad("red quad", {1, 0, 0});
    auto blue = quad("blue quad", {0, 0, 1});
    ASSERT_TRUE(red.ok() && blue.ok()) << (red.ok() ? blue.error().to_string() : red.error().to_string());
    auto plain = std::make_shared<passes::GpuMaterial>("plain", nullptr);
    scene::CameraMatrices camera;
    camera.position = glm::vec3(0.0f, 10.0f, 0.0f);
    camera.view = glm::lookAtRH(camera.position, glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f));
    camera.projection = glm::orthoRH_ZO(-2.0f, 2.0f, -2.0f, 2.0f, 0.1f, 20.0f);

    RetainedScene retained;
    GBufferGraph graph(device(), 32, camera);
    ASSERT_TRUE(retained.attach(graph.pass()).ok());
    auto left = std::make_shared<InputParam<glm::mat4>>(
        glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(-1.0f, 0.0f, 0.0f)), glm::vec3(0.9f)));
    auto right = std::make_shared<InputParam<glm::mat4>>(
        glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 0.0f)), glm::vec3(0.9f)));
    ASSERT_TRUE(retained.submit(std::make_shared<Shape>("left", kind, *red, plain, left)).ok());
    ASSERT_TRUE(retained.submit(std::make_shared<Shape>("right", kind, *blue, plain, right)).ok());
    // And a mesh of the interleaved layout in the same scene: a second vertex pool.
    const ObjectScene one = make_object_scene(ObjectSceneSpec{1, 1, 1, 1});
    auto ball = passes::make_mesh_geometry("ball", one.meshes[0].vertices, one.meshes[0].indices);
    ASSERT_TRUE(ball.ok());
    auto far_away = std::make_shared<InputParam<glm::mat4>>(glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 50)));
    ASSERT_TRUE(retained.submit(std::make_shared<Shape>("ball", passes::retained_pbr_mesh_kind(), *ball,
                                                        passes::make_mesh_material("m", plain_surface()), far_away))
                    .ok());
    auto status = graph.frame();
    ASSERT_TRUE(status.ok()) << status.error().to_string();
    EXPECT_EQ(retained.geometry_buffers().vertex_pools().size(), 2u);
    EXPECT_EQ(retained.geometry_buffers().vertex_pools()[0].buffers.size(), 2u);  // positions, colours
    auto albedo = graph.read("albedo");
    ASSERT_TRUE(albedo.ok());
    EXPECT_EQ(albedo->load(8, 16), (std::array<double, 4>{1, 0, 0, 0}));   // left quad: red
    EXPECT_EQ(albedo->load(24, 16), (std::array<double, 4>{0, 0, 1, 0}));  // right quad: blue
    EXPECT_EQ(albedo->load(16, 2), (std::array<double, 4>{0, 0, 0, 0}));   // between them: nothing
}

/// Renders a shadow map of `scene` seen through its camera: retained shapes when `retained` is
/// set, else the naive MeshObjects.
rhi::Image shadow_map(rhi::Device& device, const ObjectScene& scene, RetainedScene* retained,
                      const std::vector<std::shared_ptr<passes::MeshObject>>& naive) {
    fg::FrameGraph graph;
    auto shadow = std::make_unique<passes::ShadowMapPass>(passes::PassConfig{}, 64);
    shadow->set_light_view_projection(scene.camera.view_projection());
    if (retained) {
        EXPECT_TRUE(retained->attach(*shadow).ok());
    } else {
        for (const auto& object : naive) EXPECT_TRUE(passes::register_object(*shadow, object).ok());
    }
    EXPECT_TRUE(graph.add_pass(std::unique_ptr<fg::Pass>(std::move(shadow))).ok());
    EXPECT_TRUE(graph.mark_output(fg::port("shadow", "shadow_map")).ok());
    fg::Executor executor(device);
    fg::PlanOptions options;
    options.frame = {64, 64};
    auto status = executor.run_frame(graph, options);
    EXPECT_TRUE(status.ok()) << status.error().to_string();
    auto depth = device.read_texture(executor.texture("shadow", "shadow_map"));
    EXPECT_TRUE(depth.ok());
    return depth.ok() ? std::move(*depth) : rhi::Image{};
}

TEST_P(RetainedSceneTest, AShadowPassLeavesMaterialsOutOfItsKeys) {
    const ObjectScene scene = make_object_scene(small_spec());
    auto objects = make_retained_objects(scene);
    ASSERT_TRUE(objects.ok());
    RetainedScene retained;
    for (const auto& shape : objects->shapes) ASSERT_TRUE(retained.submit(shape).ok());
    const rhi::Image depth = shadow_map(device(), scene, &retained, {});

    // Depth needs no material: keys are (kind, culling, winding) only.
    std::set<std::tuple<bool, bool, bool>> keys;
    for (const SceneObject& object : scene.objects) {
        const SceneMaterial& material = scene.materials[object.material];
        keys.insert({material.checker, material.value.material.double_sided, glm::determinant(glm::mat3(object.model)) < 0.0f});
    }
    EXPECT_EQ(retained.stats().batches_drawn, keys.size());
    EXPECT_EQ(retained.stats().state_changes, keys.size());
    EXPECT_EQ(retained.stats().material_changes, 2u);  // one record-buffer binding per program (kind)

    // The same depth as the MeshObjects give.
    auto naive = make_naive_objects(device(), scene);
    ASSERT_TRUE(naive.ok());
    const rhi::Image expected = shadow_map(device(), scene, nullptr, naive->objects);
    auto comparison = image_io::compare_and_report(expected, depth, output_dir(),
                                              "retained_shadow." + std::string(rhi::backend_name(backend())));
    ASSERT_TRUE(comparison.ok());
    EXPECT_TRUE(comparison->equal()) << comparison->summary();
    uint64_t drawn = 0;
    for (uint32_t y = 0; y < depth.height; ++y) {
        for (uint32_t x = 0; x < depth.width; ++x) drawn += depth.load(x, y)[0] < 1.0 ? 1 : 0;
    }
    EXPECT_GT(drawn, 64u * 64u / 10);
}

TEST_P(RetainedSceneTest, ErrorsNameTheShape) {
    const ObjectScene one = make_object_scene(ObjectSceneSpec{1, 1, 1, 1});
    auto geometry = passes::make_mesh_geometry("ball", one.meshes[0].vertices, one.meshes[0].indices);
    ASSERT_TRUE(geometry.ok());
    auto material = passes::make_mesh_material("m", plain_surface());
    auto model = std::make_shared<InputParam<glm::mat4>>(glm::mat4(1.0f));
    RetainedScene retained;

    // A kind without the per-instance object index.
    auto naive_kind = std::make_shared<Shape>("plain mesh", passes::pbr_mesh_kind(), *geometry, material, model);
    auto status = retained.submit(naive_kind);
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(status.error().message.find("'plain mesh'"), std::string::npos) << status.error().message;
    EXPECT_NE(status.error().message.find("retained convention"), std::string::npos) << status.error().message;

    // Geometry of another layout than the kind reads.
    rhi::VertexBufferLayout positions{12, rhi::VertexStepMode::PerVertex, {{0, rhi::VertexFormat::Float3, 0}}};
    auto flat = passes::Geometry::create("flat", {positions}, {std::vector<std::byte>(36)}, 3, {0, 1, 2});
    ASSERT_TRUE(flat.ok());
    status = retained.submit(std::make_shared<Shape>("mismatch", passes::retained_pbr_mesh_kind(), *flat, material, model));
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find("'mismatch'"), std::string::npos) << status.error().message;
    EXPECT_NE(status.error().message.find("'flat'"), std::string::npos) << status.error().message;

    // Bad geometry is refused where it is made.
    auto bad = passes::Geometry::create("bad", {positions}, {std::vector<std::byte>(36)}, 3, {0, 1, 3});
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.error().message.find("'bad'"), std::string::npos);

    // Twice the same shape.
    auto shape = std::make_shared<Shape>("once", passes::retained_pbr_mesh_kind(), *geometry, material, model);
    ASSERT_TRUE(retained.submit(shape).ok());
    status = retained.submit(shape);
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find("'once'"), std::string::npos) << status.error().message;

    // A pass belongs to one scene.
    RetainedScene other;
    passes::GeometryPass pass;
    ASSERT_TRUE(retained.attach(pass).ok());
    status = other.attach(pass);
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().code, ErrorCode::InvalidState);
}

TEST_P(RetainedSceneTest, UniformSetPoolUploadsRunsOfChangedSlots) {
    passes::UniformSetPool pool("records", rhi::BufferUsage::Storage, 16, passes::UniformSetPool::Layout::Array, 4);
    std::vector<uint32_t> slots;
    for (int i = 0; i < 10; ++i) slots.push_back(pool.allocate());  // grows past 4 on the CPU
    auto bytes = [](uint32_t value) {
        std::vector<std::byte> out(16);
        std::memcpy(out.data(), &value, 4);
        return out;
    };
    for (uint32_t slot : slots) pool.write(slot, bytes(100 + slot));
    passes::UploadStats stats;
    ASSERT_TRUE(pool.upload(device(), stats).ok());
    EXPECT_EQ(stats.writes, 1u);  // a new buffer: written whole, once
    EXPECT_EQ(stats.sets, 10u);

    stats = {};
    for (uint32_t slot : {3u, 4u, 5u, 8u}) pool.write(slot, bytes(200 + slot));
    pool.write(9, bytes(109));  // unchanged: not uploaded
    ASSERT_TRUE(pool.upload(device(), stats).ok());
    EXPECT_EQ(stats.writes, 2u);  // slots 3-5 in one write, 8 in another
    EXPECT_EQ(stats.bytes, 4u * 16u);
    EXPECT_EQ(stats.sets, 4u);

    pool.release(4);
    EXPECT_EQ(pool.allocate(), 4u);  // freed slots are reused, lowest first
    auto read = device().read_buffer(pool.buffer(), 0, 10 * 16);
    ASSERT_TRUE(read.ok());
    for (uint32_t slot = 0; slot < 10; ++slot) {
        uint32_t value = 0;
        std::memcpy(&value, read->data() + slot * 16, 4);
        const bool changed = slot == 3 || slot == 4 || slot == 5 || slot == 8;
        EXPECT_EQ(value, (changed ? 200u : 100u) + slot) << "slot " << slot;
    }
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(RetainedSceneTest);

}  // namespace loom::test

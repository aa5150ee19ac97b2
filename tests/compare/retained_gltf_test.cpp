// glTF scenes through the retained object layer (loom::renderer::RetainedGltfScene) on each
// backend: every pass output is bit-identical to the GltfObjects' (one pass per frame, the
// immediate path), at rest and posed; posing uploads the records of the shapes that moved and
// nothing else, and rebuilds no render queue.
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "gltf_render.hpp"
#include "loom/renderer/gltf_scene.hpp"
#include "loom/renderer/retained_gltf_scene.hpp"
#include "loom/renderer/skin_palette.hpp"
#include "loom/scene/animation.hpp"
#include "loom_test/render_fixture.hpp"
#include "synthetic_scene.hpp"

namespace loom::test {
namespace {

// Draw items of animated_scene().
constexpr uint32_t kTextured = 0;  // opaque, textured, at rest
constexpr uint32_t kMasked = 1;    // MASK, double-sided, at rest
constexpr uint32_t kMirrored = 2;  // opaque, mirrored (scale -x) and normal-mapped; moves
constexpr uint32_t kBlended = 3;   // BLEND; moves

/// Four quads that exercise what the retained kind must reproduce (textures, a cut-out, a
/// mirrored normal-mapped surface, a blended one), and an animation that slides the mirrored
/// and the blended quads sideways over one second.
scene::Scene animated_scene() {
    SceneBuilder b;
    const uint32_t checker = b.texture(image_of(2, 2, rhi::Format::RGBA8Srgb,
                                                {{230, 40, 40, 255}, {240, 240, 240, 255}, {240, 240, 240, 255}, {40, 40, 230, 255}}),
                                       nearest_sampler());
    const uint32_t holes = b.texture(image_of(2, 1, rhi::Format::RGBA8Unorm, {{60, 200, 60, 255}, {60, 200, 60, 0}}),
                                     nearest_sampler());
    const uint32_t bumps = b.texture(image_of(2, 1, rhi::Format::RGBA8Unorm, {{200, 128, 230, 255}, {60, 128, 230, 255}}),
                                     nearest_sampler());
    scene::Material textured;
    textured.base_color_texture = scene::TextureRef{checker};
    textured.metallic_factor = 0.0f;
    scene::Material masked;
    masked.base_color_texture = scene::TextureRef{holes};
    masked.alpha_mode = scene::AlphaMode::Mask;
    masked.double_sided = true;
    masked.metallic_factor = 0.0f;
    scene::Material mirrored;
    mirrored.base_color_factor = glm::vec4(0.9f, 0.7f, 0.2f, 1.0f);
    mirrored.normal_texture = scene::TextureRef{bumps};
    mirrored.metallic_factor = 0.0f;
    mirrored.roughness_factor = 0.4f;
    scene::Material blended;
    blended.base_color_factor = glm::vec4(0.2f, 0.4f, 0.95f, 0.5f);
    blended.alpha_mode = scene::AlphaMode::Blend;
    blended.metallic_factor = 0.0f;

    b.quad(b.material(textured));
    b.quad(b.material(masked), glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(-0.5f, 0.4f, 0.3f)), glm::vec3(0.4f)));
    const glm::vec3 mirrored_at(0.5f, -0.4f, 0.2f), mirrored_scale(-0.4f, 0.4f, 1.0f);
    b.quad(b.material(mirrored), glm::scale(glm::translate(glm::mat4(1.0f), mirrored_at), mirrored_scale));
    const glm::vec3 blended_at(0.2f, 0.3f, 0.6f), blended_scale(0.5f);
    b.quad(b.material(blended), glm::scale(glm::translate(glm::mat4(1.0f), blended_at), blended_scale));
    b.camera();
    scene::Scene scene = b.build();
    // The animated nodes' TRS (the builder gives matrices' values only as `local`).
    scene.nodes[kMirrored].translation = mirrored_at;
    scene.nodes[kMirrored].scale = mirrored_scale;
    scene.nodes[kBlended].translation = blended_at;
    scene.nodes[kBlended].scale = blended_scale;

    scene::Animation slide;
    slide.name = "slide";
    slide.samplers.push_back(scene::AnimationSampler{
        {0.0f, 1.0f}, {0.5f, -0.4f, 0.2f, -0.3f, -0.2f, 0.2f}, scene::Interpolation::Linear, 3});
    slide.samplers.push_back(scene::AnimationSampler{
        {0.0f, 1.0f}, {0.2f, 0.3f, 0.6f, -0.4f, 0.1f, 0.6f}, scene::Interpolation::Linear, 3});
    slide.channels.push_back(scene::AnimationChannel{kMirrored, 0, scene::AnimatedProperty::Translation});
    slide.channels.push_back(scene::AnimationChannel{kBlended, 1, scene::AnimatedProperty::Translation});
    scene.animations.push_back(slide);
    return scene;
}

// Draw items of skinned_scene().
constexpr uint32_t kBackdrop = 0;  // opaque, textured, at rest
constexpr uint32_t kFlag = 1;      // skinned: its top edge follows joint 1

/// A textured backdrop and, in front of it, a skinned quad: its bottom corners follow joint 0
/// (at (0, -1, 0.5)), its top corners joint 1 (joint 0's child, at (0, 0, 0.5)), so an animation
/// that turns joint 1 about z by up to 60 degrees over a second sweeps the quad's top edge round.
/// Its mesh node is translated by (5, 0, 0), which glTF ignores for a skinned mesh.
scene::Scene skinned_scene() {
    SceneBuilder b;
    const uint32_t checker = b.texture(image_of(2, 2, rhi::Format::RGBA8Srgb,
                                                {{230, 40, 40, 255}, {240, 240, 240, 255}, {240, 240, 240, 255}, {40, 40, 230, 255}}),
                                       nearest_sampler());
    scene::Material backdrop;
    backdrop.base_color_texture = scene::TextureRef{checker};
    backdrop.metallic_factor = 0.0f;
    b.quad(b.material(backdrop), glm::scale(glm::mat4(1.0f), glm::vec3(1.5f)));
    scene::Material flag;
    flag.base_color_factor = glm::vec4(0.95f, 0.75f, 0.1f, 1.0f);
    flag.metallic_factor = 0.0f;
    flag.double_sided = true;
    b.quad(b.material(flag), glm::translate(glm::mat4(1.0f), glm::vec3(5.0f, 0.0f, 0.0f)));
    b.camera();
    scene::Scene scene = b.build();

    // The flag's vertices (corners (-1, 1), (1, 1), (1, -1), (-1, -1)) in joint space: placed at
    // z = 0.5 and scaled by 0.5 by the inverse bind matrices.
    const uint32_t hip = static_cast<uint32_t>(scene.nodes.size());
    scene::Node joint0;
    joint0.name = "hip";
    joint0.translation = glm::vec3(0.0f, -1.0f, 0.5f);
    joint0.children = {hip + 1};
    scene::Node joint1;
    joint1.name = "shoulder";
    joint1.parent = hip;
    joint1.translation = glm::vec3(0.0f, 1.0f, 0.0f);
    scene.nodes.push_back(joint0);
    scene.nodes.push_back(joint1);
    for (uint32_t joint : {hip, hip + 1}) {
        scene::Node& node = scene.nodes[joint];
        node.local = scene::trs_matrix(node.translation, node.rotation, node.scale);
    }
    std::vector<bool> every(scene.nodes.size(), true);
    scene::update_world_matrices(scene.nodes, every);
    scene::Skin skin;
    skin.joints = {hip, hip + 1};
    // Bind the mesh (modelled around the origin) half-size at z = 0.5 between the joints.
    const glm::mat4 bind = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -0.5f, 0.5f)), glm::vec3(0.5f));
    skin.inverse_bind_matrices = {glm::inverse(scene.nodes[hip].world) * bind, glm::inverse(scene.nodes[hip + 1].world) * bind};
    scene.skins.push_back(skin);
    scene::Primitive& primitive = scene.meshes[scene.draw_items[kFlag].mesh].primitives[0];
    for (const scene::Vertex& v : primitive.vertices) {
        primitive.skin.push_back(scene::SkinInfluences{glm::uvec4(v.position.y > 0.0f ? 1u : 0u, 0, 0, 0), glm::vec4(1, 0, 0, 0)});
    }
    scene.nodes[scene.draw_items[kFlag].node].skin = 0;
    scene.draw_items[kFlag].skin = 0;
    scene::place_skinned_draw_item(scene.draw_items[kFlag], scene, primitive);
    scene.bounds = scene::Bounds{};
    for (const scene::DrawItem& item : scene.draw_items) scene.bounds.extend(item.world_bounds);

    scene::Animation wave;
    wave.name = "wave";
    const float s = std::sin(glm::radians(30.0f)), c = std::cos(glm::radians(30.0f));
    wave.samplers.push_back(scene::AnimationSampler{{0.0f, 1.0f}, {0, 0, 0, 1, 0, 0, s, c}, scene::Interpolation::Linear, 4});
    wave.channels.push_back(scene::AnimationChannel{hip + 1, 0, scene::AnimatedProperty::Rotation});
    scene.animations.push_back(wave);
    return scene;
}

void expect_identical(const GltfFrame& retained, const GltfFrame& immediate, const std::string& what) {
    ASSERT_EQ(retained.images.size(), immediate.images.size()) << what;
    for (const auto& [name, image] : immediate.images) {
        auto diff = rhi::compare_images(retained.images.at(name), image, {0.0, false});
        ASSERT_TRUE(diff.ok()) << diff.error().to_string();
        EXPECT_TRUE(diff->equal()) << what << ", " << name << ": " << diff->summary();
    }
}

class RetainedGltfTest : public RenderTest {
protected:
    static constexpr uint32_t kWidth = 96;
    static constexpr uint32_t kHeight = 64;

    /// The frame the GltfObjects draw of `scene` (posed as the caller wants), with the bounds
    /// (shadow frustum, position map) of `like`: the retained pipeline keeps the bounds it was
    /// made with.
    GltfFrame immediate(const scene::Scene& scene, const renderer::PipelineScene& like, bool forward) {
        auto prepared = renderer::prepare_scene(scene);
        auto viewpoint = renderer::SceneViewpoint::choose(prepared->scene);
        EXPECT_TRUE(viewpoint.ok());
        auto gpu = renderer::GpuScene::create(device(), prepared);
        EXPECT_TRUE(gpu.ok()) << gpu.error().to_string();
        renderer::PipelineScene content = renderer::gltf_pipeline_scene(*gpu, *viewpoint);
        content.bounds = like.bounds;
        content.shadow_bounds = like.shadow_bounds;
        auto pipeline = renderer::DeferredPipeline::create(device(), std::move(content), gltf_test_settings(forward));
        EXPECT_TRUE(pipeline.ok()) << pipeline.error().to_string();
        auto frame = render_frame(device(), **pipeline, kWidth, kHeight);
        EXPECT_TRUE(frame.ok()) << frame.error().to_string();
        return frame.ok() ? std::move(*frame) : GltfFrame{};
    }
};

TEST_P(RetainedGltfTest, PosedFramesMatchTheGltfObjectsAndUploadOnlyTheRecordsThatMoved) {
    for (const bool forward : {false, true}) {
        SCOPED_TRACE(forward ? "forward" : "deferred");
        const scene::Scene rest = animated_scene();
        auto gltf = renderer::RetainedGltfScene::create(device(), renderer::prepare_scene(rest));
        ASSERT_TRUE(gltf.ok()) << gltf.error().to_string();
        EXPECT_EQ((*gltf)->shape_count(), 3u) << "the opaque and masked items";
        EXPECT_EQ((*gltf)->material_count(), 3u);
        EXPECT_EQ((*gltf)->shape(kBlended), nullptr);
        ASSERT_NE((*gltf)->shape(kMirrored), nullptr);
        EXPECT_EQ((*gltf)->shape(kMasked)->passes, (std::vector<std::string>{"masked-shadow", "geometry", "forward"}));
        auto viewpoint = renderer::SceneViewpoint::choose((*gltf)->scene());
        ASSERT_TRUE(viewpoint.ok());
        const renderer::PipelineScene content = (*gltf)->pipeline_scene(*viewpoint);
        EXPECT_TRUE(content.retained_masked_shadows);
        EXPECT_TRUE(content.opaque.empty());
        ASSERT_EQ(content.blended.size(), 1u);
        auto pipeline = renderer::DeferredPipeline::create(device(), content, gltf_test_settings(forward));
        ASSERT_TRUE(pipeline.ok()) << pipeline.error().to_string();
        ASSERT_NE((*pipeline)->masked_shadow(), nullptr);

        auto first = render_frame(device(), **pipeline, kWidth, kHeight);
        ASSERT_TRUE(first.ok()) << first.error().to_string();
        expect_identical(*first, immediate(rest, content, forward), "at rest");

        // Half a second in: the mirrored quad (a shape) and the blended one (a GltfObject) move.
        passes::RetainedScene& layer = (*gltf)->retained();
        layer.reset_stats();
        auto moved = (*gltf)->pose(0, 0.5f);
        ASSERT_TRUE(moved.ok()) << moved.error().to_string();
        EXPECT_EQ(*moved, (std::vector<uint32_t>{kMirrored, kBlended}));
        auto posed = render_frame(device(), **pipeline, kWidth, kHeight);
        ASSERT_TRUE(posed.ok()) << posed.error().to_string();
        // One record: the mirrored quad's model and normal matrices.
        EXPECT_EQ(layer.stats().object_uploads.sets, 1u);
        EXPECT_EQ(layer.stats().object_uploads.bytes, 128u);
        EXPECT_EQ(layer.stats().object_uploads.writes, 1u);
        EXPECT_EQ(layer.stats().uploaded_bytes(), 128u) << "no geometry, material or draw list";
        EXPECT_EQ(layer.stats().queue_rebuilds, 0u);
        EXPECT_EQ(layer.stats().geometries_placed, 0u);

        scene::Scene posed_scene = rest;
        (void)scene::pose(posed_scene, posed_scene.animations[0], 0.5f);
        expect_identical(*posed, immediate(posed_scene, content, forward), "posed at 0.5 s");
        auto change = rhi::compare_images(first->images.at("final"), posed->images.at("final"), {0.0, false});
        ASSERT_TRUE(change.ok());
        EXPECT_GT(change->pixels_above_threshold, 100u) << "the quads moved: " << change->summary();

        // The same pose again changes nothing, so nothing is uploaded.
        layer.reset_stats();
        ASSERT_TRUE((*gltf)->pose(0, 0.5f).ok());
        auto again = render_frame(device(), **pipeline, kWidth, kHeight);
        ASSERT_TRUE(again.ok()) << again.error().to_string();
        EXPECT_EQ(layer.stats().uploaded_bytes(), 0u);
        expect_identical(*again, *posed, "posed again");
    }
}

TEST_P(RetainedGltfTest, PoseRejectsAnAnimationTheSceneDoesNotHaveAndTimesThatAreNotTimes) {
    auto gltf = renderer::RetainedGltfScene::create(device(), renderer::prepare_scene(animated_scene()));
    ASSERT_TRUE(gltf.ok()) << gltf.error().to_string();
    auto missing = (*gltf)->pose(1, 0.0f);
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().message.find("animation 1 does not exist (the scene has 1 animation(s))"), std::string::npos)
        << missing.error().message;
    for (const float time : {-1.0f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        auto bad = (*gltf)->pose(0, time);
        ASSERT_FALSE(bad.ok()) << time;
        EXPECT_EQ(bad.error().code, ErrorCode::InvalidArgument);
    }
}

// Blended items are GltfObjects that read the posed scene, and the transparent pass sorts them
// by where the pose put them: the nearer quad, moved behind the other, is drawn first.
TEST_P(RetainedGltfTest, BlendedItemsAreSortedWhereThePoseMovesThem) {
    SceneBuilder b;
    scene::Material red;
    red.base_color_factor = glm::vec4(0.8f, 0.1f, 0.1f, 1.0f);
    b.quad(b.material(red));
    scene::Material glass;
    glass.base_color_factor = glm::vec4(0.2f, 0.4f, 0.95f, 0.5f);
    glass.alpha_mode = scene::AlphaMode::Blend;
    const uint32_t material = b.material(glass);
    b.quad(material, glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 0.5f)), glm::vec3(0.5f)));
    b.quad(material, glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0.1f, 0.1f, 1.0f)), glm::vec3(0.5f)));
    b.camera();
    scene::Scene scene = b.build();
    scene.nodes[2].translation = glm::vec3(0.1f, 0.1f, 1.0f);
    scene.nodes[2].scale = glm::vec3(0.5f);
    scene::Animation sink;
    sink.samplers.push_back(scene::AnimationSampler{{0.0f, 1.0f}, {0.1f, 0.1f, 1.0f, 0.1f, 0.1f, 0.2f},
                                                    scene::Interpolation::Linear, 3});
    sink.channels.push_back(scene::AnimationChannel{2, 0, scene::AnimatedProperty::Translation});
    scene.animations.push_back(sink);

    auto gltf = renderer::RetainedGltfScene::create(device(), renderer::prepare_scene(scene));
    ASSERT_TRUE(gltf.ok()) << gltf.error().to_string();
    auto viewpoint = renderer::SceneViewpoint::choose((*gltf)->scene());
    ASSERT_TRUE(viewpoint.ok());
    const renderer::PipelineScene content = (*gltf)->pipeline_scene(*viewpoint);
    auto pipeline = renderer::DeferredPipeline::create(device(), content, gltf_test_settings(true));
    ASSERT_TRUE(pipeline.ok()) << pipeline.error().to_string();
    auto rest = render_frame(device(), **pipeline, 64, 64);
    ASSERT_TRUE(rest.ok()) << rest.error().to_string();
    EXPECT_EQ(rest->blend_order, (std::vector<std::string>{"quad 1: quad 1 #0", "quad 2: quad 2 #0"}));
    ASSERT_TRUE((*gltf)->pose(0, 1.0f).ok());
    auto sunk = render_frame(device(), **pipeline, 64, 64);
    ASSERT_TRUE(sunk.ok()) << sunk.error().to_string();
    EXPECT_EQ(sunk->blend_order, (std::vector<std::string>{"quad 2: quad 2 #0", "quad 1: quad 1 #0"}));
    // GltfObjects placed by a scene that is posed between frames are sorted the same way.
    auto gpu = renderer::GpuScene::create(device(), renderer::prepare_scene(scene));
    ASSERT_TRUE(gpu.ok()) << gpu.error().to_string();
    auto placements = std::make_shared<scene::Scene>(scene::copy_without_images(scene));
    auto objects = renderer::DeferredPipeline::create(
        device(), renderer::gltf_pipeline_scene(*gpu, *viewpoint, placements), gltf_test_settings(true));
    ASSERT_TRUE(objects.ok()) << objects.error().to_string();
    auto before = render_frame(device(), **objects, 64, 64);
    ASSERT_TRUE(before.ok()) << before.error().to_string();
    EXPECT_EQ(before->blend_order, rest->blend_order);
    (void)scene::pose(*placements, placements->animations[0], 1.0f);
    auto after = render_frame(device(), **objects, 64, 64);
    ASSERT_TRUE(after.ok()) << after.error().to_string();
    EXPECT_EQ(after->blend_order, sunk->blend_order);
    auto diff = rhi::compare_images(after->images.at("final"), sunk->images.at("final"), {0.0, false});
    ASSERT_TRUE(diff.ok());
    EXPECT_TRUE(diff->equal()) << diff->summary();
}

// A skinned item is deformed by its joints on both paths alike: the retained layer writes the
// moved skin's two joint matrices (128 bytes) and nothing else, and draws what GltfObjects with a
// joint palette draw, at rest and posed; undeformed (no palette), the picture is the bind pose.
TEST_P(RetainedGltfTest, SkinnedItemsFollowTheirJointsOnBothPaths) {
    for (const bool forward : {false, true}) {
        SCOPED_TRACE(forward ? "forward" : "deferred");
        const scene::Scene rest = skinned_scene();
        auto gltf = renderer::RetainedGltfScene::create(device(), renderer::prepare_scene(rest));
        ASSERT_TRUE(gltf.ok()) << gltf.error().to_string();
        ASSERT_NE((*gltf)->shape(kFlag), nullptr);
        EXPECT_EQ((*gltf)->shape(kFlag)->kind()->name(), "retained-gltf-skinned-mesh");
        EXPECT_EQ((*gltf)->shape(kBackdrop)->kind()->name(), "retained-gltf-mesh");
        ASSERT_NE((*gltf)->skin_palette(), nullptr);
        auto viewpoint = renderer::SceneViewpoint::choose((*gltf)->scene());
        ASSERT_TRUE(viewpoint.ok());
        const renderer::PipelineScene content = (*gltf)->pipeline_scene(*viewpoint);
        auto pipeline = renderer::DeferredPipeline::create(device(), content, gltf_test_settings(forward));
        ASSERT_TRUE(pipeline.ok()) << pipeline.error().to_string();
        auto first = render_frame(device(), **pipeline, kWidth, kHeight);
        ASSERT_TRUE(first.ok()) << first.error().to_string();

        // The GltfObjects, placed by a scene posed alongside and deformed by a palette of their own.
        auto gpu = renderer::GpuScene::create(device(), renderer::prepare_scene(rest));
        ASSERT_TRUE(gpu.ok()) << gpu.error().to_string();
        auto placements = std::make_shared<scene::Scene>(scene::copy_without_images(rest));
        auto palette = renderer::SkinPalette::create(device(), *placements);
        ASSERT_TRUE(palette.ok()) << palette.error().to_string();
        std::shared_ptr<renderer::SkinPalette> joints = std::move(*palette);
        renderer::PipelineScene objects_content = renderer::gltf_pipeline_scene(*gpu, *viewpoint, placements, joints);
        objects_content.bounds = content.bounds;
        objects_content.shadow_bounds = content.shadow_bounds;
        auto objects = renderer::DeferredPipeline::create(device(), objects_content, gltf_test_settings(forward));
        ASSERT_TRUE(objects.ok()) << objects.error().to_string();
        auto objects_first = render_frame(device(), **objects, kWidth, kHeight);
        ASSERT_TRUE(objects_first.ok()) << objects_first.error().to_string();
        expect_identical(*first, *objects_first, "at rest");

        passes::RetainedScene& layer = (*gltf)->retained();
        layer.reset_stats();
        const uint64_t joint_bytes = (*gltf)->skin_palette()->bytes_written();
        auto moved = (*gltf)->pose(0, 1.0f);
        ASSERT_TRUE(moved.ok()) << moved.error().to_string();
        EXPECT_EQ(*moved, (std::vector<uint32_t>{kFlag}));
        EXPECT_EQ((*gltf)->skin_palette()->bytes_written() - joint_bytes, 2u * 64u) << "the skin's two joints";
        auto posed = render_frame(device(), **pipeline, kWidth, kHeight);
        ASSERT_TRUE(posed.ok()) << posed.error().to_string();
        EXPECT_EQ(layer.stats().uploaded_bytes(), 0u) << "no record: the skinned item's stays the identity";
        EXPECT_EQ(layer.stats().queue_rebuilds, 0u);

        (void)scene::pose(*placements, placements->animations[0], 1.0f);
        ASSERT_TRUE(joints->write_all(*placements).ok());
        auto objects_posed = render_frame(device(), **objects, kWidth, kHeight);
        ASSERT_TRUE(objects_posed.ok()) << objects_posed.error().to_string();
        expect_identical(*posed, *objects_posed, "posed");
        auto change = rhi::compare_images(first->images.at("final"), posed->images.at("final"), {0.0, false});
        ASSERT_TRUE(change.ok());
        EXPECT_GT(change->pixels_above_threshold, 100u) << "the flag's top swept round: " << change->summary();

        // The GPU's skinning against the CPU's: the flag's vertices moved by scene::skinned_position
        // and drawn unskinned land on the same pixels, up to the rounding of the two (edges).
        scene::Scene cpu = scene::copy_without_images(*placements);
        cpu.images = rest.images;
        {
            scene::Primitive& flag = cpu.meshes[cpu.draw_items[kFlag].mesh].primitives[0];
            const std::vector<glm::mat4> matrices = scene::joint_matrices(cpu, 0);
            for (std::size_t v = 0; v < flag.vertices.size(); ++v) {
                const glm::mat4& joint = matrices[flag.skin[v].joints.x];
                flag.vertices[v].position = scene::skinned_position(flag.vertices[v].position, flag.skin[v], matrices);
                flag.vertices[v].normal = glm::normalize(glm::mat3(joint) * flag.vertices[v].normal);
                flag.vertices[v].tangent = glm::vec4(glm::normalize(glm::mat3(joint) * glm::vec3(flag.vertices[v].tangent)), flag.vertices[v].tangent.w);
            }
            flag.skin.clear();
            cpu.draw_items[kFlag].skin.reset();
            cpu.skins.clear();
        }
        const GltfFrame cpu_frame = immediate(cpu, content, forward);
        auto cpu_diff = rhi::compare_images(cpu_frame.images.at("final"), posed->images.at("final"), {1.0, false});
        ASSERT_TRUE(cpu_diff.ok());
        EXPECT_LE(cpu_diff->pixels_above_threshold, cpu_diff->pixel_count / 100) << cpu_diff->summary();

        // Without a palette the GltfObjects draw the bind pose: the rest picture, not the posed one.
        auto undeformed = renderer::DeferredPipeline::create(
            device(), [&] {
                renderer::PipelineScene bind_pose = renderer::gltf_pipeline_scene(*gpu, *viewpoint, placements);
                bind_pose.bounds = content.bounds;
                bind_pose.shadow_bounds = content.shadow_bounds;
                return bind_pose;
            }(),
            gltf_test_settings(forward));
        ASSERT_TRUE(undeformed.ok()) << undeformed.error().to_string();
        auto bind_frame = render_frame(device(), **undeformed, kWidth, kHeight);
        ASSERT_TRUE(bind_frame.ok()) << bind_frame.error().to_string();
        auto bind_diff = rhi::compare_images(bind_frame->images.at("final"), posed->images.at("final"), {0.0, false});
        ASSERT_TRUE(bind_diff.ok());
        EXPECT_GT(bind_diff->pixels_above_threshold, 100u) << bind_diff->summary();
    }
}

LOOM_INSTANTIATE_RENDER_TEST(RetainedGltfTest);

// The posed skinned scene is drawn to the bit alike on GL and Vulkan.
TEST(RetainedGltfAcrossBackends, PosedSkinnedSceneIsIdenticalOnGlAndVulkan) {
    if (backends_under_test().size() < 2) GTEST_SKIP() << "needs both backends";
    std::vector<GltfFrame> frames;
    for (const rhi::Backend backend : backends_under_test()) {
        auto device = create_test_device(backend);
        ASSERT_TRUE(device.ok()) << device.error().to_string();
        auto gltf = renderer::RetainedGltfScene::create(**device, renderer::prepare_scene(skinned_scene()));
        ASSERT_TRUE(gltf.ok()) << gltf.error().to_string();
        ASSERT_TRUE((*gltf)->pose(0, 0.7f).ok());
        auto viewpoint = renderer::SceneViewpoint::choose((*gltf)->scene());
        ASSERT_TRUE(viewpoint.ok());
        auto pipeline = renderer::DeferredPipeline::create(**device, (*gltf)->pipeline_scene(*viewpoint), gltf_test_settings(false));
        ASSERT_TRUE(pipeline.ok()) << pipeline.error().to_string();
        auto frame = render_frame(**device, **pipeline, 96, 64);
        ASSERT_TRUE(frame.ok()) << frame.error().to_string();
        frames.push_back(std::move(*frame));
    }
    for (const auto& [name, image] : frames[0].images) {
        auto diff = rhi::compare_images(image, frames[1].images.at(name), {0.0, false});
        ASSERT_TRUE(diff.ok());
        EXPECT_TRUE(diff->equal()) << name << ": " << diff->summary();
    }
}

}  // namespace
}  // namespace loom::test

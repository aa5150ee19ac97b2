// Keyframe sampling as glTF 2.0 defines it: step, linear (slerp for rotations, along the
// shorter arc) and cubic-spline interpolation, and times outside the keyframes; and pose(),
// which plays an animation on a scene's nodes and draw items.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "loom/scene/animation.hpp"
#include "loom/scene/scene.hpp"

namespace loom::scene {
namespace {

std::array<float, 4> sampled(const AnimationSampler& sampler, float time, bool rotation = false) {
    std::array<float, 4> out{};
    sample(sampler, time, rotation, std::span<float>(out).first(sampler.components));
    return out;
}

AnimationSampler translations(Interpolation interpolation) {
    // Keyframes at 1 s and 3 s: (0, 0, 0) then (2, 4, -6).
    return {{1.0f, 3.0f}, {0, 0, 0, 2, 4, -6}, interpolation, 3};
}

TEST(AnimationSampling, LinearIsProportionalToTheTimeBetweenKeyframes) {
    const AnimationSampler s = translations(Interpolation::Linear);
    EXPECT_EQ(sampled(s, 2.0f), (std::array<float, 4>{1, 2, -3, 0}));
    EXPECT_EQ(sampled(s, 1.5f), (std::array<float, 4>{0.5f, 1, -1.5f, 0}));
}

TEST(AnimationSampling, StepHoldsTheLastKeyframeReached) {
    const AnimationSampler s = translations(Interpolation::Step);
    EXPECT_EQ(sampled(s, 2.9f), (std::array<float, 4>{0, 0, 0, 0}));
    EXPECT_EQ(sampled(s, 3.0f), (std::array<float, 4>{2, 4, -6, 0}));
}

TEST(AnimationSampling, TimesOutsideTheKeyframesTakeTheNearestValue) {
    for (Interpolation i : {Interpolation::Step, Interpolation::Linear}) {
        const AnimationSampler s = translations(i);
        EXPECT_EQ(sampled(s, 0.0f), (std::array<float, 4>{0, 0, 0, 0}));
        EXPECT_EQ(sampled(s, 10.0f), (std::array<float, 4>{2, 4, -6, 0}));
    }
    const AnimationSampler single{{0.5f}, {7, 8, 9}, Interpolation::Linear, 3};
    EXPECT_EQ(sampled(single, 2.0f), (std::array<float, 4>{7, 8, 9, 0}));
}

TEST(AnimationSampling, LinearRotationsTurnAtConstantSpeedAlongTheShorterArc) {
    // Identity, then 90 degrees about z: halfway is 45 degrees about z, not the normalised
    // average of the two at a quarter of the time (22.5 degrees, where the average gives 21.6).
    const float h = std::sin(std::numbers::pi_v<float> / 4);
    AnimationSampler s{{0.0f, 1.0f}, {0, 0, 0, 1, 0, 0, h, h}, Interpolation::Linear, 4};
    const std::array<float, 4> quarter = sampled(s, 0.25f, true);
    const float angle = 2 * std::atan2(quarter[2], quarter[3]);
    EXPECT_NEAR(angle, std::numbers::pi_v<float> / 8, 1e-6f);
    // The same end rotation written as -q: the turn is still 90 degrees, not 270.
    s.values = {0, 0, 0, 1, 0, 0, -h, -h};
    const std::array<float, 4> half = sampled(s, 0.5f, true);
    EXPECT_NEAR(2 * std::atan2(std::abs(half[2]), std::abs(half[3])), std::numbers::pi_v<float> / 4, 1e-6f);
    EXPECT_NEAR(half[0] * half[0] + half[1] * half[1] + half[2] * half[2] + half[3] * half[3], 1.0f, 1e-6f);
}

TEST(AnimationSampling, CubicSplineFollowsTheHermiteCurveOfItsTangents) {
    // One component, keyframes at 0 s and 2 s with values 0 and 1; the out-tangent of the first
    // is 1 per second, the in-tangent of the second is 0. With t = time / 2 and the tangents
    // scaled by 2 s: p(t) = (t^3 - 2t^2 + t) * 2 + (-2t^3 + 3t^2).
    const AnimationSampler s{{0.0f, 2.0f}, {/*in*/ 5, /*value*/ 0, /*out*/ 1, /*in*/ 0, /*value*/ 1, /*out*/ -5},
                             Interpolation::CubicSpline, 1};
    for (float time : {0.5f, 1.0f, 1.5f}) {
        const float t = time / 2;
        const float expected = (t * t * t - 2 * t * t + t) * 2 + (-2 * t * t * t + 3 * t * t);
        EXPECT_NEAR(sampled(s, time)[0], expected, 1e-6f) << "at " << time << " s";
    }
    EXPECT_EQ(sampled(s, 0.0f)[0], 0.0f);
    EXPECT_EQ(sampled(s, 2.0f)[0], 1.0f);
    EXPECT_EQ(sampled(s, 3.0f)[0], 1.0f);
}

TEST(AnimationSampling, CubicSplineRotationsAreNormalised) {
    // Zero tangents between identity and 90 degrees about z: the curve's midpoint is the
    // average of the two, normalised.
    const float h = std::sin(std::numbers::pi_v<float> / 4);
    const AnimationSampler s{{0.0f, 1.0f},
                             {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, h, h, 0, 0, 0, 0},
                             Interpolation::CubicSpline,
                             4};
    const std::array<float, 4> q = sampled(s, 0.5f, true);
    EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0f, 1e-6f);
    EXPECT_NEAR(2 * std::atan2(q[2], q[3]), std::numbers::pi_v<float> / 4, 1e-5f);
}

TEST(AnimationSampling, DurationIsTheLastKeyframeOfAllSamplers) {
    Animation a;
    EXPECT_EQ(a.duration(), 0.0f);
    a.samplers = {translations(Interpolation::Linear), AnimationSampler{{0.0f, 4.5f}, {0, 1}, Interpolation::Step, 1}};
    EXPECT_EQ(a.duration(), 4.5f);
}

// A parent (mesh: a unit triangle) with a child (the same mesh) and a third, unrelated node.
Scene two_level_scene() {
    Scene scene;
    Mesh mesh;
    Primitive triangle;
    for (const glm::vec3& p : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)}) triangle.vertices.push_back(Vertex{p});
    triangle.indices = {0, 1, 2};
    mesh.primitives.push_back(triangle);
    scene.meshes.push_back(mesh);
    scene.nodes.resize(3);
    scene.nodes[0].children = {1};
    scene.nodes[1].parent = 0;
    scene.nodes[1].translation = glm::vec3(0, 0, 5);
    for (uint32_t n = 0; n < 3; ++n) {
        Node& node = scene.nodes[n];
        node.mesh = 0;
        node.local = trs_matrix(node.translation, node.rotation, node.scale);
        node.world = node.parent ? scene.nodes[*node.parent].world * node.local : node.local;
        DrawItem item;
        item.node = n;
        place_draw_item(item, node, scene.meshes[0].primitives[0]);
        scene.bounds.extend(item.world_bounds);
        scene.draw_items.push_back(item);
    }
    return scene;
}

TEST(AnimationPose, MovesTheAnimatedNodesTheirDescendantsAndTheirDrawItemsOnly) {
    Scene scene = two_level_scene();
    Animation animation;
    animation.samplers = {translations(Interpolation::Linear),
                          AnimationSampler{{0.0f, 2.5f}, {1, 1, 1, 3, 1, 1}, Interpolation::Step, 3}};
    animation.channels = {{0, 0, AnimatedProperty::Translation}, {0, 1, AnimatedProperty::Scale}};
    const Scene before = scene;

    // At 2 s: translation halfway to (2, 4, -6), scale still the first keyframe's (step).
    EXPECT_EQ(pose(scene, animation, 2.0f), (std::vector<uint32_t>{0, 1}));
    EXPECT_EQ(scene.nodes[0].translation, glm::vec3(1, 2, -3));
    EXPECT_EQ(scene.nodes[0].scale, glm::vec3(1, 1, 1));
    EXPECT_EQ(scene.draw_items[0].world[3], glm::vec4(1, 2, -3, 1));
    // The child follows its parent: its own translation (0, 0, 5) on top.
    EXPECT_EQ(scene.draw_items[1].world[3], glm::vec4(1, 2, 2, 1));
    EXPECT_EQ(scene.draw_items[1].world_bounds.min, glm::vec3(1, 2, 2));
    EXPECT_EQ(scene.draw_items[1].world_bounds.max, glm::vec3(2, 3, 2));
    // The unrelated node and its item keep their matrices.
    EXPECT_EQ(scene.nodes[2].world, before.nodes[2].world);
    EXPECT_EQ(scene.draw_items[2].world, before.draw_items[2].world);
    EXPECT_EQ(scene.bounds.min, glm::vec3(0, 0, -3));
    EXPECT_EQ(scene.bounds.max, glm::vec3(2, 3, 2));

    // At 3 s the step scale (3, 1, 1) applies, after the rotation and before the translation:
    // the parent's triangle is three times as wide, the child sits at x = 2 + 3 * 0.
    pose(scene, animation, 3.0f);
    EXPECT_EQ(scene.draw_items[0].world_bounds.max, glm::vec3(5, 5, -6));
    EXPECT_EQ(scene.draw_items[1].world[3], glm::vec4(2, 4, -1, 1));
    EXPECT_FALSE(scene.draw_items[1].flips_winding);

    // A rotation channel: a quarter turn about z takes the triangle's x axis to y.
    Animation turn;
    turn.samplers = {AnimationSampler{{0.0f}, {0, 0, std::sqrt(0.5f), std::sqrt(0.5f)}, Interpolation::Linear, 4}};
    turn.channels = {{2, 0, AnimatedProperty::Rotation}};
    EXPECT_EQ(pose(scene, turn, 0.0f), (std::vector<uint32_t>{2}));
    const glm::vec4 x_axis = scene.draw_items[2].world * glm::vec4(1, 0, 0, 0);
    EXPECT_NEAR(x_axis.x, 0.0f, 1e-6f);
    EXPECT_NEAR(x_axis.y, 1.0f, 1e-6f);
    // An animation without channels moves nothing.
    EXPECT_TRUE(pose(scene, Animation{}, 1.0f).empty());
}

// A two-joint arm: joint 0 at the origin, joint 1 (its child) at (0, 1, 0), both bound where
// they stand (inverse bind matrices: the inverses of their world matrices). The skinned mesh
// (on node 2, moved away by (10, 0, 0), which glTF ignores for skinned meshes) has a vertex on
// each joint and one at (0, 2, 0) that follows joint 1 alone, and one at (1, 1, 0) half on each.
Scene arm_scene() {
    Scene scene;
    Mesh mesh;
    Primitive arm;
    for (const glm::vec3& p : {glm::vec3(0, 0, 0), glm::vec3(0, 2, 0), glm::vec3(1, 1, 0)}) arm.vertices.push_back(Vertex{p});
    arm.indices = {0, 2, 1};
    arm.skin = {SkinInfluences{glm::uvec4(0, 0, 0, 0), glm::vec4(1, 0, 0, 0)},
                SkinInfluences{glm::uvec4(1, 0, 0, 0), glm::vec4(1, 0, 0, 0)},
                SkinInfluences{glm::uvec4(0, 1, 0, 0), glm::vec4(0.5f, 0.5f, 0, 0)}};
    mesh.primitives.push_back(arm);
    scene.meshes.push_back(mesh);
    scene.nodes.resize(3);
    scene.nodes[0].children = {1};
    scene.nodes[1].parent = 0;
    scene.nodes[1].translation = glm::vec3(0, 1, 0);
    scene.nodes[2].translation = glm::vec3(10, 0, 0);
    scene.nodes[2].mesh = 0;
    scene.nodes[2].skin = 0;
    for (Node& node : scene.nodes) node.local = trs_matrix(node.translation, node.rotation, node.scale);
    std::vector<bool> every(3, true);
    update_world_matrices(scene.nodes, every);
    Skin skin;
    skin.joints = {0, 1};
    skin.inverse_bind_matrices = {glm::inverse(scene.nodes[0].world), glm::inverse(scene.nodes[1].world)};
    scene.skins.push_back(skin);
    DrawItem item;
    item.node = 2;
    item.skin = 0;
    place_skinned_draw_item(item, scene, scene.meshes[0].primitives[0]);
    scene.bounds.extend(item.world_bounds);
    scene.draw_items.push_back(item);
    return scene;
}

TEST(SkinPose, JointsPlaceTheVerticesByTheirWeightsAndTheMeshNodeIsIgnored) {
    Scene scene = arm_scene();
    // At rest every joint matrix is the identity: the mesh stands as modelled, not at x = 10.
    for (const glm::mat4& m : joint_matrices(scene, 0)) EXPECT_EQ(m, glm::mat4(1.0f));
    const DrawItem& item = scene.draw_items[0];
    EXPECT_EQ(item.world, glm::mat4(1.0f));
    EXPECT_EQ(item.world_bounds.min, glm::vec3(0, 0, 0));
    EXPECT_EQ(item.world_bounds.max, glm::vec3(1, 2, 0));

    // A quarter turn of joint 1 about z (pivot (0, 1, 0)): the tip (0, 2, 0) goes to (-1, 1, 0);
    // the vertex half on each joint goes halfway between (1, 1, 0) and its turned place (0, 2, 0).
    Animation bend;
    bend.samplers = {AnimationSampler{{0.0f, 1.0f}, {0, 0, 0, 1, 0, 0, std::sqrt(0.5f), std::sqrt(0.5f)},
                                      Interpolation::Linear, 4}};
    bend.channels = {{1, 0, AnimatedProperty::Rotation}};
    EXPECT_EQ(pose(scene, bend, 1.0f), (std::vector<uint32_t>{0}));
    const std::vector<glm::mat4> joints = joint_matrices(scene, 0);
    const Primitive& arm = scene.meshes[0].primitives[0];
    const glm::vec3 tip = skinned_position(arm.vertices[1].position, arm.skin[1], joints);
    const glm::vec3 middle = skinned_position(arm.vertices[2].position, arm.skin[2], joints);
    EXPECT_NEAR(tip.x, -1.0f, 1e-6f);
    EXPECT_NEAR(tip.y, 1.0f, 1e-6f);
    EXPECT_NEAR(middle.x, 0.5f, 1e-6f);
    EXPECT_NEAR(middle.y, 1.5f, 1e-6f);
    EXPECT_EQ(skinned_position(arm.vertices[0].position, arm.skin[0], joints), glm::vec3(0, 0, 0));
    EXPECT_NEAR(scene.draw_items[0].world_bounds.min.x, -1.0f, 1e-6f);
    EXPECT_NEAR(scene.draw_items[0].world_bounds.max.x, 0.5f, 1e-6f);
    EXPECT_NEAR(scene.draw_items[0].world_bounds.max.y, 1.5f, 1e-6f);
    EXPECT_NEAR(scene.bounds.max.y, 1.5f, 1e-6f);
    EXPECT_EQ(scene.draw_items[0].world, glm::mat4(1.0f));

    // Moving the mesh's own node moves nothing: glTF ignores it for skinned meshes.
    Animation slide;
    slide.samplers = {translations(Interpolation::Linear)};
    slide.channels = {{2, 0, AnimatedProperty::Translation}};
    EXPECT_TRUE(pose(scene, slide, 1.0f).empty());
    // Joints past the skin's end and zero weights are ignored.
    EXPECT_EQ(skinned_position(glm::vec3(1, 2, 3), SkinInfluences{glm::uvec4(7, 0, 0, 0), glm::vec4(1, 0, 0, 0)}, joints),
              glm::vec3(0, 0, 0));
}

}  // namespace
}  // namespace loom::scene

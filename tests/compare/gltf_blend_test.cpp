// Blended glTF surfaces (alphaMode BLEND) on each backend: the transparent pass blends them over
// the lit frame farthest first, behind opaque surfaces they are hidden, and the pipelines wire
// the pass after the lit pass. Checked on the forward pipeline, where the blended surfaces and an
// opaque stand-in for them are lit by the same code at the same points, so the blend is exact up
// to float rounding: expected = alpha × lit surface + (1 - alpha) × what lies behind.
#include <algorithm>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "gltf_render.hpp"
#include "loom_test/render_fixture.hpp"
#include "synthetic_scene.hpp"

namespace loom::test {
namespace {

constexpr uint32_t kCentre = 32;

glm::dvec3 colour_at(const GltfFrame& frame, const std::string& image) {
    const auto v = frame.images.at(image).load(kCentre, kCentre);
    return {v[0], v[1], v[2]};
}

/// A red opaque quad at z = 0, and quads at the given depths with their colours and modes.
struct Layer {
    float z;
    glm::vec4 colour;
    scene::AlphaMode mode;
};

scene::Scene layered(const std::vector<Layer>& layers) {
    SceneBuilder b;
    scene::Material red;
    red.base_color_factor = glm::vec4(0.8f, 0.1f, 0.1f, 1.0f);
    red.metallic_factor = 0.0f;
    b.quad(b.material(red));
    for (const Layer& layer : layers) {
        scene::Material m;
        m.base_color_factor = layer.colour;
        m.metallic_factor = 0.0f;
        m.roughness_factor = 0.6f;
        m.alpha_mode = layer.mode;
        b.quad(b.material(m), glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, layer.z)), glm::vec3(0.5f)));
    }
    b.camera();
    return b.build();
}

class GltfBlendTest : public RenderTest {
protected:
    GltfFrame render(const scene::Scene& scene, bool forward = true) {
        auto frame = render_gltf(device(), scene, forward);
        EXPECT_TRUE(frame.ok()) << frame.error().to_string();
        return frame.ok() ? std::move(*frame) : GltfFrame{};
    }
};

void expect_near(const glm::dvec3& actual, const glm::dvec3& expected, const char* what) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], 1e-3 * std::max(1.0, expected[c])) << what << ", channel " << c;
}

TEST_P(GltfBlendTest, BlendedSurfacesGoOverWhatLiesBehindFarthestFirst) {
    const glm::vec4 blue(0.1f, 0.2f, 0.9f, 0.5f), green(0.1f, 0.9f, 0.2f, 0.5f);
    using scene::AlphaMode;
    // What lies behind, and each blended surface lit as if it were opaque.
    const GltfFrame behind = render(layered({}));
    const GltfFrame blue_lit = render(layered({{0.5f, blue, AlphaMode::Opaque}}));
    const GltfFrame green_lit = render(layered({{1.0f, green, AlphaMode::Opaque}}));
    // Both blended, the nearer one (green) registered first: the pass sorts.
    const GltfFrame both = render(layered({{1.0f, green, AlphaMode::Blend}, {0.5f, blue, AlphaMode::Blend}}));
    ASSERT_FALSE(behind.images.empty() || blue_lit.images.empty() || green_lit.images.empty() || both.images.empty());

    ASSERT_EQ(both.blend_order.size(), 2u);
    EXPECT_EQ(both.blend_order[0], "quad 2: quad 2 #0") << "the farther (blue) quad first";
    EXPECT_EQ(both.blend_order[1], "quad 1: quad 1 #0");
    const glm::dvec3 c0 = colour_at(behind, "forward.color");
    const glm::dvec3 b = colour_at(blue_lit, "forward.color");
    const glm::dvec3 g = colour_at(green_lit, "forward.color");
    const glm::dvec3 expected = 0.5 * (0.5 * c0 + 0.5 * b) + 0.5 * g;
    expect_near(colour_at(both, "transparent.color"), expected, "blue, then green over it");
    // The opaque pass's output is what lay behind before blending.
    expect_near(colour_at(both, "forward.color"), c0, "forward.color");
}

TEST_P(GltfBlendTest, BlendedSurfacesBehindOpaqueOnesAreHidden) {
    const GltfFrame hidden = render(layered({{-0.5f, glm::vec4(0.1f, 0.9f, 0.2f, 0.5f), scene::AlphaMode::Blend}}));
    ASSERT_FALSE(hidden.images.empty());
    ASSERT_EQ(hidden.blend_order.size(), 1u);
    // Depth-tested against the opaque quad in front of it: not a bit changes.
    EXPECT_EQ(colour_at(hidden, "transparent.color"), colour_at(hidden, "forward.color"));
}

TEST_P(GltfBlendTest, TheTransparentPassFollowsTheLitPassInBothPipelines) {
    const scene::Scene scene = layered({{0.5f, glm::vec4(0.1f, 0.2f, 0.9f, 0.5f), scene::AlphaMode::Blend}});
    for (bool forward : {false, true}) {
        const GltfFrame frame = render(scene, forward);
        ASSERT_FALSE(frame.images.empty());
        const fg::Plan& plan = frame.plan;
        const std::string lit = forward ? "forward" : "deferred";
        std::vector<std::string> order;
        for (const fg::PlanPass& pass : plan.order) order.push_back(pass.name);
        // The memory order (the default) may run the shadow pass after the geometry; the lit
        // pass is followed by the transparent one and the post-processing, in this order.
        const std::vector<std::string> tail{lit, "transparent", "blur-h", "blur-v", "composite", "present"};
        ASSERT_GE(order.size(), tail.size());
        EXPECT_TRUE(std::equal(tail.begin(), tail.end(), order.end() - static_cast<std::ptrdiff_t>(tail.size())))
            << ::testing::PrintToString(order);
        EXPECT_EQ(order.size(), forward ? 7u : 8u) << ::testing::PrintToString(order);
        // In place: the lit colour, high pass and the opaque depth are the transparent pass's.
        EXPECT_EQ(plan.resource_of("transparent", "color"), plan.resource_of(lit, "color"));
        EXPECT_EQ(plan.resource_of("transparent", "high_pass"), plan.resource_of(lit, "high_pass"));
        EXPECT_EQ(plan.resource_of("transparent", "depth"), plan.resource_of(forward ? "forward" : "geometry", "depth"));
        EXPECT_EQ(plan.resource_of("composite", "color"), plan.resource_of(lit, "color"));
        EXPECT_EQ(frame.stats.textures, plan.textures.size());
        // Blended surfaces cast no shadow: the shadow map holds only the opaque quad.
        EXPECT_EQ(frame.blend_order.size(), 1u);
    }
}

TEST_P(GltfBlendTest, ScenesWithoutBlendedSurfacesHaveNoTransparentPass) {
    auto frame = render(layered({{0.5f, glm::vec4(0.1f, 0.2f, 0.9f, 1.0f), scene::AlphaMode::Opaque}}), false);
    ASSERT_FALSE(frame.images.empty());
    EXPECT_EQ(frame.plan.find_pass("transparent"), nullptr);
    EXPECT_EQ(frame.plan.order.size(), 7u);
    EXPECT_TRUE(frame.blend_order.empty());
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(GltfBlendTest);

}  // namespace loom::test

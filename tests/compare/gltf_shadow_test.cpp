// Shadows of glTF surfaces on each backend: masked (cut-out) surfaces cast the shadow of what
// their material keeps, through the masked shadow pass that draws into the standard pass's
// shadow map in place; blended surfaces cast none. Checked in the shadow maps themselves: the
// depth a texel holds says which surface the light sees first there.
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "gltf_render.hpp"
#include "loom_test/render_fixture.hpp"
#include "synthetic_scene.hpp"

namespace loom::test {
namespace {

// The surfaces are tilted towards the light: across the half texel between a point and the
// texel's centre the depth changes by about 0.0015. One unit apart along z is about 0.1.
constexpr double kTexelDepth = 0.004;

/// Where a world point lands in a shadow map, and its depth there.
struct LightSample {
    uint32_t x = 0, y = 0;
    double depth = 0.0;
};

LightSample in_light(const GltfFrame& frame, const glm::vec3& world, uint32_t map_size) {
    const glm::vec4 clip = frame.view.shadow.light_view_projection * glm::vec4(world, 1.0f);
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    return {static_cast<uint32_t>((ndc.x * 0.5f + 0.5f) * map_size), static_cast<uint32_t>((0.5f - ndc.y * 0.5f) * map_size),
            ndc.z};
}

/// A large opaque receiver at z = 0 and, 1 unit in front of it, a quad whose left half the
/// material cuts away (alpha 0 | 1 with `mode`).
scene::Scene cut_out_in_front(scene::AlphaMode mode) {
    SceneBuilder b;
    scene::Material receiver;
    receiver.metallic_factor = 0.0f;
    b.quad(b.material(receiver), glm::scale(glm::mat4(1.0f), glm::vec3(4.0f)));
    scene::Material m;
    m.metallic_factor = 0.0f;
    m.alpha_mode = mode;
    m.base_color_texture = scene::TextureRef{
        b.texture(image_of(2, 1, rhi::Format::RGBA8Unorm, {{255, 255, 255, 0}, {255, 255, 255, 255}}), nearest_sampler())};
    b.quad(b.material(m), glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 1.0f)));
    b.camera(6.0f);
    return b.build();
}

class GltfShadowTest : public RenderTest {};

TEST_P(GltfShadowTest, MaskedSurfacesCastTheShadowOfWhatTheirMaterialKeeps) {
    auto frame = render_gltf(device(), cut_out_in_front(scene::AlphaMode::Mask), false);
    ASSERT_TRUE(frame.ok()) << frame.error().to_string();
    const fg::Plan& plan = frame->plan;
    ASSERT_NE(plan.find_pass("masked-shadow"), nullptr);
    EXPECT_EQ(plan.resource_of("masked-shadow", "shadow_map"), plan.resource_of("shadow", "shadow_map"));
    EXPECT_EQ(plan.resource_of("deferred", "shadow_map"), plan.resource_of("shadow", "shadow_map"));

    const rhi::Image& opaque_only = frame->images.at("shadow.shadow_map");
    const rhi::Image& with_masked = frame->images.at("masked-shadow.shadow_map");
    const uint32_t size = with_masked.width;
    // The kept (right) half: the light sees it first. The cut (left) half: the receiver behind.
    const LightSample kept = in_light(*frame, {0.5f, 0.0f, 1.0f}, size);
    const LightSample cut = in_light(*frame, {-0.5f, 0.0f, 1.0f}, size);
    const LightSample receiver_behind_cut = in_light(*frame, {-0.5f, 0.0f, 0.0f}, size);
    EXPECT_NEAR(with_masked.load(kept.x, kept.y)[0], kept.depth, kTexelDepth);
    EXPECT_GT(with_masked.load(cut.x, cut.y)[0], cut.depth + 0.01) << "the cut-away half casts no shadow";
    EXPECT_GT(receiver_behind_cut.depth, cut.depth + 0.01);
    // Before the masked pass, the map held the receiver only.
    EXPECT_GT(opaque_only.load(kept.x, kept.y)[0], kept.depth + 0.01);
}

TEST_P(GltfShadowTest, BlendedSurfacesCastNoShadowAndOpaqueOnesCastTheirWholeShape) {
    for (scene::AlphaMode mode : {scene::AlphaMode::Blend, scene::AlphaMode::Opaque}) {
        auto frame = render_gltf(device(), cut_out_in_front(mode), false);
        ASSERT_TRUE(frame.ok()) << frame.error().to_string();
        EXPECT_EQ(frame->plan.find_pass("masked-shadow"), nullptr);
        const rhi::Image& map = frame->images.at("shadow.shadow_map");
        const LightSample kept = in_light(*frame, {0.5f, 0.0f, 1.0f}, map.width);
        const LightSample cut = in_light(*frame, {-0.5f, 0.0f, 1.0f}, map.width);
        const bool opaque = mode == scene::AlphaMode::Opaque;
        for (const LightSample& s : {kept, cut}) {
            if (opaque) {
                EXPECT_NEAR(map.load(s.x, s.y)[0], s.depth, kTexelDepth);
            } else {
                EXPECT_GT(map.load(s.x, s.y)[0], s.depth + 0.01);
            }
        }
    }
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(GltfShadowTest);

}  // namespace loom::test

// glTF materials and geometry through the G-buffer on each backend, on scenes built in code: a
// 2 x 2 quad facing a camera 3 units away (60° field of view, 64 x 64 pixels), so that the quad
// covers pixels 14..50 and each quarter of it lands on known pixels. The G-buffer holds what the
// "gltf-material" part computed (linear albedo, normal, metallic, roughness, emission) in half
// floats, so each value is checked against the texel it came from.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "gltf_render.hpp"
#include "loom_test/render_fixture.hpp"
#include "synthetic_scene.hpp"

namespace loom::test {
namespace {

// Pixels inside each quarter of the quad (away from the texel edge at the centre).
constexpr uint32_t kLeft = 22, kRight = 42, kTop = 22, kBottom = 42, kCentre = 32;
// Half floats hold about three decimal digits.
constexpr double kHalf = 2e-3;

glm::dvec4 at(const GltfFrame& frame, const std::string& image, uint32_t x, uint32_t y) {
    const auto v = frame.images.at(image).load(x, y);
    return {v[0], v[1], v[2], v[3]};
}

bool drawn(const GltfFrame& frame, uint32_t x, uint32_t y) {
    return glm::length(glm::dvec3(at(frame, "geometry.normal", x, y))) > 0.5;
}

scene::Material plain(const glm::vec4& base = glm::vec4(1.0f)) {
    scene::Material m;
    m.base_color_factor = base;
    m.metallic_factor = 0.0f;
    m.roughness_factor = 0.5f;
    return m;
}

class GltfMaterialTest : public RenderTest {
protected:
    GltfFrame render(const SceneBuilder& builder, bool forward = false) {
        auto frame = render_gltf(device(), builder.build(), forward);
        EXPECT_TRUE(frame.ok()) << frame.error().to_string();
        return frame.ok() ? std::move(*frame) : GltfFrame{};
    }
};

TEST_P(GltfMaterialTest, BaseColourTextureIsSampledUprightAndDecodedFromSrgb) {
    SceneBuilder b;
    scene::Material m = plain();
    m.base_color_texture = scene::TextureRef{b.texture(
        image_of(2, 2, rhi::Format::RGBA8Srgb, {{128, 0, 0, 255}, {0, 128, 0, 255}, {0, 0, 128, 255}, {255, 255, 255, 255}}),
        nearest_sampler())};
    b.quad(b.material(m));
    b.camera();
    const GltfFrame frame = render(b);
    ASSERT_FALSE(frame.images.empty());
    const double level = srgb_to_linear(128);  // 0.2158
    // uv (0,0) is the image's top-left texel: the quad's top-left quarter.
    const glm::dvec4 tl = at(frame, "geometry.albedo", kLeft, kTop);
    const glm::dvec4 tr = at(frame, "geometry.albedo", kRight, kTop);
    const glm::dvec4 bl = at(frame, "geometry.albedo", kLeft, kBottom);
    const glm::dvec4 br = at(frame, "geometry.albedo", kRight, kBottom);
    EXPECT_NEAR(tl.r, level, kHalf);
    EXPECT_NEAR(tl.g, 0.0, kHalf);
    EXPECT_NEAR(tr.g, level, kHalf);
    EXPECT_NEAR(tr.r, 0.0, kHalf);
    EXPECT_NEAR(bl.b, level, kHalf);
    EXPECT_NEAR(br.r, 1.0, kHalf);
    EXPECT_NEAR(br.b, 1.0, kHalf);
    // Outside the quad: nothing.
    EXPECT_FALSE(drawn(frame, 4, 4));
}

TEST_P(GltfMaterialTest, FactorsVertexColoursAndTheSecondUvSetMultiply) {
    SceneBuilder b;
    scene::Material m = plain(glm::vec4(0.5f, 1.0f, 1.0f, 1.0f));
    // On UV set 1, which the quad mirrors left to right.
    m.base_color_texture = scene::TextureRef{
        b.texture(image_of(2, 1, rhi::Format::RGBA8Srgb, {{255, 255, 255, 255}, {255, 0, 255, 255}}), nearest_sampler()), 1};
    b.quad(b.material(m), glm::mat4(1.0f), glm::vec4(1.0f, 1.0f, 0.25f, 1.0f));
    b.camera();
    const GltfFrame frame = render(b);
    ASSERT_FALSE(frame.images.empty());
    // Left half shows the right texel (magenta), times factor (0.5, 1, 1), times colour (1, 1, 0.25).
    const glm::dvec4 left = at(frame, "geometry.albedo", kLeft, kCentre);
    EXPECT_NEAR(left.r, 0.5, kHalf);
    EXPECT_NEAR(left.g, 0.0, kHalf);
    EXPECT_NEAR(left.b, 0.25, kHalf);
    const glm::dvec4 right = at(frame, "geometry.albedo", kRight, kCentre);
    EXPECT_NEAR(right.g, 1.0, kHalf);
}

// KHR_texture_transform: the 2x2 texture above, scaled by a half and moved half a texture to the
// right, shows its top-right texel (green) on the whole quad; rotated a quarter turn
// (counter-clockwise in UV space) about the origin and moved back, the top-left quarter of the
// quad samples what was the bottom-left texel (blue).
TEST_P(GltfMaterialTest, TextureTransformMovesTheCoordinates) {
    struct Case {
        scene::TextureTransform transform;
        std::array<int, 4> channels;  ///< the colour channel at full level in tl, tr, bl, br (3: white)
    };
    const double level = srgb_to_linear(128);
    const double half_turn = 1.5707963267948966;
    for (const Case& c : {Case{{{0.5f, 0.0f}, 0.0f, {0.5f, 0.5f}}, {1, 1, 1, 1}},
                          Case{{{0.0f, 1.0f}, static_cast<float>(half_turn), {1.0f, 1.0f}}, {2, 0, 3, 1}}}) {
        SCOPED_TRACE(testing::Message() << "rotation " << c.transform.rotation);
        SceneBuilder b;
        scene::Material m = plain();
        m.base_color_texture = scene::TextureRef{b.texture(image_of(2, 2, rhi::Format::RGBA8Srgb,
                                                                    {{128, 0, 0, 255}, {0, 128, 0, 255}, {0, 0, 128, 255}, {255, 255, 255, 255}}),
                                                           nearest_sampler()),
                                                 0, c.transform};
        b.quad(b.material(m));
        b.camera();
        const GltfFrame frame = render(b);
        ASSERT_FALSE(frame.images.empty());
        const std::array<std::pair<uint32_t, uint32_t>, 4> quarters = {{{kLeft, kTop}, {kRight, kTop}, {kLeft, kBottom}, {kRight, kBottom}}};
        for (std::size_t q = 0; q < 4; ++q) {
            const glm::dvec4 albedo = at(frame, "geometry.albedo", quarters[q].first, quarters[q].second);
            for (int ch = 0; ch < 3; ++ch) {
                const double expected = c.channels[q] == 3 ? 1.0 : (c.channels[q] == ch ? level : 0.0);
                EXPECT_NEAR(albedo[ch], expected, kHalf) << "quarter " << q << " channel " << ch;
            }
        }
    }
}

TEST_P(GltfMaterialTest, MetallicRoughnessOcclusionAndEmissiveTexturesFillTheGBuffer) {
    SceneBuilder b;
    scene::Material m = plain(glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
    m.metallic_factor = 1.0f;
    m.roughness_factor = 0.8f;
    m.metallic_roughness_texture =
        scene::TextureRef{b.texture(image_of(1, 1, rhi::Format::RGBA8Unorm, {{0, 128, 64, 255}}), nearest_sampler())};
    m.occlusion_texture =
        scene::TextureRef{b.texture(image_of(1, 1, rhi::Format::RGBA8Unorm, {{102, 0, 0, 255}}), nearest_sampler())};
    m.occlusion_strength = 0.5f;
    m.emissive_factor = glm::vec3(2.0f);
    m.emissive_texture =
        scene::TextureRef{b.texture(image_of(1, 1, rhi::Format::RGBA8Srgb, {{128, 128, 128, 255}}), nearest_sampler())};
    b.quad(b.material(m));
    b.camera();
    const GltfFrame frame = render(b);
    ASSERT_FALSE(frame.images.empty());
    const double metallic = 64.0 / 255.0, roughness = 0.8 * 128.0 / 255.0;
    // Occlusion 102/255 = 0.4 at half strength: 1 + 0.5 * (0.4 - 1) = 0.7 of the albedo.
    const double albedo = 0.5 * (1.0 + 0.5 * (102.0 / 255.0 - 1.0));
    const double emissive = 2.0 * srgb_to_linear(128);
    EXPECT_NEAR(at(frame, "geometry.position", kCentre, kCentre).a, metallic, kHalf);
    EXPECT_NEAR(at(frame, "geometry.normal", kCentre, kCentre).a, roughness, kHalf);
    const glm::dvec4 a = at(frame, "geometry.albedo", kCentre, kCentre);
    EXPECT_NEAR(a.r, albedo, kHalf);
    // The emission map holds the emitted radiance itself (HDR: 2 x the texture here).
    const glm::dvec4 e = at(frame, "geometry.emission", kCentre, kCentre);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(e[c], emissive, 2 * kHalf) << "channel " << c;
}

// Emission keeps its colour whatever the albedo: a black material glowing red and a white one
// glowing cyan (with an HDR strength, as KHR_materials_emissive_strength gives) come out of the
// G-buffer as they went in, and the deferred pipeline's lit colour equals the forward one's
// there (same lighting code; the G-buffer's half floats the only difference).
TEST_P(GltfMaterialTest, EmissionKeepsItsColourThroughTheGBuffer) {
    struct Case {
        glm::vec4 base;
        glm::vec3 emission;
    };
    for (const Case& c : {Case{{0.0f, 0.0f, 0.0f, 1.0f}, {3.0f, 0.0f, 0.0f}}, Case{{1.0f, 1.0f, 1.0f, 1.0f}, {0.0f, 1.5f, 1.5f}}}) {
        SCOPED_TRACE(testing::Message() << "emission " << c.emission.r << "," << c.emission.g << "," << c.emission.b);
        SceneBuilder b;
        scene::Material m = plain(c.base);
        m.emissive_factor = c.emission;
        b.quad(b.material(m));
        b.camera();
        const GltfFrame deferred = render(b);
        const GltfFrame forward = render(b, true);
        ASSERT_FALSE(deferred.images.empty());
        ASSERT_FALSE(forward.images.empty());
        const glm::dvec4 e = at(deferred, "geometry.emission", kCentre, kCentre);
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(e[ch], c.emission[ch], kHalf) << "channel " << ch;
        const glm::dvec4 lit_deferred = at(deferred, "deferred.color", kCentre, kCentre);
        const glm::dvec4 lit_forward = at(forward, "forward.color", kCentre, kCentre);
        for (int ch = 0; ch < 3; ++ch) {
            EXPECT_NEAR(lit_deferred[ch], lit_forward[ch], 4 * kHalf * std::max(1.0, lit_forward[ch])) << "channel " << ch;
        }
        // The red glow is red: its green and blue come only from the (black) surface's reflection.
        if (c.base.r == 0.0f) {
            EXPECT_GT(lit_deferred.r, 2.5);
            EXPECT_LT(lit_deferred.g, 0.5);
        }
    }
}

TEST_P(GltfMaterialTest, MaskDiscardsBelowTheCutoffAndOpaqueIgnoresAlpha) {
    for (scene::AlphaMode mode : {scene::AlphaMode::Mask, scene::AlphaMode::Opaque}) {
        SceneBuilder b;
        scene::Material m = plain();
        m.alpha_mode = mode;
        m.alpha_cutoff = 0.5f;
        m.base_color_texture = scene::TextureRef{
            b.texture(image_of(2, 1, rhi::Format::RGBA8Unorm, {{255, 255, 255, 100}, {255, 255, 255, 160}}), nearest_sampler())};
        b.quad(b.material(m));
        b.camera();
        const GltfFrame frame = render(b);
        ASSERT_FALSE(frame.images.empty());
        const bool mask = mode == scene::AlphaMode::Mask;
        EXPECT_EQ(drawn(frame, kLeft, kCentre), !mask) << (mask ? "mask" : "opaque");  // alpha 0.39 < 0.5
        EXPECT_TRUE(drawn(frame, kRight, kCentre)) << (mask ? "mask" : "opaque");     // alpha 0.63
    }
}

TEST_P(GltfMaterialTest, BackFacesAreCulledUnlessDoubleSidedAndThenLitFromTheSideTheyShow) {
    // The quad turned around: its front faces away from the camera.
    const glm::mat4 turned = glm::rotate(glm::mat4(1.0f), 3.14159265f, glm::vec3(0, 1, 0));
    for (bool double_sided : {false, true}) {
        SceneBuilder b;
        scene::Material m = plain();
        m.double_sided = double_sided;
        b.quad(b.material(m), turned);
        b.camera();
        const GltfFrame frame = render(b);
        ASSERT_FALSE(frame.images.empty());
        EXPECT_EQ(drawn(frame, kCentre, kCentre), double_sided);
        if (double_sided) {
            const glm::dvec3 n(at(frame, "geometry.normal", kCentre, kCentre));
            EXPECT_NEAR(n.z, 1.0, kHalf) << "the back face's normal turned towards the viewer";
        }
    }
}

TEST_P(GltfMaterialTest, MirroredTransformsKeepTheirFrontFacesAndMirrorTheirTextures) {
    SceneBuilder b;
    scene::Material m = plain();
    m.base_color_texture = scene::TextureRef{
        b.texture(image_of(2, 1, rhi::Format::RGBA8Unorm, {{255, 0, 0, 255}, {0, 0, 255, 255}}), nearest_sampler())};
    const uint32_t item = b.quad(b.material(m), glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f)));
    b.camera();
    ASSERT_TRUE(b.build().draw_items[item].flips_winding);
    const GltfFrame frame = render(b);
    ASSERT_FALSE(frame.images.empty());
    ASSERT_TRUE(drawn(frame, kLeft, kCentre)) << "a mirrored single-sided quad must not be culled";
    EXPECT_NEAR(at(frame, "geometry.normal", kLeft, kCentre).z, 1.0, kHalf);
    EXPECT_NEAR(at(frame, "geometry.albedo", kLeft, kCentre).b, 1.0, kHalf);  // the right texel, mirrored
    EXPECT_NEAR(at(frame, "geometry.albedo", kRight, kCentre).r, 1.0, kHalf);
}

TEST_P(GltfMaterialTest, NormalMapsTiltTheNormalAlongTheTangentFrameAlsoWhenMirrored) {
    // Tangent-space (0.71, 0.00, 0.71): tilted towards the tangent (+x), scaled by normal_scale.
    const std::array<uint8_t, 4> texel{218, 128, 218, 255};
    const glm::dvec3 map(texel[0] / 255.0 * 2 - 1, texel[1] / 255.0 * 2 - 1, texel[2] / 255.0 * 2 - 1);
    struct Case {
        float scale;
        bool mirrored;
    };
    for (const Case c : {Case{1.0f, false}, Case{0.5f, false}, Case{1.0f, true}}) {
        SceneBuilder b;
        scene::Material m = plain();
        m.normal_scale = c.scale;
        m.normal_texture = scene::TextureRef{b.texture(image_of(1, 1, rhi::Format::RGBA8Unorm, {texel}), nearest_sampler())};
        b.quad(b.material(m), c.mirrored ? glm::scale(glm::mat4(1.0f), glm::vec3(-1, 1, 1)) : glm::mat4(1.0f));
        b.camera();
        const GltfFrame frame = render(b);
        ASSERT_FALSE(frame.images.empty());
        // World tangent +x (-x when mirrored), bitangent +y, normal +z.
        glm::dvec3 expected = glm::normalize(glm::dvec3(map.x * c.scale * (c.mirrored ? -1 : 1), map.y * c.scale, map.z));
        const glm::dvec3 n(at(frame, "geometry.normal", kCentre, kCentre));
        EXPECT_NEAR(n.x, expected.x, kHalf) << "scale " << c.scale << (c.mirrored ? ", mirrored" : "");
        EXPECT_NEAR(n.y, expected.y, kHalf);
        EXPECT_NEAR(n.z, expected.z, kHalf);
    }
}

TEST_P(GltfMaterialTest, MipmapsAverageDistantTexturesInLinearLight) {
    // A 256 x 256 checkerboard of single black and white texels, seen from so far that a pixel
    // covers about 64 x 64 texels: every mip level above 0 is the linear mean 0.5 (sRGB 188).
    std::vector<std::array<uint8_t, 4>> texels;
    for (uint32_t y = 0; y < 256; ++y) {
        for (uint32_t x = 0; x < 256; ++x) {
            const uint8_t v = ((x + y) % 2) ? 255 : 0;
            texels.push_back({v, v, v, 255});
        }
    }
    rhi::SamplerDesc trilinear;
    trilinear.mipmap_filter = rhi::Filter::Linear;
    trilinear.address_u = trilinear.address_v = rhi::AddressMode::Repeat;
    SceneBuilder b;
    scene::Material m = plain();
    m.base_color_texture = scene::TextureRef{b.texture(image_of(256, 256, rhi::Format::RGBA8Srgb, texels), trilinear)};
    b.quad(b.material(m), glm::scale(glm::mat4(1.0f), glm::vec3(0.1f)));
    b.camera();
    const GltfFrame frame = render(b);
    ASSERT_FALSE(frame.images.empty());
    ASSERT_TRUE(drawn(frame, kCentre, kCentre));
    // Averaged in sRGB space it would be 0.21; without mipmaps 0 or 1.
    EXPECT_NEAR(at(frame, "geometry.albedo", kCentre, kCentre).r, srgb_to_linear(188), 0.01);
}

TEST_P(GltfMaterialTest, TheForwardPassEvaluatesTheSameMaterial) {
    // A masked, double-sided, normal-mapped quad seen from behind: forward and deferred light it
    // alike (up to the G-buffer's half floats).
    SceneBuilder b;
    scene::Material m = plain(glm::vec4(0.8f, 0.3f, 0.1f, 1.0f));
    m.double_sided = true;
    m.alpha_mode = scene::AlphaMode::Mask;
    m.base_color_texture = scene::TextureRef{
        b.texture(image_of(2, 1, rhi::Format::RGBA8Unorm, {{255, 255, 255, 0}, {255, 255, 255, 255}}), nearest_sampler())};
    m.normal_texture = scene::TextureRef{b.texture(image_of(1, 1, rhi::Format::RGBA8Unorm, {{200, 140, 220, 255}}), nearest_sampler())};
    b.quad(b.material(m), glm::rotate(glm::mat4(1.0f), 3.14159265f, glm::vec3(0, 1, 0)));
    b.camera();
    const GltfFrame deferred = render(b, false);
    const GltfFrame forward = render(b, true);
    ASSERT_FALSE(deferred.images.empty());
    ASSERT_FALSE(forward.images.empty());
    // Turned around, the texture's opaque right half shows on the left.
    const glm::dvec4 lit_deferred = at(deferred, "deferred.color", kLeft, kCentre);
    const glm::dvec4 lit_forward = at(forward, "forward.color", kLeft, kCentre);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(lit_forward[c], lit_deferred[c], 0.01 * std::max(1.0, lit_deferred[c])) << c;
    EXPECT_GT(lit_forward.r, lit_forward.b) << "the orange albedo, lit";
    // The masked half is background in both: the forward pass's clear colour, the sky.
    EXPECT_FALSE(drawn(deferred, kRight, kCentre));
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(GltfMaterialTest);

}  // namespace loom::test

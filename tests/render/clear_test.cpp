// Clears of colour and depth/stencil formats read back exactly, in loom's CPU layouts.
#include <cmath>
#include <cstring>

#include "loom_test/render_fixture.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

using rhi::Format;

class ClearTest : public RenderTest {};

struct ColorCase {
    Format format;
    std::array<double, 4> clear;
    std::array<double, 4> expected;  ///< as Image::load() returns it
};

// sRGB encoding (IEC 61966-2-1) of a linear value, as 8-bit level.
double srgb_level(double linear) {
    const double s = linear <= 0.0031308 ? linear * 12.92 : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
    return std::nearbyint(s * 255.0);
}

std::vector<ColorCase> color_cases() {
    const double f01 = static_cast<double>(0.1f);  // a float clear value reads back as the float
    return {
        {Format::RGBA8Unorm, {0.2, 0.4, 0.6, 1.0}, {51 / 255.0, 102 / 255.0, 153 / 255.0, 1.0}},
        // Clears of sRGB attachments encode the (linear) clear colour; alpha stays linear.
        // srgb(0.5) * 255 = 187.52, far enough from .5 that any correct encoder gives 188.
        {Format::RGBA8Srgb, {0.5, 0.0, 1.0, 0.25}, {srgb_level(0.5) / 255.0, 0.0, 1.0, 64 / 255.0}},
        {Format::RGBA16Float, {0.25, -2.5, 1024.0, 0.125}, {0.25, -2.5, 1024.0, 0.125}},
        {Format::RGBA32Float, {0.1, -7.75, 65536.5, 1.0}, {f01, -7.75, 65536.5, 1.0}},
        // Missing channels read as 0, missing alpha as 1.
        {Format::R32Uint, {4000000000.0, 0, 0, 0}, {4000000000.0, 0.0, 0.0, 1.0}},
        {Format::RGBA8Uint, {1, 2, 250, 255}, {1, 2, 250, 255}},
        {Format::RGBA8Sint, {-128, 127, -1, 0}, {-128, 127, -1, 0}},
        {Format::RG8Snorm, {-1.0, 64 / 127.0, 0, 0}, {-1.0, 64 / 127.0, 0.0, 1.0}},
        {Format::R11G11B10Float, {0.5, 2.0, 0.25, 0}, {0.5, 2.0, 0.25, 1.0}},
        {Format::RGB10A2Unorm, {0.0, 1.0, 512 / 1023.0, 1 / 3.0}, {0.0, 1.0, 512 / 1023.0, 1 / 3.0}},
    };
}

TEST_P(ClearTest, ColorFormatsReadBackExactly) {
    for (const ColorCase& c : color_cases()) {
        SCOPED_TRACE(std::string(rhi::format_name(c.format)));
        if (!device().capabilities().format(c.format).color_attachment) {
            ADD_FAILURE() << "format not renderable on this device";
            continue;
        }
        LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "clear target", c.format, 5, 3));
        LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
            list.begin_render_pass(clear_pass("clear", target, c.clear));
            list.end_render_pass();
        }));
        LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
        ASSERT_EQ(image.format, c.format);
        ASSERT_EQ(image.width, 5u);
        ASSERT_EQ(image.height, 3u);
        for (uint32_t y = 0; y < image.height; ++y) {
            for (uint32_t x = 0; x < image.width; ++x) {
                const auto v = image.load(x, y);
                for (std::size_t i = 0; i < 4; ++i) {
                    ASSERT_EQ(v[i], c.expected[i]) << "channel " << i << " at " << x << "," << y;
                }
            }
        }
        LOOM_ASSERT_OK(device().destroy(target));
    }
}

TEST_P(ClearTest, MultisampledColourTargetsReadBackResolved) {
    // read_texture resolves a multisampled colour texture on every backend (a blit on GL, a
    // resolve on Vulkan); cleared samples are all equal, so every texel is the clear value.
    const ColorCase cases[] = {
        {Format::RGBA8Unorm, {0.2, 0.4, 0.6, 1.0}, {51 / 255.0, 102 / 255.0, 153 / 255.0, 1.0}},
        {Format::RGBA16Float, {0.25, -2.5, 1024.0, 0.125}, {0.25, -2.5, 1024.0, 0.125}},
        {Format::RGBA8Uint, {1, 2, 250, 255}, {1, 2, 250, 255}},
    };
    int tested = 0;
    for (const ColorCase& c : cases) {
        SCOPED_TRACE(std::string(rhi::format_name(c.format)));
        if ((device().capabilities().format(c.format).sample_counts & 4u) == 0) continue;
        rhi::TextureDesc desc;
        desc.name = "multisampled target";
        desc.format = c.format;
        desc.width = 6;
        desc.height = 2;
        desc.samples = 4;
        desc.usage = rhi::TextureUsage::ColorAttachment;
        LOOM_ASSIGN_OR_FAIL(auto target, device().create_texture(desc));
        const uint64_t textures_before = device().resource_stats().textures;
        LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
            list.begin_render_pass(clear_pass("clear", target, c.clear));
            list.end_render_pass();
        }));
        for (int read = 0; read < 2; ++read) {  // the source is left usable: a second read gives the same
            LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
            ASSERT_EQ(image.format, c.format);
            ASSERT_EQ(image.width, 6u);
            ASSERT_EQ(image.height, 2u);
            for (uint32_t y = 0; y < image.height; ++y) {
                for (uint32_t x = 0; x < image.width; ++x) ASSERT_EQ(image.load(x, y), c.expected) << "texel " << x << "," << y;
            }
        }
        LOOM_ASSERT_OK(device().wait_idle());
        EXPECT_EQ(device().resource_stats().textures, textures_before) << "the resolve's temporary texture is gone";
        LOOM_ASSERT_OK(device().destroy(target));
        ++tested;
    }
    if (tested == 0) GTEST_SKIP() << "no format with 4 samples on this device";
}

struct DepthCase {
    Format format;
    float depth;
    uint32_t stencil;
    double expected_depth;  ///< as Image::load()[0] returns it
};

TEST_P(ClearTest, DepthFormatsReadBackExactly) {
    // Unorm depth is round(d * (2^n - 1)); the clear values are chosen 0.25 away from a
    // rounding tie so that the level is unambiguous.
    const std::vector<DepthCase> cases = {
        {Format::Depth32F, 0.375f, 0, 0.375},
        {Format::Depth16, 0.25f, 0, 16384 / 65535.0},
        {Format::Depth24, 0.25f, 0, 4194304 / 16777215.0},
        {Format::Depth24Stencil8, 0.75f, 0x5A, 12582911 / 16777215.0},
        {Format::Depth32FStencil8, 0.625f, 200, 0.625},
    };
    for (const DepthCase& c : cases) {
        SCOPED_TRACE(std::string(rhi::format_name(c.format)));
        LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "depth target", c.format, 4, 2));
        rhi::RenderPassDesc pass;
        pass.label = "depth clear";
        rhi::DepthAttachment d;
        d.texture = target;
        d.clear_depth = c.depth;
        d.stencil_load = rhi::LoadOp::Clear;
        d.stencil_store = rhi::StoreOp::Store;
        d.clear_stencil = c.stencil;
        pass.depth = d;
        LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
            list.begin_render_pass(pass);
            list.end_render_pass();
        }));
        LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
        ASSERT_EQ(image.format, c.format);
        const bool stencil = rhi::format_info(c.format).has_stencil();
        for (uint32_t y = 0; y < image.height; ++y) {
            for (uint32_t x = 0; x < image.width; ++x) {
                const auto v = image.load(x, y);
                ASSERT_EQ(v[0], c.expected_depth) << "depth at " << x << "," << y;
                if (stencil) {
                    ASSERT_EQ(v[1], c.stencil) << "stencil at " << x << "," << y;
                }
            }
        }
        if (c.format == Format::Depth24Stencil8) {
            // loom's layout: depth in the low 24 bits, stencil in the high 8.
            uint32_t word = 0;
            std::memcpy(&word, image.texel(0, 0).data(), 4);
            EXPECT_EQ(word, 12582911u | (0x5Au << 24));
        }
        if (c.format == Format::Depth32FStencil8) {
            // Float depth, then the stencil byte at offset 4, padding zero.
            EXPECT_EQ(static_cast<uint8_t>(image.texel(0, 0)[4]), 200);
            EXPECT_EQ(static_cast<uint8_t>(image.texel(0, 0)[5]), 0);
        }
        LOOM_ASSERT_OK(device().destroy(target));
    }
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(ClearTest);

}  // namespace loom::test

#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "loom/rhi/image.hpp"
#include "loom_test/test_support.hpp"

using namespace loom;
using namespace loom::rhi;

TEST(Image, LoadStoreRoundTripsRepresentableValuesOfEveryFormat) {
    for (Format f : all_formats()) {
        const FormatInfo& info = format_info(f);
        Image image(2, 1, f);
        std::array<double, 4> value{};
        if (info.is_depth_stencil()) {
            value = {info.has_depth() ? 0.5 : 0.0, info.has_stencil() ? 17.0 : 0.0, 0.0, 0.0};
        } else {
            switch (info.color_kind()) {
                case ChannelKind::Unorm: value = {1.0, 0.0, 1.0, 1.0}; break;
                case ChannelKind::Snorm: value = {-1.0, 1.0, 0.0, 1.0}; break;
                case ChannelKind::Uint: value = {200.0, 3.0, 0.0, 1.0}; break;
                case ChannelKind::Sint: value = {-100.0, 3.0, 0.0, 1.0}; break;
                case ChannelKind::Float: value = {0.5, 2.0, 0.25, 1.0}; break;
                default: break;
            }
            for (std::size_t i = info.channel_count(); i < 4; ++i) value[i] = (i == 3) ? 1.0 : 0.0;
        }
        image.store(1, 0, value);
        const auto back = image.load(1, 0);
        // 0.5 depth is not a unorm level: allow half a level there, exact elsewhere.
        const double depth_tolerance = info.features.depth.kind == ChannelKind::Unorm
                                           ? 0.5 / (std::ldexp(1.0, info.features.depth.bits) - 1.0)
                                           : 1e-9;
        for (std::size_t i = 0; i < 4; ++i) {
            if (info.is_depth_stencil() && i >= 2) continue;
            EXPECT_NEAR(back[i], value[i], i == 0 && info.has_depth() ? depth_tolerance : 1e-9)
                << format_name(f) << " channel " << i;
        }
        // The untouched texel stays zero (or the missing-channel defaults).
        const auto zero = image.load(0, 0);
        EXPECT_EQ(zero[0], 0.0) << format_name(f);
    }
}

TEST(Image, HalfFloatsRoundToNearestEven) {
    Image image(1, 1, Format::R16Float);
    image.store(0, 0, {1.0 + 1.0 / 2048.0, 0, 0, 0});  // exactly half-way between 1 and next half
    EXPECT_EQ(image.load(0, 0)[0], 1.0);
    image.store(0, 0, {65504.0, 0, 0, 0});
    EXPECT_EQ(image.load(0, 0)[0], 65504.0);
    image.store(0, 0, {1e6, 0, 0, 0});
    EXPECT_TRUE(std::isinf(image.load(0, 0)[0]));
}

TEST(Image, Bgra8StoresBlueFirstInMemory) {
    Image image(1, 1, Format::BGRA8Unorm);
    image.store(0, 0, {1.0, 0.0, 0.0, 1.0});  // red
    EXPECT_EQ(static_cast<uint8_t>(image.pixels[0]), 0);
    EXPECT_EQ(static_cast<uint8_t>(image.pixels[2]), 255);
    EXPECT_EQ(image.load(0, 0)[0], 1.0);
}

TEST(Image, PackedFormatsDecodeKnownWords) {
    Image rgb10a2(1, 1, Format::RGB10A2Unorm);
    const uint32_t word = 1023u | (0u << 10) | (512u << 20) | (3u << 30);
    std::memcpy(rgb10a2.pixels.data(), &word, 4);
    const auto v = rgb10a2.load(0, 0);
    EXPECT_EQ(v[0], 1.0);
    EXPECT_EQ(v[1], 0.0);
    EXPECT_NEAR(v[2], 512.0 / 1023.0, 1e-12);
    EXPECT_EQ(v[3], 1.0);

    Image e5(1, 1, Format::RGB9E5Float);
    e5.store(0, 0, {1.0, 0.5, 0.0, 0.0});
    const auto w = e5.load(0, 0);
    EXPECT_EQ(w[0], 1.0);
    EXPECT_EQ(w[1], 0.5);
    EXPECT_EQ(w[2], 0.0);

    Image r11(1, 1, Format::R11G11B10Float);
    r11.store(0, 0, {1.0, 0.5, 2.0, 0.0});
    uint32_t bits;
    std::memcpy(&bits, r11.pixels.data(), 4);
    EXPECT_EQ(bits & 0x7FFu, 15u << 6);  // 1.0: exponent 15, mantissa 0
    const auto r = r11.load(0, 0);
    EXPECT_EQ(r[0], 1.0);
    EXPECT_EQ(r[1], 0.5);
    EXPECT_EQ(r[2], 2.0);
}

TEST(ImageCompare, IdenticalImagesAreEqualWithInfinitePsnr) {
    Image a(4, 4, Format::RGBA8Unorm);
    a.store(1, 2, {0.5, 0.25, 1.0, 1.0});
    auto cmp = compare_images(a, a);
    ASSERT_TRUE(cmp.ok());
    EXPECT_TRUE(cmp->equal());
    EXPECT_EQ(cmp->max_channel_diff, 0.0);
    EXPECT_TRUE(std::isinf(cmp->psnr));
    EXPECT_EQ(cmp->pixel_count, 16u);
}

TEST(ImageCompare, CountsPixelsAboveThresholdInLevels) {
    Image a(4, 1, Format::RGBA8Unorm);
    Image b = a;
    b.texel(0, 0)[0] = std::byte{1};   // 1 level
    b.texel(1, 0)[1] = std::byte{5};   // 5 levels
    b.texel(2, 0)[3] = std::byte{200}; // alpha
    auto exact = compare_images(a, b);
    ASSERT_TRUE(exact.ok());
    EXPECT_EQ(exact->pixels_above_threshold, 3u);
    EXPECT_EQ(exact->max_channel_diff, 200.0);
    auto loose = compare_images(a, b, {.threshold = 5.0});
    EXPECT_EQ(loose->pixels_above_threshold, 1u);
    // PSNR = 10 log10(1 / mse), mse over the 16 channel samples of normalised differences.
    const double mse = ((1.0 / 255) * (1.0 / 255) + (5.0 / 255) * (5.0 / 255) + (200.0 / 255) * (200.0 / 255)) / 16.0;
    EXPECT_NEAR(exact->psnr, 10.0 * std::log10(1.0 / mse), 1e-9);
    ASSERT_TRUE(exact->heatmap.has_value());
    EXPECT_EQ(exact->heatmap->load(3, 0)[0], 0.0);  // equal pixel is black
    EXPECT_GT(exact->heatmap->load(2, 0)[0], 0.9);  // largest difference is bright
    EXPECT_GT(exact->heatmap->load(0, 0)[0], 0.3);  // any difference above threshold is visible
}

TEST(ImageCompare, FloatImagesCompareInValues) {
    Image a(2, 1, Format::RGBA32Float);
    Image b = a;
    b.store(1, 0, {0.0, 0.001, 0.0, 1.0});
    a.store(1, 0, {0.0, 0.0, 0.0, 1.0});
    auto cmp = compare_images(a, b, {.threshold = 0.01});
    ASSERT_TRUE(cmp.ok());
    EXPECT_NEAR(cmp->max_channel_diff, 0.001, 1e-9);
    EXPECT_TRUE(cmp->equal());
}

TEST(ImageCompare, SizeOrFormatMismatchIsAnError) {
    auto size = compare_images(Image(2, 2, Format::RGBA8Unorm), Image(2, 3, Format::RGBA8Unorm));
    ASSERT_FALSE(size.ok());
    EXPECT_NE(size.error().message.find("2x2 vs 2x3"), std::string::npos);
    auto format = compare_images(Image(2, 2, Format::RGBA8Unorm), Image(2, 2, Format::R8Unorm));
    ASSERT_FALSE(format.ok());
    EXPECT_NE(format.error().message.find("RGBA8Unorm vs R8Unorm"), std::string::npos);
}

TEST(ImagePng, DepthImagesAreNormalisedForDisplay) {
    Image depth(3, 1, Format::Depth32F);
    depth.store(0, 0, {0.2, 0, 0, 0});
    depth.store(1, 0, {0.4, 0, 0, 0});
    depth.store(2, 0, {1.0, 0, 0, 0});  // far plane stays white, outside the range
    const Image shown = to_rgba8(depth);
    EXPECT_EQ(shown.load(0, 0)[0], 0.0);
    EXPECT_EQ(shown.load(1, 0)[0], 1.0);
    EXPECT_EQ(shown.load(2, 0)[0], 1.0);
}

// loom::scene's CPU mip chains: sizes, box filtering with rounding, sRGB averaged in linear light.
#include <array>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "loom/scene/mip_chain.hpp"

namespace loom::test {
namespace {

using scene::mip_chain;
using scene::mip_level_count;

// An image whose texels, row by row, are `texels` (four bytes each).
rhi::Image image_of(uint32_t width, uint32_t height, rhi::Format format, const std::vector<std::array<uint8_t, 4>>& texels) {
    rhi::Image image(width, height, format);
    for (uint32_t i = 0; i < texels.size(); ++i) std::memcpy(image.texel(i % width, i / width).data(), texels[i].data(), 4);
    return image;
}

TEST(MipChain, HalvesDownToOneTexelRoundingOddSizesDown) {
    EXPECT_EQ(mip_level_count(1, 1), 1u);
    EXPECT_EQ(mip_level_count(256, 256), 9u);
    EXPECT_EQ(mip_level_count(5, 3), 3u);  // 5x3, 2x1, 1x1
    EXPECT_EQ(mip_level_count(1, 1024), 11u);
    const auto levels = mip_chain(rhi::Image(5, 3, rhi::Format::RGBA8Unorm));
    ASSERT_EQ(levels.size(), 3u);
    EXPECT_EQ(levels[1].width, 2u);
    EXPECT_EQ(levels[1].height, 1u);
    EXPECT_EQ(levels[2].width, 1u);
    EXPECT_EQ(levels[2].height, 1u);
}

TEST(MipChain, AveragesTwoByTwoBlocksWithRounding) {
    const rhi::Image image = image_of(4, 2, rhi::Format::RGBA8Unorm,
                                      {{0, 10, 255, 255}, {1, 20, 255, 255}, {100, 0, 0, 0}, {200, 0, 0, 0},
                                       {2, 30, 255, 255}, {4, 41, 255, 255}, {50, 0, 0, 0}, {51, 0, 0, 2}});
    const auto levels = mip_chain(image);
    ASSERT_EQ(levels.size(), 3u);
    EXPECT_EQ(levels[0].pixels, image.pixels);
    const auto texel = [](const rhi::Image& i, uint32_t x) {
        std::array<int, 4> out{};
        for (int c = 0; c < 4; ++c) out[c] = std::to_integer<int>(i.texel(x, 0)[c]);
        return out;
    };
    EXPECT_EQ(texel(levels[1], 0), (std::array<int, 4>{2, 25, 255, 255}));  // (0+1+2+4)/4 = 1.75 -> 2, 101/4 -> 25
    EXPECT_EQ(texel(levels[1], 1), (std::array<int, 4>{100, 0, 0, 1}));     // 401/4 = 100.25, 2/4 = 0.5 -> 1
}

TEST(MipChain, AveragesSrgbImagesInLinearLight) {
    const auto levels = mip_chain(image_of(2, 1, rhi::Format::RGBA8Srgb, {{0, 0, 0, 0}, {255, 255, 255, 255}}));
    ASSERT_EQ(levels.size(), 2u);
    EXPECT_EQ(levels[1].format, rhi::Format::RGBA8Srgb);
    // Linear 0.5 is sRGB 188; averaged as stored it would be 128. Alpha is linear: 128.
    EXPECT_EQ(std::to_integer<int>(levels[1].texel(0, 0)[0]), 188);
    EXPECT_EQ(std::to_integer<int>(levels[1].texel(0, 0)[3]), 128);
}

}  // namespace
}  // namespace loom::test

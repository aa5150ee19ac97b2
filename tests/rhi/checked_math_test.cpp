#include <cstdint>
#include <limits>

#include <gtest/gtest.h>

#include "loom/rhi/checked_math.hpp"

namespace checked = loom::checked;

TEST(CheckedMath, AddAndMultiplyReportOverflow) {
    constexpr uint64_t max = std::numeric_limits<uint64_t>::max();
    EXPECT_EQ(checked::add<uint64_t>(max - 1, 1), max);
    EXPECT_EQ(checked::add<uint64_t>(max, 1), std::nullopt);
    EXPECT_EQ(checked::mul<uint32_t>(65536, 65535), 65536u * 65535u);
    EXPECT_EQ(checked::mul<uint32_t>(65536, 65536), std::nullopt);
}

TEST(CheckedMath, ProductOfATextureThatWrapsTo0IsAnOverflow) {
    // 2^30 x 2^30 texels of 16 bytes: 2^64 bytes, which wraps to exactly 0 in 64 bits.
    EXPECT_EQ(checked::product({1ull << 30, 1ull << 30, 16}), std::nullopt);
    EXPECT_EQ(checked::product({1920, 1080, 8}), 1920ull * 1080 * 8);
    EXPECT_EQ(checked::product({}), 1u);
}

TEST(CheckedMath, AlignUp) {
    EXPECT_EQ(checked::align_up(0, 256), 0u);
    EXPECT_EQ(checked::align_up(1, 256), 256u);
    EXPECT_EQ(checked::align_up(512, 256), 512u);
    EXPECT_EQ(checked::align_up(std::numeric_limits<uint64_t>::max() - 3, 256), std::nullopt);
    EXPECT_EQ(checked::align_up(5, 0), std::nullopt);
}

TEST(CheckedMath, DoubleToIntegerRefusesWhatDoesNotFit) {
    EXPECT_EQ(checked::to_integer<uint32_t>(5368709120.0), std::nullopt);  // 5 x 2^30
    EXPECT_EQ(checked::to_integer<uint32_t>(4294967295.0), 4294967295u);
    EXPECT_EQ(checked::to_integer<uint32_t>(4294967296.0), std::nullopt);
    EXPECT_EQ(checked::to_integer<uint32_t>(-1.0), std::nullopt);
    EXPECT_EQ(checked::to_integer<uint32_t>(std::numeric_limits<double>::infinity()), std::nullopt);
    EXPECT_EQ(checked::to_integer<uint32_t>(std::numeric_limits<double>::quiet_NaN()), std::nullopt);
    EXPECT_EQ(checked::to_integer<int32_t>(-2147483648.0), std::numeric_limits<int32_t>::min());
    EXPECT_EQ(checked::to_integer<int32_t>(2147483648.0), std::nullopt);
}

TEST(CheckedMath, Narrow) {
    EXPECT_EQ(checked::narrow<uint32_t>(uint64_t{1} << 34), std::nullopt);
    EXPECT_EQ(checked::narrow<uint32_t>(int64_t{-1}), std::nullopt);
    EXPECT_EQ(checked::narrow<uint32_t>(uint64_t{7}), 7u);
}

TEST(CheckedMath, RangeFitsWithoutWrapping) {
    EXPECT_TRUE(checked::range_fits(0, 16, 16));
    EXPECT_TRUE(checked::range_fits(16, 0, 16));
    EXPECT_FALSE(checked::range_fits(0, 17, 16));
    EXPECT_FALSE(checked::range_fits(17, 0, 16));
    // UINT64_MAX - 3 + 8 wraps to 4, which a naive "offset + size > capacity" would accept.
    EXPECT_FALSE(checked::range_fits(UINT64_MAX - 3, 8, 16));
    EXPECT_TRUE(checked::range_fits(UINT64_MAX - 8, 8, UINT64_MAX));
}

#include <set>

#include <gtest/gtest.h>

#include "loom/rhi/format.hpp"

using namespace loom::rhi;

TEST(Format, EveryFormatRoundTripsThroughItsFeatures) {
    for (Format f : all_formats()) {
        const FormatInfo& info = format_info(f);
        EXPECT_EQ(info.format, f);
        auto back = format_from_features(info.features);
        ASSERT_TRUE(back.has_value()) << info.name;
        EXPECT_EQ(*back, f) << info.name;
    }
}

TEST(Format, EveryFormatRoundTripsThroughItsName) {
    std::set<std::string_view> names;
    for (Format f : all_formats()) {
        EXPECT_TRUE(names.insert(format_name(f)).second) << "duplicate name " << format_name(f);
        EXPECT_EQ(parse_format(format_name(f)), f);
    }
    EXPECT_FALSE(parse_format("RGBA8").has_value());
    EXPECT_FALSE(parse_format("rgba8unorm").has_value());
}

TEST(Format, FeaturesAreDistinctPerFormat) {
    const auto formats = all_formats();
    for (std::size_t i = 0; i < formats.size(); ++i) {
        for (std::size_t j = i + 1; j < formats.size(); ++j) {
            EXPECT_FALSE(format_info(formats[i]).features == format_info(formats[j]).features)
                << format_name(formats[i]) << " and " << format_name(formats[j]);
        }
    }
}

TEST(Format, UnknownFeatureSetHasNoFormat) {
    FormatFeatures rgb16f{};
    rgb16f.color = {Channel{16, ChannelKind::Float}, Channel{16, ChannelKind::Float}, Channel{16, ChannelKind::Float}, Channel{}};
    EXPECT_FALSE(format_from_features(rgb16f).has_value());
}

TEST(Format, DestructuredFeaturesOfRepresentativeFormats) {
    const FormatInfo& rgba16f = format_info(Format::RGBA16Float);
    EXPECT_EQ(rgba16f.bytes_per_texel, 8u);
    EXPECT_EQ(rgba16f.channel_count(), 4u);
    for (const Channel& c : rgba16f.features.color) EXPECT_EQ(c, (Channel{16, ChannelKind::Float}));
    EXPECT_FALSE(rgba16f.is_depth_stencil());

    const FormatInfo& r11 = format_info(Format::R11G11B10Float);
    EXPECT_EQ(r11.features.color[0].bits, 11);
    EXPECT_EQ(r11.features.color[1].bits, 11);
    EXPECT_EQ(r11.features.color[2].bits, 10);
    EXPECT_FALSE(r11.features.color[3].present());
    EXPECT_EQ(r11.bytes_per_texel, 4u);

    const FormatInfo& e5 = format_info(Format::RGB9E5Float);
    EXPECT_EQ(e5.features.shared_exponent_bits, 5);
    EXPECT_EQ(e5.features.color[0].bits, 9);

    const FormatInfo& srgb = format_info(Format::RGBA8Srgb);
    EXPECT_TRUE(srgb.features.srgb);
    EXPECT_FALSE(format_info(Format::RGBA8Unorm).features.srgb);
    EXPECT_TRUE(format_info(Format::BGRA8Unorm).features.bgra);

    const FormatInfo& d24s8 = format_info(Format::Depth24Stencil8);
    EXPECT_TRUE(d24s8.has_depth());
    EXPECT_TRUE(d24s8.has_stencil());
    EXPECT_EQ(d24s8.features.depth, (Channel{24, ChannelKind::Unorm}));
    EXPECT_EQ(d24s8.features.stencil_bits, 8);
    EXPECT_EQ(d24s8.channel_count(), 0u);

    const FormatInfo& d32f = format_info(Format::Depth32F);
    EXPECT_EQ(d32f.features.depth, (Channel{32, ChannelKind::Float}));
    EXPECT_FALSE(d32f.has_stencil());

    const FormatInfo& s8 = format_info(Format::Stencil8);
    EXPECT_FALSE(s8.has_depth());
    EXPECT_TRUE(s8.has_stencil());

    EXPECT_TRUE(format_info(Format::RGBA8Uint).is_integer());
    EXPECT_FALSE(format_info(Format::RGBA8Snorm).is_integer());
    EXPECT_EQ(format_info(Format::RG8Snorm).color_kind(), ChannelKind::Snorm);
}

TEST(Format, UndefinedIsNeitherColourNorDepth) {
    const FormatInfo& u = format_info(Format::Undefined);
    EXPECT_FALSE(u.is_color());
    EXPECT_FALSE(u.is_depth_stencil());
    EXPECT_EQ(u.bytes_per_texel, 0u);
    EXPECT_EQ(all_formats().size(), kFormatCount - 1);
}

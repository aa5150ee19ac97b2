// The join of §6.1 case by case, its extension to every property, and the resolution of a
// joined spec to an rhi::Format.
#include <gtest/gtest.h>

#include "loom/framegraph/join.hpp"
#include "loom/framegraph/resolved_spec.hpp"

namespace loom::fg {
namespace {

using rhi::ChannelKind;
using rhi::Format;
using rhi::TextureUsage;

JoinContext named(std::optional<Extent2D> frame = std::nullopt) {
    JoinContext context;
    context.frame = frame;
    context.a_name = "geometry.albedo";
    context.b_name = "deferred.albedo";
    return context;
}

// The format a join of two formats resolves to.
Format joined_format(const TextureSpec& a, const TextureSpec& b) {
    auto joined = join(a, b, named());
    EXPECT_TRUE(joined.ok()) << joined.error().to_string();
    if (!joined) return Format::Undefined;
    auto resolved = resolve_format(joined->format, "test");
    EXPECT_TRUE(resolved.ok()) << resolved.error().to_string();
    return resolved.ok() ? resolved->format : Format::Undefined;
}

// The error message of a join that must fail with ErrorCode::Join.
std::string join_failure(const TextureSpec& a, const TextureSpec& b, std::optional<Extent2D> frame = std::nullopt) {
    auto joined = join(a, b, named(frame));
    EXPECT_FALSE(joined.ok());
    if (joined.ok()) return {};
    EXPECT_EQ(joined.error().code, ErrorCode::Join);
    // Every failure names both ports.
    EXPECT_NE(joined.error().message.find("geometry.albedo"), std::string::npos) << joined.error().message;
    EXPECT_NE(joined.error().message.find("deferred.albedo"), std::string::npos) << joined.error().message;
    return joined.error().message;
}

TextureSpec of(Format f) { return TextureSpec::of(f); }

// ---- format: the rules of §6.1 -------------------------------------------------------------

TEST(JoinFormat, EqualFormatsJoinToThemselves) {
    for (Format f : rhi::all_formats()) EXPECT_EQ(joined_format(of(f), of(f)), f) << rhi::format_name(f);
}

TEST(JoinFormat, FeatureFlagsMustMatch) {
    EXPECT_NE(join_failure(of(Format::RGBA8Unorm), of(Format::RGBA8Srgb)).find("sRGB linear vs srgb"), std::string::npos);
    EXPECT_NE(join_failure(of(Format::RGBA8Unorm), of(Format::BGRA8Unorm)).find("memory order rgba vs bgra"),
              std::string::npos);
    rhi::FormatFeatures compressed = rhi::format_info(Format::RGBA8Unorm).features;
    compressed.compressed = true;
    EXPECT_NE(join_failure(of(Format::RGBA8Unorm), TextureSpec{}.with_features(compressed)).find("compression"),
              std::string::npos);
}

TEST(JoinFormat, SharingMustMatch) {
    const std::string message = join_failure(of(Format::RGB9E5Float), of(Format::R11G11B10Float));
    EXPECT_NE(message.find("shared exponent 5 bits vs 0 bits"), std::string::npos) << message;
    EXPECT_NE(message.find("RGB9E5Float vs R11G11B10Float"), std::string::npos) << message;
}

TEST(JoinFormat, ChannelKindsMustMatch) {
    const std::string message = join_failure(of(Format::RGBA16Float), of(Format::RGBA16Unorm));
    EXPECT_NE(message.find("channel R kind 16 float vs 16 unorm"), std::string::npos) << message;
    EXPECT_FALSE(joinable(of(Format::R32Uint), of(Format::R32Sint)));
    EXPECT_FALSE(joinable(of(Format::RG8Snorm), of(Format::RG8Unorm)));
}

TEST(JoinFormat, BitsTakeTheMaximumPerChannel) {
    EXPECT_EQ(joined_format(of(Format::R8Unorm), of(Format::RGBA16Unorm)), Format::RGBA16Unorm);
    EXPECT_EQ(joined_format(of(Format::R11G11B10Float), of(Format::RGBA16Float)), Format::RGBA16Float);
    EXPECT_EQ(joined_format(of(Format::R16Float), of(Format::RG32Float)), Format::RG32Float);
    // R10 G10 B10 A8 has no enum value: the smallest format covering it is RGBA16Unorm.
    auto joined = join(of(Format::RGBA8Unorm), of(Format::RGB10A2Unorm));
    ASSERT_TRUE(joined.ok());
    EXPECT_EQ(joined->format->color[0], (rhi::Channel{10, ChannelKind::Unorm}));
    EXPECT_EQ(joined->format->color[3], (rhi::Channel{8, ChannelKind::Unorm}));
    auto resolved = resolve_format(joined->format, "test");
    ASSERT_TRUE(resolved.ok());
    EXPECT_EQ(resolved->format, Format::RGBA16Unorm);
    EXPECT_EQ(resolved->match, FormatMatch::Covering);
}

TEST(JoinFormat, AbsentChannelsStayAbsent) {
    auto joined = join(of(Format::R16Float), TextureSpec::color(1, 8, ChannelKind::Float));
    ASSERT_TRUE(joined.ok());
    EXPECT_EQ(*joined->format, rhi::format_info(Format::R16Float).features);
    EXPECT_FALSE(joined->format->color[1].present());
    // A partial constraint is met by a richer format.
    EXPECT_EQ(joined_format(TextureSpec::color(3, 16, ChannelKind::Float), of(Format::RGBA16Float)), Format::RGBA16Float);
    EXPECT_EQ(joined_format(TextureSpec::color(2, 8, ChannelKind::Unorm), of(Format::RG16Unorm)), Format::RG16Unorm);
}

TEST(JoinFormat, DepthDoesNotJoinColour) {
    const std::string message = join_failure(of(Format::Depth32F), of(Format::RGBA8Unorm));
    EXPECT_NE(message.find("depth/stencil and colour"), std::string::npos) << message;
    EXPECT_FALSE(joinable(of(Format::Stencil8), of(Format::R8Uint)));
}

TEST(JoinFormat, DepthAndStencilJoinSeparately) {
    EXPECT_EQ(joined_format(of(Format::Depth16), of(Format::Depth24)), Format::Depth24);
    EXPECT_EQ(joined_format(of(Format::Depth24), of(Format::Stencil8)), Format::Depth24Stencil8);
    EXPECT_EQ(joined_format(of(Format::Depth32F), of(Format::Stencil8)), Format::Depth32FStencil8);
    EXPECT_EQ(joined_format(of(Format::Depth24Stencil8), of(Format::Depth16)), Format::Depth24Stencil8);
    EXPECT_EQ(joined_format(of(Format::Stencil8), of(Format::Depth32FStencil8)), Format::Depth32FStencil8);
    const std::string message = join_failure(of(Format::Depth32F), of(Format::Depth24));
    EXPECT_NE(message.find("depth kind float vs unorm"), std::string::npos) << message;
    // 16-bit depth with stencil has no enum value; 24-bit depth + stencil covers it.
    auto d16s8 = join(of(Format::Depth16), of(Format::Stencil8));
    ASSERT_TRUE(d16s8.ok());
    auto resolved = resolve_format(d16s8->format, "test");
    ASSERT_TRUE(resolved.ok());
    EXPECT_EQ(resolved->format, Format::Depth24Stencil8);
    EXPECT_EQ(resolved->match, FormatMatch::Covering);
}

TEST(JoinFormat, UnconstrainedFormatTakesTheOther) {
    EXPECT_EQ(joined_format(TextureSpec{}, of(Format::RG16Float)), Format::RG16Float);
    EXPECT_EQ(joined_format(of(Format::Depth24), TextureSpec{}), Format::Depth24);
    auto both_open = join(TextureSpec{}, TextureSpec{});
    ASSERT_TRUE(both_open.ok());
    EXPECT_FALSE(both_open->format.has_value());
}

TEST(JoinFormat, IsCommutativeOnEveryPairOfFormats) {
    for (Format a : rhi::all_formats()) {
        for (Format b : rhi::all_formats()) {
            auto ab = join(of(a), of(b));
            auto ba = join(of(b), of(a));
            ASSERT_EQ(ab.ok(), ba.ok()) << rhi::format_name(a) << " " << rhi::format_name(b);
            if (ab.ok()) {
                EXPECT_EQ(*ab, *ba) << rhi::format_name(a) << " " << rhi::format_name(b);
            }
        }
    }
}

// ---- the other properties --------------------------------------------------------------------

TEST(JoinSpec, SizesMustBeEqualOnceEvaluated) {
    const TextureSpec full = TextureSpec{}.with_scale(1.0f);
    const TextureSpec fixed = TextureSpec{}.with_size(1920, 1080);
    auto same = join(full, fixed, named(Extent2D{1920, 1080}));
    ASSERT_TRUE(same.ok());
    EXPECT_EQ(same->size->evaluate({1920, 1080}), (Extent2D{1920, 1080}));

    const std::string message = join_failure(full, fixed, Extent2D{1280, 720});
    EXPECT_NE(message.find("size 1280x720 (1 x frame) vs 1920x1080"), std::string::npos) << message;
    EXPECT_NE(join_failure(full, fixed).find("only be compared against a frame size"), std::string::npos);
    EXPECT_NE(join_failure(TextureSpec{}.with_size(512, 512), TextureSpec{}.with_size(512, 256)).find("512x512 vs 512x256"),
              std::string::npos);
    EXPECT_TRUE(joinable(TextureSpec{}.with_scale(0.5f), TextureSpec{}.with_scale(0.5f)));
    EXPECT_FALSE(joinable(TextureSpec{}.with_scale(0.5f), TextureSpec{}.with_scale(0.25f), Extent2D{1920, 1080}));
}

TEST(JoinSpec, SamplesMipsLayersAreEqualOrUnconstrained) {
    EXPECT_NE(join_failure(TextureSpec{}.with_samples(4), TextureSpec{}.with_samples(1)).find("samples 4 vs 1"),
              std::string::npos);
    EXPECT_NE(join_failure(TextureSpec{}.with_mips(5), TextureSpec{}.with_mips(1)).find("mips 5 vs 1"), std::string::npos);
    EXPECT_NE(join_failure(TextureSpec{}.with_layers(6), TextureSpec{}.with_layers(2)).find("layers 6 vs 2"),
              std::string::npos);
    auto joined = join(TextureSpec{}.with_samples(4).with_layers(2), TextureSpec{}.with_mips(1).with_samples(4));
    ASSERT_TRUE(joined.ok());
    EXPECT_EQ(joined->samples, 4u);
    EXPECT_EQ(joined->mips, 1u);
    EXPECT_EQ(joined->layers, 2u);
}

TEST(JoinSpec, UsageIsTheUnion) {
    auto joined = join(TextureSpec{}.with_usage(TextureUsage::Storage), TextureSpec{}.with_usage(TextureUsage::CopySrc));
    ASSERT_TRUE(joined.ok());
    EXPECT_EQ(joined->usage, TextureUsage::Storage | TextureUsage::CopySrc);
}

// ---- resolution ------------------------------------------------------------------------------

TEST(Resolve, DefaultsForUnconstrainedProperties) {
    auto resolved = resolve(TextureSpec{}, Extent2D{800, 600}, "x.y");
    ASSERT_TRUE(resolved.ok());
    EXPECT_EQ(resolved->format, Format::RGBA8Unorm);
    EXPECT_EQ(resolved->format_match, FormatMatch::Default);
    EXPECT_EQ(resolved->extent, (Extent2D{800, 600}));
    EXPECT_EQ(resolved->samples, 1u);
    EXPECT_EQ(resolved->mips, 1u);
    EXPECT_EQ(resolved->layers, 1u);
}

TEST(Resolve, RelativeSizesRoundAndStayPositive) {
    EXPECT_EQ(SizeSpec::relative(0.5f).evaluate({1920, 1080}), (Extent2D{960, 540}));
    EXPECT_EQ(SizeSpec::relative(1.0f / 3.0f).evaluate({1000, 10}), (Extent2D{333, 3}));
    EXPECT_EQ(SizeSpec::relative(0.001f).evaluate({100, 100}), (Extent2D{1, 1}));
    EXPECT_EQ(SizeSpec::relative(0.5f, 0.25f).evaluate({64, 64}), (Extent2D{32, 16}));
}

TEST(Resolve, FeaturesWithoutEnumValueTakeTheSmallestCoveringFormat) {
    struct Case {
        TextureSpec spec;
        Format expected;
    };
    const Case cases[] = {
        {TextureSpec::color(3, 16, ChannelKind::Float), Format::RGBA16Float},   // alpha added
        {TextureSpec::color(3, 8, ChannelKind::Unorm), Format::RGBA8Unorm},     // ties go to enum order
        {TextureSpec::color(3, 10, ChannelKind::Float), Format::R11G11B10Float},
        {TextureSpec::color(1, 12, ChannelKind::Unorm), Format::R16Unorm},
        {TextureSpec::color(2, 24, ChannelKind::Float), Format::RG32Float},
        {TextureSpec::depth_stencil(20, ChannelKind::Unorm), Format::Depth24},
        {TextureSpec::depth_stencil(0, ChannelKind::Unorm, 4), Format::Stencil8},
    };
    for (const Case& c : cases) {
        auto resolved = resolve(c.spec, Extent2D{4, 4}, "x.y");
        ASSERT_TRUE(resolved.ok()) << resolved.error().to_string();
        EXPECT_EQ(resolved->format, c.expected) << describe_features(*c.spec.format);
        EXPECT_EQ(resolved->format_match, FormatMatch::Covering) << describe_features(*c.spec.format);
    }
}

TEST(Resolve, NoCoveringFormatIsAJoinError) {
    auto resolved = resolve(TextureSpec::color(3, 32, ChannelKind::Uint), Extent2D{4, 4}, "lights.index");
    ASSERT_FALSE(resolved.ok());
    EXPECT_EQ(resolved.error().code, ErrorCode::Join);
    EXPECT_NE(resolved.error().message.find("lights.index"), std::string::npos);
    EXPECT_NE(resolved.error().message.find("RGB32 uint"), std::string::npos) << resolved.error().message;
}

TEST(Resolve, ImpossibleCountsAreErrors) {
    auto three_samples = resolve(TextureSpec{}.with_samples(3), Extent2D{4, 4}, "msaa.color");
    ASSERT_FALSE(three_samples.ok());
    EXPECT_NE(three_samples.error().message.find("msaa.color: samples 3"), std::string::npos);
    auto too_many_mips = resolve(TextureSpec{}.with_size(16, 8).with_mips(6), Extent2D{4, 4}, "bloom.chain");
    ASSERT_FALSE(too_many_mips.ok());
    EXPECT_NE(too_many_mips.error().message.find("mips 6 not in 1..5"), std::string::npos);
    EXPECT_TRUE(resolve(TextureSpec{}.with_size(16, 8).with_mips(5), Extent2D{4, 4}, "x").ok());
    auto multisampled_mips = resolve(TextureSpec{}.with_samples(4).with_mips(2), Extent2D{64, 64}, "x.y");
    ASSERT_FALSE(multisampled_mips.ok());
}

TEST(Resolve, CoversAddsOnlyAlpha) {
    const auto& rgba16f = rhi::format_info(Format::RGBA16Float).features;
    const auto& r16f = rhi::format_info(Format::R16Float).features;
    EXPECT_TRUE(covers(rgba16f, color_features(3, 16, ChannelKind::Float)));
    EXPECT_FALSE(covers(rgba16f, r16f));  // G and B would be added
    EXPECT_FALSE(covers(rhi::format_info(Format::Depth24Stencil8).features,
                        rhi::format_info(Format::Depth24).features));  // no added stencil
    EXPECT_FALSE(covers(rhi::format_info(Format::RGBA8Srgb).features, color_features(3, 8, ChannelKind::Unorm)));
}

TEST(Describe, FeaturesReadable) {
    EXPECT_EQ(describe_features(rhi::format_info(Format::RGBA16Float).features), "RGBA16Float");
    EXPECT_EQ(describe_features(color_features(3, 16, ChannelKind::Float)), "RGB16 float");
    rhi::FormatFeatures d16s8 = rhi::format_info(Format::Depth16).features;
    d16s8.stencil_bits = 8;
    EXPECT_EQ(describe_features(d16s8), "depth16 unorm + stencil8");
    EXPECT_EQ(describe_size(SizeSpec::relative(0.5f)), "0.5 x frame");
    EXPECT_EQ(describe_usage(TextureUsage::Sampled | TextureUsage::Storage), "sampled|storage");
}

}  // namespace
}  // namespace loom::fg

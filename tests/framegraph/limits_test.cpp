// The one set of limits (texture_spec.hpp) and checked sizes: every entry point refuses what
// is past them with the real value, and no size wraps.
#include <gtest/gtest.h>

#include "loom/framegraph/framegraph.hpp"

namespace loom::fg {
namespace {

using rhi::Format;

Error plan_error(TextureSpec spec, Extent2D frame) {
    FrameGraph graph;
    EXPECT_TRUE(graph.add_pass(Pass("a").output("x", spec)).ok());
    EXPECT_TRUE(graph.mark_output(port("a", "x")).ok());
    PlanOptions options;
    options.frame = frame;
    auto plan = build_plan(graph, options);
    EXPECT_FALSE(plan.ok());
    return plan.ok() ? Error{} : plan.error();
}

TEST(Limits, AFrameOf2To30SquaredIsRefusedNotPlannedAs0Bytes) {
    const Error error = plan_error(TextureSpec::of(Format::RGBA16Float), {1u << 30, 1u << 30});
    EXPECT_EQ(error.code, ErrorCode::Graph);
    EXPECT_EQ(error.message, "a.x: size 1073741824x1073741824 is beyond the limit of 65536 texels per side");
}

TEST(Limits, AScaledSizeIsReportedAsAskedNotAsAConvertedValue) {
    // 5 x 2^30 does not fit in 32 bits; it was planned 1,073,741,824 wide (undefined behaviour).
    const Error error = plan_error(TextureSpec::of(Format::RGBA8Unorm).with_scale(5.0f), {1u << 30, 64});
    EXPECT_EQ(error.message, "a.x: size 5368709120x320 (5 x frame of 1073741824x64) is beyond the limit of 65536 texels per side");
    // At the limit exactly it plans.
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("a").output("x", TextureSpec::of(Format::R8Unorm).with_scale(2.0f, 1.0f))).ok());
    ASSERT_TRUE(graph.mark_output(port("a", "x")).ok());
    PlanOptions options;
    options.frame = {kMaxTextureExtent / 2, 1};
    auto plan = build_plan(graph, options);
    ASSERT_TRUE(plan.ok()) << plan.error().to_string();
    ASSERT_EQ(plan->textures.size(), 1u);
    EXPECT_EQ(plan->textures[0].spec.extent, (Extent2D{kMaxTextureExtent, 1}));
    EXPECT_EQ(plan->textures[0].bytes, align_up(kMaxTextureExtent, DefaultMemoryModel::kDefaultAlignment));
}

TEST(Limits, AbsoluteSizesAndLayersPastTheLimitAreRefused) {
    EXPECT_EQ(plan_error(TextureSpec::of(Format::R8Unorm).with_size(kMaxTextureExtent + 1, 4), {64, 64}).message,
              "a.x: size 65537x4 is beyond the limit of 65536 texels per side");
    EXPECT_EQ(plan_error(TextureSpec::of(Format::R8Unorm).with_layers(kMaxTextureLayers + 1), {64, 64}).message,
              "a.x: layers 2049 is beyond the limit of 2048");
}

TEST(Limits, TheMemoryModelNeverWraps) {
    rhi::TextureDesc desc;
    desc.name = "huge";
    desc.format = Format::RGBA32Float;
    desc.width = 1u << 30;
    desc.height = 1u << 30;  // 2^60 texels x 16 bytes = 2^64: wrapped to exactly 0
    EXPECT_EQ(DefaultMemoryModel::checked_texture_bytes(desc), std::nullopt);
    EXPECT_EQ(DefaultMemoryModel::texture_bytes(desc), std::numeric_limits<uint64_t>::max());
    DefaultMemoryModel model;
    auto requirements = model.requirements(desc);
    ASSERT_FALSE(requirements.ok());
    EXPECT_EQ(requirements.error().message, "texture 'huge' (1073741824x1073741824, 1 layers, 1 mips, 1 samples) needs more than 2^64 bytes");
    // Rounding up to the alignment overflows too, just under 2^64.
    desc.format = Format::R8Unorm;
    desc.width = 0xffffffffu;
    desc.height = 0xffffffffu;
    desc.depth_or_layers = 0xffffffffu;
    EXPECT_FALSE(model.requirements(desc).ok());
    // Mip chains past 32 levels are 1x1 levels, counted without shifting past 32 bits.
    desc.width = 4;
    desc.height = 4;
    desc.depth_or_layers = 1;
    desc.mip_levels = 40;
    EXPECT_EQ(DefaultMemoryModel::checked_texture_bytes(desc), 16u + 4u + 1u + 37u);
}

TEST(Limits, GraphFilesUseTheSameLimits) {
    auto frame = parse_graph_json(R"({"frame": {"width": 1073741824, "height": 1073741824}, "passes": []})", "g.json");
    ASSERT_FALSE(frame.ok());
    EXPECT_EQ(frame.error().message, "g.json: /frame/width: must be at most 65536, not 1073741824");
    auto size = parse_graph_json(R"({"passes": [{"name": "a", "outputs": [{"name": "x", "size": [17179869184, 64]}]}]})",
                                 "g.json");
    ASSERT_FALSE(size.ok());
    EXPECT_EQ(size.error().message, "g.json: /passes/0/outputs/0/size: each side must be in 1..65536, not [17179869184,64]");
    auto at_limit = parse_graph_json(R"({"frame": {"width": 65536, "height": 1}, "passes": []})", "g.json");
    EXPECT_TRUE(at_limit.ok());
}

}  // namespace
}  // namespace loom::fg

// The flagship pipeline on GL and on Vulkan: the same plan, the textures each backend created
// match it, and every intermediate and the final picture compare equal.
//
// Tolerance, measured and explained: llvmpipe and lavapipe share the rasteriser, but GL compiles
// SPIRV-Cross's GLSL with Mesa's GLSL front end while Vulkan compiles the SPIR-V; the two round
// some arithmetic differently. The parts transform positions in one fixed order without fused
// multiply-adds (transform_point, "precise"), which made the shadow map bit-exact and cut the
// differing G-buffer depths from 80% to 0.4% of the pixels. What remains: triangles the clipper
// cuts at the view's edges (the ground plane), and single fragments of the lighting and checker
// arithmetic. Every texture is therefore allowed to differ by one rounding step of its format at
// its peak value (format_steps.hpp: one half-float step for the RGBA16F maps, one float step
// for depth, one level for RGBA8) in at most 1% of its pixels; the shadow map must be exact.
// The blurred maps are the exception to the 1%: every high-pass texel that differs is spread
// over the blur's kernel ((2r+1)^2 texels, r = 8 at 180 rows), so they may differ in 5%.
// And one in 10,000 texels (at least one) may differ by more than a step: on a shadow's edge, a
// one-step difference of a G-buffer position (1/512 world units around 2..4, a third of a shadow
// texel; the interpolated position can differ where the depth does not) moves the texel's
// shadow lookup and changes how much of the sun it receives. Measured at 320x180: G-buffer depth 0.53% (one float step), albedo 0.13%, lit
// colour 0.13%, high pass 0.02%, horizontal blur 0.16%, vertical blur 1.09%, final picture 0.02%
// (11 texels, one 8-bit level); at 1280x720 (loom-deferred's PNGs): final picture 282 texels
// (0.03%), one of them 21 levels apart, the rest one level.
#include <iostream>

#include <gtest/gtest.h>

#include "flagship_support.hpp"
#include "format_steps.hpp"
#include "loom_test/render_fixture.hpp"
#include "loom_test/test_support.hpp"

#include "loom/image_io/image_io.hpp"

namespace loom::test {
namespace {

bool both_backends(std::string& why_not) {
    const auto backends = backends_under_test();
    const bool gl = std::find(backends.begin(), backends.end(), rhi::Backend::OpenGL) != backends.end();
    const bool vulkan = std::find(backends.begin(), backends.end(), rhi::Backend::Vulkan) != backends.end();
    if (!gl || !vulkan) why_not = "needs both the GL and the Vulkan backend";
    return gl && vulkan;
}

TEST(FlagshipCrossBackend, EveryTextureAndThePlanMatch) {
    std::string why_not;
    if (!both_backends(why_not)) GTEST_SKIP() << why_not;
    FlagshipFrame frames[2];
    const rhi::Backend backends[2] = {rhi::Backend::OpenGL, rhi::Backend::Vulkan};
    for (int i = 0; i < 2; ++i) {
        auto device = create_test_device(backends[i]);
        ASSERT_TRUE(device.ok()) << device.error().to_string();
        auto frame = render_flagship(**device, 320, 180);
        ASSERT_TRUE(frame.ok()) << rhi::backend_name(backends[i]) << ": " << frame.error().to_string();
        frames[i] = std::move(*frame);
        EXPECT_EQ(frames[i].stats.textures, frames[i].stats.plan_textures) << rhi::backend_name(backends[i]);
    }
    EXPECT_EQ(fg::plan_hash(frames[0].plan), fg::plan_hash(frames[1].plan));
    EXPECT_TRUE(frames[0].plan == frames[1].plan);

    const std::filesystem::path dir = output_dir() / "passes" / "cross_backend";
    std::filesystem::create_directories(dir);
    ASSERT_EQ(frames[0].images.size(), frames[1].images.size());
    for (const auto& [name, gl_image] : frames[0].images) {
        auto vk = frames[1].images.find(name);
        ASSERT_NE(vk, frames[1].images.end()) << name;
        auto report = image_io::compare_and_report(gl_image, vk->second, dir, name);  // pictures when they differ
        ASSERT_TRUE(report.ok()) << name << ": " << report.error().to_string();
        const StepComparison steps = compare_steps(gl_image, vk->second);
        std::cout << "gl vs vulkan, " << name << ": " << steps.summary() << "\n";
        if (name == "shadow.shadow_map") {
            EXPECT_EQ(steps.pixels_differing, 0u) << name << ": " << steps.summary();
        } else {
            const bool blurred = name.rfind("blur-", 0) == 0;
            EXPECT_LE(steps.pixels_beyond_one_step, steps.pixel_count / 10000 + 1) << name << ": " << steps.summary();
            EXPECT_LE(steps.fraction_differing(), blurred ? 0.05 : 0.01) << name << ": " << steps.summary();
        }
    }
}

}  // namespace
}  // namespace loom::test

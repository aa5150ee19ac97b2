// Runs the loom-triangle sample as a user would and checks the PNG it writes: background in
// the corners, the triangle's colour at the centre.
#include <cstdlib>
#include <filesystem>
#include <string>

#include "loom/image_io/image_io.hpp"
#include "loom/rhi/image.hpp"
#include "loom_test/render_fixture.hpp"

#ifndef LOOM_TRIANGLE_EXE
#error "LOOM_TRIANGLE_EXE must name the loom-triangle executable"
#endif

namespace loom::test {
namespace {

class TriangleSampleTest : public ::testing::TestWithParam<rhi::Backend> {
protected:
    static int run(const std::string& arguments) {
        const std::string command = std::string("\"") + LOOM_TRIANGLE_EXE + "\" " + arguments;
        return std::system(command.c_str());
    }
};

TEST_P(TriangleSampleTest, WritesTheTrianglePng) {
    const std::string backend(rhi::backend_name(GetParam()));
    const std::filesystem::path png = output_dir() / "samples" / ("triangle_" + backend + ".png");
    std::filesystem::remove(png);
    ASSERT_EQ(run("--backend " + backend + " --size 160x120 --out \"" + png.string() + "\""), 0);
    auto image = image_io::read_png(png);
    ASSERT_TRUE(image.ok()) << image.error().to_string();
    ASSERT_EQ(image->width, 160u);
    ASSERT_EQ(image->height, 120u);
    auto at = [&](uint32_t x, uint32_t y) {
        auto t = image->texel(x, y);
        return std::array<int, 4>{int(t[0]), int(t[1]), int(t[2]), int(t[3])};
    };
    // The background (0.08, 0.08, 0.12) in 8 bits: 20.4 -> 20, 30.6 -> 31.
    const std::array<int, 4> background{20, 20, 31, 255};
    EXPECT_EQ(at(0, 0), background);
    EXPECT_EQ(at(159, 0), background);
    EXPECT_EQ(at(0, 119), background);
    EXPECT_EQ(at(159, 119), background);
    // The colour at the centre pixel, from its barycentric weights: at NDC (x, y) inside the
    // triangle (-0.5,-0.5) red, (0.5,-0.5) green, (0,0.5) blue, blue = 0.5 + y and
    // red/green = (1 - blue) / 2 -/+ x. Interpolation is not exact in the last bit: 1 level.
    const double x = (80 + 0.5) / 160 * 2 - 1, y = 1 - (60 + 0.5) / 120 * 2;
    const double blue = 0.5 + y, red = (1 - blue) / 2 - x, green = (1 - blue) / 2 + x;
    const auto centre = at(80, 60);
    EXPECT_NEAR(centre[0], red * 255, 1.0);
    EXPECT_NEAR(centre[1], green * 255, 1.0);
    EXPECT_NEAR(centre[2], blue * 255, 1.0);
    EXPECT_EQ(centre[3], 255);
    // Orientation: blue apex at the top, red at the bottom-left, green at the bottom-right.
    const auto apex = at(80, 32);     // NDC y = 0.45
    const auto left = at(42, 88);     // near (-0.47, -0.47)
    const auto right = at(117, 88);   // near (0.47, -0.47)
    EXPECT_GT(apex[2], 200);
    EXPECT_GT(left[0], 200);
    EXPECT_GT(right[1], 200);
}

TEST_P(TriangleSampleTest, RejectsBadArgumentsWithAnError) {
    EXPECT_NE(run("--size 0x10 --backend " + std::string(rhi::backend_name(GetParam()))), 0);
    EXPECT_NE(run("--no-such-option"), 0);
    EXPECT_NE(run("--backend metal"), 0);
    EXPECT_EQ(run("--help"), 0);
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(TriangleSampleTest);

}  // namespace loom::test

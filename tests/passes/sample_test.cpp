// loom-deferred run as a user runs it, on both backends at a small size: it succeeds without a
// validation or debug message, writes every picture, and GL and Vulkan write the same plan and
// the same pictures (within one 8-bit level in at most 1% of the pixels, 5% for the blurred
// maps, and one texel in 10,000 further apart: the tolerance of cross_backend_test.cpp, which
// explains it).
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "format_steps.hpp"
#include "loom/image_io/image_io.hpp"
#include "loom/rhi/image.hpp"
#include "loom_test/render_fixture.hpp"
#include "loom_test/test_support.hpp"

namespace loom::test {
namespace {

std::string read_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/// Runs loom-deferred with `arguments`; returns its exit status and what it printed.
int run_sample(const std::string& arguments, std::string& output) {
    // One log per test: ctest runs this file's tests in parallel.
    const std::filesystem::path log =
        output_dir() / "passes" / (std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + ".log");
    std::filesystem::create_directories(log.parent_path());
    const std::string command = std::string("\"") + LOOM_DEFERRED_EXE + "\" " + arguments + " > \"" + log.string() + "\" 2>&1";
    const int status = std::system(command.c_str());
    output = read_file(log);
    return status;
}

const char* const kPictures[] = {
    "final",         "shadow.shadow_map", "geometry.position",  "geometry.normal", "geometry.albedo", "geometry.emission",
    "geometry.depth", "geometry.material", "figure3-gbuffer",   "deferred.color",  "deferred.high_pass",
    "blur-h.color",  "blur-v.color",      "composite.final",    "present.target",
};

TEST(DeferredSample, GlAndVulkanWriteTheSamePlanAndPictures) {
    const auto backends = backends_under_test();
    if (backends.size() < 2) GTEST_SKIP() << "needs both the GL and the Vulkan backend";
    const std::filesystem::path root = output_dir() / "passes" / "sample";
    std::string plans[2];
    for (int i = 0; i < 2; ++i) {
        const std::string backend = i == 0 ? "gl" : "vulkan";
        const std::filesystem::path dir = root / backend;
        std::filesystem::remove_all(dir);
        std::string output;
        // The same allocator on both: by default each device gets its cheapest (the next test).
        ASSERT_EQ(run_sample("--backend " + backend + " --allocator interval --size 256x144 --out \"" + dir.string() + "\"",
                             output),
                  0)
            << output;
        EXPECT_EQ(output.find("[error]"), std::string::npos) << output;
        EXPECT_EQ(output.find("[warning]"), std::string::npos) << output;
        EXPECT_NE(output.find("RGBA16Float 256x144: 6 texture(s) for 9 output(s)"), std::string::npos) << output;
        for (const char* picture : kPictures) {
            EXPECT_TRUE(std::filesystem::exists(dir / (std::string(picture) + ".png"))) << backend << ": " << picture;
        }
        EXPECT_TRUE(std::filesystem::exists(dir / "plan.dot"));
        EXPECT_TRUE(std::filesystem::exists(dir / "summary.txt"));
        plans[i] = read_file(dir / "plan.json");
        EXPECT_FALSE(plans[i].empty());
    }
    EXPECT_EQ(plans[0], plans[1]) << "the plans differ";

    for (const char* picture : kPictures) {
        const std::string file = std::string(picture) + ".png";
        auto gl = image_io::read_png(root / "gl" / file);
        auto vulkan = image_io::read_png(root / "vulkan" / file);
        ASSERT_TRUE(gl.ok() && vulkan.ok()) << file;
        ASSERT_EQ(gl->width, vulkan->width) << file;
        const StepComparison comparison = compare_steps(*gl, *vulkan);
        EXPECT_LE(comparison.pixels_beyond_one_step, comparison.pixel_count / 10000 + 1) << file << ": "
                                                                                       << comparison.summary();
        const bool blurred = std::string(picture).rfind("blur-", 0) == 0;
        EXPECT_LE(comparison.fraction_differing(), blurred ? 0.05 : 0.01) << file << ": " << comparison.summary();
        if (comparison.pixels_differing != 0) {
            (void)image_io::compare_and_report(*gl, *vulkan, root, std::string(picture) + ".gl-vs-vulkan");
        }
    }
}

/// The "bytes" of the plan loom-deferred wrote into `dir`.
uint64_t plan_bytes(const std::filesystem::path& dir) {
    const std::string plan = read_file(dir / "plan.json");
    const std::size_t summary = plan.find("\"summary\"");
    const std::size_t bytes = plan.find("\"bytes\":", summary);
    if (summary == std::string::npos || bytes == std::string::npos) return 0;
    return std::strtoull(plan.c_str() + bytes + 8, nullptr, 10);
}

TEST(DeferredSample, ByDefaultEachDeviceGetsItsCheapestAllocator) {
    // Vulkan (placed resources): the heap allocator, which needs fewer bytes for this frame than
    // the interval allocator; GL (none): interval. The picture does not depend on it.
    const std::filesystem::path root = output_dir() / "passes" / "sample-auto";
    for (rhi::Backend b : backends_under_test()) {
        const std::string backend(rhi::backend_name(b));
        SCOPED_TRACE(backend);
        std::string output;
        ASSERT_EQ(run_sample("--backend " + backend + " --size 256x144 --out \"" + (root / backend).string() + "\"", output), 0)
            << output;
        EXPECT_EQ(output.find("[error]"), std::string::npos) << output;
        const bool placed = b == rhi::Backend::Vulkan;
        EXPECT_NE(output.find(placed ? "allocator heap (auto)" : "allocator interval (auto)"), std::string::npos) << output;
        if (!placed) continue;
        ASSERT_EQ(run_sample("--backend vulkan --allocator interval --size 256x144 --out \"" + (root / "interval").string() + "\"",
                             output),
                  0)
            << output;
        EXPECT_NE(output.find("allocator interval, "), std::string::npos) << output;
        const uint64_t heap = plan_bytes(root / backend), interval = plan_bytes(root / "interval");
        EXPECT_GT(heap, 0u);
        EXPECT_LT(heap, interval) << "heap " << heap << " bytes, interval " << interval;
        auto chosen = image_io::read_png(root / backend / "final.png");
        auto pooled = image_io::read_png(root / "interval" / "final.png");
        ASSERT_TRUE(chosen.ok() && pooled.ok());
        EXPECT_EQ(chosen->pixels, pooled->pixels);
    }
}

TEST(DeferredSample, RejectsAMissingSceneFileAndBadArgumentsAndExplainsWhy) {
    std::string output;
    EXPECT_NE(run_sample("--scene model.gltf", output), 0);
    EXPECT_NE(output.find("Io: model.gltf: file not found"), std::string::npos) << output;
    EXPECT_NE(run_sample("--pipeline sideways", output), 0);
    EXPECT_NE(output.find("--pipeline expects deferred or forward"), std::string::npos) << output;
    EXPECT_EQ(run_sample("--help", output), 0);
    EXPECT_NE(output.find("--allocator"), std::string::npos) << output;
}

}  // namespace
}  // namespace loom::test

// The tools on the real test data (LOOM_DATA_DIR/gltf: glTF sample models and invalid files
// written by others), as CI runs them: loom-compare over every valid model through both
// pipelines on every compiled-in backend, loom-compare --expect-errors over every invalid file,
// and loom-deferred --scene on models. Skipped with a message when the data is missing, failed
// when CI=true.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <sys/wait.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

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

/// Runs `exe` with `arguments`, stdout to `out`, stderr to `err`; returns the exit status.
int run(const char* exe, const std::string& arguments, const std::filesystem::path& out, const std::filesystem::path& err) {
    std::filesystem::create_directories(out.parent_path());
    const std::string command = std::string("\"") + exe + "\" " + arguments + " > \"" + out.string() + "\" 2> \"" +
                                err.string() + "\"";
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// .gltf and .glb files under `dir` (recursively), skipping `skip` directories.
std::set<std::string> scene_files(const std::filesystem::path& dir, const std::string& skip = "") {
    std::set<std::string> files;
    for (auto it = std::filesystem::recursive_directory_iterator(dir); it != std::filesystem::recursive_directory_iterator(); ++it) {
        if (!skip.empty() && it->is_directory() && it->path().filename() == skip) {
            it.disable_recursion_pending();
            continue;
        }
        const std::string ext = it->path().extension().string();
        if (it->is_regular_file() && (ext == ".gltf" || ext == ".glb")) files.insert(it->path().string());
    }
    return files;
}

TEST(CompareOnData, EveryValidModelRendersAlikeOnEveryBackendThroughBothPipelines) {
    LOOM_REQUIRE_DATA_DIR(data);
    const std::filesystem::path dir = output_dir() / "compare" / "valid";
    std::filesystem::remove_all(dir);
    // 256x144 keeps CI quick; the thresholds are loom-compare's defaults.
    const int status = run(LOOM_COMPARE_EXE, "--scenes \"" + (data / "gltf").string() + "\" --size 256x144 --json --out \"" +
                                                 dir.string() + "\"",
                           dir / "stdout.json", dir / "stderr.txt");
    const std::string log = read_file(dir / "stderr.txt");
    EXPECT_EQ(status, 0) << log;
    const nlohmann::json json = nlohmann::json::parse(read_file(dir / "stdout.json"), nullptr, false);
    ASSERT_FALSE(json.is_discarded()) << "stdout is not one JSON object\n" << log;

    const std::set<std::string> expected = scene_files(data / "gltf", "invalid");
    ASSERT_GE(expected.size(), 10u);
    const std::size_t backends = backends_under_test().size();
    EXPECT_EQ(json["summary"]["cases"], expected.size() * 2);
    EXPECT_EQ(json["summary"]["failed"], 0) << log;
    std::set<std::string> seen;
    for (const auto& c : json["cases"]) {
        seen.insert(c["file"].get<std::string>());
        EXPECT_TRUE(c["passed"].get<bool>()) << c["scene"] << " " << c["pipeline"] << ": " << c["failures"].dump();
        ASSERT_EQ(c["backends"].size(), backends);
        for (const auto& run : c["backends"]) {
            EXPECT_TRUE(run["rendered"].get<bool>()) << c["scene"] << " " << run["backend"];
            EXPECT_TRUE(run["messages"].empty()) << c["scene"] << " " << run["backend"] << ": " << run["messages"].dump();
            EXPECT_TRUE(std::filesystem::exists(dir / run["image"].get<std::string>()));
        }
        if (backends == 2) {
            EXPECT_EQ(c["backends"][0]["plan"]["hash"], c["backends"][1]["plan"]["hash"]) << c["scene"];
            EXPECT_TRUE(std::filesystem::exists(dir / c["image"]["diff"].get<std::string>()));
        }
        // The forward pipeline against the deferred one: within loom-compare's documented
        // tolerance (2 levels at no more than 0.5 % of the pixels), with its heat map.
        if (c["pipeline"] == "forward") {
            const auto& against = c["against_deferred"];
            ASSERT_TRUE(against.is_object()) << c["scene"];
            EXPECT_LE(against["pixels_above_threshold"].get<double>(), 0.005 * against["pixel_count"].get<double>()) << c["scene"];
            EXPECT_TRUE(std::filesystem::exists(dir / against["diff"].get<std::string>())) << c["scene"];
        } else {
            EXPECT_TRUE(c["against_deferred"].is_null()) << c["scene"];
        }
        // Something was drawn: the sky behind the model changes by at most a level or two from
        // one pixel to the next, so the model's outline (and its shading and textures) are the
        // pixels that differ from their left or upper neighbour by more; a model covering over
        // 1% of the frame has an outline of well over 0.1% of its pixels.
        {
            auto picture = image_io::read_png(dir / c["backends"][0]["image"].get<std::string>());
            ASSERT_TRUE(picture.ok());
            uint64_t edges = 0;
            for (uint32_t y = 1; y < picture->height; ++y) {
                for (uint32_t x = 1; x < picture->width; ++x) {
                    const auto p = picture->load(x, y), left = picture->load(x - 1, y), up = picture->load(x, y - 1);
                    double difference = 0.0;
                    for (int ch = 0; ch < 3; ++ch) {
                        difference = std::max({difference, std::abs(p[ch] - left[ch]), std::abs(p[ch] - up[ch])});
                    }
                    edges += difference > 6.0 / 255.0 ? 1 : 0;
                }
            }
            EXPECT_GT(edges, uint64_t{picture->width} * picture->height / 1000) << c["scene"] << " " << c["pipeline"];
        }
    }
    std::set<std::string> canonical_expected;
    for (const std::string& file : expected) canonical_expected.insert(std::filesystem::path(file).lexically_normal().string());
    std::set<std::string> canonical_seen;
    for (const std::string& file : seen) canonical_seen.insert(std::filesystem::path(file).lexically_normal().string());
    EXPECT_EQ(canonical_seen, canonical_expected);
    EXPECT_NE(read_file(dir / "report.html").find("<img src=\"cases/"), std::string::npos);
    EXPECT_TRUE(std::filesystem::exists(dir / "report.json"));
}

TEST(CompareOnData, EveryInvalidFileGetsAOneLineErrorNamingIt) {
    LOOM_REQUIRE_DATA_DIR(data);
    const std::filesystem::path dir = output_dir() / "compare" / "invalid";
    std::filesystem::remove_all(dir);
    const int status = run(LOOM_COMPARE_EXE, "--expect-errors --scenes \"" + (data / "gltf" / "invalid").string() +
                                                 "\" --json --out \"" + dir.string() + "\"",
                           dir / "stdout.json", dir / "stderr.txt");
    const std::string log = read_file(dir / "stderr.txt");
    EXPECT_EQ(status, 0) << log;
    const nlohmann::json json = nlohmann::json::parse(read_file(dir / "stdout.json"), nullptr, false);
    ASSERT_FALSE(json.is_discarded()) << log;
    const std::set<std::string> expected = scene_files(data / "gltf" / "invalid");
    ASSERT_GE(expected.size(), 15u);
    EXPECT_EQ(json["summary"]["cases"], expected.size());
    EXPECT_EQ(json["summary"]["failed"], 0) << log;
    for (const auto& c : json["cases"]) {
        EXPECT_TRUE(c["passed"].get<bool>()) << c["scene"] << ": " << c["failures"].dump();
        const std::string error = c["error"].is_string() ? c["error"].get<std::string>() : "";
        EXPECT_EQ(error.find('\n'), std::string::npos) << c["scene"];
        EXPECT_TRUE(error.rfind("Parse: ", 0) == 0 || error.rfind("Io: ", 0) == 0) << c["scene"] << ": " << error;
        EXPECT_NE(error.find(std::filesystem::path(c["file"].get<std::string>()).filename().string()), std::string::npos)
            << error;
    }
}

TEST(CompareOnData, AValidModelGivenAsInvalidFailsTheRun) {
    LOOM_REQUIRE_DATA_DIR(data);
    const std::filesystem::path dir = output_dir() / "compare" / "not_invalid";
    const std::filesystem::path box = data / "gltf" / "Box" / "glTF-Binary" / "Box.glb";
    ASSERT_TRUE(std::filesystem::exists(box));
    const int status = run(LOOM_COMPARE_EXE, "--expect-errors --scenes \"" + box.string() + "\" --json --out \"" +
                                                 dir.string() + "\"",
                           dir / "stdout.json", dir / "stderr.txt");
    EXPECT_EQ(status, 1);
    const nlohmann::json json = nlohmann::json::parse(read_file(dir / "stdout.json"), nullptr, false);
    ASSERT_FALSE(json.is_discarded());
    EXPECT_EQ(json["summary"]["failed"], 1);
    EXPECT_NE(json["cases"][0]["failures"][0].get<std::string>().find("loaded without an error"), std::string::npos);
}

TEST(DeferredOnData, RendersAModelOnEveryBackendWithTheSamePlan) {
    LOOM_REQUIRE_DATA_DIR(data);
    const std::filesystem::path model = data / "gltf" / "AlphaBlendModeTest" / "glTF-Binary" / "AlphaBlendModeTest.glb";
    std::string plans[2];
    std::size_t i = 0;
    for (rhi::Backend backend : backends_under_test()) {
        const std::filesystem::path dir = output_dir() / "compare" / "deferred" / std::string(rhi::backend_name(backend));
        std::filesystem::remove_all(dir);
        const int status = run(LOOM_DEFERRED_EXE, "--backend " + std::string(rhi::backend_name(backend)) +
                                                      " --size 192x108 --scene \"" + model.string() + "\" --out \"" +
                                                      dir.string() + "\"",
                               dir.parent_path() / (std::string(rhi::backend_name(backend)) + ".txt"),
                               dir.parent_path() / (std::string(rhi::backend_name(backend)) + ".err"));
        const std::string output = read_file(dir.parent_path() / (std::string(rhi::backend_name(backend)) + ".txt")) +
                                   read_file(dir.parent_path() / (std::string(rhi::backend_name(backend)) + ".err"));
        ASSERT_EQ(status, 0) << output;
        EXPECT_EQ(output.find("[error]"), std::string::npos) << output;
        EXPECT_EQ(output.find("[warning]"), std::string::npos) << output;
        EXPECT_NE(output.find("blended draw item(s)"), std::string::npos) << output;
        for (const char* picture : {"final.png", "transparent.color.png", "geometry.albedo.png", "figure3-gbuffer.png"}) {
            EXPECT_TRUE(std::filesystem::exists(dir / picture)) << picture;
        }
        if (i < 2) plans[i++] = read_file(dir / "plan.json");
    }
    if (i == 2) {
        EXPECT_EQ(plans[0], plans[1]);
    }
}

TEST(DeferredOnData, RejectsAMissingFileACameraItDoesNotHaveAndAnInvalidFile) {
    LOOM_REQUIRE_DATA_DIR(data);
    const std::filesystem::path dir = output_dir() / "compare" / "deferred_errors";
    struct Case {
        std::string arguments;
        std::string message;
    };
    const Case cases[] = {
        {"--scene \"" + (dir / "missing.gltf").string() + "\"", "missing.gltf"},
        {"--scene \"" + (data / "gltf" / "Box" / "glTF" / "Box.gltf").string() + "\" --camera 3",
         "camera 3 does not exist (the scene has 0 camera(s))"},
        {"--scene \"" + (data / "gltf" / "invalid" / "node" / "node_loop.gltf").string() + "\"", "node_loop.gltf"},
        {"--camera 1", "--camera needs a glTF scene"},
    };
    for (const Case& c : cases) {
        const int status = run(LOOM_DEFERRED_EXE, c.arguments + " --size 64x36 --out \"" + (dir / "out").string() + "\"",
                               dir / "stdout.txt", dir / "stderr.txt");
        const std::string error = read_file(dir / "stderr.txt");
        EXPECT_NE(status, 0) << c.arguments;
        EXPECT_NE(error.find(c.message), std::string::npos) << c.arguments << ": " << error;
        EXPECT_EQ(std::count(error.begin(), error.end(), '\n'), 1) << "one line: " << error;
    }
}

}  // namespace
}  // namespace loom::test

// The tools on the real test data (LOOM_DATA_DIR/gltf: glTF sample models and invalid files
// written by others), as CI runs them: loom-compare over every valid model through both
// pipelines on every compiled-in backend, loom-compare --expect-errors over every invalid file,
// loom-compare's inspector pages (read back, and one opened in headless Chromium), and
// loom-deferred --scene on models, and an animated model posed and drawn on every backend.
// Skipped with a message when the data is missing, failed when CI=true.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <sys/wait.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gltf_render.hpp"
#include "inspect_test_support.hpp"
#include "loom/gltf/gltf.hpp"
#include "loom/image_io/image_io.hpp"
#include "loom/rhi/image.hpp"
#include "loom_test/browser.hpp"
#include "loom_test/render_fixture.hpp"
#include "loom_test/test_support.hpp"

namespace loom::test {
namespace {

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

/// The rows of loom-deferred's animation.csv as numbers, after checking its header.
std::vector<std::vector<double>> read_animation_csv(const std::filesystem::path& path) {
    std::istringstream csv(read_file(path));
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line, "frame,time,moved,retained_bytes,layer_bytes,immediate_bytes,identical");
    std::vector<std::vector<double>> rows;
    while (std::getline(csv, line)) {
        std::istringstream fields(line);
        std::vector<double> values;
        for (std::string field; std::getline(fields, field, ',');) values.push_back(std::stod(field));
        EXPECT_EQ(values.size(), 7u) << line;
        rows.push_back(std::move(values));
    }
    return rows;
}

/// Writes `dir`/arm.gltf (and arm.bin): a vertical strip four units tall, skinned to two joints
/// (the hip at the origin, the elbow two units up, its child), the lower rows on the hip, the
/// upper rows on the elbow, the middle row half on each; one animation bends the elbow 45
/// degrees about z and back over two seconds.
std::filesystem::path write_skinned_gltf(const std::filesystem::path& dir) {
    std::vector<float> positions;
    std::vector<uint8_t> joints;
    std::vector<float> weights;
    for (int row = 0; row <= 4; ++row) {
        for (const float x : {-0.5f, 0.5f}) {
            positions.insert(positions.end(), {x, static_cast<float>(row), 0.0f});
            joints.insert(joints.end(), {0, 1, 0, 0});
            const float elbow = row < 2 ? 0.0f : row == 2 ? 0.5f : 1.0f;
            weights.insert(weights.end(), {1.0f - elbow, elbow, 0.0f, 0.0f});
        }
    }
    std::vector<uint16_t> indices;
    for (uint16_t row = 0; row < 4; ++row) {
        const uint16_t v = static_cast<uint16_t>(row * 2);
        indices.insert(indices.end(), {v, static_cast<uint16_t>(v + 1), static_cast<uint16_t>(v + 3), v,
                                       static_cast<uint16_t>(v + 3), static_cast<uint16_t>(v + 2)});
    }
    const std::vector<float> inverse_binds = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
                                              1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -2, 0, 1};
    const float s = std::sin(3.14159265f / 8.0f), c = std::cos(3.14159265f / 8.0f);
    const std::vector<float> times = {0.0f, 1.0f, 2.0f};
    const std::vector<float> rotations = {0, 0, 0, 1, 0, 0, s, c, 0, 0, 0, 1};

    std::string bin;
    nlohmann::json views = nlohmann::json::array();
    auto add = [&](const void* data, std::size_t size) {
        while (bin.size() % 4 != 0) bin.push_back('\0');
        views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", size}});
        bin.append(static_cast<const char*>(data), size);
        return views.size() - 1;
    };
    const auto v_positions = add(positions.data(), positions.size() * 4);
    const auto v_joints = add(joints.data(), joints.size());
    const auto v_weights = add(weights.data(), weights.size() * 4);
    const auto v_indices = add(indices.data(), indices.size() * 2);
    const auto v_binds = add(inverse_binds.data(), inverse_binds.size() * 4);
    const auto v_times = add(times.data(), times.size() * 4);
    const auto v_rotations = add(rotations.data(), rotations.size() * 4);
    const nlohmann::json gltf = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0, 2}}}}},
        {"nodes", {{{"name", "hip"}, {"children", {1}}}, {{"name", "elbow"}, {"translation", {0, 2, 0}}},
                   {{"name", "arm"}, {"mesh", 0}, {"skin", 0}}}},
        {"skins", {{{"joints", {0, 1}}, {"inverseBindMatrices", 4}, {"skeleton", 0}}}},
        {"materials", {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.6, 0.1, 1.0}}, {"metallicFactor", 0.0}}},
                        {"doubleSided", true}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"JOINTS_0", 1}, {"WEIGHTS_0", 2}}},
                                      {"indices", 3},
                                      {"material", 0}}}}}}},
        {"animations", {{{"samplers", {{{"input", 5}, {"output", 6}}}},
                         {"channels", {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "rotation"}}}}}}}}},
        {"accessors",
         {{{"bufferView", v_positions}, {"componentType", 5126}, {"count", 10}, {"type", "VEC3"},
           {"min", {-0.5, 0.0, 0.0}}, {"max", {0.5, 4.0, 0.0}}},
          {{"bufferView", v_joints}, {"componentType", 5121}, {"count", 10}, {"type", "VEC4"}},
          {{"bufferView", v_weights}, {"componentType", 5126}, {"count", 10}, {"type", "VEC4"}},
          {{"bufferView", v_indices}, {"componentType", 5123}, {"count", indices.size()}, {"type", "SCALAR"}},
          {{"bufferView", v_binds}, {"componentType", 5126}, {"count", 2}, {"type", "MAT4"}},
          {{"bufferView", v_times}, {"componentType", 5126}, {"count", 3}, {"type", "SCALAR"}, {"min", {0.0}}, {"max", {2.0}}},
          {{"bufferView", v_rotations}, {"componentType", 5126}, {"count", 3}, {"type", "VEC4"}}}},
        {"bufferViews", views},
        {"buffers", {{{"uri", "arm.bin"}, {"byteLength", bin.size()}}}},
    };
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "arm.bin", std::ios::binary) << bin;
    std::ofstream(dir / "arm.gltf", std::ios::binary) << gltf.dump(2);
    return dir / "arm.gltf";
}

TEST(CompareOnData, EveryValidModelRendersAlikeOnEveryBackendThroughBothPipelines) {
    LOOM_REQUIRE_DATA_DIR(data);
    const std::filesystem::path dir = output_dir() / "compare" / "valid";
    std::filesystem::remove_all(dir);
    // 256x144 keeps CI quick. GL and Vulkan must draw every model to the bit (--threshold 0;
    // samples/compare/README.md has the measurements at larger sizes).
    const int status = run(LOOM_COMPARE_EXE, "--scenes \"" + (data / "gltf").string() +
                                                 "\" --size 256x144 --threshold 0 --json --out \"" + dir.string() + "\"",
                           dir / "stdout.json", dir / "stderr.txt");
    const std::string log = read_file(dir / "stderr.txt");
    EXPECT_EQ(status, 0) << log;
    const nlohmann::json json = nlohmann::json::parse(read_file(dir / "stdout.json"), nullptr, false);
    ASSERT_FALSE(json.is_discarded()) << "stdout is not one JSON object\n" << log;

    const std::set<std::string> expected = scene_files(data / "gltf", "invalid");
    ASSERT_GE(expected.size(), 10u);
    const std::size_t backends = backends_under_test().size();
    const std::string html = read_file(dir / "report.html");
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
            // Its inspector page, linked from the report (what a page holds: the tests below).
            ASSERT_TRUE(run["inspector"].is_string()) << c["scene"] << " " << run["backend"];
            EXPECT_TRUE(std::filesystem::exists(dir / run["inspector"].get<std::string>()));
            EXPECT_NE(html.find("href=\"" + run["inspector"].get<std::string>() + "\""), std::string::npos);
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
    EXPECT_NE(html.find("<img src=\"cases/"), std::string::npos);
    EXPECT_TRUE(std::filesystem::exists(dir / "report.json"));
}

// CesiumMilkTruck's animation (its wheels turn about their axles) posed halfway and drawn through
// the deferred pipeline: on every backend the wheels move and the rest of the picture does not,
// and the posed pictures of GL and Vulkan agree: more than one 8-bit level apart in at most 1 % of
// the pixels (the flagship's cross-backend tolerance, tests/passes/cross_backend_test.cpp).
TEST(AnimationOnData, CesiumMilkTruckPosedHalfwayTurnsItsWheelsAlikeOnEveryBackend) {
    LOOM_REQUIRE_DATA_DIR(data);
    auto loaded = gltf::load(data / "gltf" / "CesiumMilkTruck" / "glTF" / "CesiumMilkTruck.gltf");
    ASSERT_TRUE(loaded.ok()) << loaded.error().to_string();
    ASSERT_EQ(loaded->animations.size(), 1u);
    scene::Scene posed = *loaded;
    EXPECT_EQ(scene::pose(posed, posed.animations[0], 0.625f), (std::vector<uint32_t>{3, 4}));  // the two wheels
    const std::filesystem::path dir = output_dir() / "animation";
    std::filesystem::create_directories(dir);
    std::vector<rhi::Image> posed_pictures;
    for (const rhi::Backend backend : backends_under_test()) {
        SCOPED_TRACE(rhi::backend_name(backend));
        auto device = create_test_device(backend);
        ASSERT_TRUE(device.ok()) << device.error().to_string();
        auto still = render_gltf(**device, *loaded, false, 160, 120);
        auto moved = render_gltf(**device, posed, false, 160, 120);
        ASSERT_TRUE(still.ok()) << still.error().to_string();
        ASSERT_TRUE(moved.ok()) << moved.error().to_string();
        const rhi::Image& before = still->images.at("final");
        const rhi::Image& after = moved->images.at("final");
        auto change = rhi::compare_images(before, after);
        ASSERT_TRUE(change.ok()) << change.error().to_string();
        // The wheels are a small part of the picture, and they do change.
        EXPECT_GT(change->pixels_above_threshold, 20u) << change->summary();
        EXPECT_LT(change->pixels_above_threshold, change->pixel_count / 10) << change->summary();
        std::cout << "posed CesiumMilkTruck on " << rhi::backend_name(backend) << ", against the static pose: "
                  << change->summary() << "\n";
        ASSERT_TRUE(image_io::write_png(after, dir / ("posed-" + std::string(rhi::backend_name(backend)) + ".png")).ok());
        posed_pictures.push_back(after);
        ASSERT_TRUE((*device)->wait_idle().ok());
    }
    if (posed_pictures.size() == 2) {
        auto across = rhi::compare_images(posed_pictures[0], posed_pictures[1], {1.0, false});
        ASSERT_TRUE(across.ok()) << across.error().to_string();
        EXPECT_LE(across->pixels_above_threshold, across->pixel_count / 100) << across->summary();
        std::cout << "posed CesiumMilkTruck, GL against Vulkan: " << across->summary() << "\n";
    }
}

// The two backends light alike to the bit: DamagedHelmet (normal-mapped, with a smooth metal
// visor whose specular highlight turns one bit of n.h into several 8-bit levels) through both
// pipelines, every pass output compared exactly. Before the shaders wrote their dot products out
// (dot3 and friends in loom/common.glsl), 1,318 pixels differed by up to 4 levels at 1280x720.
TEST(CrossBackendOnData, DamagedHelmetIsLitBitIdenticallyOnGlAndVulkan) {
    LOOM_REQUIRE_DATA_DIR(data);
    if (backends_under_test().size() < 2) GTEST_SKIP() << "needs both backends";
    auto loaded = gltf::load(data / "gltf" / "DamagedHelmet" / "glTF-Binary" / "DamagedHelmet.glb");
    ASSERT_TRUE(loaded.ok()) << loaded.error().to_string();
    for (const bool forward : {false, true}) {
        SCOPED_TRACE(forward ? "forward" : "deferred");
        std::vector<GltfFrame> frames;
        for (const rhi::Backend backend : backends_under_test()) {
            auto device = create_test_device(backend);
            ASSERT_TRUE(device.ok()) << device.error().to_string();
            auto frame = render_gltf(**device, *loaded, forward, 960, 540);
            ASSERT_TRUE(frame.ok()) << frame.error().to_string();
            frames.push_back(std::move(*frame));
        }
        ASSERT_EQ(frames[0].images.size(), frames[1].images.size());
        for (const auto& [name, image] : frames[0].images) {
            auto diff = rhi::compare_images(image, frames[1].images.at(name), {0.0, false});
            ASSERT_TRUE(diff.ok()) << diff.error().to_string();
            EXPECT_TRUE(diff->equal()) << name << ": " << diff->summary();
        }
    }
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

/// loom-compare on `scene` with `arguments` into `dir` (emptied first unless `keep`): its
/// exit status and its report.json (null when stdout is not JSON; the log is in dir/stderr.txt).
std::pair<int, nlohmann::json> run_compare(const std::filesystem::path& dir, const std::filesystem::path& scene,
                                           const std::string& arguments, bool keep = false) {
    if (!keep) std::filesystem::remove_all(dir);
    const int status =
        run(LOOM_COMPARE_EXE, "--scenes \"" + scene.string() + "\" --json --out \"" + dir.string() + "\" " + arguments,
            dir / "stdout.json", dir / "stderr.txt");
    return {status, nlohmann::json::parse(read_file(dir / "stdout.json"), nullptr, false)};
}

/// The files under `dir` whose names end in `suffix`, relative to `dir` ('/'-separated).
std::set<std::string> files_ending_in(const std::filesystem::path& dir, const std::string& suffix) {
    std::set<std::string> files;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        if (entry.is_regular_file() && name.size() > suffix.size() && name.ends_with(suffix)) {
            files.insert(entry.path().lexically_relative(dir).generic_string());
        }
    }
    return files;
}

std::size_t occurrences(const std::string& text, const std::string& part) {
    std::size_t n = 0;
    for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
    return n;
}

// Every case's frame on every backend gets an inspector page, linked from the report's table and
// from its case, named in report.json; the page embeds that frame's input as loom-deferred
// --inspect writes it: the plan the backend ran (the report's hash), its schedule, a timing per
// pass, what the backend created, every allocator's figures.
TEST(CompareOnData, EachCaseAndBackendGetsALinkedInspectorPageOfItsFrame) {
    LOOM_REQUIRE_DATA_DIR(data);
    const std::filesystem::path dir = output_dir() / "compare" / "inspector_pages";
    const auto [status, json] = run_compare(dir, data / "gltf" / "Box" / "glTF-Binary" / "Box.glb", "--size 64x36");
    const std::string log = read_file(dir / "stderr.txt");
    EXPECT_EQ(status, 0) << log;
    ASSERT_FALSE(json.is_discarded()) << log;
    ASSERT_EQ(json["cases"].size(), 2u) << "deferred and forward";
    const std::string html = read_file(dir / "report.html");
    std::set<std::string> named;
    for (const auto& c : json["cases"]) {
        ASSERT_EQ(c["backends"].size(), backends_under_test().size());
        for (const auto& run : c["backends"]) {
            const std::string backend = run["backend"].get<std::string>();
            SCOPED_TRACE(c["id"].get<std::string>() + " on " + backend);
            ASSERT_TRUE(run["inspector"].is_string());
            const std::string file = run["inspector"].get<std::string>();
            EXPECT_EQ(file, "cases/" + c["id"].get<std::string>() + "/" + backend + ".inspector.html");
            named.insert(file);
            EXPECT_EQ(occurrences(html, "href=\"" + file + "\""), 2u) << "linked from the table and the case";

            const std::string page = read_file(dir / file);
            ASSERT_FALSE(page.empty());
            EXPECT_NE(page.find("<title>loom inspector: Box.glb — " + c["pipeline"].get<std::string>() + " on " +
                                backend + "</title>"),
                      std::string::npos);
            const nlohmann::json input = inspect_test::embedded_input(page);
            ASSERT_TRUE(input.is_object());
            EXPECT_EQ(input.at("format"), "loom-inspect-input");
            EXPECT_EQ(input.at("source").get<std::string>().rfind("loom-compare on " + backend + ", ", 0), 0u)
                << input.at("source");
            const auto& plan = input.at("plan");
            EXPECT_EQ(plan.at("hash"), run["plan"]["hash"]) << "the plan this backend ran";
            const auto& passes = plan.at("passes");
            EXPECT_EQ(passes.size(), run["plan"]["passes"].get<std::size_t>());
            EXPECT_GE(passes.size(), 5u);
            EXPECT_EQ(input.at("schedule").size(), passes.size());
            ASSERT_EQ(input.at("timings").size(), passes.size());
            for (std::size_t i = 0; i < passes.size(); ++i)
                EXPECT_EQ(input.at("timings")[i].at("pass"), passes[i].at("name"));
            EXPECT_EQ(input.at("allocations").at("textures"), run["created"]["textures"]);
            EXPECT_EQ(input.at("allocations").at("texture_bytes"), run["created"]["bytes"]);
            EXPECT_EQ(input.at("allocators").size(), 3u);
        }
    }
    EXPECT_EQ(files_ending_in(dir, ".inspector.html"), named) << "a page for each case and backend, none besides";
}

TEST(CompareOnData, NoInspectWritesAndLinksNoPage) {
    LOOM_REQUIRE_DATA_DIR(data);
    const std::filesystem::path dir = output_dir() / "compare" / "no_inspect";
    const auto [status, json] = run_compare(dir, data / "gltf" / "Box" / "glTF-Binary" / "Box.glb",
                                            "--size 64x36 --pipeline deferred --no-inspect");
    EXPECT_EQ(status, 0) << read_file(dir / "stderr.txt");
    ASSERT_FALSE(json.is_discarded());
    ASSERT_EQ(json["cases"].size(), 1u);
    for (const auto& run : json["cases"][0]["backends"]) {
        EXPECT_TRUE(run["rendered"].get<bool>());
        EXPECT_TRUE(run["inspector"].is_null()) << run["backend"];
    }
    EXPECT_TRUE(files_ending_in(dir, ".inspector.html").empty());
    EXPECT_EQ(read_file(dir / "report.html").find("class=\"inspector\""), std::string::npos);
}

// A page that cannot be written (a directory stands where it goes) fails its case with a message
// naming the file; the run goes on, and the other backend's page is written and linked.
TEST(CompareOnData, APageThatCannotBeWrittenFailsItsCaseNamingTheFile) {
    LOOM_REQUIRE_DATA_DIR(data);
    const std::filesystem::path dir = output_dir() / "compare" / "unwritable_page";
    std::filesystem::remove_all(dir);
    const std::string blocked = "cases/Box.glb.deferred/gl.inspector.html";
    std::filesystem::create_directories(dir / blocked);
    const auto [status, json] = run_compare(dir, data / "gltf" / "Box" / "glTF-Binary" / "Box.glb",
                                            "--size 64x36 --pipeline deferred", /*keep=*/true);
    const std::string log = read_file(dir / "stderr.txt");
    EXPECT_EQ(status, 1) << log;
    ASSERT_FALSE(json.is_discarded()) << log;
    ASSERT_EQ(json["cases"].size(), 1u);
    const auto& c = json["cases"][0];
    EXPECT_EQ(c["passed"], false);
    ASSERT_EQ(c["failures"].size(), 1u) << c["failures"].dump();
    const std::string failure = c["failures"][0].get<std::string>();
    EXPECT_EQ(failure.rfind("gl inspector page " + blocked + ": Io: cannot write ", 0), 0u) << failure;
    EXPECT_NE(failure.find((dir / blocked).string()), std::string::npos) << failure;
    EXPECT_TRUE(std::filesystem::is_directory(dir / blocked)) << "what stood there is left alone";
    const std::string html = read_file(dir / "report.html");
    for (const auto& run : c["backends"]) {
        EXPECT_TRUE(run["rendered"].get<bool>()) << run["backend"];
        if (run["backend"] == "gl") {
            EXPECT_TRUE(run["inspector"].is_null());
        } else {
            ASSERT_TRUE(run["inspector"].is_string()) << run["backend"];
            EXPECT_TRUE(std::filesystem::is_regular_file(dir / run["inspector"].get<std::string>()));
        }
    }
    EXPECT_EQ(html.find("href=\"" + blocked + "\""), std::string::npos);
}

// A page loom-compare wrote, opened in headless Chromium: its script runs without an error and
// lists the plan's passes in execution order.
TEST(CompareOnData, AnInspectorPageOpensInChromiumWithTheCasesPasses) {
    LOOM_REQUIRE_DATA_DIR(data);
    LOOM_REQUIRE_CHROMIUM(chromium);
    const std::filesystem::path dir = output_dir() / "compare" / "inspector_chromium";
    const auto [status, json] =
        run_compare(dir, data / "gltf" / "Box" / "glTF-Binary" / "Box.glb", "--size 64x36 --pipeline forward");
    ASSERT_EQ(status, 0) << read_file(dir / "stderr.txt");
    ASSERT_FALSE(json.is_discarded());
    const auto& run = json["cases"][0]["backends"].back();
    ASSERT_TRUE(run["inspector"].is_string());
    const std::filesystem::path page = dir / run["inspector"].get<std::string>();
    const nlohmann::json input = inspect_test::embedded_input(read_file(page));
    ASSERT_TRUE(input.is_object());
    std::vector<std::string> order;
    for (const auto& pass : input.at("plan").at("order")) order.push_back(pass.get<std::string>());
    ASSERT_FALSE(order.empty());

    const PageDump dump = dump_dom(chromium, page, "", page.parent_path());
    EXPECT_EQ(dump.status, 0) << dump.log;
    EXPECT_EQ(attribute_of(dump.dom, "body", "data-status"), "ok") << from_element(dump.dom, "errors").substr(0, 2000);
    EXPECT_EQ(attribute_of(dump.dom, "body", "data-errors"), "0");
    const std::string_view passes = from_element(dump.dom, "pass-list");
    EXPECT_EQ(attribute_values(passes.substr(0, passes.find("</ol>")), "data-pass"), order);
}

TEST(DeferredOnData, RendersAModelOnEveryBackendWithTheSamePlan) {
    LOOM_REQUIRE_DATA_DIR(data);
    const std::filesystem::path model = data / "gltf" / "AlphaBlendModeTest" / "glTF-Binary" / "AlphaBlendModeTest.glb";
    std::string plans[2];
    std::size_t i = 0;
    for (rhi::Backend backend : backends_under_test()) {
        const std::filesystem::path dir = output_dir() / "compare" / "deferred" / std::string(rhi::backend_name(backend));
        std::filesystem::remove_all(dir);
        // One allocator on both: by default each device gets its cheapest (heap on Vulkan).
        const int status = run(LOOM_DEFERRED_EXE, "--backend " + std::string(rhi::backend_name(backend)) +
                                                      " --allocator interval --size 192x108 --scene \"" + model.string() + "\" --out \"" +
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

// --time poses the file's animations: CesiumMilkTruck's wheels turn, so the picture changes.
TEST(DeferredOnData, PosesTheFilesAnimationsAtTheTimeAsked) {
    LOOM_REQUIRE_DATA_DIR(data);
    const std::filesystem::path model = data / "gltf" / "CesiumMilkTruck" / "glTF" / "CesiumMilkTruck.gltf";
    const std::string backend(rhi::backend_name(backends_under_test().front()));
    const std::filesystem::path dir = output_dir() / "compare" / "deferred_time";
    std::filesystem::remove_all(dir);
    std::vector<rhi::Image> pictures;
    for (const std::string& time : std::vector<std::string>{"", " --time 0.625"}) {
        const std::filesystem::path out = dir / (time.empty() ? "static" : "posed");
        const int status = run(LOOM_DEFERRED_EXE, "--backend " + backend + " --size 160x90 --scene \"" + model.string() +
                                                      "\"" + time + " --out \"" + out.string() + "\"",
                               out / "stdout.txt", out / "stderr.txt");
        const std::string output = read_file(out / "stdout.txt") + read_file(out / "stderr.txt");
        ASSERT_EQ(status, 0) << output;
        EXPECT_EQ(output.find("[warning]"), std::string::npos) << output;
        EXPECT_EQ(output.find("posed at 0.625000 s (1 animation(s))") != std::string::npos, !time.empty()) << output;
        auto picture = image_io::read_png(out / "final.png");
        ASSERT_TRUE(picture.ok()) << picture.error().to_string();
        pictures.push_back(std::move(*picture));
    }
    auto change = rhi::compare_images(pictures[0], pictures[1], {0.0, false});
    ASSERT_TRUE(change.ok()) << change.error().to_string();
    EXPECT_GT(change->pixels_above_threshold, 10u) << change->summary();
}

// --animate plays CesiumMilkTruck through the retained layer and the per-draw objects side by side:
// the pictures are identical frame for frame, each frame after the first uploads the two wheels'
// records (2 x 128 bytes) into the layer and fewer bytes in all than the per-draw path, and the
// contact sheets of GL and Vulkan agree (the posed-truck tolerance above).
TEST(DeferredOnData, AnimatesCesiumMilkTruckUploadingOnlyTheWheelsAlikeOnEveryBackend) {
    LOOM_REQUIRE_DATA_DIR(data);
    const std::filesystem::path model = data / "gltf" / "CesiumMilkTruck" / "glTF" / "CesiumMilkTruck.gltf";
    const std::filesystem::path dir = output_dir() / "compare" / "deferred_animate";
    std::filesystem::remove_all(dir);
    std::vector<rhi::Image> sheets;
    for (const rhi::Backend backend : backends_under_test()) {
        const std::string name(rhi::backend_name(backend));
        SCOPED_TRACE(name);
        const std::filesystem::path out = dir / name;
        const int status = run(LOOM_DEFERRED_EXE, "--backend " + name + " --size 160x90 --scene \"" + model.string() +
                                                      "\" --animate 6 --out \"" + out.string() + "\"",
                               out / "stdout.txt", out / "stderr.txt");
        const std::string output = read_file(out / "stdout.txt") + read_file(out / "stderr.txt");
        ASSERT_EQ(status, 0) << output;
        EXPECT_EQ(output.find("[warning]"), std::string::npos) << output;
        EXPECT_NE(output.find("5 retained shape(s), 0 blended item(s), 1 animation(s) of up to 1.25"), std::string::npos)
            << output;
        EXPECT_NE(output.find("identical in 6 of 6"), std::string::npos) << output;
        const std::vector<std::vector<double>> rows = read_animation_csv(out / "animation.csv");
        ASSERT_EQ(rows.size(), 6u);
        for (std::size_t f = 0; f < rows.size(); ++f) {
            const std::vector<double>& v = rows[f];
            ASSERT_EQ(v.size(), 7u);
            EXPECT_DOUBLE_EQ(v[0], static_cast<double>(f));
            EXPECT_NEAR(v[1], 1.25 * static_cast<double>(f) / 5.0, 1e-5);
            EXPECT_EQ(v[2], 2) << "the wheels, frame " << f;
            if (f > 0) {
                EXPECT_EQ(v[4], 256) << "two records, frame " << f;
                EXPECT_LT(v[3], v[5]) << "the retained frame uploads less, frame " << f;
            }
            EXPECT_EQ(v[6], 1) << "identical pictures, frame " << f;
        }
        auto sheet = image_io::read_png(out / "animation.png");
        ASSERT_TRUE(sheet.ok()) << sheet.error().to_string();
        EXPECT_EQ(sheet->width, 3u * 160u);
        EXPECT_EQ(sheet->height, 2u * 90u);
        // The first and the fourth tile differ where the wheels turn, and only a little.
        uint64_t different = 0;
        for (uint32_t y = 0; y < 90; ++y) {
            for (uint32_t x = 0; x < 160; ++x) different += sheet->load(x, y) != sheet->load(x, 90 + y) ? 1 : 0;
        }
        EXPECT_GT(different, 20u);
        EXPECT_LT(different, 160u * 90u / 10u);
        sheets.push_back(std::move(*sheet));
    }
    if (sheets.size() == 2) {
        auto across = rhi::compare_images(sheets[0], sheets[1], {1.0, false});
        ASSERT_TRUE(across.ok()) << across.error().to_string();
        EXPECT_LE(across->pixels_above_threshold, across->pixel_count / 100) << across->summary();
        std::cout << "CesiumMilkTruck's six frames, GL against Vulkan: " << across->summary() << "\n";
    }
}

// --animate plays a skinned file (written here: the test data has no skinned model) on every
// backend: the retained and per-draw paths draw identical pictures, each frame after the first
// writes the two joints' matrices (128 bytes) into the layer and no record, the elbow bends the
// strip, and GL and Vulkan draw the same contact sheet.
TEST(DeferredAnimation, PlaysASkinnedFileWritingOnlyItsJointsAlikeOnEveryBackend) {
    const std::filesystem::path dir = output_dir() / "compare" / "deferred_skinned";
    std::filesystem::remove_all(dir);
    const std::filesystem::path model = write_skinned_gltf(dir / "model");
    std::vector<rhi::Image> sheets;
    for (const rhi::Backend backend : backends_under_test()) {
        const std::string name(rhi::backend_name(backend));
        SCOPED_TRACE(name);
        const std::filesystem::path out = dir / name;
        const int status = run(LOOM_DEFERRED_EXE, "--backend " + name + " --size 96x64 --scene \"" + model.string() +
                                                      "\" --animate 5 --out \"" + out.string() + "\"",
                               out / "stdout.txt", out / "stderr.txt");
        const std::string output = read_file(out / "stdout.txt") + read_file(out / "stderr.txt");
        ASSERT_EQ(status, 0) << output;
        EXPECT_EQ(output.find("warning"), std::string::npos) << output;
        EXPECT_NE(output.find("1 retained shape(s), 0 blended item(s), 1 animation(s) of up to 2"), std::string::npos) << output;
        EXPECT_NE(output.find("identical in 5 of 5"), std::string::npos) << output;
        const std::vector<std::vector<double>> rows = read_animation_csv(out / "animation.csv");
        ASSERT_EQ(rows.size(), 5u);
        for (std::size_t f = 1; f < rows.size(); ++f) {
            EXPECT_EQ(rows[f][2], 1) << "the skinned item, frame " << f;
            EXPECT_EQ(rows[f][4], 128) << "two joint matrices and no record, frame " << f;
        }
        auto sheet = image_io::read_png(out / "animation.png");
        ASSERT_TRUE(sheet.ok()) << sheet.error().to_string();
        ASSERT_EQ(sheet->width, 3u * 96u);
        ASSERT_EQ(sheet->height, 2u * 64u);
        // Frame 0 (straight) against frame 2 (bent 45 degrees at 1 s).
        uint64_t different = 0;
        for (uint32_t y = 0; y < 64; ++y) {
            for (uint32_t x = 0; x < 96; ++x) different += sheet->load(x, y) != sheet->load(2 * 96 + x, y) ? 1 : 0;
        }
        EXPECT_GT(different, 30u);
        sheets.push_back(std::move(*sheet));
    }
    if (sheets.size() == 2) {
        auto across = rhi::compare_images(sheets[0], sheets[1], {0.0, false});
        ASSERT_TRUE(across.ok()) << across.error().to_string();
        EXPECT_TRUE(across->equal()) << across->summary();
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
        {"--time 1", "--time needs a glTF scene"},
        {"--scene \"" + (data / "gltf" / "Box" / "glTF" / "Box.gltf").string() + "\" --time -1",
         "--time expects seconds (a number, 0 or more), got '-1'"},
        {"--animate 3", "--animate needs a glTF scene"},
        {"--scene \"" + (data / "gltf" / "Box" / "glTF" / "Box.gltf").string() + "\" --animate 0",
         "--animate expects a number of frames (1 to 4096), got '0'"},
        {"--scene \"" + (data / "gltf" / "Box" / "glTF" / "Box.gltf").string() + "\" --animate 3",
         "Box.gltf: the file has no animation to play"},
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

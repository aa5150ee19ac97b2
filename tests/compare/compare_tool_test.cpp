// loom-compare's pieces without a GPU: the command line, which files a run covers, the reports.
#include <fstream>
#include <limits>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "compare_options.hpp"
#include "loom_test/test_support.hpp"
#include "report.hpp"
#include "scene_files.hpp"

namespace loom::test {
namespace {

using namespace loom::compare;

Result<Options> parse(std::vector<std::string> args) { return parse_options(args); }

TEST(CompareOptions, DefaultsAndEveryOption) {
    auto defaults = parse({});
    ASSERT_TRUE(defaults.ok());
    EXPECT_EQ(defaults->pipelines, (std::vector<PipelineKind>{PipelineKind::Deferred, PipelineKind::Forward}));
    EXPECT_TRUE(defaults->scenes.empty());
    EXPECT_EQ(defaults->threshold, 1.0);
    EXPECT_FALSE(defaults->json);

    auto options = parse({"--pipeline", "forward", "--scenes", "a.gltf", "dir", "--size=256x144", "--out", "o",
                          "--threshold", "2.5", "--max-differing", "0.001", "--json", "--expect-errors"});
    ASSERT_TRUE(options.ok()) << options.error().to_string();
    EXPECT_EQ(options->pipelines, std::vector<PipelineKind>{PipelineKind::Forward});
    EXPECT_EQ(options->scenes, (std::vector<std::filesystem::path>{"a.gltf", "dir"}));
    EXPECT_EQ(options->width, 256u);
    EXPECT_EQ(options->height, 144u);
    EXPECT_EQ(options->out, "o");
    EXPECT_EQ(options->threshold, 2.5);
    EXPECT_EQ(options->max_differing, 0.001);
    EXPECT_TRUE(options->json);
    EXPECT_TRUE(options->expect_errors);
    EXPECT_EQ(parse({"--pipeline", "deferred"})->pipelines, std::vector<PipelineKind>{PipelineKind::Deferred});
    EXPECT_EQ(parse({"--pipeline", "all"})->pipelines.size(), 2u);
}

TEST(CompareOptions, MistakesAreOneLineErrorsNamingTheArgument) {
    const std::pair<std::vector<std::string>, std::string> cases[] = {
        {{"--pipeline", "sideways"}, "--pipeline expects deferred, forward or all, got 'sideways'"},
        {{"--scenes"}, "--scenes needs at least one file or directory"},
        {{"--scenes", "--json"}, "--scenes needs at least one file or directory"},
        {{"--size", "wide"}, "--size expects WIDTHxHEIGHT"},
        {{"--threshold", "-1"}, "--threshold expects a number from 0"},
        {{"--max-differing", "2"}, "--max-differing expects a number from 0"},
        {{"--out"}, "--out needs a value"},
        {{"--frobnicate"}, "unknown argument '--frobnicate'"},
    };
    for (const auto& [args, message] : cases) {
        auto parsed = parse(args);
        ASSERT_FALSE(parsed.ok()) << args.front();
        EXPECT_EQ(parsed.error().code, ErrorCode::InvalidArgument);
        EXPECT_EQ(parsed.error().message.rfind(message, 0), 0u) << parsed.error().message;
        EXPECT_EQ(parsed.error().message.find('\n'), std::string::npos);
    }
}

class SceneFilesTest : public ::testing::Test {
protected:
    void SetUp() override {
        // One tree per test: ctest runs this fixture's tests in parallel, and each rebuilds it.
        root_ = output_dir() / "compare" / "scene_files" /
                ::testing::UnitTest::GetInstance()->current_test_info()->name() / "models";
        std::filesystem::remove_all(root_);
        for (const char* file : {"b/model.gltf", "a/model.GLB", "a/notes.txt", "a/data.bin", "invalid/broken.gltf",
                                 "c/invalid/deeper.glb"}) {
            std::filesystem::create_directories((root_ / file).parent_path());
            std::ofstream(root_ / file) << "{}";
        }
    }
    std::filesystem::path root_;
};

TEST_F(SceneFilesTest, SearchesDirectoriesSortedSkippingInvalidOnes) {
    const std::vector<std::filesystem::path> inputs{root_};
    auto files = find_scene_files(inputs);
    ASSERT_TRUE(files.ok()) << files.error().to_string();
    ASSERT_EQ(files->size(), 2u);
    EXPECT_EQ((*files)[0].name, "models/a/model.GLB");
    EXPECT_EQ((*files)[1].name, "models/b/model.gltf");
    EXPECT_EQ((*files)[1].path, root_ / "b" / "model.gltf");
}

TEST_F(SceneFilesTest, InvalidDirectoriesAndFilesGivenThemselvesAreSearched) {
    const std::vector<std::filesystem::path> inputs{root_ / "invalid", root_ / "a" / "notes.txt"};
    auto files = find_scene_files(inputs);
    ASSERT_TRUE(files.ok()) << files.error().to_string();
    ASSERT_EQ(files->size(), 2u);
    EXPECT_EQ((*files)[0].name, "invalid/broken.gltf");
    EXPECT_EQ((*files)[1].name, "notes.txt");  // a file given by itself, whatever its extension
}

TEST_F(SceneFilesTest, AMissingPathIsAnError) {
    const std::vector<std::filesystem::path> inputs{root_ / "nowhere"};
    auto files = find_scene_files(inputs);
    ASSERT_FALSE(files.ok());
    EXPECT_EQ(files.error().message, (root_ / "nowhere").string() + ": no such file or directory");
}

std::vector<CaseResult> two_cases() {
    CaseResult passed;
    passed.scene = "models/Box.gltf";
    passed.pipeline = "deferred";
    passed.id = "models_Box.gltf.deferred";
    passed.runs = {BackendRun{rhi::Backend::OpenGL}, BackendRun{rhi::Backend::Vulkan}};
    passed.image = ImageMetrics{0.0, 0, 100, std::numeric_limits<double>::infinity(), "cases/x/diff.png"};
    CaseResult failed = passed;
    failed.scene = "models/<Duck>.gltf";
    failed.id = "models_Duck.gltf.forward";
    failed.pipeline = "forward";
    failed.image = ImageMetrics{12.0, 3, 100, 41.5, "cases/y/diff.png"};
    failed.failures = {"pictures differ: 3 pixels"};
    return {passed, failed};
}

TEST(CompareReport, JsonHasTheCasesAndTheSummary) {
    const std::vector<CaseResult> cases = two_cases();
    Options options;
    const RunInfo run{&options, {rhi::Backend::OpenGL, rhi::Backend::Vulkan}, summarize(cases, 1.25)};
    const nlohmann::json json = nlohmann::json::parse(report_json(cases, run));
    EXPECT_EQ(json["summary"]["cases"], 2);
    EXPECT_EQ(json["summary"]["passed"], 1);
    EXPECT_EQ(json["summary"]["failed"], 1);
    EXPECT_EQ(json["summary"]["backends"], (nlohmann::json{"gl", "vulkan"}));
    ASSERT_EQ(json["cases"].size(), 2u);
    EXPECT_EQ(json["cases"][0]["passed"], true);
    EXPECT_TRUE(json["cases"][0]["image"]["psnr"].is_null()) << "identical pictures: no finite PSNR";
    EXPECT_EQ(json["cases"][0]["image"]["identical"], true);
    EXPECT_EQ(json["cases"][1]["passed"], false);
    EXPECT_EQ(json["cases"][1]["failures"][0], "pictures differ: 3 pixels");
    EXPECT_EQ(json["cases"][1]["image"]["psnr"], 41.5);
    EXPECT_EQ(json["cases"][1]["backends"][1]["backend"], "vulkan");
}

TEST(CompareReport, HtmlShowsFailuresFirstWithTheirPictures) {
    const std::vector<CaseResult> cases = two_cases();
    Options options;
    const RunInfo run{&options, {rhi::Backend::OpenGL, rhi::Backend::Vulkan}, summarize(cases, 1.0)};
    const std::string html = report_html(cases, run);
    const auto failed_at = html.find("id=\"models_Duck.gltf.forward\"");
    const auto passed_at = html.find("id=\"models_Box.gltf.deferred\"");
    ASSERT_NE(failed_at, std::string::npos);
    ASSERT_NE(passed_at, std::string::npos);
    EXPECT_LT(failed_at, passed_at);
    EXPECT_NE(html.find("&lt;Duck&gt;"), std::string::npos) << "names are escaped";
    EXPECT_NE(html.find("<img src=\"cases/y/diff.png\""), std::string::npos);
    EXPECT_NE(html.find("2 case(s)"), std::string::npos);
    EXPECT_EQ(report_order(cases).front()->id, "models_Duck.gltf.forward");
    // One file but for the pictures: inline scripts and style, nothing fetched.
    EXPECT_EQ(html.find("<script src"), std::string::npos);
    EXPECT_EQ(html.find("<link"), std::string::npos);
    EXPECT_EQ(html.find("http"), std::string::npos);
    EXPECT_NE(html.find("id=\"viewer\""), std::string::npos);
}

}  // namespace
}  // namespace loom::test

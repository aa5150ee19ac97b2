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
    EXPECT_TRUE(defaults->inspector_pages);

    auto options =
        parse({"--pipeline", "forward", "--scenes", "a.gltf", "dir", "--size=256x144", "--out", "o", "--threshold",
               "2.5", "--max-differing", "0.001", "--json", "--expect-errors", "--no-inspect"});
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
    EXPECT_FALSE(options->inspector_pages);
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
    passed.runs[0].inspector_file = "cases/models_Box.gltf.deferred/gl.inspector.html";
    passed.runs[1].inspector_file = "cases/models_Box.gltf.deferred/vulkan.inspector.html";
    passed.image = ImageMetrics{0.0, 0, 100, std::numeric_limits<double>::infinity(), "cases/x/diff.png"};
    CaseResult failed = passed;
    failed.scene = "models/<Duck>.gltf";
    failed.id = "models_Duck.gltf.forward";
    failed.pipeline = "forward";
    failed.image = ImageMetrics{12.0, 3, 100, 41.5, "cases/y/diff.png"};
    failed.failures = {"pictures differ: 3 pixels"};
    // GL's page was written, Vulkan's was not (a failure of its own).
    failed.runs[0].inspector_file = "cases/models_Duck.gltf.forward/gl.inspector.html";
    failed.runs[1].inspector_file.clear();
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
    EXPECT_EQ(json["cases"][0]["backends"][1]["inspector"], "cases/models_Box.gltf.deferred/vulkan.inspector.html");
    EXPECT_EQ(json["cases"][1]["backends"][0]["inspector"], "cases/models_Duck.gltf.forward/gl.inspector.html");
    EXPECT_TRUE(json["cases"][1]["backends"][1]["inspector"].is_null()) << "no page written: none named";
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

// Each written page is linked twice, from the table (its row) and from its case, named by its
// backend; a backend without a page has no link.
TEST(CompareReport, HtmlLinksEveryInspectorPageFromTheTableAndItsCase) {
    const std::vector<CaseResult> cases = two_cases();
    Options options;
    const RunInfo run{&options, {rhi::Backend::OpenGL, rhi::Backend::Vulkan}, summarize(cases, 1.0)};
    const std::string html = report_html(cases, run);
    const auto count = [&](const std::string& text) {
        std::size_t n = 0;
        for (std::size_t at = html.find(text); at != std::string::npos; at = html.find(text, at + 1)) ++n;
        return n;
    };
    for (const CaseResult& c : cases) {
        for (const BackendRun& backend_run : c.runs) {
            const std::string backend(rhi::backend_name(backend_run.backend));
            if (backend_run.inspector_file.empty()) continue;
            EXPECT_EQ(count("<a class=\"inspector\" data-backend=\"" + backend + "\" href=\"" +
                            backend_run.inspector_file + "\">" + backend + "</a>"),
                      2u)
                << backend_run.inspector_file;
        }
    }
    EXPECT_EQ(count("class=\"inspector\""), 6u) << "three pages, two links each";
    // The table's link comes in the case's row, before the case's section.
    const auto row = html.find("<tr><td class=\"fail\">FAIL</td><td><a href=\"#models_Duck.gltf.forward\">");
    ASSERT_NE(row, std::string::npos);
    const auto row_end = html.find("</tr>", row);
    EXPECT_NE(html.substr(row, row_end - row).find("cases/models_Duck.gltf.forward/gl.inspector.html"),
              std::string::npos);
    const auto section = html.find("id=\"models_Duck.gltf.forward\"");
    const auto next_section = html.find("id=\"models_Box.gltf.deferred\"");
    EXPECT_NE(html.substr(section, next_section - section).find("cases/models_Duck.gltf.forward/gl.inspector.html"),
              std::string::npos);
}

}  // namespace
}  // namespace loom::test

// Runs the loom-plan tool as a user would: on the sample graphs, with --json and --dot, and on
// broken graphs and arguments.
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <nlohmann/json.hpp>

#include "loom_test/test_support.hpp"

namespace {

struct ToolRun {
    int status = -1;
    std::string out;
    std::string err;
};

std::string read_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

ToolRun run_tool(const std::string& arguments) {
    // One directory per test: ctest runs the tests of this file in parallel.
    const std::filesystem::path dir =
        loom::test::output_dir() / "loom_plan" / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::filesystem::create_directories(dir);
    const auto out = dir / "stdout.txt";
    const auto err = dir / "stderr.txt";
    const std::string command = std::string("\"") + LOOM_PLAN_TOOL + "\" " + arguments + " >\"" + out.string() +
                                "\" 2>\"" + err.string() + "\"";
    const int raw = std::system(command.c_str());
    ToolRun run;
    run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    run.out = read_file(out);
    run.err = read_file(err);
    return run;
}

std::string graph(std::string_view name) { return std::string("\"") + LOOM_PLAN_GRAPHS + "/" + std::string(name) + "\""; }
std::string broken(std::string_view name) { return std::string("\"") + LOOM_BROKEN_GRAPHS + "/" + std::string(name) + "\""; }

int line_count(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

TEST(PlanTool, PrintsATableForEveryAllocator) {
    for (const char* allocator : {"paper", "interval", "heap"}) {
        const ToolRun run = run_tool(graph("figure2.json") + " --allocator " + allocator);
        EXPECT_EQ(run.status, 0) << run.err;
        EXPECT_TRUE(run.err.empty()) << run.err;
        EXPECT_NE(run.out.find(std::string("plan: allocator ") + allocator), std::string::npos) << run.out;
        EXPECT_NE(run.out.find("composite.final (output)"), std::string::npos) << run.out;
    }
}

TEST(PlanTool, JsonOutputParsesWithTheFigure2Summary) {
    for (const char* allocator : {"paper", "interval"}) {
        const ToolRun run = run_tool(graph("figure2.json") + " --json --allocator " + allocator);
        ASSERT_EQ(run.status, 0) << run.err;
        const auto json = nlohmann::json::parse(run.out);
        const auto& summary = json.at("summary");
        EXPECT_EQ(summary.at("textures"), 6) << allocator;
        EXPECT_EQ(summary.at("naive_textures"), 8) << allocator;
        EXPECT_EQ(summary.at("lower_bound_textures"), 6) << allocator;
        // 2048² Depth32F + 5 (plan) or 7 (naive) × 1920x1080 RGBA16Float in 64 KiB pages.
        EXPECT_EQ(summary.at("bytes"), 16777216 + 5 * 16646144) << allocator;
        EXPECT_EQ(summary.at("naive_bytes"), 16777216 + 7 * 16646144) << allocator;
        EXPECT_EQ(summary.at("lower_bound_bytes"), 16777216 + 5 * 16646144) << allocator;
        EXPECT_EQ(json.at("order"), nlohmann::json({"shadow", "geometry", "deferred", "blur", "composite"}));
        EXPECT_TRUE(json.at("culled").empty());
        EXPECT_EQ(json.at("resources").size(), 8u);
    }
    const ToolRun heap = run_tool(graph("figure2.json") + " --json --allocator heap");
    ASSERT_EQ(heap.status, 0) << heap.err;
    const auto json = nlohmann::json::parse(heap.out);
    EXPECT_EQ(json.at("summary").at("bytes"), json.at("summary").at("lower_bound_bytes"));
}

TEST(PlanTool, OtherSampleGraphsPlan) {
    const ToolRun tint = run_tool(graph("deferred_tint.json") + " --json");
    ASSERT_EQ(tint.status, 0) << tint.err;
    EXPECT_EQ(nlohmann::json::parse(tint.out).at("summary").at("naive_textures"), 4);
    const ToolRun postfx = run_tool(graph("postfx.json") + " --json --frame 640x360");
    ASSERT_EQ(postfx.status, 0) << postfx.err;
    const auto json = nlohmann::json::parse(postfx.out);
    EXPECT_EQ(json.at("culled"), nlohmann::json({"debug_motion"}));
    EXPECT_EQ(json.at("frame").at("width"), 640);
}

TEST(PlanTool, WritesDot) {
    const std::filesystem::path dot = loom::test::output_dir() / "loom_plan" / "figure2.dot";
    std::filesystem::remove(dot);
    const ToolRun run = run_tool(graph("figure2.json") + " --dot \"" + dot.string() + "\"");
    ASSERT_EQ(run.status, 0) << run.err;
    const std::string text = read_file(dot);
    EXPECT_EQ(text.rfind("digraph plan {", 0), 0u);
    EXPECT_NE(text.find("2: deferred"), std::string::npos);
}

TEST(PlanTool, BrokenGraphsFailWithOneLine) {
    struct Case {
        std::string arguments;
        std::string error;
    };
    const Case cases[] = {
        {broken("broken_cycle.json"),
         "broken_cycle.json: /passes/0: cycle: a -> b -> a (a.out feeds b.in; b.out feeds a.in) (see also /passes/1)\n"},
        {broken("broken_unconnected.json"), "broken_unconnected.json: /passes/1/inputs/1: required input lit.shadow is not "
                                            "connected\n"},
        {broken("broken_format.json"), "/passes/2/outputs/0/format: unknown format \"RGBA17F\"\n"},
        {broken("broken_syntax.json"), "invalid JSON"},
        {broken("missing.json"), "loom-plan: Io: cannot read graph file"},
        // Hostile input: each used to abort, or to plan something other than what was written.
        {broken("broken_huge_number.json"), "broken_huge_number.json:1:21: the number 1e400 at /frame/width is out of "
                                            "range (beyond a double)\n"},
        {broken("broken_duplicate_key.json"), "broken_duplicate_key.json:1:77: duplicate key \"outputs\" at /outputs\n"},
        {broken("broken_dotted_port.json"), "/passes/0: add_pass: pass 'a': the port name 'b.x' contains '.', which "
                                            "separates pass and port names\n"},
    };
    for (const Case& c : cases) {
        const ToolRun run = run_tool(c.arguments);
        EXPECT_EQ(run.status, 1) << c.arguments;
        EXPECT_TRUE(run.out.empty()) << run.out;
        EXPECT_EQ(line_count(run.err), 1) << run.err;
        EXPECT_NE(run.err.find(c.error), std::string::npos) << run.err;
    }
}

TEST(PlanTool, BadArgumentsFailWithOneLine) {
    for (const std::string& arguments : {std::string(""), graph("figure2.json") + " --allocator best",
                                        graph("figure2.json") + " --frame 12", graph("figure2.json") + " --bogus",
                                        graph("figure2.json") + " --dot"}) {
        const ToolRun run = run_tool(arguments);
        EXPECT_EQ(run.status, 2) << arguments;
        EXPECT_EQ(line_count(run.err), 1) << run.err;
        EXPECT_EQ(run.err.rfind("loom-plan: ", 0), 0u) << run.err;
    }
}

}  // namespace

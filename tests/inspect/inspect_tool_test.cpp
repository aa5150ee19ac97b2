// loom-inspect and loom-plan --inspect run as a user would, without a browser: what they write,
// and the errors a wrong file or argument gets.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "inspect_test_support.hpp"
#include "loom_test/test_support.hpp"

namespace {

using namespace loom::inspect_test;

std::string graph(std::string_view name) { return quoted(std::filesystem::path(LOOM_PLAN_GRAPHS) / name); }

std::size_t count(std::string_view text, std::string_view what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string_view::npos; at = text.find(what, at + what.size())) ++n;
    return n;
}

TEST(InspectTool, PlanInspectWritesThePlanItsScheduleAndEveryAllocator) {
    const auto dir = test_dir();
    const ToolRun plan = run(LOOM_PLAN_TOOL, graph("figure2.json") + " --allocator heap --json --inspect " + quoted(dir / "in.json"));
    ASSERT_EQ(plan.status, 0) << plan.err;
    const auto input = nlohmann::json::parse(read_file(dir / "in.json"));
    EXPECT_EQ(input.at("format"), "loom-inspect-input");
    EXPECT_EQ(input.at("version"), 1);
    // The plan inside is the one --json printed.
    EXPECT_EQ(input.at("plan"), nlohmann::json::parse(plan.out));
    ASSERT_EQ(input.at("schedule").size(), input.at("plan").at("passes").size());
    EXPECT_EQ(input.at("schedule")[0].at("pass"), "shadow");
    std::vector<std::string> allocators;
    for (const auto& row : input.at("allocators")) allocators.push_back(row.at("allocator"));
    EXPECT_EQ(allocators, (std::vector<std::string>{"paper", "interval", "heap"}));
    EXPECT_EQ(input.at("allocators")[2].at("bytes"), input.at("plan").at("summary").at("bytes"));
}

TEST(InspectTool, PlanInspectIsRefusedWithCompare) {
    const ToolRun run_ = run(LOOM_PLAN_TOOL, graph("figure2.json") + " --compare --inspect x.json");
    EXPECT_EQ(run_.status, 2);
    EXPECT_NE(run_.err.find("leave out --inspect"), std::string::npos) << run_.err;
}

TEST(InspectTool, AcceptsAPlanAGraphAndAnInputAlike) {
    const auto dir = test_dir();
    ASSERT_EQ(run(LOOM_PLAN_TOOL, graph("postfx.json") + " --json").status, 0);
    const ToolRun plan_json = run(LOOM_PLAN_TOOL, graph("postfx.json") + " --json");
    write_file(dir / "plan.json", plan_json.out);
    ASSERT_EQ(run(LOOM_PLAN_TOOL, graph("postfx.json") + " --inspect " + quoted(dir / "in.json")).status, 0);
    for (const char* source : {"plan.json", "in.json"}) {
        const ToolRun made = run(LOOM_INSPECT_TOOL, quoted(dir / source) + " --out " + quoted(dir / (std::string(source) + ".html")));
        EXPECT_EQ(made.status, 0) << made.err;
    }
    const ToolRun from_graph = run(LOOM_INSPECT_TOOL, graph("postfx.json") + " --out " + quoted(dir / "graph.html"));
    EXPECT_EQ(from_graph.status, 0) << from_graph.err;
    // The same plan in all three pages, and the barriers only where the input carries them.
    const nlohmann::json plan = nlohmann::json::parse(plan_json.out);
    const nlohmann::json from_plan = embedded_input(read_file(dir / "plan.json.html"));
    const nlohmann::json from_input = embedded_input(read_file(dir / "in.json.html"));
    const nlohmann::json from_graph_file = embedded_input(read_file(dir / "graph.html"));
    EXPECT_EQ(from_plan.at("plan"), plan);
    EXPECT_EQ(from_input, nlohmann::json::parse(read_file(dir / "in.json"))) << "an inspector input is embedded as it is";
    EXPECT_EQ(from_graph_file.at("plan").at("hash"), plan.at("hash"));
    EXPECT_FALSE(from_plan.contains("schedule"));
    EXPECT_TRUE(from_input.contains("schedule"));
    EXPECT_TRUE(from_graph_file.contains("schedule"));
}

TEST(InspectTool, NamesCannotEndTheEmbeddedScript) {
    const auto dir = test_dir();
    const ToolRun plan_json = run(LOOM_PLAN_TOOL, graph("figure2.json") + " --json");
    ASSERT_EQ(plan_json.status, 0);
    auto plan = nlohmann::json::parse(plan_json.out);
    // A name with markup, as a hand-edited plan may have: embedded, it must stay text.
    plan["passes"][0]["name"] = "shadow</script><script>alert(1)</script><!--";
    write_file(dir / "plan.json", plan.dump());
    const ToolRun made = run(LOOM_INSPECT_TOOL, quoted(dir / "plan.json") + " --out " + quoted(dir / "page.html") + " --title \"<b>x</b>\"");
    ASSERT_EQ(made.status, 0) << made.err;
    const std::string page = read_file(dir / "page.html");
    // The template's own scripts: the error collector, the input, the inflater and the inspector.
    EXPECT_EQ(count(page, "</script>"), 4u);
    EXPECT_EQ(count(page, "<!--"), 0u);
    // The input is compressed, in base64: the name is in it, unchanged, and not in the page's text.
    EXPECT_EQ(embedded_input(page).at("plan").at("passes")[0].at("name"), plan["passes"][0]["name"]);
    EXPECT_EQ(page.find("shadow<"), std::string::npos);
    EXPECT_NE(page.find("&lt;b&gt;x&lt;/b&gt;"), std::string::npos);
}

TEST(InspectTool, AWrongFileIsAnErrorNamingTheFileAndMember) {
    const auto dir = test_dir();
    const ToolRun plan_json = run(LOOM_PLAN_TOOL, graph("figure2.json") + " --json");
    auto plan = nlohmann::json::parse(plan_json.out);
    plan["resources"][2]["lifetime"] = {3, 1};
    write_file(dir / "plan.json", plan.dump());
    ToolRun made = run(LOOM_INSPECT_TOOL, quoted(dir / "plan.json") + " --out " + quoted(dir / "page.html"));
    EXPECT_EQ(made.status, 1);
    EXPECT_NE(made.err.find("plan.json: /resources/2/lifetime: first is after last"), std::string::npos) << made.err;

    plan = nlohmann::json::parse(plan_json.out);
    plan["passes"][1]["ports"][0]["resource"] = 99;
    write_file(dir / "plan.json", plan.dump());
    made = run(LOOM_INSPECT_TOOL, quoted(dir / "plan.json") + " --out " + quoted(dir / "page.html"));
    EXPECT_EQ(made.status, 1);
    EXPECT_NE(made.err.find("/passes/1/ports/0/resource: 99 is not a resource index"), std::string::npos) << made.err;

    write_file(dir / "broken.json", "{\"passes\": [");
    made = run(LOOM_INSPECT_TOOL, quoted(dir / "broken.json"));
    EXPECT_EQ(made.status, 1);
    EXPECT_NE(made.err.find("broken.json: not valid JSON"), std::string::npos) << made.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "page.html"));
}

TEST(InspectTool, TimingsOfAPassThePlanLacksAreRefused) {
    const auto dir = test_dir();
    write_file(dir / "timings.json", R"({"timings": [{"pass": "shadow", "cpu_ms": 0.5, "gpu_ms": null},
                                                     {"pass": "bloom", "cpu_ms": 0.5, "gpu_ms": 1.0}]})");
    const ToolRun made = run(LOOM_INSPECT_TOOL, graph("figure2.json") + " --timings " + quoted(dir / "timings.json") +
                                                    " --out " + quoted(dir / "page.html"));
    EXPECT_EQ(made.status, 1);
    EXPECT_NE(made.err.find("timings.json: /timings/1/pass: 'bloom' is not a pass that runs in the plan"), std::string::npos)
        << made.err;
}

// write_page_file, which loom-compare's pages go through too: a page that cannot be written is
// an Io error naming the file, and what stood at its path is left alone.
TEST(InspectTool, AnOutputThatCannotBeWrittenIsAnIoErrorNamingIt) {
    const auto dir = test_dir();
    for (const std::filesystem::path& out : {dir / "missing" / "page.html", dir / "taken.html"}) {
        if (out.filename() == "taken.html") std::filesystem::create_directory(out);
        const ToolRun made = run(LOOM_INSPECT_TOOL, graph("figure2.json") + " --out " + quoted(out));
        EXPECT_EQ(made.status, 1) << out;
        EXPECT_EQ(made.err, "loom-inspect: Io: cannot write " + out.string() + "\n");
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "missing"));
    EXPECT_TRUE(std::filesystem::is_directory(dir / "taken.html"));
}

TEST(InspectTool, BadArgumentsAreArgumentErrors) {
    EXPECT_EQ(run(LOOM_INSPECT_TOOL, "").status, 2);
    EXPECT_EQ(run(LOOM_INSPECT_TOOL, graph("figure2.json") + " --bogus 1").status, 2);
    EXPECT_EQ(run(LOOM_INSPECT_TOOL, graph("figure2.json") + " --frame 0x3").status, 2);
    const ToolRun allocator = run(LOOM_INSPECT_TOOL, graph("figure2.json") + " --allocator nope --out /dev/null");
    EXPECT_EQ(allocator.status, 2) << allocator.err;
    EXPECT_NE(allocator.err.find("nope"), std::string::npos) << allocator.err;
}

// The input a rendering sample writes: the plan of the frame it rendered with the schedule, a
// timing per pass, what the executor created and every allocator's figures; loom-inspect reads it.
void check_sample_input(const std::string& program, const std::string& arguments) {
    const auto dir = test_dir();
    const ToolRun rendered = run(program, "--backend gl --out " + quoted(dir / "out") + " --inspect " + quoted(dir / "in.json") + " " + arguments);
    ASSERT_EQ(rendered.status, 0) << rendered.err;
    const auto input = nlohmann::json::parse(read_file(dir / "in.json"));
    const auto& passes = input.at("plan").at("passes");
    EXPECT_EQ(input.at("schedule").size(), passes.size());
    ASSERT_EQ(input.at("timings").size(), passes.size());
    for (std::size_t i = 0; i < passes.size(); ++i) EXPECT_EQ(input.at("timings")[i].at("pass"), passes[i].at("name"));
    EXPECT_GT(input.at("allocations").at("textures"), 0);
    EXPECT_EQ(input.at("allocators").size(), 3u);
    EXPECT_NE(input.at("source").get<std::string>().find(" on gl, "), std::string::npos) << input.at("source");
    // The same plan the sample wrote as plan.json.
    EXPECT_EQ(input.at("plan"), nlohmann::json::parse(read_file(dir / "out" / "plan.json")));
    const ToolRun made = run(LOOM_INSPECT_TOOL, quoted(dir / "in.json") + " --out " + quoted(dir / "page.html"));
    EXPECT_EQ(made.status, 0) << made.err;
}

TEST(InspectTool, DeferredSampleWritesItsFramesInput) {
#ifdef LOOM_DEFERRED_EXE
    check_sample_input(LOOM_DEFERRED_EXE, "--size 64x48");
#else
    GTEST_SKIP() << "loom-deferred is not built (LOOM_WITH_GLTF=OFF)";
#endif
}

TEST(InspectTool, EngineSampleWritesItsFramesInput) {
#ifdef LOOM_ENGINE_EXE
    check_sample_input(LOOM_ENGINE_EXE, "--size 128x96 --shadow-size 256 --lights 32");
#else
    GTEST_SKIP() << "loom-engine is not built (LOOM_WITH_GLTF=OFF)";
#endif
}

}  // namespace

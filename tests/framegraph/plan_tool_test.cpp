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

// The summary of `graph` planned by `allocator` in declared order (the figures the guides
// quote), as loom-plan --json prints it.
nlohmann::json summary_of(std::string_view graph_file, const char* allocator) {
    const ToolRun run = run_tool(graph(graph_file) + " --order declared --json --allocator " + allocator);
    EXPECT_EQ(run.status, 0) << run.err;
    return run.status == 0 ? nlohmann::json::parse(run.out).at("summary") : nlohmann::json{};
}

// Figures are the DefaultMemoryModel's at 1920x1080: textures in 64 KiB pages, buffers in
// 256-byte steps.
TEST(PlanTool, BloomPyramidDownAndUpSamplesMipByMipInOneTexture) {
    // scene.hdr 1920x1080 RGBA16Float (254 pages), the 960x540 4-mip pyramid (85 pages), the
    // final RGBA8 (127 pages): all three live at the composite, so every allocator needs them all.
    constexpr uint64_t kBytes = 16646144 + 5570560 + 8323072;
    for (const char* allocator : {"paper", "interval", "heap"}) {
        const auto summary = summary_of("bloom_pyramid.json", allocator);
        EXPECT_EQ(summary.at("textures"), 3) << allocator;
        EXPECT_EQ(summary.at("buffers"), 0) << allocator;
        EXPECT_EQ(summary.at("bytes"), kBytes) << allocator;
        EXPECT_EQ(summary.at("lower_bound_bytes"), kBytes) << allocator;
    }
    const ToolRun run = run_tool(graph("bloom_pyramid.json"));
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find("  4  down3      <src=t1(mip 2)  <>pyramid=t1(mip 3)\n"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("  5  up2        <src=t1(mip 3)  <>pyramid=t1(mip 2)\n"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("  bright.pyramid            RGBA16Float  960x540 m4  1-8   t1       5.3 MiB\n"),
              std::string::npos)
        << run.out;
}

TEST(PlanTool, HzbChainIsBuiltByComputeMipByMipAndAliasesTheColourInAHeap) {
    // Depth32F (127 pages), the 960x540 R32Float 5-mip chain (43 pages), the RGBA16Float colour
    // (254 pages) and the 20 KiB indirect draw buffer.
    const auto paper = summary_of("hzb_chain.json", "paper");
    EXPECT_EQ(paper, nlohmann::json::parse(R"({"textures": 3, "bytes": 27807744, "naive_textures": 3,
        "naive_bytes": 27807744, "lower_bound_textures": 3, "lower_bound_bytes": 24989696, "buffers": 1,
        "buffer_bytes": 20480, "naive_buffers": 1, "lower_bound_buffers": 1})"));
    EXPECT_EQ(summary_of("hzb_chain.json", "interval"), paper);
    // The chain dies at the culling pass, before the colour is drawn: in a heap they share bytes,
    // and the heap is the lower bound (depth + draws + colour, live together at the draw).
    const auto heap = summary_of("hzb_chain.json", "heap");
    EXPECT_EQ(heap.at("bytes"), 8323072 + 20480 + 16646144);
    EXPECT_EQ(heap.at("bytes"), heap.at("lower_bound_bytes"));

    const ToolRun run = run_tool(graph("hzb_chain.json"));
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find("  2  hzb1 [compute]  <src=t1(mip 0)  <>hzb=t1(mip 1)\n"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("  cull.draws  20480 B aligned 16  storage|indirect  6-7   b0      20.0 KiB\n"),
              std::string::npos)
        << run.out;
    EXPECT_NE(run.out.find("  plan         3         1        26.5 MiB  1.113\n"), std::string::npos) << run.out;
}

TEST(PlanTool, LightListIsAComputeBuiltBufferReadByTheLightingPass) {
    // 120 x 68 tiles of 1 KiB, and 20 bytes of indirect arguments in one 256-byte step.
    for (const char* allocator : {"paper", "interval", "heap"}) {
        const auto summary = summary_of("light_list.json", allocator);
        EXPECT_EQ(summary.at("buffers"), 2) << allocator;
        EXPECT_EQ(summary.at("naive_buffers"), 2) << allocator;
        EXPECT_EQ(summary.at("lower_bound_buffers"), 2) << allocator;
        EXPECT_EQ(summary.at("buffer_bytes"), 8355840 + 256) << allocator;
        EXPECT_EQ(summary.at("bytes"), 8323072 + 16646144 + 8355840 + 256) << allocator;
        EXPECT_EQ(summary.at("lower_bound_bytes"), summary.at("bytes")) << allocator;
    }
    const ToolRun run = run_tool(graph("light_list.json") + " --order declared --json");
    ASSERT_EQ(run.status, 0) << run.err;
    const auto json = nlohmann::json::parse(run.out);
    EXPECT_EQ(json.at("buffers")[0].at("size"), 8355840);
    EXPECT_EQ(json.at("buffers")[0].at("usage"), nlohmann::json({"storage"}));
    EXPECT_EQ(json.at("buffers")[1].at("size"), 20);
    EXPECT_EQ(json.at("buffers")[1].at("usage"), nlohmann::json({"storage", "indirect"}));
    EXPECT_EQ(json.at("passes")[1].at("kind"), "compute");
    EXPECT_EQ(json.at("passes")[4].at("ports")[0].at("usage"), nlohmann::json({"indirect"}));

    const ToolRun table = run_tool(graph("light_list.json") + " --order declared");
    ASSERT_EQ(table.status, 0) << table.err;
    EXPECT_NE(table.out.find("               textures  buffers  bytes     bytes / lower bound\n"
                             "  plan         2         2        31.8 MiB  1.000\n"
                             "  naive        2         2        31.8 MiB  1.000\n"
                             "  lower bound  2         2        31.8 MiB  1.000\n"
                             "  buffer bytes: 8.0 MiB\n"),
              std::string::npos)
        << table.out;
}

TEST(PlanTool, AsyncSsaoPrintsSyncsTransfersAndHeldLifetimes) {
    // docs/framegraph.md, Async compute, quotes these lines.
    const ToolRun run = run_tool(graph("async_ssao.json") + " --order declared");
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find("  2  ssao_blur [compute, async]  <raw=t1  >ao=t2\n"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("queue syncs\n"
                           "  signal         after        wait           before\n"
                           "  graphics       0 depth      async_compute  1 ssao\n"
                           "  async_compute  2 ssao_blur  graphics       5 lighting\n\n"
                           "ownership transfers\n"
                           "  resource      from           release after  to        acquire before\n"
                           "  ssao_blur.ao  async_compute  2 ssao_blur    graphics  5 lighting\n"),
              std::string::npos)
        << run.out;
    EXPECT_NE(run.out.find("  depth.depth             Depth32F     1920x1080  0-4 shared    t0       7.9 MiB\n"
                           "  ssao.raw                R16Float     960x540    1-2 held 1-4  t1       1.0 MiB\n"),
              std::string::npos)
        << run.out;
    // The heap reaches the lower bound; paper refuses async plans (bad arguments: status 2).
    const auto heap = summary_of("async_ssao.json", "heap");
    EXPECT_EQ(heap.at("bytes"), heap.at("lower_bound_bytes"));
    const ToolRun paper = run_tool(graph("async_ssao.json") + " --allocator paper");
    EXPECT_EQ(paper.status, 2);
    EXPECT_NE(paper.err.find("allocator 'paper'"), std::string::npos) << paper.err;
}

TEST(PlanTool, CompareShowsEveryAllocatorBesideTheNaiveFiguresAndTheBound) {
    // The engine frames' figures, pinned one by one in engine_frames_test.cpp, side by side.
    const ToolRun gta = run_tool(graph("gta5_frame.json") + " --order declared --compare");
    ASSERT_EQ(gta.status, 0) << gta.err;
    EXPECT_EQ(gta.out,
              "memory at 1920x1080, sharing equal, order declared\n"
              "               textures  buffers  bytes                 bytes / lower bound\n"
              "  naive        28        2        198115584  188.9 MiB  2.290\n"
              "  paper        20        2        118489344  113.0 MiB  1.370\n"
              "  interval     20        2        118489344  113.0 MiB  1.370\n"
              "  heap         28        2        86507520   82.5 MiB   1.000\n"
              "  lower bound  20        2        86507520   82.5 MiB   1.000\n");
    // paper refuses a frame with async compute passes, on its own row.
    const ToolRun doom = run_tool(graph("doom2016_frame.json") + " --order declared --compare --json");
    ASSERT_EQ(doom.status, 0) << doom.err;
    const auto json = nlohmann::json::parse(doom.out);
    EXPECT_EQ(json.at("allocators").at("paper"), nullptr);
    EXPECT_EQ(json.at("allocators").at("heap").at("bytes"), json.at("lower_bound_bytes"));
    EXPECT_EQ(json.at("lower_bound_bytes"), 349462784);
    EXPECT_EQ(json.at("allocators").at("interval").at("bytes"), 379412992);
    const ToolRun table = run_tool(graph("doom2016_frame.json") + " --order declared --compare");
    EXPECT_NE(table.out.find("  paper        refuses: allocator 'paper' colours ports pass by pass"), std::string::npos)
        << table.out;
}

TEST(PlanTool, MemoryOrderLowersTheEngineFramesPeaks) {
    // The figures of docs/BENCHMARKS.md, "Pass order"; the order comes from --order or the file.
    const ToolRun gta = run_tool(graph("gta5_frame.json") + " --order memory --json --allocator heap");
    ASSERT_EQ(gta.status, 0) << gta.err;
    const auto json = nlohmann::json::parse(gta.out);
    EXPECT_EQ(json.at("pass_order"), "memory");
    EXPECT_EQ(json.at("summary").at("lower_bound_bytes"), 73662464);
    // The heap allocator's placements miss that bound by two pages (it reaches the declared one).
    EXPECT_EQ(json.at("summary").at("bytes"), 73793536);
    EXPECT_EQ(summary_of("gta5_frame.json", "heap").at("lower_bound_bytes"), 86507520);
    const ToolRun compare = run_tool(graph("unreal_deferred_frame.json") + " --order memory --compare --json");
    ASSERT_EQ(compare.status, 0) << compare.err;
    const auto unreal = nlohmann::json::parse(compare.out);
    EXPECT_EQ(unreal.at("order"), "memory");
    EXPECT_EQ(unreal.at("lower_bound_bytes"), 119537664);
    EXPECT_EQ(unreal.at("allocators").at("heap").at("bytes"), 119537664);
    const ToolRun table = run_tool(graph("gta5_frame.json") + " --order memory --compare");
    EXPECT_EQ(table.out.rfind("memory at 1920x1080, sharing equal, order memory\n", 0), 0u) << table.out;
    // The memory order is the default: without --order (and without "order" in the file).
    const ToolRun by_default = run_tool(graph("gta5_frame.json") + " --json --allocator heap");
    ASSERT_EQ(by_default.status, 0) << by_default.err;
    EXPECT_EQ(nlohmann::json::parse(by_default.out).at("pass_order"), "memory");
    EXPECT_EQ(nlohmann::json::parse(by_default.out).at("summary").at("lower_bound_bytes"), 73662464);
    const ToolRun bad = run_tool(graph("gta5_frame.json") + " --order fastest");
    EXPECT_EQ(bad.status, 2);
    EXPECT_EQ(bad.err, "loom-plan: --order must be declared or memory, not 'fastest'\n");
}

TEST(PlanTool, WritesDot) {
    const std::filesystem::path dot = loom::test::output_dir() / "loom_plan" / "figure2.dot";
    std::filesystem::remove(dot);
    const ToolRun run = run_tool(graph("figure2.json") + " --dot \"" + dot.string() + "\"");
    ASSERT_EQ(run.status, 0) << run.err;
    const std::string text = read_file(dot);
    EXPECT_EQ(text.rfind("digraph plan {", 0), 0u);
    EXPECT_NE(text.find("2: deferred"), std::string::npos);

    const std::filesystem::path buffers = loom::test::output_dir() / "loom_plan" / "light_list.dot";
    std::filesystem::remove(buffers);
    const ToolRun light_list = run_tool(graph("light_list.json") + " --order declared --dot \"" + buffers.string() + "\"");
    ASSERT_EQ(light_list.status, 0) << light_list.err;
    EXPECT_NE(read_file(buffers).find("p1:f1:e -> p2:f0:w [color=\"#637939\", fontcolor=\"#637939\", style=dashed, "
                                      "label=\"b0\"];"),
              std::string::npos)
        << read_file(buffers);
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

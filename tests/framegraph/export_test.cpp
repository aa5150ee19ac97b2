// JSON, DOT and table export of a plan.
#include <gtest/gtest.h>

#include <sstream>

#include <nlohmann/json.hpp>

#include "loom/framegraph/framegraph.hpp"

namespace loom::fg {
namespace {

using rhi::Format;

Plan small_plan(const std::string& allocator) {
    FrameGraph graph;
    EXPECT_TRUE(graph.add_pass(Pass("scene").output("color", TextureSpec::of(Format::RGBA16Float)).output("depth", TextureSpec::of(Format::Depth32F))).ok());
    EXPECT_TRUE(graph.add_pass(Pass("post").input("color").input("depth").output("final", TextureSpec::of(Format::RGBA8Unorm))).ok());
    EXPECT_TRUE(graph.add_pass(Pass("tint").inout("final")).ok());
    EXPECT_TRUE(graph.add_pass(Pass("unused").input("color").output("x")).ok());
    EXPECT_TRUE(graph.connect(port("scene", "color"), port("post", "color")).ok());
    EXPECT_TRUE(graph.connect(port("scene", "depth"), port("post", "depth")).ok());
    EXPECT_TRUE(graph.connect(port("post", "final"), port("tint", "final")).ok());
    EXPECT_TRUE(graph.connect(port("scene", "color"), port("unused", "color")).ok());
    EXPECT_TRUE(graph.mark_output(port("tint", "final")).ok());
    PlanOptions options;
    options.frame = {64, 32};
    options.allocator = allocator;
    auto plan = build_plan(graph, options);
    EXPECT_TRUE(plan.ok()) << plan.error().to_string();
    return plan.ok() ? std::move(*plan) : Plan{};
}

TEST(Export, JsonHasEverySummaryFieldAndTheStructure) {
    const Plan plan = small_plan("heap");
    const auto json = nlohmann::json::parse(plan_to_json(plan));
    const auto& summary = json.at("summary");
    EXPECT_EQ(summary.at("textures").get<uint32_t>(), plan.summary.textures);
    EXPECT_EQ(summary.at("bytes").get<uint64_t>(), plan.summary.bytes);
    EXPECT_EQ(summary.at("naive_textures").get<uint32_t>(), 3u);
    EXPECT_EQ(summary.at("naive_bytes").get<uint64_t>(), plan.summary.naive_bytes);
    EXPECT_EQ(summary.at("lower_bound_textures").get<uint32_t>(), plan.summary.lower_bound_textures);
    EXPECT_EQ(summary.at("lower_bound_bytes").get<uint64_t>(), plan.summary.lower_bound_bytes);
    EXPECT_EQ(json.at("order"), nlohmann::json({"scene", "post", "tint"}));
    EXPECT_EQ(json.at("culled"), nlohmann::json({"unused"}));
    EXPECT_EQ(json.at("allocator"), "heap");
    ASSERT_EQ(json.at("resources").size(), 3u);
    const auto& color = json.at("resources")[0];
    EXPECT_EQ(color.at("name"), "scene.color");
    EXPECT_EQ(color.at("format"), "RGBA16Float");
    EXPECT_EQ(color.at("width"), 64);
    EXPECT_EQ(color.at("lifetime"), nlohmann::json({0, 1}));
    EXPECT_EQ(color.at("usage"), nlohmann::json({"sampled", "color_attachment"}));
    const auto& final_color = json.at("resources")[2];
    EXPECT_EQ(final_color.at("ports"), nlohmann::json({"post.final", "tint.final"}));
    EXPECT_TRUE(final_color.at("graph_output").get<bool>());
    EXPECT_EQ(json.at("textures")[0].at("heap"), 0);
    EXPECT_EQ(json.at("heaps").size(), 1u);
    EXPECT_EQ(json.at("edges")[2], nlohmann::json({{"from", "post.final"}, {"to", "tint.final"}, {"resource", 2}, {"texture", 2}}));
    EXPECT_EQ(json.at("hash").get<std::string>().size(), 16u);
    EXPECT_EQ(json.at("passes")[2].at("ports")[0].at("kind"), "inout");
}

TEST(Export, DotDrawsPassesPortsAndTextureColouredEdges) {
    const Plan plan = small_plan("interval");
    const std::string dot = plan_to_dot(plan);
    EXPECT_EQ(dot.rfind("digraph plan {", 0), 0u);
    EXPECT_NE(dot.find("p1 [label=\"{{<f0> color (t0)|<f1> depth (t1)}|1: post|{<f2> final (t2)}}\"];"),
              std::string::npos)
        << dot;
    EXPECT_NE(dot.find("p0:f0:e -> p1:f0:w [color=\"#1f77b4\", fontcolor=\"#1f77b4\", label=\"t0\"];"), std::string::npos)
        << dot;
    EXPECT_NE(dot.find("c0 [label=\"unused (culled)\", style=dashed"), std::string::npos) << dot;
    EXPECT_NE(dot.find("p2:f0:e -> output"), std::string::npos) << dot;
    EXPECT_EQ(dot.back(), '\n');
    EXPECT_EQ(std::count(dot.begin(), dot.end(), '{') - std::count(dot.begin(), dot.end(), '}'), 0);
}

TEST(Export, TableListsOrderResourcesTexturesAndSummary) {
    const std::string table = plan_to_table(small_plan("paper"));
    EXPECT_NE(table.find("plan: allocator paper, frame 64x32, sharing equal"), std::string::npos) << table;
    EXPECT_NE(table.find("order (3 passes; culled: unused)"), std::string::npos) << table;
    EXPECT_NE(table.find("tint   <>final=t2"), std::string::npos) << table;
    EXPECT_NE(table.find("post.final (output)"), std::string::npos) << table;
    EXPECT_NE(table.find("lower bound"), std::string::npos);
    EXPECT_EQ(format_bytes(512), "512 B");
    EXPECT_EQ(format_bytes(1536), "1.5 KiB");
    EXPECT_EQ(format_bytes(3 * 1024 * 1024), "3.0 MiB");
}

TEST(Export, StreamedJsonIsWhatTheWholeDocumentDumpsAtEveryIndent) {
    // write_plan_json writes member by member; the text must be what nlohmann's dump of the
    // whole document prints (sorted keys, its escaping and its indentation), at every indent.
    Plan plan = small_plan("heap");
    plan.resources[0].name = "scene.\"color\"\t\u00e9";  // escaping goes through json
    plan.culled.push_back("second culled");
    const auto document = nlohmann::json::parse(plan_to_json(plan));
    for (int indent : {-1, 0, 1, 2, 4}) {
        std::ostringstream streamed;
        write_plan_json(streamed, plan, indent);
        EXPECT_EQ(streamed.str(), document.dump(indent)) << "indent " << indent;
        EXPECT_EQ(plan_to_json(plan, indent), streamed.str()) << "indent " << indent;
    }
}

TEST(Export, StreamedDotAndTableAreTheReturnedText) {
    const Plan plan = small_plan("heap");
    std::ostringstream dot;
    write_plan_dot(dot, plan);
    EXPECT_EQ(dot.str(), plan_to_dot(plan));
    std::ostringstream table;
    write_plan_table(table, plan);
    EXPECT_EQ(table.str(), plan_to_table(plan));
    EXPECT_NE(table.str().find("heaps: "), std::string::npos) << table.str();
}

}  // namespace
}  // namespace loom::fg

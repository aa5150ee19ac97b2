// JSON, DOT and table export of a plan.
#include <gtest/gtest.h>

#include <sstream>

#include <nlohmann/json.hpp>

#include "loom/framegraph/framegraph.hpp"

namespace loom::fg {
namespace {

using rhi::Format;

Plan small_plan(AllocatorKind allocator) {
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
    options.order = PassOrder::Declared;
    options.frame = {64, 32};
    options.allocator = allocator;
    auto plan = build_plan(graph, options);
    EXPECT_TRUE(plan.ok()) << plan.error().to_string();
    return plan.ok() ? std::move(*plan) : Plan{};
}

// Buffers, pass kinds and ranges: a mip written in place, a compute-built buffer read in part.
Plan buffer_plan(AllocatorKind allocator) {
    FrameGraph graph;
    const TextureSpec pyramid = TextureSpec::of(Format::RGBA8Unorm).with_size(16, 16).with_mips(3);
    EXPECT_TRUE(graph.add_pass(Pass("base").output("pyramid", pyramid, mip(0))).ok());
    EXPECT_TRUE(graph.add_pass(Pass("down").set_kind(PassKind::Compute).input("src", {}, mip(0)).inout("pyramid", {}, mip(1))).ok());
    EXPECT_TRUE(graph.add_pass(Pass("cull")
                                   .set_kind(PassKind::Compute)
                                   .input("pyramid")
                                   .buffer_output("lights", BufferSpec::of_size(1024).with_alignment(16)))
                    .ok());
    EXPECT_TRUE(graph.add_pass(Pass("shade")
                                   .buffer_input("lights", BufferSpec{}.with_usage(rhi::BufferUsage::Uniform), BufferRange{0, 256})
                                   .output("color", TextureSpec::of(Format::RGBA8Unorm)))
                    .ok());
    EXPECT_TRUE(graph.connect(port("base", "pyramid"), port("down", "src")).ok());
    EXPECT_TRUE(graph.connect(port("base", "pyramid"), port("down", "pyramid")).ok());
    EXPECT_TRUE(graph.connect(port("down", "pyramid"), port("cull", "pyramid")).ok());
    EXPECT_TRUE(graph.connect(port("cull", "lights"), port("shade", "lights")).ok());
    EXPECT_TRUE(graph.mark_output(port("shade", "color")).ok());
    PlanOptions options;
    options.order = PassOrder::Declared;
    options.frame = {64, 48};
    options.allocator = allocator;
    auto plan = build_plan(graph, options);
    EXPECT_TRUE(plan.ok()) << plan.error().to_string();
    return plan.ok() ? std::move(*plan) : Plan{};
}

TEST(Export, JsonHasEverySummaryFieldAndTheStructure) {
    const Plan plan = small_plan(AllocatorKind::Heap);
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
    const Plan plan = small_plan(AllocatorKind::Interval);
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
    const std::string table = plan_to_table(small_plan(AllocatorKind::Paper));
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
    Plan plan = small_plan(AllocatorKind::Heap);
    plan.resources[0].name = "scene.\"color\"\t\u00e9";  // escaping goes through json
    plan.culled.push_back("second culled");
    // Buffers, their ports, edges, spec classes and placements have members of their own.
    for (const Plan& each : {plan, buffer_plan(AllocatorKind::Heap), buffer_plan(AllocatorKind::Interval)}) {
        const auto document = nlohmann::json::parse(plan_to_json(each));
        for (int indent : {-1, 0, 1, 2, 4}) {
            std::ostringstream streamed;
            write_plan_json(streamed, each, indent);
            EXPECT_EQ(streamed.str(), document.dump(indent)) << each.allocator << " indent " << indent;
            EXPECT_EQ(plan_to_json(each, indent), streamed.str()) << each.allocator << " indent " << indent;
        }
    }
}

TEST(Export, StreamedDotAndTableAreTheReturnedText) {
    const Plan plan = small_plan(AllocatorKind::Heap);
    std::ostringstream dot;
    write_plan_dot(dot, plan);
    EXPECT_EQ(dot.str(), plan_to_dot(plan));
    std::ostringstream table;
    write_plan_table(table, plan);
    EXPECT_EQ(table.str(), plan_to_table(plan));
    EXPECT_NE(table.str().find("heaps: "), std::string::npos) << table.str();
}

TEST(Export, TextureOnlyPlansPrintWhatTheyPrintedBeforeBuffers) {
    // Pinned whole: buffers, kinds and ranges add nothing to a texture-only plan's DOT and table
    // (the same text loom-plan printed for the sample graphs before they existed, and since the
    // memory order became the default, the order the plan was made in).
    EXPECT_EQ(plan_to_dot(small_plan(AllocatorKind::Interval)),
              "digraph plan {\n"
              "  rankdir=LR;\n"
              "  node [shape=record, fontname=\"Helvetica\", fontsize=10];\n"
              "  edge [fontname=\"Helvetica\", fontsize=9];\n"
              "  label=\"interval allocator: 3 textures, 192.0 KiB (naive 3, 192.0 KiB), declared order\";\n"
              "  p0 [label=\"{0: scene|{<f0> color (t0)|<f1> depth (t1)}}\"];\n"
              "  p1 [label=\"{{<f0> color (t0)|<f1> depth (t1)}|1: post|{<f2> final (t2)}}\"];\n"
              "  p2 [label=\"{2: tint|{<f0> final (t2)}}\"];\n"
              "  c0 [label=\"unused (culled)\", style=dashed, color=gray, fontcolor=gray];\n"
              "  p0:f0:e -> p1:f0:w [color=\"#1f77b4\", fontcolor=\"#1f77b4\", label=\"t0\"];\n"
              "  p0:f1:e -> p1:f1:w [color=\"#ff7f0e\", fontcolor=\"#ff7f0e\", label=\"t1\"];\n"
              "  p1:f2:e -> p2:f0:w [color=\"#2ca02c\", fontcolor=\"#2ca02c\", label=\"t2\"];\n"
              "  output [shape=doublecircle, label=\"output\"];\n"
              "  p2:f0:e -> output [color=\"#2ca02c\", label=\"t2\"];\n"
              "}\n");
    EXPECT_EQ(plan_to_table(small_plan(AllocatorKind::Paper)),
              "plan: allocator paper, frame 64x32, sharing equal, order declared\n"
              "\n"
              "order (3 passes; culled: unused)\n"
              "  #  pass   ports\n"
              "  0  scene  >color=t0  >depth=t1\n"
              "  1  post   <color=t0  <depth=t1  >final=t2\n"
              "  2  tint   <>final=t2\n"
              "\n"
              "resources\n"
              "  resource             format       size   life  texture  bytes\n"
              "  scene.color          RGBA16Float  64x32  0-1   t0       64.0 KiB\n"
              "  scene.depth          Depth32F     64x32  0-1   t1       64.0 KiB\n"
              "  post.final (output)  RGBA8Unorm   64x32  1-2   t2       64.0 KiB\n"
              "\n"
              "textures\n"
              "  texture  spec               holds        bytes     placement\n"
              "  t0       RGBA16Float 64x32  scene.color  64.0 KiB  -\n"
              "  t1       Depth32F 64x32     scene.depth  64.0 KiB  -\n"
              "  t2       RGBA8Unorm 64x32   post.final   64.0 KiB  -\n"
              "\n"
              "summary\n"
              "               textures  bytes      bytes / lower bound\n"
              "  plan         3         192.0 KiB  1.000\n"
              "  naive        3         192.0 KiB  1.000\n"
              "  lower bound  3         192.0 KiB  1.000\n");
}

TEST(Export, TableShowsPassKindsRangesBufferResourcesBuffersAndTheirFigures) {
    EXPECT_EQ(plan_to_table(buffer_plan(AllocatorKind::Heap)),
              "plan: allocator heap, frame 64x48, sharing equal, order declared\n"
              "\n"
              "order (4 passes)\n"
              "  #  pass            ports\n"
              "  0  base            >pyramid=t0(mip 0)\n"
              "  1  down [compute]  <src=t0(mip 0)  <>pyramid=t0(mip 1)\n"
              "  2  cull [compute]  <pyramid=t0  >lights=b0\n"
              "  3  shade           <lights=b0(bytes 0+256)  >color=t1\n"
              "\n"
              "resources\n"
              "  resource              format      size      life  texture  bytes\n"
              "  base.pyramid          RGBA8Unorm  16x16 m3  0-2   t0       64.0 KiB\n"
              "  shade.color (output)  RGBA8Unorm  64x48     3-3   t1       64.0 KiB\n"
              "\n"
              "textures\n"
              "  texture  spec                     holds         bytes     placement\n"
              "  t0       RGBA8Unorm 16x16 3 mips  base.pyramid  64.0 KiB  heap 0 @ 0\n"
              "  t1       RGBA8Unorm 64x48         shade.color   64.0 KiB  heap 0 @ 0\n"
              "\n"
              "buffer resources\n"
              "  resource     size               usage            life  buffer  bytes\n"
              "  cull.lights  1024 B aligned 16  uniform|storage  2-3   b0      1.0 KiB\n"
              "\n"
              "buffers\n"
              "  buffer  spec                                          holds        bytes    placement\n"
              "  b0      buffer 1024 bytes uniform|storage aligned 16  cull.lights  1.0 KiB  heap 0 @ 65536\n"
              "\n"
              "summary\n"
              "               textures  buffers  bytes      bytes / lower bound\n"
              "  plan         2         1        65.0 KiB   1.000\n"
              "  naive        2         1        129.0 KiB  1.985\n"
              "  lower bound  2         1        65.0 KiB   1.000\n"
              "  buffer bytes: 1.0 KiB\n"
              "  heaps: 65.0 KiB\n");
}

TEST(Export, DotDrawsBufferEdgesDashedAndLabelsPartialRanges) {
    EXPECT_EQ(plan_to_dot(buffer_plan(AllocatorKind::Interval)),
              "digraph plan {\n"
              "  rankdir=LR;\n"
              "  node [shape=record, fontname=\"Helvetica\", fontsize=10];\n"
              "  edge [fontname=\"Helvetica\", fontsize=9];\n"
              "  label=\"interval allocator: 2 textures, 1 buffers, 129.0 KiB (naive 2 + 1 buffers, 129.0 KiB), declared order\";\n"
              "  p0 [label=\"{0: base|{<f0> pyramid (t0 mip 0)}}\"];\n"
              "  p1 [label=\"{{<f0> src (t0 mip 0)}|1: down [compute]|{<f1> pyramid (t0 mip 1)}}\"];\n"
              "  p2 [label=\"{{<f0> pyramid (t0)}|2: cull [compute]|{<f1> lights (b0)}}\"];\n"
              "  p3 [label=\"{{<f0> lights (b0 bytes 0+256)}|3: shade|{<f1> color (t1)}}\"];\n"
              "  p0:f0:e -> p1:f0:w [color=\"#1f77b4\", fontcolor=\"#1f77b4\", label=\"t0 mip 0\"];\n"
              "  p0:f0:e -> p1:f1:w [color=\"#1f77b4\", fontcolor=\"#1f77b4\", label=\"t0 mip 1\"];\n"
              "  p1:f1:e -> p2:f0:w [color=\"#1f77b4\", fontcolor=\"#1f77b4\", label=\"t0\"];\n"
              "  p2:f1:e -> p3:f0:w [color=\"#637939\", fontcolor=\"#637939\", style=dashed, label=\"b0 bytes 0+256\"];\n"
              "  output [shape=doublecircle, label=\"output\"];\n"
              "  p3:f1:e -> output [color=\"#ff7f0e\", label=\"t1\"];\n"
              "}\n");
}

TEST(Export, JsonCarriesPassKindsPortRangesBufferResourcesBuffersAndTheBufferSummary) {
    using nlohmann::json;
    const auto plan = json::parse(plan_to_json(buffer_plan(AllocatorKind::Heap)));
    EXPECT_EQ(plan.at("passes")[0].at("kind"), "graphics");
    EXPECT_EQ(plan.at("passes")[1].at("kind"), "compute");
    EXPECT_EQ(plan.at("passes")[1].at("ports")[1],
              json::parse(R"({"kind": "inout", "name": "pyramid", "optional": false, "resource": 0, "texture": 0,
                              "type": "texture", "usage": ["storage"],
                              "range": {"base_mip": 1, "mip_count": 1, "base_layer": 0, "layer_count": 1}})"));
    EXPECT_EQ(plan.at("passes")[3].at("ports")[0],
              json::parse(R"({"buffer": 0, "kind": "input", "name": "lights", "optional": false, "resource": 1,
                              "type": "buffer", "usage": ["uniform"], "range": {"offset": 0, "size": 256}})"));
    EXPECT_EQ(plan.at("edges")[3], json::parse(R"({"buffer": 0, "from": "cull.lights", "resource": 1, "to": "shade.lights"})"));
    EXPECT_EQ(plan.at("edges")[1],
              json::parse(R"({"from": "base.pyramid", "resource": 0, "texture": 0, "to": "down.pyramid"})"));
    EXPECT_EQ(plan.at("resources")[1],
              json::parse(R"({"alignment": 256, "buffer": 0, "bytes": 1024, "graph_output": false, "lifetime": [2, 3],
                              "name": "cull.lights", "occupancy": [2, 3], "ports": ["cull.lights", "shade.lights"],
                              "queue_shared": false, "size": 1024,
                              "spec_alignment": 16, "spec_class": 1, "type": "buffer", "usage": ["uniform", "storage"]})"));
    EXPECT_EQ(plan.at("resources")[0].at("type"), "texture");
    EXPECT_EQ(plan.at("spec_classes")[1],
              json::parse(R"({"peak_live": 1, "resources": [1], "size": 1024, "spec_alignment": 16, "type": "buffer",
                              "usage": ["uniform", "storage"]})"));
    EXPECT_EQ(plan.at("buffers"),
              json::parse(R"([{"alignment": 256, "bytes": 1024, "heap": 0, "name": "b0", "offset": 65536, "resources": [1],
                               "size": 1024, "spec_alignment": 16, "usage": ["uniform", "storage"]}])"));
    // 64 KiB per texture (the model's page), the buffer after them; the heap holds the two
    // textures, which do not live at once, in one place.
    EXPECT_EQ(plan.at("summary"),
              json::parse(R"({"buffer_bytes": 1024, "buffers": 1, "bytes": 66560, "lower_bound_buffers": 1,
                              "lower_bound_bytes": 66560, "lower_bound_textures": 2, "naive_buffers": 1,
                              "naive_bytes": 132096, "naive_textures": 2, "textures": 2})"));
    EXPECT_EQ(plan.at("heaps"), json::parse("[66560]"));
    // A texture-only plan has the members too, empty or zero.
    const auto textures = json::parse(plan_to_json(small_plan(AllocatorKind::Interval)));
    EXPECT_EQ(textures.at("buffers"), json::array());
    EXPECT_EQ(textures.at("summary").at("buffers"), 0);
    EXPECT_EQ(textures.at("summary").at("naive_buffers"), 0);
    EXPECT_EQ(textures.at("passes")[0].at("ports")[0].at("range"),
              json::parse(R"({"base_mip": 0, "mip_count": 1, "base_layer": 0, "layer_count": 1})"));
}

}  // namespace
}  // namespace loom::fg

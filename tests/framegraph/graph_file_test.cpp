// JSON graph files: the format, aliases, partial constraints, parts, and errors with paths.
#include <gtest/gtest.h>

#include "loom/framegraph/framegraph.hpp"

namespace loom::fg {
namespace {

using rhi::Format;

constexpr std::string_view kBriefExample = R"({ "frame": {"width": 1920, "height": 1080},
  "passes": [
    {"name": "shadow",   "outputs": [{"name": "shadow_map", "format": "Depth32F", "size": [2048, 2048]}]},
    {"name": "geometry", "outputs": [{"name": "position", "format": "RGBA16F"}, {"name": "normal", "format": "RGBA16F"}]},
    {"name": "deferred", "inputs":  [{"name": "shadow_map"}, {"name": "position"}, {"name": "normal"}],
                         "outputs": [{"name": "color", "format": "RGBA16F", "scale": 1.0}]},
    {"name": "tint",     "inouts":  [{"name": "color"}], "side_effect": false}
  ],
  "connections": [["shadow.shadow_map", "deferred.shadow_map"], ["geometry.position", "deferred.position"],
                  ["geometry.normal", "deferred.normal"], ["deferred.color", "tint.color"]],
  "outputs": ["tint.color"] })";

Error parse_error(std::string_view text) {
    auto file = parse_graph_json(text, "g.json");
    EXPECT_FALSE(file.ok());
    return file.ok() ? Error{} : file.error();
}

/// The planning error of a graph file that parses, located in the file.
Error planning_error(std::string_view text) {
    auto file = parse_graph_json(text, "g.json");
    EXPECT_TRUE(file.ok()) << (file.ok() ? "" : file.error().message);
    if (!file.ok()) return {};
    PlanOptions options;
    options.frame = file->frame;
    auto plan = build_plan(file->graph, options);
    EXPECT_FALSE(plan.ok());
    return plan.ok() ? Error{} : locate_in_graph_file(*file, plan.take_error());
}

TEST(GraphFile, TheExampleGraphParsesAndPlans) {
    auto file = parse_graph_json(kBriefExample, "example.json");
    ASSERT_TRUE(file.ok()) << file.error().to_string();
    EXPECT_EQ(file->frame, (Extent2D{1920, 1080}));
    EXPECT_EQ(file->graph.pass_count(), 4u);
    PlanOptions options;
    options.frame = file->frame;
    auto plan = build_plan(file->graph, options);
    ASSERT_TRUE(plan.ok()) << plan.error().to_string();
    ASSERT_EQ(plan->order.size(), 4u);
    EXPECT_EQ(plan->order[3].name, "tint");
    EXPECT_EQ(plan->texture_of("tint", "color"), plan->texture_of("deferred", "color"));
    EXPECT_EQ(plan->resource_of("shadow", "shadow_map")->spec.extent, (Extent2D{2048, 2048}));
    EXPECT_EQ(plan->resource_of("shadow", "shadow_map")->spec.format, Format::Depth32F);
    EXPECT_EQ(plan->resource_of("deferred", "color")->spec.format, Format::RGBA16Float);
    EXPECT_EQ(plan->summary.naive_textures, 4u);
}

TEST(GraphFile, FormatNamesAndAliases) {
    EXPECT_EQ(parse_format_alias("RGBA16Float"), Format::RGBA16Float);
    EXPECT_EQ(parse_format_alias("RGBA16F"), Format::RGBA16Float);
    EXPECT_EQ(parse_format_alias("RGBA32F"), Format::RGBA32Float);
    EXPECT_EQ(parse_format_alias("R16F"), Format::R16Float);
    EXPECT_EQ(parse_format_alias("RG32F"), Format::RG32Float);
    EXPECT_EQ(parse_format_alias("R11G11B10F"), Format::R11G11B10Float);
    EXPECT_EQ(parse_format_alias("RGBA8"), Format::RGBA8Unorm);
    EXPECT_EQ(parse_format_alias("R16"), Format::R16Unorm);
    EXPECT_EQ(parse_format_alias("rgba8unorm"), Format::RGBA8Unorm);
    EXPECT_EQ(parse_format_alias("D32F"), Format::Depth32F);
    EXPECT_EQ(parse_format_alias("D24S8"), Format::Depth24Stencil8);
    EXPECT_EQ(parse_format_alias("Depth32F"), Format::Depth32F);
    EXPECT_FALSE(parse_format_alias("RGBA17F").has_value());
    EXPECT_FALSE(parse_format_alias("R32").has_value());  // Float or Uint? Say which.
    EXPECT_FALSE(parse_format_alias("").has_value());
}

TEST(GraphFile, PortProperties) {
    auto file = parse_graph_json(R"({"passes": [
        {"name": "p", "outputs": [
          {"name": "hdr", "channels": 3, "bits": 16, "kind": "float", "scale": [0.5, 0.25]},
          {"name": "msaa", "format": "RGBA8", "samples": 4, "size": [64, 32]},
          {"name": "chain", "format": "R16F", "mips": 3, "layers": 6, "usage": ["storage", "copy_dst"]},
          {"name": "depth", "depth": 24, "stencil": 8},
          {"name": "maybe", "optional": true, "srgb": true}]}],
        "outputs": ["p.hdr"]})");
    ASSERT_TRUE(file.ok()) << file.error().to_string();
    const Pass& pass = file->graph.pass(PassId{0});
    const TextureSpec& hdr = pass.find_port("hdr")->spec;
    EXPECT_EQ(hdr.format, color_features(3, 16, rhi::ChannelKind::Float));
    EXPECT_EQ(hdr.size, SizeSpec::relative(0.5f, 0.25f));
    const TextureSpec& msaa = pass.find_port("msaa")->spec;
    EXPECT_EQ(msaa.samples, 4u);
    EXPECT_EQ(msaa.size, SizeSpec::absolute(64, 32));
    const TextureSpec& chain = pass.find_port("chain")->spec;
    EXPECT_EQ(chain.mips, 3u);
    EXPECT_EQ(chain.layers, 6u);
    EXPECT_EQ(chain.usage, rhi::TextureUsage::Storage | rhi::TextureUsage::CopyDst);
    EXPECT_EQ(pass.find_port("depth")->spec.format, rhi::format_info(Format::Depth24Stencil8).features);
    EXPECT_TRUE(pass.find_port("maybe")->optional);
    EXPECT_EQ(pass.find_port("maybe")->spec.format, rhi::format_info(Format::RGBA8Srgb).features);
}

TEST(GraphFile, PassesComposedFromPortSets) {
    auto file = parse_graph_json(R"({"passes": [
        {"name": "deferred", "outputs": [{"name": "color", "channels": 3, "bits": 16, "kind": "float"}],
         "parts": [{"name": "shadow-render", "inputs": [{"name": "shadow_map", "optional": true}],
                    "outputs": [{"name": "color", "format": "RGBA16F"}]}]}],
        "outputs": ["deferred.color"]})");
    ASSERT_TRUE(file.ok()) << file.error().to_string();
    const Port* color = file->graph.pass(PassId{0}).find_port("color");
    EXPECT_EQ(color->port_sets, (std::vector<std::string>{"deferred", "shadow-render"}));
    EXPECT_EQ(color->spec.format, rhi::format_info(Format::RGBA16Float).features);

    const Error clash = parse_error(R"({"passes": [{"name": "d", "outputs": [{"name": "c"}],
        "parts": [{"name": "other", "inputs": [{"name": "c"}]}]}]})");
    EXPECT_EQ(clash.code, ErrorCode::Graph);
    EXPECT_EQ(clash.message, "g.json: /passes/0: pass 'd': port 'c' is declared as output by port set 'd' and as input "
                             "by port set 'other'");
}

TEST(GraphFile, ErrorsCarryTheJsonPath) {
    struct Case {
        std::string_view text;
        std::string_view message;
    };
    const Case cases[] = {
        {R"({"passes": [{"name": "a"}, {"name": "b"}, {"name": "c", "outputs": [{"name": "x", "format": "RGBA17F"}]}]})",
         R"(g.json: /passes/2/outputs/0/format: unknown format "RGBA17F")"},
        {R"({"passes": [], "extra": 1})",
         "g.json: /extra: unknown key (expected one of: frame, passes, connections, outputs, description, order, "
         "order_constraints)"},
        {R"({"passes": [{"name": "a", "outputs": [{"name": "x", "colour": 1}]}]})",
         "g.json: /passes/0/outputs/0/colour: unknown key (expected one of: name, type, format, channels, bits, kind, "
         "srgb, depth, stencil, size, scale, samples, mips, layers, cube, range, optional, usage)"},
        {R"({"frame": {"width": 0, "height": 10}, "passes": []})",
         "g.json: /frame/width: must be a positive integer, not 0"},
        {R"({"passes": [{"name": "a", "outputs": [{"name": "x", "samples": 2.5}]}]})",
         "g.json: /passes/0/outputs/0/samples: must be a positive integer, not 2.5"},
        {R"({"passes": [{"name": "a", "outputs": [{"name": "x", "samples": 3}]}]})",
         "g.json: /passes/0/outputs/0/samples: must be one of 1, 2, 4, 8, 16, 32, 64, not 3"},
        {R"({"passes": [{"name": "a", "outputs": [{"name": "x", "samples": 128}]}]})",
         "g.json: /passes/0/outputs/0/samples: must be at most 64, not 128"},
        {R"({"passes": [{"name": "a", "outputs": [{"name": "x", "layers": 2049}]}]})",
         "g.json: /passes/0/outputs/0/layers: must be at most 2048, not 2049"},
        {R"({"passes": [{"name": "a", "outputs": [{"name": "x", "mips": 18}]}]})",
         "g.json: /passes/0/outputs/0/mips: must be at most 17, not 18"},
        {R"({"passes": [{"name": "a", "outputs": [{"name": "x", "size": [10]}]}]})",
         "g.json: /passes/0/outputs/0/size: must be [width, height] in texels, not [10]"},
        {R"({"passes": [{"name": "a", "outputs": [{"name": "x", "kind": "half"}]}]})",
         R"(g.json: /passes/0/outputs/0/kind: must be one of unorm, snorm, float, uint, sint, not "half")"},
        {R"({"passes": [{"name": "a", "outputs": [{"name": "x", "format": "R8", "bits": 8}]}]})",
         "g.json: /passes/0/outputs/0: give \"format\" or partial constraints (channels, bits, kind, srgb, depth, "
         "stencil), not both"},
        {R"({"passes": [{"name": "a", "outputs": [{"name": "x", "usage": ["sampled", "texture"]}]}]})",
         R"(g.json: /passes/0/outputs/0/usage/1: unknown usage "texture" (sampled, color_attachment, depth_stencil_attachment, storage, copy_src, copy_dst))"},
        {R"({"passes": [{"name": "a", "side_effect": "yes"}]})",
         R"(g.json: /passes/0/side_effect: must be true or false, not "yes")"},
        {R"({"passes": [{"outputs": []}]})", "g.json: /passes/0/name: a pass needs a non-empty string name"},
        {R"({"passes": {}})", "g.json: /passes: must be an array"},
        {R"({"connections": []})", R"(g.json: missing "passes")"},
        {R"({"passes": [{"name": "a", "outputs": [{"name": "x"}]}], "connections": [["a.x"]]})",
         R"(g.json: /connections/0: must be ["pass.port", "pass.port"])"},
        {R"({"passes": [{"name": "a", "outputs": [{"name": "x"}]}], "connections": [["a.x", "bx"]]})",
         R"(g.json: /connections/0/1: "bx" is not of the form "pass.port")"},
        // The pass order and its constraints.
        {R"({"passes": [], "order": "fastest"})", R"(g.json: /order: must be one of declared, memory, not "fastest")"},
        {R"({"passes": [], "order": 1})", R"(g.json: /order: must be one of declared, memory, not 1)"},
        {R"({"passes": [{"name": "a", "keep_declared_order": 1}]})",
         R"(g.json: /passes/0/keep_declared_order: must be true or false, not 1)"},
        {R"({"passes": [], "order_constraints": {}})",
         R"(g.json: /order_constraints: must be an array of ["earlier pass", "later pass"])"},
        {R"({"passes": [{"name": "a"}], "order_constraints": [["a"]]})",
         R"(g.json: /order_constraints/0: must be ["earlier pass", "later pass"])"},
        {R"({"passes": [{"name": "a"}], "order_constraints": [["a", 2]]})",
         R"(g.json: /order_constraints/0/1: must be a pass name, not 2)"},
    };
    for (const Case& c : cases) {
        const Error error = parse_error(c.text);
        EXPECT_EQ(error.code, ErrorCode::Parse) << c.text;
        EXPECT_EQ(error.message, c.message) << c.text;
    }
}

TEST(GraphFile, PassKindsBufferPortsAndRanges) {
    auto file = parse_graph_json(R"({"passes": [
        {"name": "cull", "kind": "compute",
         "outputs": [{"name": "lights", "type": "buffer", "size": {"per_tile": 1024, "tile": [16, 8]}},
                     {"name": "heads", "type": "buffer", "size": {"per_pixel": 4, "scale": 0.5}, "usage": ["storage"]},
                     {"name": "args", "type": "buffer", "size": 20, "alignment": 4, "optional": true},
                     {"name": "chain", "format": "R32F", "mips": 4, "layers": 6, "range": {"mip": 0, "layers": [2, 3]}}]},
        {"name": "save", "kind": "copy",
         "inputs": [{"name": "tail", "type": "buffer", "usage": ["copy_src", "indirect"], "range": {"offset": 512}},
                    {"name": "head", "type": "buffer", "range": {"offset": 16, "size": 256}},
                    {"name": "levels", "range": {"mips": [1]}},
                    {"name": "layer", "range": {"layer": 5, "mips": [1, 2]}}]},
        {"name": "draw", "kind": "graphics", "side_effect": true}]})");
    ASSERT_TRUE(file.ok()) << file.error().to_string();
    const Pass& cull = file->graph.pass(PassId{0});
    EXPECT_EQ(cull.kind(), PassKind::Compute);
    EXPECT_EQ(file->graph.pass(PassId{1}).kind(), PassKind::Copy);
    EXPECT_EQ(file->graph.pass(PassId{2}).kind(), PassKind::Graphics);

    const Port* lights = cull.find_port("lights");
    EXPECT_EQ(lights->type, ResourceType::Buffer);
    EXPECT_EQ(lights->buffer, BufferSpec::sized(BufferSize::per_tile(16, 8, 1024)));
    EXPECT_EQ(lights->bytes, BufferRange{});
    EXPECT_EQ(cull.find_port("heads")->buffer,
              BufferSpec::sized(BufferSize::per_pixel(4, 0.5f)).with_usage(rhi::BufferUsage::Storage));
    const Port* args = cull.find_port("args");
    EXPECT_EQ(args->buffer, BufferSpec::of_size(20).with_alignment(4));
    EXPECT_TRUE(args->optional);
    EXPECT_EQ(args->kind, PortKind::Output);
    const Port* chain = cull.find_port("chain");
    EXPECT_EQ(chain->type, ResourceType::Texture);
    EXPECT_EQ(chain->spec.mips, 4u);
    EXPECT_EQ(chain->range, (SubresourceRange{0, 1, 2, 3}));

    const Pass& save = file->graph.pass(PassId{1});
    EXPECT_EQ(save.find_port("tail")->buffer.usage, rhi::BufferUsage::CopySrc | rhi::BufferUsage::Indirect);
    EXPECT_EQ(save.find_port("tail")->bytes, (BufferRange{512, 0}));
    EXPECT_EQ(save.find_port("head")->bytes, (BufferRange{16, 256}));
    EXPECT_EQ(save.find_port("levels")->range, (SubresourceRange{1, rhi::kRemainingSubresources, 0, rhi::kRemainingSubresources}));
    EXPECT_EQ(save.find_port("layer")->range, (SubresourceRange{1, 2, 5, 1}));
}

TEST(GraphFile, CubeMaps) {
    auto file = parse_graph_json(R"({"passes": [
        {"name": "sky", "outputs": [{"name": "faces", "format": "RGBA16F", "size": [64, 64], "cube": true, "range": {"layer": 0}}]},
        {"name": "odd", "outputs": [{"name": "faces", "format": "RGBA16F", "size": [64, 64], "cube": true, "layers": 4}]}],
        "outputs": ["sky.faces", "odd.faces"]})");
    ASSERT_TRUE(file.ok()) << file.error().to_string();
    EXPECT_EQ(file->graph.pass(PassId{0}).find_port("faces")->spec,
              TextureSpec::of(rhi::Format::RGBA16Float).with_size(64, 64).with_cube());
    // A cube with other than six layers is refused when planned, naming the port.
    PlanOptions options;
    options.frame = file->frame;
    auto plan = file->graph.plan(options);
    ASSERT_FALSE(plan.ok());
    EXPECT_NE(plan.error().message.find("odd.faces: a cube map has 6 square single-sampled faces, not 4 layers"),
              std::string::npos)
        << plan.error().message;
    auto not_bool = parse_graph_json(R"({"passes": [{"name": "a", "outputs": [{"name": "x", "cube": 1}]}]})", "g.json");
    ASSERT_FALSE(not_bool.ok());
    EXPECT_NE(not_bool.error().message.find("/passes/0/outputs/0/cube"), std::string::npos) << not_bool.error().message;
}

TEST(GraphFile, BufferKindAndRangeErrorsCarryTheJsonPath) {
    struct Case {
        std::string_view port;  // one output port of pass "a"
        std::string_view message;
    };
    const Case cases[] = {
        {R"({"name": "x", "type": "image"})", R"(/passes/0/outputs/0/type: must be "texture" or "buffer", not "image")"},
        {R"({"name": "x", "type": "buffer", "usage": ["sampled"]})",
         R"(/passes/0/outputs/0/usage/0: unknown buffer usage "sampled" (vertex, index, uniform, storage, indirect, copy_src, copy_dst))"},
        {R"({"name": "x", "type": "buffer", "format": "RGBA8"})",
         R"(/passes/0/outputs/0/format: "format" is a property of texture ports; a buffer port takes name, type, size, usage, alignment, range, optional)"},
        {R"({"name": "x", "type": "buffer", "mips": 2})",
         R"(/passes/0/outputs/0/mips: "mips" is a property of texture ports; a buffer port takes name, type, size, usage, alignment, range, optional)"},
        {R"({"name": "x", "type": "buffer", "size": 64, "colour": 1})",
         "/passes/0/outputs/0/colour: unknown key (expected one of: name, type, size, usage, alignment, range, optional)"},
        {R"({"name": "x", "alignment": 16})",
         R"(/passes/0/outputs/0/alignment: "alignment" is a property of buffer ports; a texture port takes none (add "type": "buffer" for a buffer port))"},
        {R"({"name": "x", "size": 1024})",
         R"(/passes/0/outputs/0/size: must be [width, height] in texels, not 1024 (a buffer's size needs "type": "buffer"))"},
        {R"({"name": "x", "type": "buffer", "size": [64, 64]})",
         R"(/passes/0/outputs/0/size: must be a byte count, {"per_pixel": bytes, "scale": s} or {"per_tile": bytes, "tile": [w, h]}, not [64,64])"},
        {R"({"name": "x", "type": "buffer", "size": 0})", "/passes/0/outputs/0/size: must be a positive integer, not 0"},
        {R"({"name": "x", "type": "buffer", "size": 1099511627777})",
         "/passes/0/outputs/0/size: must be at most 1099511627776, not 1099511627777"},
        {R"({"name": "x", "type": "buffer", "size": {"per_tile": 64}})",
         R"(/passes/0/outputs/0/size: missing "tile": [width, height] in pixels)"},
        {R"({"name": "x", "type": "buffer", "size": {"per_tile": 64, "tile": [16, 0]}})",
         "/passes/0/outputs/0/size/tile/1: must be a positive integer, not 0"},
        {R"({"name": "x", "type": "buffer", "size": {"per_tile": 64, "per_pixel": 4}})",
         R"(/passes/0/outputs/0/size: give "per_pixel" or "per_tile" (one of them))"},
        {R"({"name": "x", "type": "buffer", "size": {"per_tile": 64, "tile": [8, 8], "scale": 0.5}})",
         R"(/passes/0/outputs/0/size/scale: goes with "per_pixel", not "per_tile")"},
        {R"({"name": "x", "type": "buffer", "size": {"per_pixel": 4, "scale": 0}})",
         "/passes/0/outputs/0/size/scale: must be a number in (0, 16], not 0"},
        {R"({"name": "x", "type": "buffer", "size": {"bytes": 4}})",
         "/passes/0/outputs/0/size/bytes: unknown key (expected one of: per_pixel, scale, per_tile, tile)"},
        {R"({"name": "x", "type": "buffer", "alignment": 48})", "/passes/0/outputs/0/alignment: must be a power of two, not 48"},
        {R"({"name": "x", "type": "buffer", "alignment": 131072})",
         "/passes/0/outputs/0/alignment: must be at most 65536, not 131072"},
        {R"({"name": "x", "type": "buffer", "range": {"offset": -1}})",
         "/passes/0/outputs/0/range/offset: must be a non-negative integer, not -1"},
        {R"({"name": "x", "type": "buffer", "range": {"offset": 8, "size": 0}})",
         "/passes/0/outputs/0/range/size: must be a positive integer, not 0"},
        {R"({"name": "x", "type": "buffer", "range": {"mip": 1}})",
         "/passes/0/outputs/0/range/mip: unknown key (expected one of: offset, size)"},
        {R"({"name": "x", "type": "buffer", "range": [0, 64]})",
         R"(/passes/0/outputs/0/range: must be {"offset": bytes, "size": bytes} (no size: to the end), not [0,64])"},
        {R"({"name": "x", "range": {"mip": 17}})", "/passes/0/outputs/0/range/mip: must be at most 16, not 17"},
        {R"({"name": "x", "range": {"mip": 1, "mips": [1, 2]}})", R"(/passes/0/outputs/0/range: give "mip" or "mips", not both)"},
        {R"({"name": "x", "range": {"mips": [1, 0]}})", "/passes/0/outputs/0/range/mips/1: must be a positive integer, not 0"},
        {R"({"name": "x", "range": {"mips": []}})",
         "/passes/0/outputs/0/range/mips: must be [base, count] or [base] (from base to the last), not []"},
        {R"({"name": "x", "range": {"layers": [2047, 2]}})", "/passes/0/outputs/0/range/layers/1: must be at most 1, not 2"},
        {R"({"name": "x", "range": {"level": 1}})",
         "/passes/0/outputs/0/range/level: unknown key (expected one of: mip, mips, layer, layers)"},
        {R"({"name": "x", "range": 2})",
         R"(/passes/0/outputs/0/range: must be an object such as {"mip": 1} or {"mips": [1, 2], "layer": 0}, not 2)"},
    };
    for (const Case& c : cases) {
        const std::string text = R"({"passes": [{"name": "a", "outputs": [)" + std::string(c.port) + "]}]}";
        const Error error = parse_error(text);
        EXPECT_EQ(error.code, ErrorCode::Parse) << text;
        EXPECT_EQ(error.message, "g.json: " + std::string(c.message)) << text;
    }
    const Error kind = parse_error(R"({"passes": [{"name": "a", "kind": "raster"}]})");
    EXPECT_EQ(kind.code, ErrorCode::Parse);
    EXPECT_EQ(kind.message, R"(g.json: /passes/0/kind: must be one of graphics, compute, copy, not "raster")");
    // A port set's port names the whole way down: the deepest pointer a graph file has.
    const Error deep = parse_error(R"({"passes": [{"name": "a", "parts": [{"name": "p", "outputs": [
        {"name": "x", "type": "buffer", "size": {"per_tile": 4, "tile": [8, 1.5]}}]}]}]})");
    EXPECT_EQ(deep.message, "g.json: /passes/0/parts/0/outputs/0/size/tile/1: must be a positive integer, not 1.5");
}

TEST(GraphFile, BufferAndRangePlanningErrorsNameTheirPointers) {
    // No port sizes the buffer: its producer, then its reader.
    const Error unsized = planning_error(R"({"passes": [
        {"name": "fill", "kind": "compute", "outputs": [{"name": "data", "type": "buffer"}]},
        {"name": "use", "inputs": [{"name": "data", "type": "buffer"}], "outputs": [{"name": "c", "format": "RGBA8"}]}],
      "connections": [["fill.data", "use.data"]], "outputs": ["use.c"]})");
    EXPECT_EQ(unsized.code, ErrorCode::Graph);
    EXPECT_EQ(unsized.message,
              "g.json: /passes/0/outputs/0: buffer fill.data: no port gives its size (declare it on the producing port: "
              "BufferSpec::of_size, BufferSize::per_pixel or BufferSize::per_tile) (see also /passes/1/inputs/0)");

    // A mip the texture does not have.
    const Error beyond = planning_error(R"({"passes": [
        {"name": "a", "outputs": [{"name": "t", "format": "RGBA8", "mips": 2}]},
        {"name": "b", "inputs": [{"name": "t", "range": {"mip": 2}}], "outputs": [{"name": "c", "format": "RGBA8"}]}],
      "connections": [["a.t", "b.t"]], "outputs": ["b.c"]})");
    EXPECT_EQ(beyond.message, "g.json: /passes/1/inputs/0: port b.t uses mip 2 of texture a.t, which has 2 mips and 1 layers");

    // Bytes past the buffer's end.
    const Error bytes = planning_error(R"({"passes": [
        {"name": "a", "kind": "compute", "outputs": [{"name": "d", "type": "buffer", "size": 64}]},
        {"name": "b", "inputs": [{"name": "d", "type": "buffer", "range": {"offset": 32, "size": 64}}],
         "outputs": [{"name": "c", "format": "RGBA8"}]}],
      "connections": [["a.d", "b.d"]], "outputs": ["b.c"]})");
    EXPECT_EQ(bytes.message, "g.json: /passes/1/inputs/0: port b.d uses bytes 32+64 of buffer a.d, which has 64 bytes");

    // Reading and modifying the same mips in one pass.
    const Error overlap = planning_error(R"({"passes": [
        {"name": "a", "outputs": [{"name": "t", "format": "RGBA8", "size": [16, 16], "mips": 3}]},
        {"name": "b", "inputs": [{"name": "src", "range": {"mips": [0, 2]}}], "inouts": [{"name": "t", "range": {"mip": 1}}]}],
      "connections": [["a.t", "b.src"], ["a.t", "b.t"]], "outputs": ["b.t"]})");
    EXPECT_EQ(overlap.message,
              "g.json: /passes/1/inouts/0: pass 'b' reads a.t through b.src while modifying it in place through b.t (one "
              "pass may read and modify one resource only in disjoint ranges) (see also /passes/1/inputs/0, "
              "/passes/0/outputs/0)");

    // A texture port connected to a buffer port.
    const Error mixed = parse_error(R"({"passes": [
        {"name": "a", "kind": "compute", "outputs": [{"name": "d", "type": "buffer", "size": 64}]},
        {"name": "b", "inputs": [{"name": "d"}], "side_effect": true}],
      "connections": [["a.d", "b.d"]]})");
    EXPECT_EQ(mixed.code, ErrorCode::Graph);
    EXPECT_EQ(mixed.message, "g.json: /connections/0: connect a.d -> b.d: a.d is a buffer port but b.d is a texture port");
}

TEST(GraphFile, GraphErrorsKeepTheirCodeAndGainAPath) {
    const Error unknown = parse_error(R"({"passes": [{"name": "a", "outputs": [{"name": "x"}]}],
                                         "connections": [["a.x", "b.y"]]})");
    EXPECT_EQ(unknown.code, ErrorCode::Graph);
    EXPECT_EQ(unknown.message, "g.json: /connections/0: connect a.x -> b.y: unknown pass 'b'");
    const Error duplicate = parse_error(R"({"passes": [{"name": "a"}, {"name": "a"}]})");
    EXPECT_EQ(duplicate.message, "g.json: /passes/1: add_pass: a pass called 'a' already exists");
    const Error output = parse_error(R"({"passes": [{"name": "a", "inputs": [{"name": "x"}]}], "outputs": ["a.x"]})");
    EXPECT_EQ(output.code, ErrorCode::Graph);
    EXPECT_NE(output.message.find("g.json: /outputs/0: mark_output a.x"), std::string::npos);
}

TEST(GraphFile, ThePassOrderItsPinsAndItsRequirements) {
    auto file = parse_graph_json(R"({"order": "memory",
      "passes": [{"name": "a", "outputs": [{"name": "out"}], "keep_declared_order": true},
                 {"name": "b", "outputs": [{"name": "out"}], "side_effect": true}],
      "order_constraints": [["b", "a"]], "outputs": ["a.out"]})",
                                 "g.json");
    ASSERT_TRUE(file.ok()) << file.error().to_string();
    EXPECT_EQ(file->order, PassOrder::Memory);
    EXPECT_TRUE(file->graph.pass(PassId{0}).keeps_declared_order());
    EXPECT_FALSE(file->graph.pass(PassId{1}).keeps_declared_order());
    ASSERT_EQ(file->graph.order_requirements().size(), 1u);
    EXPECT_EQ(file->graph.order_requirements()[0], (std::pair{PassId{1}, PassId{0}}));
    auto declared = parse_graph_json(R"({"passes": [], "order": "declared"})");
    ASSERT_TRUE(declared.ok());
    EXPECT_EQ(declared->order, PassOrder::Declared);
    auto unsaid = parse_graph_json(R"({"passes": []})");
    ASSERT_TRUE(unsaid.ok());
    EXPECT_EQ(unsaid->order, PassOrder::Memory);  // kDefaultPassOrder

    // A requirement naming an unknown pass is a graph error at its pointer.
    const Error unknown = parse_error(R"({"passes": [{"name": "a"}], "order_constraints": [["a", "z"]]})");
    EXPECT_EQ(unknown.code, ErrorCode::Graph);
    EXPECT_EQ(unknown.message, "g.json: /order_constraints/0: require_order 'a' before 'z': unknown pass 'z'");
    // One against the data flow is a cycle, blamed where its passes are declared.
    const Error cycle = planning_error(R"({"passes": [
        {"name": "a", "outputs": [{"name": "out", "format": "RGBA8"}]},
        {"name": "b", "inputs": [{"name": "in"}], "outputs": [{"name": "out", "format": "RGBA8"}]}],
      "connections": [["a.out", "b.in"]], "outputs": ["b.out"], "order_constraints": [["b", "a"]]})");
    EXPECT_EQ(cycle.code, ErrorCode::Graph);
    EXPECT_EQ(cycle.message,
              "g.json: /passes/0: cycle: a -> b -> a (a.out feeds b.in; require_order puts b before a) (see also "
              "/passes/1)");
}

TEST(GraphFile, PlanningErrorsNameTheFileAndTheJsonPointerOfWhatTheyBlame) {
    // An input nobody feeds: where the input is declared (here in a port set of the pass).
    const Error unconnected = planning_error(R"({"passes": [
        {"name": "a", "outputs": [{"name": "out", "format": "RGBA8"}]},
        {"name": "b", "outputs": [{"name": "out", "format": "RGBA8"}],
         "parts": [{"name": "lit", "inputs": [{"name": "shadow"}]}]}],
      "outputs": ["a.out", "b.out"]})");
    EXPECT_EQ(unconnected.code, ErrorCode::Graph);
    EXPECT_EQ(unconnected.message, "g.json: /passes/1/parts/0/inputs/0: required input b.shadow is not connected");

    // A failed join: the port that contradicts first, then the one that constrained first.
    const Error join = planning_error(R"({"passes": [
        {"name": "a", "outputs": [{"name": "out", "format": "RGBA8"}]},
        {"name": "b", "inputs": [{"name": "in", "format": "Depth32F"}], "outputs": [{"name": "out", "format": "RGBA8"}]}],
      "connections": [["a.out", "b.in"]], "outputs": ["b.out"]})");
    EXPECT_EQ(join.code, ErrorCode::Join);
    EXPECT_EQ(join.message.rfind("g.json: /passes/1/inputs/0: cannot join a.out and b.in: ", 0), 0u) << join.message;
    EXPECT_NE(join.message.find(" (see also /passes/0/outputs/0)"), std::string::npos) << join.message;

    // A cycle: every pass on it, in the cycle's order.
    const Error cycle = planning_error(R"({"passes": [
        {"name": "x", "outputs": [{"name": "out", "format": "RGBA8"}]},
        {"name": "a", "inputs": [{"name": "in"}], "outputs": [{"name": "out", "format": "RGBA8"}]},
        {"name": "b", "inputs": [{"name": "in"}], "outputs": [{"name": "out", "format": "RGBA8"}]}],
      "connections": [["a.out", "b.in"], ["b.out", "a.in"]], "outputs": ["b.out", "x.out"]})");
    EXPECT_EQ(cycle.message,
              "g.json: /passes/1: cycle: a -> b -> a (a.out feeds b.in; b.out feeds a.in) (see also /passes/2)");

    // A size beyond the limits once the frame scales it: every port of the resource.
    const Error size = planning_error(R"({"frame": {"width": 40000, "height": 100}, "passes": [
        {"name": "a", "outputs": [{"name": "out", "format": "RGBA8", "scale": 2}]},
        {"name": "b", "inputs": [{"name": "in"}], "side_effect": true}],
      "connections": [["a.out", "b.in"]]})");
    EXPECT_EQ(size.message.rfind("g.json: /passes/0/outputs/0: ", 0), 0u) << size.message;
    EXPECT_NE(size.message.find("(see also /passes/1/inputs/0)"), std::string::npos) << size.message;

    // Nothing to blame by name: the file alone.
    const Error nothing = planning_error(R"({"passes": [{"name": "a", "outputs": [{"name": "out", "format": "RGBA8"}]}]})");
    EXPECT_EQ(nothing.message.rfind("g.json: nothing to run", 0), 0u) << nothing.message;
}

TEST(GraphFile, SyntaxErrorsGiveLineAndColumn) {
    const Error error = parse_error("{\n  \"passes\": [\n    {\"name\": \"a\",}\n  ]\n}\n");
    EXPECT_EQ(error.code, ErrorCode::Parse);
    EXPECT_EQ(error.message.rfind("g.json:3:18: invalid JSON", 0), 0u) << error.message;
}

TEST(GraphFile, NumbersBeyondADoubleAreAParseErrorNotAnException) {
    const Error width = parse_error(R"({"frame": {"width": 1e400, "height": 10}, "passes": []})");
    EXPECT_EQ(width.code, ErrorCode::Parse);
    EXPECT_EQ(width.message, "g.json:1:21: the number 1e400 at /frame/width is out of range (beyond a double)");
    const Error negative = parse_error(R"({"passes": [{"name": "a", "outputs": [{"name": "x", "scale": -1e999}]}]})");
    EXPECT_EQ(negative.message,
              "g.json:1:62: the number -1e999 at /passes/0/outputs/0/scale is out of range (beyond a double)");
    // Within a double but beyond any limit: an ordinary range error, not a crash.
    const Error big = parse_error(R"({"frame": {"width": 1e300, "height": 10}, "passes": []})");
    EXPECT_EQ(big.message, "g.json: /frame/width: must be a positive integer, not 1e+300");
}

std::string repeated(std::string_view text, std::size_t count) {
    std::string out;
    for (std::size_t i = 0; i < count; ++i) out += text;
    return out;
}

TEST(GraphFile, NestingDeeperThanTheLimitIsRefusedBeforeParsing) {
    // 70,000 levels overflowed the stack while the error message was formatted; 5 MB of '['
    // took 401 MB. Both now stop at the first bracket past the limit, which the prefix's three
    // containers ({, [ and {) leave as the run's (limit - 2)th.
    const std::string prefix = R"({"passes": [{"name": "a", "side_effect": )";
    const std::string deep = prefix + std::string(70000, '[') + std::string(70000, ']') + "}]}";
    const Error error = parse_error(deep);
    EXPECT_EQ(error.code, ErrorCode::Parse);
    EXPECT_EQ(error.message, "g.json:1:" + std::to_string(prefix.size() + kMaxGraphFileDepth - 2) +
                                 ": nested deeper than " + std::to_string(kMaxGraphFileDepth) +
                                 " levels at /passes/0/side_effect" + repeated("/0", kMaxGraphFileDepth - 3));

    const Error brackets = parse_error(std::string(5 << 20, '['));
    EXPECT_EQ(brackets.message, "g.json:1:" + std::to_string(kMaxGraphFileDepth + 1) + ": nested deeper than " +
                                    std::to_string(kMaxGraphFileDepth) + " levels at " +
                                    repeated("/0", kMaxGraphFileDepth));

    // A document exactly at the limit reaches the reader (which then finds no object).
    const std::string at_limit = std::string(kMaxGraphFileDepth, '[') + std::string(kMaxGraphFileDepth, ']');
    EXPECT_EQ(parse_error(at_limit).message, "g.json: the top level must be an object");
}

TEST(GraphFile, DuplicateKeysAreRefusedWithTheirPath) {
    const Error top = parse_error(R"({"passes": [], "passes": []})");
    EXPECT_EQ(top.code, ErrorCode::Parse);
    EXPECT_EQ(top.message, R"(g.json:1:16: duplicate key "passes" at /passes)");
    const Error port = parse_error("{\"passes\": [{\"name\": \"a\",\n \"outputs\": [{\"name\": \"x\", \"format\": \"R8\", "
                                   "\"\\u0066ormat\": \"RGBA8\"}]}]}");
    EXPECT_EQ(port.message, R"(g.json:2:44: duplicate key "format" at /passes/0/outputs/0/format)");
    // The same key in different objects is fine.
    EXPECT_TRUE(parse_graph_json(R"({"passes": [{"name": "a"}, {"name": "b"}]})", "g.json").ok());
}

TEST(GraphFile, ErrorLocationsAreJsonPointersWithEscapedKeys) {
    // RFC 6901: '~' is written ~0 and '/' is written ~1 in a reference token.
    const Error unknown = parse_error(R"({"passes": [{"name": "a", "outputs": [{"name": "x", "a/b~c": 1}]}]})");
    EXPECT_EQ(unknown.code, ErrorCode::Parse);
    EXPECT_EQ(unknown.message.substr(0, 48), "g.json: /passes/0/outputs/0/a~1b~0c: unknown key");
    const Error duplicate = parse_error(R"({"passes": [], "~/": 1, "~/": 2})");
    EXPECT_EQ(duplicate.message, R"(g.json:1:25: duplicate key "~/" at /~0~1)");
    const Error frame = parse_error(R"({"frame": {"width": 0, "height": 1}, "passes": []})");
    EXPECT_EQ(frame.message, "g.json: /frame/width: must be a positive integer, not 0");
}

TEST(GraphFile, NamesWithDotsOrControlCharactersAreRefused) {
    const Error dotted_port = parse_error(R"({"passes": [{"name": "a", "outputs": [{"name": "b.x"}]}]})");
    EXPECT_EQ(dotted_port.code, ErrorCode::Graph);
    EXPECT_EQ(dotted_port.message, "g.json: /passes/0: add_pass: pass 'a': the port name 'b.x' contains '.', which "
                                   "separates pass and port names");
    const Error dotted_pass = parse_error(R"({"passes": [{"name": "a.b", "outputs": [{"name": "x"}]}]})");
    EXPECT_EQ(dotted_pass.message,
              "g.json: /passes/0: add_pass: the pass name 'a.b' contains '.', which separates pass and port names");
    const Error newline = parse_error(R"({"passes": [{"name": "a\nb"}]})");
    EXPECT_EQ(newline.message,
              "g.json: /passes/0: add_pass: the pass name 'a\\nb' contains a control character (code 10)");
    EXPECT_EQ(newline.message.find('\n'), std::string::npos);
}

TEST(GraphFile, LongValuesAreCutShortInMessages) {
    const std::string long_name(100000, 'x');
    const Error error = parse_error(R"({"passes": [{"name": "a", "side_effect": ")" + long_name + R"("}]})");
    EXPECT_EQ(error.message, "g.json: /passes/0/side_effect: must be true or false, not \"" + std::string(59, 'x') +
                                 "...");
}

TEST(GraphFile, MissingFileIsAnIoError) {
    auto file = load_graph_file("/nonexistent/graph.json");
    ASSERT_FALSE(file.ok());
    EXPECT_EQ(file.error().code, ErrorCode::Io);
    EXPECT_NE(file.error().message.find("/nonexistent/graph.json"), std::string::npos);
}

}  // namespace
}  // namespace loom::fg

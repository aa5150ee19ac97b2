// Errors a user can make with a graph, each caught before any GPU work, each naming the
// passes and ports at fault.
#include <gtest/gtest.h>

#include "loom/framegraph/graph.hpp"
#include "loom/framegraph/graph_file.hpp"

namespace loom::fg {
namespace {

using rhi::Format;

// producer → consumer → sink, with a graph output at the end.
FrameGraph chain() {
    FrameGraph graph;
    EXPECT_TRUE(graph.add_pass(Pass("producer").output("color")).ok());
    EXPECT_TRUE(graph.add_pass(Pass("consumer").input("source").output("color")).ok());
    EXPECT_TRUE(graph.add_pass(Pass("sink").input("source").optional_input("extra").output("final")).ok());
    EXPECT_TRUE(graph.connect(port("producer", "color"), port("consumer", "source")).ok());
    EXPECT_TRUE(graph.connect(port("consumer", "color"), port("sink", "source")).ok());
    EXPECT_TRUE(graph.mark_output(port("sink", "final")).ok());
    return graph;
}

Error connect_error(FrameGraph& graph, const PortRef& from, const PortRef& to) {
    Status status = graph.connect(from, to);
    EXPECT_FALSE(status.ok());
    if (status.ok()) return {};
    EXPECT_EQ(status.error().code, ErrorCode::Graph);
    return status.error();
}

Error plan_error(const FrameGraph& graph, PlanOptions options = {}) {
    auto plan = build_plan(graph, options);
    EXPECT_FALSE(plan.ok());
    return plan.ok() ? Error{} : plan.error();
}

TEST(GraphErrors, NamesThatWouldCollideOrSplitLinesAreRefused) {
    // Pass "a" port "b.x" and pass "a.b" port "x" would both name the resource "a.b.x", and
    // "a.b.x" cannot say which; a newline would split the plan table's rows.
    FrameGraph graph;
    const auto dotted_port = graph.add_pass(Pass("a").output("b.x"));
    ASSERT_FALSE(dotted_port.ok());
    EXPECT_EQ(dotted_port.error().code, ErrorCode::Graph);
    EXPECT_EQ(dotted_port.error().message,
              "add_pass: pass 'a': the port name 'b.x' contains '.', which separates pass and port names");
    const auto dotted_pass = graph.add_pass(Pass("a.b").output("x"));
    ASSERT_FALSE(dotted_pass.ok());
    EXPECT_EQ(dotted_pass.error().message,
              "add_pass: the pass name 'a.b' contains '.', which separates pass and port names");
    const auto newline = graph.add_pass(Pass("tint").inout("color\nalpha"));
    ASSERT_FALSE(newline.ok());
    EXPECT_EQ(newline.error().message,
              "add_pass: pass 'tint': the port name 'color\\nalpha' contains a control character (code 10)");
    const auto bell = graph.add_pass(Pass(std::string("a\x07")).output("x"));
    ASSERT_FALSE(bell.ok());
    EXPECT_EQ(bell.error().message, "add_pass: the pass name 'a\\x07' contains a control character (code 7)");
    EXPECT_EQ(graph.pass_count(), 0u);
    // Everything else is a name: spaces, dashes, non-ASCII.
    EXPECT_TRUE(graph.add_pass(Pass("bloom pass-2 \xc3\xa9").output("colour (linear)")).ok());
    EXPECT_EQ(name_problem(""), "is empty");
    EXPECT_EQ(name_problem("ok"), std::nullopt);
}

TEST(GraphErrors, PortSetNamesFollowTheRulesOfPassAndPortNames) {
    // A port set's name is printed in errors and kept in every port's list of port sets
    // (Port::port_sets): a newline in it would split those lines like one in a port name.
    FrameGraph graph;
    Pass lit("lit");
    lit.add(PortSet("shadow\nrender").input("shadow"));
    EXPECT_EQ(lit.find_port("shadow"), nullptr);
    const auto newline = graph.add_pass(std::move(lit));
    ASSERT_FALSE(newline.ok());
    EXPECT_EQ(newline.error().code, ErrorCode::Graph);
    EXPECT_EQ(newline.error().message,
              "pass 'lit': the port set name 'shadow\\nrender' contains a control character (code 10)");
    EXPECT_EQ(graph.add_pass(Pass("lit").add(PortSet("deferred.render").output("color"))).error().message,
              "pass 'lit': the port set name 'deferred.render' contains '.', which separates pass and port names");
    EXPECT_EQ(graph.add_pass(Pass("lit").add(PortSet("").output("color"))).error().message,
              "pass 'lit': the port set name '' is empty");
    // A bad name is what is reported, also where its ports would have clashed with others.
    EXPECT_EQ(graph.add_pass(Pass("tonemap").add(PortSet("ok").output("c")).add(PortSet("x\ty").input("c"))).error().message,
              "pass 'tonemap': the port set name 'x\\ty' contains a control character (code 9)");
    // A bad pass name is reported as such even when its port sets also clash.
    EXPECT_EQ(graph.add_pass(Pass("a\nb").add(PortSet("p").output("c")).add(PortSet("q").input("c"))).error().message,
              "add_pass: the pass name 'a\\nb' contains a control character (code 10)");
    EXPECT_EQ(graph.pass_count(), 0u);
    EXPECT_TRUE(graph.add_pass(Pass("lit").add(PortSet("shadow-render 2").input("shadow"))).ok());
}

TEST(GraphErrors, GraphFilePortSetNamesAreCheckedAndLocated) {
    auto file = parse_graph_json(
        R"({"passes": [{"name": "lit", "parts": [{"name": "shadow\nrender", "inputs": [{"name": "shadow"}]}]}]})",
        "g.json");
    ASSERT_FALSE(file.ok());
    EXPECT_EQ(file.error().code, ErrorCode::Graph);
    EXPECT_EQ(file.error().message.find('\n'), std::string::npos) << file.error().message;
    EXPECT_NE(file.error().message.find("/passes/0"), std::string::npos) << file.error().message;
    EXPECT_NE(file.error().message.find("the port set name 'shadow\\nrender' contains a control character"),
              std::string::npos)
        << file.error().message;
}

TEST(GraphErrors, ReferencesWithControlCharactersGiveOneLineErrors) {
    // Found by fuzz/names: connect and mark_output printed the caller's references as given,
    // so a newline in one split the error.
    FrameGraph graph = chain();
    EXPECT_EQ(connect_error(graph, port("a\nb", "c"), port("sink", "extra")).message,
              "connect a\\nb.c -> sink.extra: unknown pass 'a\\nb'");
    EXPECT_EQ(connect_error(graph, port("producer", "color\r"), port("sink", "extra")).message,
              "connect producer.color\\x0d -> sink.extra: unknown port 'color\\x0d' on pass 'producer' (its ports: "
              "color)");
    const Status output = graph.mark_output(port("sink", "final\t2"));
    ASSERT_FALSE(output.ok());
    EXPECT_EQ(output.error().message,
              "mark_output sink.final\\t2: unknown port 'final\\t2' on pass 'sink' (its ports: source, extra, final)");
    const Status side_effect = graph.set_side_effect("sink\n");
    ASSERT_FALSE(side_effect.ok());
    EXPECT_EQ(side_effect.error().message, "set_side_effect: unknown pass 'sink\\n'");
}

TEST(GraphErrors, UnknownPass) {
    FrameGraph graph = chain();
    EXPECT_EQ(connect_error(graph, port("shadow", "map"), port("sink", "extra")).message,
              "connect shadow.map -> sink.extra: unknown pass 'shadow'");
    EXPECT_EQ(connect_error(graph, port("producer", "color"), port("bloom", "source")).message,
              "connect producer.color -> bloom.source: unknown pass 'bloom'");
}

TEST(GraphErrors, UnknownPortListsThePortsOfThePass) {
    FrameGraph graph = chain();
    EXPECT_EQ(connect_error(graph, port("producer", "colour"), port("sink", "extra")).message,
              "connect producer.colour -> sink.extra: unknown port 'colour' on pass 'producer' (its ports: color)");
}

TEST(GraphErrors, WrongDirection) {
    FrameGraph graph = chain();
    EXPECT_EQ(connect_error(graph, port("consumer", "source"), port("sink", "extra")).message,
              "connect consumer.source -> sink.extra: consumer.source is an input; a connection starts at an output "
              "or inout");
    EXPECT_EQ(connect_error(graph, port("producer", "color"), port("consumer", "color")).message,
              "connect producer.color -> consumer.color: consumer.color is an output; a connection ends at an input "
              "or inout");
}

TEST(GraphErrors, AnInputTakesOneSource) {
    FrameGraph graph = chain();
    EXPECT_EQ(connect_error(graph, port("producer", "color"), port("sink", "source")).message,
              "connect producer.color -> sink.source: sink.source is already connected to consumer.color; an input "
              "takes one source");
}

TEST(GraphErrors, OneInPlaceWriterPerTexture) {
    FrameGraph graph = chain();
    ASSERT_TRUE(graph.add_pass(Pass("tint").inout("color")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("grain").inout("color")).ok());
    ASSERT_TRUE(graph.connect(port("producer", "color"), port("tint", "color")).ok());
    const Error error = connect_error(graph, port("producer", "color"), port("grain", "color"));
    EXPECT_NE(error.message.find("producer.color is already modified in place by tint.color"), std::string::npos)
        << error.message;
    EXPECT_TRUE(graph.connect(port("tint", "color"), port("grain", "color")).ok());
}

TEST(GraphErrors, CycleNamesItsPassesInOrder) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("start").output("seed")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("a").input("in").optional_input("back").output("out")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("b").input("in").output("out")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("c").input("in").output("out").output("loop")).ok());
    ASSERT_TRUE(graph.connect(port("start", "seed"), port("a", "in")).ok());
    ASSERT_TRUE(graph.connect(port("a", "out"), port("b", "in")).ok());
    ASSERT_TRUE(graph.connect(port("b", "out"), port("c", "in")).ok());
    ASSERT_TRUE(graph.connect(port("c", "loop"), port("a", "back")).ok());
    ASSERT_TRUE(graph.mark_output(port("c", "out")).ok());
    const Error error = plan_error(graph);
    EXPECT_EQ(error.code, ErrorCode::Graph);
    EXPECT_EQ(error.message, "cycle: a -> b -> c -> a (a.out feeds b.in; b.out feeds c.in; c.loop feeds a.back)");
    EXPECT_EQ(graph.validate().error().message, error.message);
}

TEST(GraphErrors, SelfLoopIsACycle) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("feedback").optional_input("previous").output("color")).ok());
    ASSERT_TRUE(graph.connect(port("feedback", "color"), port("feedback", "previous")).ok());
    ASSERT_TRUE(graph.mark_output(port("feedback", "color")).ok());
    EXPECT_EQ(plan_error(graph).message, "cycle: feedback -> feedback (feedback.color feeds feedback.previous)");
}

TEST(GraphErrors, CycleThroughAnInPlaceModification) {
    // `reader` reads the colour before `tint` modifies it, but also needs tint's mask.
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("scene").output("color")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("tint").inout("color").output("mask")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("reader").input("color").input("mask").output("out")).ok());
    ASSERT_TRUE(graph.connect(port("scene", "color"), port("tint", "color")).ok());
    ASSERT_TRUE(graph.connect(port("scene", "color"), port("reader", "color")).ok());
    ASSERT_TRUE(graph.connect(port("tint", "mask"), port("reader", "mask")).ok());
    ASSERT_TRUE(graph.mark_output(port("reader", "out")).ok());
    EXPECT_EQ(plan_error(graph).message,
              "cycle: tint -> reader -> tint (tint.mask feeds reader.mask; reader.color reads scene.color before "
              "tint.color modifies it in place)");
}

TEST(GraphErrors, RequiredInputLeftUnconnected) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("geometry").output("albedo")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("deferred").input("albedo").input("normal").output("color")).ok());
    ASSERT_TRUE(graph.connect(port("geometry", "albedo"), port("deferred", "albedo")).ok());
    ASSERT_TRUE(graph.mark_output(port("deferred", "color")).ok());
    const Error error = plan_error(graph);
    EXPECT_EQ(error.code, ErrorCode::Graph);
    EXPECT_EQ(error.message, "required input deferred.normal is not connected");
}

TEST(GraphErrors, OptionalInputMayStayUnconnected) {
    FrameGraph graph = chain();
    auto plan = build_plan(graph, {});
    ASSERT_TRUE(plan.ok()) << plan.error().to_string();
    const PlanPass* sink = plan->find_pass("sink");
    ASSERT_NE(sink, nullptr);
    EXPECT_EQ(sink->ports[1].name, "extra");
    EXPECT_FALSE(sink->ports[1].resource.has_value());
}

TEST(GraphErrors, PassReadingWhatItModifiesInPlace) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("scene").output("color")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("smear").input("original").inout("color")).ok());
    ASSERT_TRUE(graph.connect(port("scene", "color"), port("smear", "original")).ok());
    ASSERT_TRUE(graph.connect(port("scene", "color"), port("smear", "color")).ok());
    ASSERT_TRUE(graph.mark_output(port("smear", "color")).ok());
    EXPECT_EQ(plan_error(graph).message,
              "pass 'smear' reads scene.color through smear.original while modifying it in place through smear.color "
              "(one pass may read and modify one resource only in disjoint ranges)");
}

TEST(GraphErrors, PassNamesAreUniqueAndNonEmpty) {
    FrameGraph graph = chain();
    auto duplicate = graph.add_pass(Pass("producer"));
    ASSERT_FALSE(duplicate.ok());
    EXPECT_EQ(duplicate.error().message, "add_pass: a pass called 'producer' already exists");
    EXPECT_FALSE(graph.add_pass(Pass("")).ok());
}

TEST(GraphErrors, GraphOutputsAreProducedTextures) {
    FrameGraph graph = chain();
    Status status = graph.mark_output(port("sink", "source"));
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find("mark_output sink.source: an input cannot be a graph output"),
              std::string::npos);
    EXPECT_EQ(graph.mark_output(port("sink", "nope")).error().message,
              "mark_output sink.nope: unknown port 'nope' on pass 'sink' (its ports: source, extra, final)");
    EXPECT_FALSE(graph.set_side_effect("nobody").ok());
}

TEST(GraphErrors, NothingToRun) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("lonely").output("color")).ok());
    const Error error = plan_error(graph);
    EXPECT_EQ(error.code, ErrorCode::Graph);
    EXPECT_NE(error.message.find("nothing to run"), std::string::npos);
}

TEST(GraphErrors, ConflictingConnectedPortsNameBothPorts) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("geometry").output("position", TextureSpec::of(Format::RGBA16Float))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("ids").output("id", TextureSpec::of(Format::R32Uint))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("deferred").input("position", TextureSpec::of(Format::R32Uint)).input("id").output("color")).ok());
    ASSERT_TRUE(graph.connect(port("geometry", "position"), port("deferred", "position")).ok());
    ASSERT_TRUE(graph.connect(port("ids", "id"), port("deferred", "id")).ok());
    ASSERT_TRUE(graph.mark_output(port("deferred", "color")).ok());
    const Error error = plan_error(graph);
    EXPECT_EQ(error.code, ErrorCode::Join);
    EXPECT_EQ(error.message,
              "cannot join geometry.position and deferred.position: format channel R kind 16 float vs 32 uint "
              "(RGBA16Float vs R32Uint)");
}

TEST(GraphErrors, JoinErrorNamesThePortThatSetTheConflictingProperty) {
    // The format comes from `a.out`, the size from `b.in`; `c.in` contradicts the size.
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("a").output("out", TextureSpec::of(Format::RGBA8Unorm))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("b").input("in", TextureSpec{}.with_size(256, 256)).output("out")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("c").input("in", TextureSpec{}.with_scale(0.5f)).output("out")).ok());
    ASSERT_TRUE(graph.connect(port("a", "out"), port("b", "in")).ok());
    ASSERT_TRUE(graph.connect(port("a", "out"), port("c", "in")).ok());
    ASSERT_TRUE(graph.mark_output(port("b", "out")).ok());
    ASSERT_TRUE(graph.mark_output(port("c", "out")).ok());
    PlanOptions options;
    options.frame = {1024, 768};
    EXPECT_EQ(plan_error(graph, options).message,
              "cannot join b.in and c.in: size 256x256 vs 512x384 (0.5 x frame) (frame 1024x768)");
}

TEST(GraphErrors, ErrorsInCulledPassesAreStillReported) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("scene").output("color", TextureSpec::of(Format::RGBA8Unorm))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("unused").input("depth", TextureSpec::of(Format::Depth16))).ok());
    ASSERT_TRUE(graph.connect(port("scene", "color"), port("unused", "depth")).ok());
    ASSERT_TRUE(graph.mark_output(port("scene", "color")).ok());
    const Error error = plan_error(graph);
    EXPECT_EQ(error.code, ErrorCode::Join);
    EXPECT_NE(error.message.find("cannot join scene.color and unused.depth"), std::string::npos) << error.message;
}

TEST(GraphErrors, BadOptions) {
    FrameGraph graph = chain();
    PlanOptions options;
    // A value outside AllocatorKind (only a cast makes one; names are parsed where they come in,
    // GraphErrors.AllocatorNames) is refused at plan time.
    options.allocator = static_cast<AllocatorKind>(7);
    Error error = plan_error(graph, options);
    EXPECT_EQ(error.code, ErrorCode::InvalidArgument);
    EXPECT_EQ(error.message, "plan: unknown allocator kind 7");
    options.allocator = AllocatorKind::Paper;
    options.frame = {0, 720};
    EXPECT_EQ(plan_error(graph, options).code, ErrorCode::InvalidArgument);
}

// Names are parsed once, where they come from a user; the kinds and the names match both ways.
TEST(GraphErrors, AllocatorNames) {
    for (AllocatorKind kind : allocator_kinds()) {
        auto parsed = parse_allocator(allocator_name(kind));
        ASSERT_TRUE(parsed.ok()) << allocator_name(kind);
        EXPECT_EQ(*parsed, kind);
    }
    EXPECT_EQ(allocator_names().size(), allocator_kinds().size());
    auto typo = parse_allocator("Heap");
    ASSERT_FALSE(typo.ok());
    EXPECT_EQ(typo.error().code, ErrorCode::InvalidArgument);
    EXPECT_EQ(typo.error().message, "unknown allocator 'Heap' (known: paper, interval, heap)");
}

}  // namespace
}  // namespace loom::fg

// The phases of build_plan one by one (framegraph/src/plan_phases.hpp), each given plain data
// and checked value by value: cull, schedule, join, resolve, spec classes, the allocation
// problem, allocate (with a fake allocator for the answers no real allocator gives) and summary.
#include <algorithm>

#include <gtest/gtest.h>

#include "loom/framegraph/framegraph.hpp"
#include "plan_phases.hpp"
#include "random_graph.hpp"

namespace loom::fg::detail {
namespace {

using rhi::Format;
using rhi::TextureUsage;

constexpr Extent2D kFrame{64, 32};

// Declared out of order; "debug_view" is culled (nothing reads its output), "stats" runs for its
// side effect, and present.final is a graph output.
//   gbuffer.albedo → light.albedo    gbuffer.depth → light.depth    light.hdr → present.hdr
//   gbuffer.debug (optional) → debug_view.debug
FrameGraph deferred_graph() {
    FrameGraph graph;
    EXPECT_TRUE(graph.add_pass(Pass("present").input("hdr").output("final", TextureSpec{}.with_size(16, 16))).ok());
    EXPECT_TRUE(graph
                    .add_pass(Pass("gbuffer")
                                  .output("albedo", TextureSpec::of(Format::RGBA16Float))
                                  .output("depth", TextureSpec::of(Format::Depth32F))
                                  .optional_output("debug"))
                    .ok());
    EXPECT_TRUE(graph.add_pass(Pass("debug_view").input("debug").output("view")).ok());
    EXPECT_TRUE(graph.add_pass(Pass("light").input("albedo").input("depth").output("hdr")).ok());
    EXPECT_TRUE(graph
                    .add_pass(Pass("stats")
                                  .output("histogram", TextureSpec::of(Format::R32Float).with_size(256, 1))
                                  .set_side_effect())
                    .ok());
    EXPECT_TRUE(graph.connect(port("gbuffer", "albedo"), port("light", "albedo")).ok());
    EXPECT_TRUE(graph.connect(port("gbuffer", "depth"), port("light", "depth")).ok());
    EXPECT_TRUE(graph.connect(port("gbuffer", "debug"), port("debug_view", "debug")).ok());
    EXPECT_TRUE(graph.connect(port("light", "hdr"), port("present", "hdr")).ok());
    EXPECT_TRUE(graph.mark_output(port("present", "final")).ok());
    return graph;
}

Dependencies must_analyze(const FrameGraph& graph) {
    auto dependencies = analyze(graph);
    EXPECT_TRUE(dependencies.ok()) << dependencies.error().to_string();
    return dependencies.ok() ? std::move(*dependencies) : Dependencies{};
}

Schedule must_schedule(const FrameGraph& graph) {
    const Dependencies dependencies = must_analyze(graph);
    auto kept = cull_passes(graph, dependencies);
    EXPECT_TRUE(kept.ok()) << kept.error().to_string();
    return kept.ok() ? schedule_passes(dependencies, *kept) : Schedule{};
}

ResolvedSpec resolved_spec(Format format, FormatMatch match, Extent2D extent, TextureUsage usage) {
    ResolvedSpec spec;
    spec.format = format;
    spec.format_match = match;
    spec.extent = extent;
    spec.usage = usage;
    return spec;
}

// ---- cull and schedule -----------------------------------------------------------------------

TEST(PlanPhases, CullKeepsWhatOutputsAndSideEffectsNeedAndScheduleOrdersIt) {
    const FrameGraph graph = deferred_graph();
    const Dependencies dependencies = must_analyze(graph);
    auto kept = cull_passes(graph, dependencies);
    ASSERT_TRUE(kept.ok()) << kept.error().to_string();
    EXPECT_EQ(*kept, (std::vector<bool>{true, true, false, true, true}));
    EXPECT_EQ(culled_pass_names(graph, *kept), (std::vector<std::string>{"debug_view"}));

    // gbuffer and stats are ready at first, gbuffer declared first; then light (declared before
    // stats); then present (declared before stats); then stats.
    const Schedule schedule = schedule_passes(dependencies, *kept);
    EXPECT_EQ(schedule.order, (std::vector<uint32_t>{1, 3, 0, 4}));
    EXPECT_EQ(schedule.position, (std::vector<uint32_t>{2, 0, kNotScheduled, 1, 3}));
}

TEST(PlanPhases, CullFailsWhenNothingWouldRun) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("scene").output("color")).ok());
    auto kept = cull_passes(graph, must_analyze(graph));
    ASSERT_FALSE(kept.ok());
    EXPECT_EQ(kept.error().code, ErrorCode::Graph);
    EXPECT_EQ(kept.error().message,
              "nothing to run: no graph output and no side-effect pass (mark_output the final texture)");
}

TEST(PlanPhases, ScheduleBreaksTiesByDeclarationOrder) {
    // Pass 3 must run before 0, and 4 before 1; 2 is free.
    const Dependencies dependencies{{{}, {}, {}, {0}, {1}}, {{3}, {4}, {}, {}, {}}};
    const Schedule all = schedule_passes(dependencies, {true, true, true, true, true});
    EXPECT_EQ(all.order, (std::vector<uint32_t>{2, 3, 0, 4, 1}));
    EXPECT_EQ(all.position, (std::vector<uint32_t>{2, 4, 0, 1, 3}));

    const Schedule without_1 = schedule_passes(dependencies, {true, false, true, true, true});
    EXPECT_EQ(without_1.order, (std::vector<uint32_t>{2, 3, 0, 4}));
    EXPECT_EQ(without_1.position, (std::vector<uint32_t>{2, kNotScheduled, 0, 1, 3}));
}

// ---- join -------------------------------------------------------------------------------------

TEST(PlanPhases, JoinCollectsEveryGroupInDeclarationOrder) {
    const FrameGraph graph = deferred_graph();
    const std::vector<JoinedGroup> groups = join_port_groups(graph, kFrame);
    const std::vector<std::vector<PortAddress>> expected_ports{
        {{0, 1}},          // present.final
        {{1, 0}, {3, 0}},  // gbuffer.albedo → light.albedo
        {{1, 1}, {3, 1}},  // gbuffer.depth → light.depth
        {{1, 2}, {2, 0}},  // gbuffer.debug → debug_view.debug (a culled reader: joined all the same)
        {{2, 1}},          // debug_view.view
        {{3, 2}, {0, 0}},  // light.hdr → present.hdr
        {{4, 0}},          // stats.histogram
    };
    ASSERT_EQ(groups.size(), expected_ports.size());
    for (std::size_t g = 0; g < groups.size(); ++g) {
        EXPECT_EQ(groups[g].ports, expected_ports[g]) << g;
        EXPECT_TRUE(groups[g].spec.ok()) << g;
    }
    EXPECT_EQ(*groups[1].spec, TextureSpec::of(Format::RGBA16Float));
    EXPECT_EQ(*groups[5].spec, TextureSpec{});
}

TEST(PlanPhases, JoinFollowsInOutsAndJoinsInGroupOrder) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("scene").output("color", TextureSpec::of(Format::RGBA16Float))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("tint").inout("color", TextureSpec{}.with_size(32, 16))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("histogram").input("color", TextureSpec{}.with_samples(1))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("present").input("color")).ok());
    ASSERT_TRUE(graph.connect(port("scene", "color"), port("histogram", "color")).ok());
    ASSERT_TRUE(graph.connect(port("scene", "color"), port("tint", "color")).ok());
    ASSERT_TRUE(graph.connect(port("tint", "color"), port("present", "color")).ok());

    const std::vector<JoinedGroup> groups = join_port_groups(graph, kFrame);
    ASSERT_EQ(groups.size(), 1u);
    EXPECT_EQ(groups[0].ports, (std::vector<PortAddress>{{0, 0}, {2, 0}, {1, 0}, {3, 0}}));
    ASSERT_TRUE(groups[0].spec.ok());
    EXPECT_EQ(*groups[0].spec, TextureSpec::of(Format::RGBA16Float).with_size(32, 16).with_samples(1));
}

TEST(PlanPhases, JoinErrorsNameThePortThatConstrainedThePropertyAndThePortThatContradictsIt) {
    // geometry constrains the format, blur only the size; tonemap contradicts geometry.
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("geometry").output("color", TextureSpec::of(Format::RGBA8Unorm))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("blur").input("color", TextureSpec{}.with_size(64, 32))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("tonemap").input("color", TextureSpec::of(Format::RGBA16Float))).ok());
    ASSERT_TRUE(graph.connect(port("geometry", "color"), port("blur", "color")).ok());
    ASSERT_TRUE(graph.connect(port("geometry", "color"), port("tonemap", "color")).ok());

    const std::vector<JoinedGroup> groups = join_port_groups(graph, kFrame);
    ASSERT_EQ(groups.size(), 1u);
    ASSERT_FALSE(groups[0].spec.ok());
    const Error& error = groups[0].spec.error();
    EXPECT_EQ(error.code, ErrorCode::Join);
    EXPECT_EQ(error.message,
              "cannot join geometry.color and tonemap.color: format channel R kind 8 unorm vs 16 float "
              "(RGBA8Unorm vs RGBA16Float)");
    EXPECT_EQ(error.subjects, (std::vector<std::string>{"tonemap.color", "geometry.color"}));

    // A relative size against an absolute one: equal once the frame is known, else a conflict.
    FrameGraph sized;
    ASSERT_TRUE(sized.add_pass(Pass("a").output("x", TextureSpec{}.with_scale(0.5f))).ok());
    ASSERT_TRUE(sized.add_pass(Pass("b").input("x", TextureSpec{}.with_size(32, 16))).ok());
    ASSERT_TRUE(sized.connect(port("a", "x"), port("b", "x")).ok());
    EXPECT_TRUE(join_port_groups(sized, kFrame)[0].spec.ok());
    const std::vector<JoinedGroup> other_frame = join_port_groups(sized, {128, 128});
    ASSERT_FALSE(other_frame[0].spec.ok());
    EXPECT_EQ(other_frame[0].spec.error().subjects, (std::vector<std::string>{"b.x", "a.x"}));
}

// ---- resolve ----------------------------------------------------------------------------------

TEST(PlanPhases, ResolveMakesTheResourcesOfRunningPassesWithUsagesLifetimesAndBytes) {
    const FrameGraph graph = deferred_graph();
    const Schedule schedule = must_schedule(graph);
    DefaultMemoryModel memory(256);
    auto resolved = resolve_resources(graph, join_port_groups(graph, kFrame), schedule, kFrame, memory);
    ASSERT_TRUE(resolved.ok()) << resolved.error().to_string();

    // By producer position (gbuffer 0, light 1, present 2, stats 3), then port. gbuffer.debug
    // has no resource: it is optional and its only reader is culled.
    std::vector<PlanResource> expected(5);
    expected[0].name = "gbuffer.albedo";
    expected[0].ports = {"gbuffer.albedo", "light.albedo"};
    expected[0].requested_format = TextureSpec::of(Format::RGBA16Float).format;
    expected[0].spec = resolved_spec(Format::RGBA16Float, FormatMatch::Exact, kFrame,
                                     TextureUsage::ColorAttachment | TextureUsage::Sampled);
    expected[0].lifetime = {0, 1};
    expected[0].bytes = 64 * 32 * 8;
    expected[1].name = "gbuffer.depth";
    expected[1].ports = {"gbuffer.depth", "light.depth"};
    expected[1].requested_format = TextureSpec::of(Format::Depth32F).format;
    expected[1].spec = resolved_spec(Format::Depth32F, FormatMatch::Exact, kFrame,
                                     TextureUsage::DepthStencilAttachment | TextureUsage::Sampled);
    expected[1].lifetime = {0, 1};
    expected[1].bytes = 64 * 32 * 4;
    expected[2].name = "light.hdr";
    expected[2].ports = {"light.hdr", "present.hdr"};
    expected[2].spec = resolved_spec(kDefaultFormat, FormatMatch::Default, kFrame,
                                     TextureUsage::ColorAttachment | TextureUsage::Sampled);
    expected[2].lifetime = {1, 2};
    expected[2].bytes = 64 * 32 * 4;
    // A graph output is copied out after the frame: CopySrc, and alive to the last position.
    expected[3].name = "present.final";
    expected[3].ports = {"present.final"};
    expected[3].spec = resolved_spec(kDefaultFormat, FormatMatch::Default, {16, 16},
                                     TextureUsage::ColorAttachment | TextureUsage::CopySrc);
    expected[3].lifetime = {2, 3};
    expected[3].graph_output = true;
    expected[3].bytes = 16 * 16 * 4;
    expected[4].name = "stats.histogram";
    expected[4].ports = {"stats.histogram"};
    expected[4].requested_format = TextureSpec::of(Format::R32Float).format;
    expected[4].spec = resolved_spec(Format::R32Float, FormatMatch::Exact, {256, 1}, TextureUsage::ColorAttachment);
    expected[4].lifetime = {3, 3};
    expected[4].bytes = 256 * 4;
    for (PlanResource& resource : expected) {
        resource.alignment = 256;
        resource.occupancy = resource.lifetime;  // no async passes: held exactly while alive
    }
    // The ports are kept as addresses and named only when the plan is put together.
    for (const PlanResource& resource : resolved->resources) EXPECT_TRUE(resource.ports.empty()) << resource.name;
    name_resource_ports(plan_passes(graph, schedule, *resolved), *resolved);
    EXPECT_EQ(resolved->resources, expected);

    EXPECT_EQ(resolved->resource_of_port, (std::vector<std::vector<uint32_t>>{
                                              {2, 3},                      // present: hdr, final
                                              {0, 1, kNoResource},         // gbuffer: albedo, depth, debug
                                              {kNoResource, kNoResource},  // debug_view (culled)
                                              {0, 1, 2},                   // light: albedo, depth, hdr
                                              {4},                         // stats
                                          }));
    EXPECT_EQ(resolved->graph_output_resources, (std::vector<uint32_t>{3}));

    // Each running pass with the resource and the usage of each port's role.
    const std::vector<PlanPass> passes = plan_passes(graph, schedule, *resolved);
    ASSERT_EQ(passes.size(), 4u);
    // A texture port with a resource uses its one mip and layer.
    auto planned = [](std::string name, PortKind kind, bool optional, std::optional<uint32_t> resource, TextureUsage usage) {
        PlanPort port{std::move(name), kind, optional, resource, usage};
        if (resource) port.range = {0, 1, 0, 1};
        return port;
    };
    EXPECT_EQ(passes[0], (PlanPass{"gbuffer",
                                   1,
                                   false,
                                   {planned("albedo", PortKind::Output, false, 0u, TextureUsage::ColorAttachment),
                                    planned("depth", PortKind::Output, false, 1u, TextureUsage::DepthStencilAttachment),
                                    planned("debug", PortKind::Output, true, std::nullopt, TextureUsage::None)}}));
    EXPECT_EQ(passes[1], (PlanPass{"light",
                                   3,
                                   false,
                                   {planned("albedo", PortKind::Input, false, 0u, TextureUsage::Sampled),
                                    planned("depth", PortKind::Input, false, 1u, TextureUsage::Sampled),
                                    planned("hdr", PortKind::Output, false, 2u, TextureUsage::ColorAttachment)}}));
    EXPECT_EQ(passes[2].name, "present");
    EXPECT_EQ(
        passes[3],
        (PlanPass{"stats", 4, true, {planned("histogram", PortKind::Output, false, 4u, TextureUsage::ColorAttachment)}}));

    // Connections between running passes, by position; the one into debug_view is left out.
    EXPECT_EQ(plan_edges(graph, schedule, resolved->resource_of_port),
              (std::vector<PlanEdge>{{0, 0, 1, 0, 0}, {0, 1, 1, 1, 1}, {1, 2, 2, 0, 2}}));
}

TEST(PlanPhases, ResolveErrorsNameTheRunningPortsOfTheResource) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("a").output("x", TextureSpec{}.with_samples(3))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("b").input("x").output("out")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("c").input("x").output("unused")).ok());
    ASSERT_TRUE(graph.connect(port("a", "x"), port("b", "x")).ok());
    ASSERT_TRUE(graph.connect(port("a", "x"), port("c", "x")).ok());
    ASSERT_TRUE(graph.mark_output(port("b", "out")).ok());
    DefaultMemoryModel memory;
    auto resolved = resolve_resources(graph, join_port_groups(graph, kFrame), must_schedule(graph), kFrame, memory);
    ASSERT_FALSE(resolved.ok());
    EXPECT_EQ(resolved.error().code, ErrorCode::Graph);
    EXPECT_EQ(resolved.error().message, "a.x: samples 3 is not one of 1, 2, 4, 8, 16, 32, 64");
    EXPECT_EQ(resolved.error().subjects, (std::vector<std::string>{"a.x", "b.x"}));  // c is culled
}

TEST(PlanPhases, ResolveReportsTheFirstGroupAtFaultWhateverItsFault) {
    // Group 0 (first.x) does not resolve; group 1 (second.y) does not join and belongs to no
    // running pass. The first group's error comes first.
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("first").output("x", TextureSpec{}.with_samples(3))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("second").output("y", TextureSpec::of(Format::RGBA8Unorm))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("third").input("y", TextureSpec::of(Format::Depth32F)).output("z")).ok());
    ASSERT_TRUE(graph.connect(port("second", "y"), port("third", "y")).ok());
    ASSERT_TRUE(graph.mark_output(port("first", "x")).ok());
    const Schedule schedule = must_schedule(graph);
    ASSERT_EQ(schedule.order, (std::vector<uint32_t>{0}));
    DefaultMemoryModel memory;
    const std::vector<JoinedGroup> groups = join_port_groups(graph, kFrame);
    auto resolved = resolve_resources(graph, groups, schedule, kFrame, memory);
    ASSERT_FALSE(resolved.ok());
    EXPECT_EQ(resolved.error().message, "first.x: samples 3 is not one of 1, 2, 4, 8, 16, 32, 64");

    // Without the first fault, the join error of the culled group is reported.
    const std::vector<JoinedGroup> join_fault_only{groups[1]};
    resolved = resolve_resources(graph, join_fault_only, schedule, kFrame, memory);
    ASSERT_FALSE(resolved.ok());
    EXPECT_EQ(resolved.error().code, ErrorCode::Join);
    EXPECT_EQ(resolved.error().subjects, (std::vector<std::string>{"third.y", "second.y"}));
}

class FailingMemoryModel final : public MemoryModel {
public:
    Result<rhi::MemoryRequirements> requirements(const rhi::TextureDesc& desc) override {
        return make_error(ErrorCode::OutOfMemory, "no memory for " + desc.name);
    }
};

TEST(PlanPhases, ResolvePassesOnMemoryModelErrors) {
    const FrameGraph graph = deferred_graph();
    FailingMemoryModel memory;
    auto resolved = resolve_resources(graph, join_port_groups(graph, kFrame), must_schedule(graph), kFrame, memory);
    ASSERT_FALSE(resolved.ok());
    EXPECT_EQ(resolved.error().code, ErrorCode::OutOfMemory);
    EXPECT_EQ(resolved.error().message, "no memory for present.final");  // the first group
}

// ---- spec classes -----------------------------------------------------------------------------

PlanResource resource(std::string name, Format format, Extent2D extent, TextureUsage usage, Lifetime lifetime,
                      uint64_t bytes) {
    PlanResource out;
    out.name = std::move(name);
    out.spec = resolved_spec(format, FormatMatch::Exact, extent, usage);
    out.lifetime = lifetime;
    out.occupancy = lifetime;
    out.bytes = bytes;
    out.alignment = 256;
    return out;
}

std::vector<PlanResource> class_resources() {
    return {
        resource("a", Format::RGBA8Unorm, {64, 64}, TextureUsage::ColorAttachment, {0, 1}, 100),
        resource("b", Format::R8Unorm, {64, 64}, TextureUsage::Sampled, {0, 2}, 200),
        resource("c", Format::RGBA8Unorm, {64, 64}, TextureUsage::Sampled, {1, 2}, 100),
        resource("d", Format::RGBA16Float, {64, 64}, TextureUsage::ColorAttachment, {2, 2}, 400),
        resource("e", Format::RGBA8Unorm, {32, 32}, TextureUsage::ColorAttachment, {2, 2}, 50),
    };
}

TEST(PlanPhases, EqualSharingMakesAClassPerTextureShape) {
    const SpecClassAssignment classes = assign_spec_classes(class_resources(), SpecSharing::Equal, kFrame, 3);
    EXPECT_EQ(classes.class_of_resource, (std::vector<uint32_t>{0, 1, 0, 2, 3}));
    const auto rgba8 = resolved_spec(Format::RGBA8Unorm, FormatMatch::Exact, {64, 64},
                                     TextureUsage::ColorAttachment | TextureUsage::Sampled);
    EXPECT_EQ(
        classes.classes,
        (std::vector<SpecClass>{
            {rgba8, {0, 2}, 2, ResourceType::Texture, {}},  // a and c are both alive at position 1
            {resolved_spec(Format::R8Unorm, FormatMatch::Exact, {64, 64}, TextureUsage::Sampled), {1}, 1, ResourceType::Texture, {}},
            {resolved_spec(Format::RGBA16Float, FormatMatch::Exact, {64, 64}, TextureUsage::ColorAttachment), {3}, 1,
             ResourceType::Texture, {}},
            {resolved_spec(Format::RGBA8Unorm, FormatMatch::Exact, {32, 32}, TextureUsage::ColorAttachment), {4}, 1,
             ResourceType::Texture, {}},
        }));
    EXPECT_EQ(classes.peak_live_bytes, 200u + 100u + 400u + 50u);  // position 2: b, c, d, e
}

TEST(PlanPhases, JoinableSharingPutsEachResourceInTheFirstClassItJoins) {
    const SpecClassAssignment classes = assign_spec_classes(class_resources(), SpecSharing::Joinable, kFrame, 3);
    // b (R8) joins a's class (RGBA8); d (RGBA16Float) does not, e (another size) joins nothing.
    EXPECT_EQ(classes.class_of_resource, (std::vector<uint32_t>{0, 0, 0, 1, 2}));
    ASSERT_EQ(classes.classes.size(), 3u);
    EXPECT_EQ(classes.classes[0].spec, resolved_spec(Format::RGBA8Unorm, FormatMatch::Exact, {64, 64},
                                                     TextureUsage::ColorAttachment | TextureUsage::Sampled));
    EXPECT_EQ(classes.classes[0].resources, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(classes.classes[0].peak_live, 3u);
    EXPECT_EQ(classes.classes[1].resources, (std::vector<uint32_t>{3}));
    EXPECT_EQ(classes.classes[2].resources, (std::vector<uint32_t>{4}));
    EXPECT_EQ(classes.peak_live_bytes, 750u);
}

// ---- allocate ---------------------------------------------------------------------------------

TEST(PlanPhases, TheAllocationProblemComesFromThePlansPorts) {
    // a.out → b.in; b.canvas starts a resource in place; b.canvas → c.in; c.out is a graph output.
    const PlanPort unread_debug{"debug", PortKind::Output, true, std::nullopt, {}};
    const std::vector<PlanPass> order{
        {"a", 0, false, {{"out", PortKind::Output, false, 0u, {}}, unread_debug}},
        {"b", 1, false, {{"in", PortKind::Input, false, 0u, {}}, {"canvas", PortKind::InOut, true, 1u, {}}}},
        {"c", 2, false, {{"in", PortKind::Input, false, 1u, {}}, {"out", PortKind::Output, false, 2u, {}}}},
    };
    std::vector<PlanResource> resources{
        resource("a.out", Format::RGBA8Unorm, kFrame, {}, {0, 1}, 100),
        resource("b.canvas", Format::RGBA16Float, kFrame, {}, {1, 2}, 200),
        resource("c.out", Format::RGBA8Unorm, kFrame, {}, {2, 2}, 100),
    };
    resources[1].spec_class = 1;
    const AllocationProblem problem = make_allocation_problem(order, resources, {2}, 2, 4096);

    ASSERT_EQ(problem.passes.size(), 3u);
    const std::vector<std::vector<uint32_t>> inputs{{}, {0, 1}, {1}};
    const std::vector<std::vector<uint32_t>> non_inputs{{0}, {1}, {2}};
    for (uint32_t at = 0; at < 3; ++at) {
        EXPECT_EQ(problem.passes[at].inputs, inputs[at]) << at;
        EXPECT_EQ(problem.passes[at].non_inputs, non_inputs[at]) << at;
        EXPECT_EQ(problem.passes[at].begins, (std::vector<uint32_t>{at})) << at;
    }
    ASSERT_EQ(problem.resources.size(), 3u);
    EXPECT_EQ(problem.resources[1].spec_class, 1u);
    EXPECT_EQ(problem.resources[1].lifetime, (Lifetime{1, 2}));
    EXPECT_EQ(problem.resources[1].bytes, 200u);
    EXPECT_EQ(problem.resources[1].alignment, 256u);
    EXPECT_EQ(problem.resources[1].name, "b.canvas");
    EXPECT_EQ(problem.graph_outputs, (std::vector<uint32_t>{2}));
    EXPECT_EQ(problem.spec_class_count, 2u);
    EXPECT_EQ(problem.max_heap_bytes, 4096u);
}

// Gives the same answer to every problem: what a buggy allocator might return.
class FakeAllocator final : public Allocator {
public:
    explicit FakeAllocator(Result<Allocation> answer) : answer_(std::move(answer)) {}
    [[nodiscard]] std::string_view name() const override { return "fake"; }
    [[nodiscard]] Result<Allocation> allocate(const AllocationProblem&) const override { return answer_; }

private:
    Result<Allocation> answer_;
};

std::vector<PlanResource> allocation_resources() {
    return {
        resource("a.out", Format::RGBA8Unorm, {64, 64}, TextureUsage::ColorAttachment, {0, 0}, 1000),
        resource("b.out", Format::RGBA8Unorm, {64, 64}, TextureUsage::ColorAttachment, {0, 1}, 1001),
        resource("c.out", Format::RGBA8Unorm, {64, 64}, TextureUsage::Sampled, {1, 1}, 1002),
        resource("d.out", Format::RGBA16Float, {64, 64}, TextureUsage::ColorAttachment, {1, 1}, 1003),
    };
}

Result<TextureAssignment> allocate_with(Result<Allocation> answer) {
    const std::vector<PlanResource> resources = allocation_resources();
    AllocationProblem problem;
    problem.resources.resize(resources.size());
    DefaultMemoryModel memory(256);
    return allocate_textures(FakeAllocator(std::move(answer)), problem, resources, kFrame, memory);
}

TEST(PlanPhases, AllocateNumbersTexturesByFirstUse) {
    // The allocator's texture 2 is first used by resource 0, texture 0 by 1, texture 1 by 3.
    Allocation answer;
    answer.texture_of_resource = {2, 0, 2, 1};
    answer.texture_count = 3;
    answer.texture_placement = {{0, 0}, {0, 65536}, {1, 0}};
    answer.heap_sizes = {131072, 65536};
    auto assignment = allocate_with(answer);
    ASSERT_TRUE(assignment.ok()) << assignment.error().to_string();

    EXPECT_EQ(assignment->texture_of_resource, (std::vector<uint32_t>{0, 1, 0, 2}));
    const std::vector<PlanResource> resources = allocation_resources();
    ASSERT_EQ(assignment->textures.size(), 3u);
    // Shared: the join of a and c (usage: the union), bytes from the memory model.
    EXPECT_EQ(assignment->textures[0],
              (PlanTexture{"t0",
                           resolved_spec(Format::RGBA8Unorm, FormatMatch::Exact, {64, 64},
                                         TextureUsage::ColorAttachment | TextureUsage::Sampled),
                           {0, 2},
                           64 * 64 * 4,
                           256,
                           HeapRange{1, 0}}));
    // Not shared: the resource's own spec and bytes.
    EXPECT_EQ(assignment->textures[1], (PlanTexture{"t1", resources[1].spec, {1}, 1001, 256, HeapRange{0, 0}}));
    EXPECT_EQ(assignment->textures[2], (PlanTexture{"t2", resources[3].spec, {3}, 1003, 256, HeapRange{0, 65536}}));
    EXPECT_EQ(assignment->heaps, (std::vector<uint64_t>{131072, 65536}));

    // Without placements, no texture is placed.
    answer.texture_placement.clear();
    answer.heap_sizes.clear();
    assignment = allocate_with(answer);
    ASSERT_TRUE(assignment.ok()) << assignment.error().to_string();
    for (const PlanTexture& texture : assignment->textures) EXPECT_EQ(texture.placement, std::nullopt);
    EXPECT_TRUE(assignment->heaps.empty());
}

TEST(PlanPhases, AllocateRefusesMalformedAnswers) {
    struct Case {
        std::vector<uint32_t> texture_of_resource;
        uint32_t texture_count;
        std::size_t placements;
        std::string message;
    };
    const std::string malformed = "allocator 'fake' returned a malformed allocation";
    const std::vector<Case> cases{
        {{0, 0, 0}, 1, 0, malformed},                                              // a resource without a texture
        {{0, 1, 0, 3}, 3, 0, malformed},                                           // a texture beyond the count
        {{0, 1, 0, 2}, 3, 2, malformed},                                           // placements for only 2 of 3
        {{0, 1, 0, 2}, 4, 0, "allocator 'fake' made a texture no resource uses"},  // texture 3
        {{0, 0, 1, 1}, 2, 0, "allocator 'fake' put d.out into a texture of a spec it does not join with"},
    };
    for (const Case& c : cases) {
        Allocation answer;
        answer.texture_of_resource = c.texture_of_resource;
        answer.texture_count = c.texture_count;
        answer.texture_placement.resize(c.placements);
        auto assignment = allocate_with(answer);
        ASSERT_FALSE(assignment.ok()) << c.message;
        EXPECT_EQ(assignment.error().code, ErrorCode::Graph) << c.message;
        EXPECT_EQ(assignment.error().message, c.message);
    }
    // The allocator's own error comes back as it is.
    auto refused = allocate_with(make_error(ErrorCode::OutOfMemory, "heap budget of 1 byte is too small"));
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().code, ErrorCode::OutOfMemory);
    EXPECT_EQ(refused.error().message, "heap budget of 1 byte is too small");
}

// ---- summary ----------------------------------------------------------------------------------

TEST(PlanPhases, SummaryCountsTexturesBytesAndBounds) {
    Plan plan;
    plan.resources = {resource("a", Format::RGBA8Unorm, kFrame, {}, {0, 0}, 100),
                      resource("b", Format::RGBA8Unorm, kFrame, {}, {1, 1}, 50),
                      resource("c", Format::RGBA16Float, kFrame, {}, {0, 1}, 300)};
    plan.spec_classes = {{plan.resources[0].spec, {0, 1}, 1, ResourceType::Texture, {}},
                         {plan.resources[2].spec, {2}, 1, ResourceType::Texture, {}}};
    plan.textures = {{"t0", plan.resources[0].spec, {0, 1}, 100, 256, std::nullopt},
                     {"t1", plan.resources[2].spec, {2}, 300, 256, std::nullopt}};
    EXPECT_EQ(summarize_plan(plan, 400), (PlanSummary{2, 400, 3, 450, 2, 400}));

    // Placed textures: the memory is the heaps', not the textures'.
    plan.textures[0].placement = HeapRange{0, 0};
    plan.textures[1].placement = HeapRange{1, 0};
    plan.heaps = {1000, 24};
    EXPECT_EQ(summarize_plan(plan, 400), (PlanSummary{2, 1024, 3, 450, 2, 400}));
}

// build_plan joins and resolves group by group (resolve_resources without groups): the same
// resources, numbering, ports and first error as joining every group first.
TEST(PlanPhases, ResolvingWhileJoiningGivesWhatJoiningFirstGives) {
    auto same = [](const FrameGraph& graph, const std::string& what) {
        auto dependencies = analyze(graph);
        ASSERT_TRUE(dependencies.ok()) << what;
        auto kept = cull_passes(graph, *dependencies);
        ASSERT_TRUE(kept.ok()) << what;
        const Schedule schedule = schedule_passes(*dependencies, *kept);
        DefaultMemoryModel memory;
        auto joined_first = resolve_resources(graph, join_port_groups(graph, kFrame), schedule, kFrame, memory);
        auto while_joining = resolve_resources(graph, schedule, kFrame, memory);
        ASSERT_EQ(joined_first.ok(), while_joining.ok()) << what;
        if (!joined_first.ok()) {
            EXPECT_EQ(joined_first.error().message, while_joining.error().message) << what;
            EXPECT_EQ(joined_first.error().subjects, while_joining.error().subjects) << what;
            return;
        }
        EXPECT_EQ(joined_first->resources, while_joining->resources) << what;
        EXPECT_EQ(joined_first->resource_of_port, while_joining->resource_of_port) << what;
        EXPECT_EQ(joined_first->graph_output_resources, while_joining->graph_output_resources) << what;
        EXPECT_EQ(joined_first->starts, while_joining->starts) << what;
        EXPECT_EQ(joined_first->running_ports, while_joining->running_ports) << what;
        EXPECT_EQ(joined_first->first_running_port, while_joining->first_running_port) << what;
    };
    same(deferred_graph(), "deferred");
    for (uint64_t seed = 1; seed <= 60; ++seed) {
        testing::RandomGraphOptions options;
        options.passes = 2 + static_cast<uint32_t>(seed % 30);
        options.buffer_percent = seed % 2 == 0 ? 25 : 0;
        options.subresource_percent = seed % 3 == 0 ? 20 : 0;
        same(testing::random_graph(seed, options), "seed " + std::to_string(seed));
    }
    // A group that does not resolve before one that does not join (and is culled).
    FrameGraph faults;
    ASSERT_TRUE(faults.add_pass(Pass("first").output("x", TextureSpec{}.with_samples(3))).ok());
    ASSERT_TRUE(faults.add_pass(Pass("second").output("y", TextureSpec::of(Format::RGBA8Unorm))).ok());
    ASSERT_TRUE(faults.add_pass(Pass("third").input("y", TextureSpec::of(Format::Depth32F)).output("z")).ok());
    ASSERT_TRUE(faults.connect(port("second", "y"), port("third", "y")).ok());
    ASSERT_TRUE(faults.mark_output(port("first", "x")).ok());
    same(faults, "faults");
    // Only the join fault of a culled group.
    FrameGraph join_fault;
    ASSERT_TRUE(join_fault.add_pass(Pass("first").output("x").set_side_effect()).ok());
    ASSERT_TRUE(join_fault.add_pass(Pass("second").output("y", TextureSpec::of(Format::RGBA8Unorm))).ok());
    ASSERT_TRUE(join_fault.add_pass(Pass("third").input("y", TextureSpec::of(Format::Depth32F)).output("z")).ok());
    ASSERT_TRUE(join_fault.connect(port("second", "y"), port("third", "y")).ok());
    same(join_fault, "join fault");
}

// The dependency lists of analyze: per pass, its values sorted and unique, from pairs in any
// order, whatever lists are empty.
TEST(PlanPhases, IndexListsSortAndDeduplicateEachPassesValues) {
    std::vector<std::pair<uint32_t, uint32_t>> pairs{{3, 7}, {0, 5}, {3, 1}, {0, 5}, {3, 7}, {0, 2}, {3, 4}, {0, 5}};
    const IndexLists lists(5, pairs);
    ASSERT_EQ(lists.size(), 5u);
    auto values = [&](uint32_t index) { return std::vector<uint32_t>(lists[index].begin(), lists[index].end()); };
    EXPECT_EQ(values(0), (std::vector<uint32_t>{2, 5}));
    EXPECT_TRUE(values(1).empty());
    EXPECT_TRUE(values(2).empty());
    EXPECT_EQ(values(3), (std::vector<uint32_t>{1, 4, 7}));
    EXPECT_TRUE(values(4).empty());
    std::vector<std::pair<uint32_t, uint32_t>> none;
    const IndexLists empty(3, none);
    EXPECT_EQ(empty.size(), 3u);
    EXPECT_TRUE(empty[2].empty());
}

// Lists given as rows (each list's values one after another) come out as the pairs constructor
// makes them: each sorted, duplicates dropped, empty rows kept.
TEST(PlanPhases, IndexListsFromRowsSortAndDeduplicateEachRow) {
    const IndexLists lists(std::vector<uint32_t>{0, 3, 3, 7, 8}, std::vector<uint32_t>{5, 2, 5, 9, 1, 9, 4, 0});
    ASSERT_EQ(lists.size(), 4u);
    EXPECT_TRUE(std::ranges::equal(lists[0], std::vector<uint32_t>{2, 5}));
    EXPECT_TRUE(lists[1].empty());
    EXPECT_TRUE(std::ranges::equal(lists[2], std::vector<uint32_t>{1, 4, 9}));
    EXPECT_TRUE(std::ranges::equal(lists[3], std::vector<uint32_t>{0}));
    EXPECT_EQ(IndexLists(std::vector<uint32_t>{0}, std::vector<uint32_t>{}).size(), 0u);
}

// Transposed lists hold the same pairs the other way, each list sorted, as the pairs
// constructor would make them; values past the lists' own count are indices too.
TEST(PlanPhases, IndexListsTransposedHoldTheSamePairsTheOtherWay) {
    std::vector<std::pair<uint32_t, uint32_t>> pairs{{3, 7}, {0, 5}, {3, 1}, {0, 2}, {3, 4}, {4, 5}, {1, 7}};
    const IndexLists lists(5, pairs);
    const IndexLists transposed = lists.transposed(8);
    for (auto& [index, value] : pairs) std::swap(index, value);
    const IndexLists expected(8, pairs);
    ASSERT_EQ(transposed.size(), 8u);
    for (uint32_t j = 0; j < 8; ++j) {
        EXPECT_TRUE(std::ranges::equal(transposed[j], expected[j])) << j;
    }
    EXPECT_TRUE(std::ranges::equal(transposed[5], std::vector<uint32_t>{0, 4}));
    EXPECT_TRUE(std::ranges::equal(transposed[7], std::vector<uint32_t>{1, 3}));
    EXPECT_TRUE(transposed[6].empty());
    EXPECT_EQ(IndexLists(2, std::vector<std::pair<uint32_t, uint32_t>>{}).transposed(0).size(), 0u);
}

}  // namespace
}  // namespace loom::fg::detail

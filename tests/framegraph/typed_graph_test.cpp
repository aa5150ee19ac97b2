// The typed fast path of FrameGraph: connections, graph outputs and side effects by the handles
// add_pass and port_of give, reads by the handle of a write (Pass::read), reserve and clear.
// Plans made through it equal those made by names; its errors name the passes and ports.
#include <gtest/gtest.h>

#include "loom/framegraph/framegraph.hpp"

namespace loom::fg {
namespace {

using rhi::Format;

// geometry -> blur -> composite by names.
FrameGraph by_names() {
    FrameGraph graph;
    EXPECT_TRUE(graph.add_pass(Pass("geometry").output("albedo", TextureSpec::of(Format::RGBA8Unorm)).output("depth", TextureSpec::of(Format::Depth32F))).ok());
    EXPECT_TRUE(graph.add_pass(Pass("blur").input("color").output("out", TextureSpec::of(Format::RGBA8Unorm).with_scale(0.5f))).ok());
    EXPECT_TRUE(graph.add_pass(Pass("composite").input("color").input("blurred").input("depth").output("final")).ok());
    EXPECT_TRUE(graph.connect(port("geometry", "albedo"), port("blur", "color")).ok());
    EXPECT_TRUE(graph.connect(port("geometry", "albedo"), port("composite", "color")).ok());
    EXPECT_TRUE(graph.connect(port("blur", "out"), port("composite", "blurred")).ok());
    EXPECT_TRUE(graph.connect(port("geometry", "depth"), port("composite", "depth")).ok());
    EXPECT_TRUE(graph.mark_output(port("composite", "final")).ok());
    return graph;
}

// The same graph by handles: ports by position, connections by address.
void declare_by_handles(FrameGraph& graph) {
    const PassId geometry = *graph.add_pass(Pass("geometry").output("albedo", TextureSpec::of(Format::RGBA8Unorm)).output("depth", TextureSpec::of(Format::Depth32F)));
    const PassId blur = *graph.add_pass(Pass("blur").input("color").output("out", TextureSpec::of(Format::RGBA8Unorm).with_scale(0.5f)));
    const PassId composite = *graph.add_pass(Pass("composite").input("color").input("blurred").input("depth").output("final"));
    EXPECT_TRUE(graph.connect(port_of(geometry, 0), port_of(blur, 0)).ok());
    EXPECT_TRUE(graph.connect(port_of(geometry, 0), port_of(composite, 0)).ok());
    EXPECT_TRUE(graph.connect(port_of(blur, 1), port_of(composite, 1)).ok());
    EXPECT_TRUE(graph.connect(port_of(geometry, 1), port_of(composite, 2)).ok());
    EXPECT_TRUE(graph.mark_output(port_of(composite, 3)).ok());
}

TEST(TypedGraph, ConnectingByHandlesPlansAsByNames) {
    FrameGraph named = by_names();
    FrameGraph typed;
    declare_by_handles(typed);
    EXPECT_EQ(typed.connections(), named.connections());
    EXPECT_EQ(typed.outputs(), named.outputs());
    auto a = build_plan(named, {});
    auto b = build_plan(typed, {});
    ASSERT_TRUE(a && b);
    EXPECT_EQ(plan_hash(*a), plan_hash(*b));
    EXPECT_TRUE(*a == *b);
}

TEST(TypedGraph, ReadTakesTheHandleOfTheWriteInOneStep) {
    FrameGraph graph;
    const PassId geometry = *graph.add_pass(Pass("geometry").output("albedo", TextureSpec::of(Format::RGBA8Unorm)));
    auto blur = graph.add_pass(Pass("blur").read(port_of(geometry, 0)).read(port_of(geometry, 0), {}, mip(0)).output("out"));
    ASSERT_TRUE(blur) << blur.error().to_string();
    const Pass& pass = graph.pass(*blur);
    ASSERT_EQ(pass.ports().size(), 3u);
    EXPECT_EQ(pass.ports()[0].name, "read0");
    EXPECT_EQ(pass.ports()[1].name, "read1");
    EXPECT_EQ(pass.ports()[0].kind, PortKind::Input);
    EXPECT_EQ(graph.source(port_of(*blur, 0)), port_of(geometry, 0));
    EXPECT_EQ(graph.source(port_of(*blur, 1)), port_of(geometry, 0));
    EXPECT_EQ(graph.connections().size(), 2u);
    ASSERT_TRUE(graph.set_side_effect(*blur).ok());
    EXPECT_TRUE(build_plan(graph, {}));
}

TEST(TypedGraph, ReadsOfPortsOutsideTheGraphOrOfInputsAreRefusedAndLeaveTheGraphAsItWas) {
    FrameGraph graph;
    const PassId geometry = *graph.add_pass(Pass("geometry").input("history").output("albedo"));
    auto unknown = graph.add_pass(Pass("blur").read(port_of(PassId{7}, 0)));
    ASSERT_FALSE(unknown);
    EXPECT_EQ(unknown.error().code, ErrorCode::Graph);
    EXPECT_NE(unknown.error().message.find("'blur'"), std::string::npos) << unknown.error().message;
    EXPECT_NE(unknown.error().message.find("pass #7"), std::string::npos) << unknown.error().message;
    auto input = graph.add_pass(Pass("blur").read(port_of(geometry, 0)));
    ASSERT_FALSE(input);
    EXPECT_NE(input.error().message.find("geometry.history, an input"), std::string::npos) << input.error().message;
    auto clash = graph.add_pass(Pass("blur").input("read0").read(port_of(geometry, 1)));
    ASSERT_FALSE(clash);
    EXPECT_NE(clash.error().message.find("'read0'"), std::string::npos) << clash.error().message;
    EXPECT_EQ(graph.pass_count(), 1u);
    EXPECT_TRUE(graph.connections().empty());
}

TEST(TypedGraph, AReadWhoseNameAPortDeclaredBetweenReadsTakesIsRefused) {
    // read0 comes from read(); the pass then declares read1 itself, which the next read() would
    // be called.
    FrameGraph graph;
    const PassId geometry = *graph.add_pass(Pass("geometry").output("albedo"));
    auto clash = graph.add_pass(Pass("blur").read(port_of(geometry, 0)).output("read1").read(port_of(geometry, 0)));
    ASSERT_FALSE(clash);
    EXPECT_EQ(clash.error().message, "pass 'blur': read() names its input 'read1', a name the pass already declares");
    // Declared after the reads, the name is the pass's own: no clash.
    auto after = graph.add_pass(Pass("blur").read(port_of(geometry, 0)).read(port_of(geometry, 0)).output("read2"));
    ASSERT_TRUE(after) << after.error().to_string();
    EXPECT_EQ(graph.pass(*after).ports().size(), 3u);
}

TEST(TypedGraph, ErrorsByHandleReadAsErrorsByName) {
    FrameGraph named = by_names();
    FrameGraph typed = by_names();
    // A second source for composite.color.
    Status by_name = named.connect(port("blur", "out"), port("composite", "color"));
    Status by_handle = typed.connect(port_of(PassId{1}, 1), port_of(PassId{2}, 0));
    ASSERT_FALSE(by_name.ok());
    ASSERT_FALSE(by_handle.ok());
    EXPECT_EQ(by_handle.error().message, by_name.error().message);
    // Wrong direction.
    by_handle = typed.connect(port_of(PassId{1}, 0), port_of(PassId{2}, 1));
    ASSERT_FALSE(by_handle.ok());
    EXPECT_NE(by_handle.error().message.find("blur.color is an input"), std::string::npos) << by_handle.error().message;
    // Addresses outside the graph.
    by_handle = typed.connect(port_of(PassId{0}, 9), port_of(PassId{2}, 1));
    ASSERT_FALSE(by_handle.ok());
    EXPECT_EQ(by_handle.error().code, ErrorCode::Graph);
    EXPECT_NE(by_handle.error().message.find("port #9 of pass 'geometry'"), std::string::npos) << by_handle.error().message;
    Status output = typed.mark_output(port_of(PassId{5}, 0));
    ASSERT_FALSE(output.ok());
    EXPECT_NE(output.error().message.find("pass #5"), std::string::npos) << output.error().message;
    output = typed.mark_output(port_of(PassId{1}, 0));
    ASSERT_FALSE(output.ok());
    EXPECT_NE(output.error().message.find("blur.color: an input cannot be a graph output"), std::string::npos);
    EXPECT_FALSE(typed.set_side_effect(PassId{3}).ok());
}

TEST(TypedGraph, AClearedGraphIsDeclaredAgainAndPlannedAfresh) {
    FrameGraph graph;
    graph.reserve(3, 8);
    declare_by_handles(graph);
    auto first = graph.plan();
    ASSERT_TRUE(first);
    graph.clear();
    EXPECT_EQ(graph.pass_count(), 0u);
    EXPECT_TRUE(graph.connections().empty());
    EXPECT_TRUE(graph.outputs().empty());
    EXPECT_FALSE(graph.find_pass("geometry"));
    declare_by_handles(graph);
    auto second = graph.plan();
    ASSERT_TRUE(second);
    EXPECT_EQ(graph.plans_built(), 2u);
    EXPECT_NE(first->get(), second->get());
    EXPECT_EQ(plan_hash(**first), plan_hash(**second));
}

// The graph of declare_by_handles, or one declaration of it changed (variant 1..12).
void declare_variant(FrameGraph& graph, int variant) {
    Pass geometry("geometry");
    geometry.output("albedo", TextureSpec::of(variant == 1 ? Format::RGBA16Float : Format::RGBA8Unorm))
        .output("depth", TextureSpec::of(Format::Depth32F));
    if (variant == 2) geometry.set_side_effect();
    if (variant == 3) geometry.keep_declared_order();
    Pass blur(variant == 4 ? "blur2" : "blur");
    blur.input("color").output("out", TextureSpec::of(Format::RGBA8Unorm).with_scale(variant == 5 ? 0.25f : 0.5f));
    if (variant == 6) blur.set_kind(PassKind::Compute);
    if (variant == 7) blur.set_kind(PassKind::Compute).set_queue(Queue::AsyncCompute);
    if (variant == 8) blur.add(PortSet("extra").input("color"));
    Pass composite("composite");
    composite.input("color").input("blurred").input("depth").output("final");
    const PassId g = *graph.add_pass(std::move(geometry));
    const PassId b = *graph.add_pass(std::move(blur));
    const PassId c = *graph.add_pass(std::move(composite));
    if (variant == 9) {  // the same connections in another order
        EXPECT_TRUE(graph.connect(port_of(g, 0), port_of(c, 0)).ok());
        EXPECT_TRUE(graph.connect(port_of(g, 0), port_of(b, 0)).ok());
    } else {
        EXPECT_TRUE(graph.connect(port_of(g, 0), port_of(b, 0)).ok());
        EXPECT_TRUE(graph.connect(port_of(g, 0), port_of(c, 0)).ok());
    }
    EXPECT_TRUE(graph.connect(port_of(b, 1), port_of(c, 1)).ok());
    EXPECT_TRUE(graph.connect(port_of(g, 1), port_of(c, 2)).ok());
    EXPECT_TRUE(graph.mark_output(port_of(c, 3)).ok());
    if (variant == 10) {
        EXPECT_TRUE(graph.mark_output(port_of(g, 1)).ok());
    }
    if (variant == 11) {
        EXPECT_TRUE(graph.require_order("blur", "composite").ok());
    }
    if (variant == 12) {
        EXPECT_TRUE(graph.set_side_effect(b).ok());
    }
}

// An engine declaring the same graph every frame after redeclare() gets the plan of the first
// frame back, the same object, planned once; redeclaring without planning in between keeps it.
TEST(TypedGraph, RedeclaringTheSameGraphReturnsThePreviousPlan) {
    FrameGraph graph;
    declare_variant(graph, 0);
    auto first = graph.plan();
    ASSERT_TRUE(first);
    for (int frame = 0; frame < 3; ++frame) {
        graph.redeclare();
        EXPECT_EQ(graph.pass_count(), 0u);
        EXPECT_TRUE(graph.connections().empty());
        EXPECT_FALSE(graph.find_pass("geometry"));
        declare_variant(graph, 0);
        if (frame == 1) {  // a frame that declares but does not plan
            graph.redeclare();
            declare_variant(graph, 0);
        }
        if (frame == 2) {  // a side effect set and cleared again leaves the graph as it was
            ASSERT_TRUE(graph.set_side_effect("blur").ok());
            ASSERT_TRUE(graph.set_side_effect("blur", false).ok());
        }
        auto again = graph.plan();
        ASSERT_TRUE(again);
        EXPECT_EQ(again->get(), first->get());
    }
    EXPECT_EQ(graph.plans_built(), 1u);
    // The plan of the graph by names is the same plan.
    FrameGraph named = by_names();
    EXPECT_EQ(**named.plan(), **first);
}

// Any difference from the planned graph plans afresh, and the plan is the one a new graph gets;
// declared again as it now is, that new plan is kept.
TEST(TypedGraph, RedeclaringAnotherGraphPlansAfresh) {
    for (int variant = 1; variant <= 12; ++variant) {
        SCOPED_TRACE("variant " + std::to_string(variant));
        FrameGraph graph;
        declare_variant(graph, 0);
        auto first = graph.plan();
        ASSERT_TRUE(first);
        graph.redeclare();
        declare_variant(graph, variant);
        auto changed = graph.plan();
        ASSERT_TRUE(changed) << changed.error().message;
        EXPECT_NE(changed->get(), first->get());
        EXPECT_EQ(graph.plans_built(), 2u);
        FrameGraph fresh;
        declare_variant(fresh, variant);
        EXPECT_EQ(**fresh.plan(), **changed);

        graph.redeclare();
        declare_variant(graph, variant);
        auto kept = graph.plan();
        ASSERT_TRUE(kept);
        EXPECT_EQ(kept->get(), changed->get());
        EXPECT_EQ(graph.plans_built(), 2u);
    }
}

// A pass fewer or more, other options, and redeclare() with no plan to compare with all plan
// afresh; clear() forgets the previous graph.
TEST(TypedGraph, RedeclaringPlansAfreshWhenNothingCanBeReused) {
    FrameGraph graph;
    declare_variant(graph, 0);
    auto first = graph.plan();
    ASSERT_TRUE(first);

    graph.redeclare();
    declare_variant(graph, 0);
    ASSERT_TRUE(graph.add_pass(Pass("late").output("out").set_side_effect()).ok());
    auto more = graph.plan();
    ASSERT_TRUE(more);
    EXPECT_EQ(more->get()->order.size(), 4u);
    EXPECT_EQ(graph.plans_built(), 2u);

    graph.redeclare();
    declare_variant(graph, 0);
    auto fewer = graph.plan();
    ASSERT_TRUE(fewer);
    EXPECT_EQ(**fewer, **first);
    EXPECT_EQ(graph.plans_built(), 3u);

    graph.redeclare();
    declare_variant(graph, 0);
    PlanOptions wider;
    wider.frame = {2560, 1440};
    auto resized = graph.plan(wider);
    ASSERT_TRUE(resized);
    EXPECT_EQ(resized->get()->frame.width, 2560u);
    EXPECT_EQ(graph.plans_built(), 4u);

    graph.clear();
    declare_variant(graph, 0);
    graph.redeclare();  // no plan of this graph: as clear()
    declare_variant(graph, 0);
    ASSERT_TRUE(graph.plan(wider));
    EXPECT_EQ(graph.plans_built(), 5u);

    // A graph that fails to plan keeps no plan to return.
    graph.redeclare();
    ASSERT_TRUE(graph.add_pass(Pass("lonely").input("in").output("out").set_side_effect()).ok());
    EXPECT_FALSE(graph.plan(wider));
    graph.redeclare();
    declare_variant(graph, 0);
    ASSERT_TRUE(graph.plan(wider));
    EXPECT_EQ(graph.plans_built(), 6u);
}

// The flat facts the planner reads instead of each Port say what the ports say: kind, type,
// the kind of their pass, optional, requested usage, whether the spec constrains anything and
// whether the range or bytes are the whole resource.
TEST(TypedGraph, PortFactsSayWhatThePortsSay) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("make")
                                   .output("plain")
                                   .output("storage", TextureSpec::any().with_usage(rhi::TextureUsage::Storage))
                                   .buffer_output("sized", BufferSpec::of_size(256))
                                   .optional_output("spare"))
                    .ok());
    ASSERT_TRUE(graph.add_pass(Pass("mips")
                                   .set_kind(PassKind::Compute)
                                   .input("level", {}, SubresourceRange{1, 1, 0, rhi::kRemainingSubresources})
                                   .buffer_input("part", {}, BufferRange{0, 64})
                                   .inout("all"))
                    .ok());
    const std::span<const PortFacts> make = graph.port_facts(PassId{0});
    ASSERT_EQ(make.size(), 4u);
    EXPECT_EQ(make[0].kind, PortKind::Output);
    EXPECT_TRUE(make[0].unconstrained);
    EXPECT_TRUE(make[0].whole);
    EXPECT_FALSE(make[0].optional);
    EXPECT_EQ(make[1].requested_usage, rhi::TextureUsage::Storage);
    EXPECT_FALSE(make[1].unconstrained);
    EXPECT_EQ(make[2].type, ResourceType::Buffer);
    EXPECT_FALSE(make[2].unconstrained);
    EXPECT_TRUE(make[2].whole);
    EXPECT_TRUE(make[3].optional);
    for (const PortFacts& facts : make) EXPECT_EQ(facts.pass_kind, PassKind::Graphics);

    const std::span<const PortFacts> mips = graph.port_facts(PassId{1});
    ASSERT_EQ(mips.size(), 3u);
    EXPECT_EQ(mips[0].kind, PortKind::Input);
    EXPECT_FALSE(mips[0].whole);
    EXPECT_TRUE(mips[0].unconstrained);
    EXPECT_EQ(mips[1].type, ResourceType::Buffer);
    EXPECT_TRUE(mips[1].unconstrained);
    EXPECT_FALSE(mips[1].whole);
    EXPECT_EQ(mips[2].kind, PortKind::InOut);
    EXPECT_TRUE(mips[2].whole);
    for (const PortFacts& facts : mips) EXPECT_EQ(facts.pass_kind, PassKind::Compute);
    EXPECT_EQ(&graph.facts(port_of(PassId{1}, 2)), &mips[2]);
    EXPECT_EQ(&graph.port_at(port_of(PassId{1}, 2)), &graph.pass(PassId{1}).ports()[2]);

    graph.clear();
    ASSERT_TRUE(graph.add_pass(Pass("again").input("in").output("out")).ok());
    ASSERT_EQ(graph.port_facts(PassId{0}).size(), 2u);
    EXPECT_EQ(graph.port_facts(PassId{0})[1].kind, PortKind::Output);
}

// The pass-name index (open addressing, grown as passes come): every name is found after it grew
// many times, with and without reserve, a taken name is refused, and after clear() no old name is
// found while the same names can be added again.
TEST(TypedGraph, PassNamesAreFoundThroughGrowthReserveAndClear) {
    for (const bool reserved : {false, true}) {
        FrameGraph graph;
        if (reserved) graph.reserve(1000, 1000);
        for (uint32_t round = 0; round < 2; ++round) {
            for (uint32_t i = 0; i < 1000; ++i) {
                auto id = graph.add_pass(Pass("pass" + std::to_string(i)).output("out").set_side_effect());
                ASSERT_TRUE(id) << id.error().message;
                EXPECT_EQ(id->index, i);
            }
            for (uint32_t i = 0; i < 1000; ++i) {
                auto found = graph.find_pass("pass" + std::to_string(i));
                ASSERT_TRUE(found) << i;
                EXPECT_EQ(found->index, i);
            }
            EXPECT_FALSE(graph.find_pass("pass1000"));
            EXPECT_FALSE(graph.find_pass(""));
            auto taken = graph.add_pass(Pass("pass999").output("out"));
            ASSERT_FALSE(taken);
            EXPECT_NE(taken.error().message.find("a pass called 'pass999' already exists"), std::string::npos);
            graph.clear();
            EXPECT_FALSE(graph.find_pass("pass0"));
            EXPECT_FALSE(graph.find_pass("pass999"));
        }
    }
}

}  // namespace
}  // namespace loom::fg

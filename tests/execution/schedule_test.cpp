// The execution schedule, computed without a device: which texture backs each port, the
// transitions before each pass, load/store actions, imports, histories, and the errors that
// name the port at fault.
#include <gtest/gtest.h>

#include "loom/framegraph/framegraph.hpp"

namespace loom::fg {
namespace {

using rhi::Format;
using rhi::LoadOp;
using rhi::ResourceState;
using rhi::StoreOp;

const TextureSpec kColor = TextureSpec::of(Format::RGBA16Float);
const TextureSpec kShadow = TextureSpec::of(Format::Depth32F).with_size(64, 64);

TextureSlot plan_texture(uint32_t index) { return {TextureSlot::Kind::Plan, index}; }

FrameGraph figure2() {
    FrameGraph graph;
    EXPECT_TRUE(graph.add_pass(Pass("shadow").output("shadow_map", kShadow)).ok());
    EXPECT_TRUE(graph.add_pass(Pass("geometry").output("position", kColor).output("normal", kColor).output("albedo", kColor)).ok());
    EXPECT_TRUE(graph.add_pass(Pass("deferred")
                                   .add(PortSet("deferred").input("position").input("normal").input("albedo").output("color", kColor))
                                   .add(PortSet("shadow-render").input("shadow_map", kShadow).output("color"))
                                   .add(PortSet("high-pass-render").output("high_pass", kColor)))
                    .ok());
    EXPECT_TRUE(graph.add_pass(Pass("blur").input("previous_pass").output("color", kColor)).ok());
    EXPECT_TRUE(graph.add_pass(Pass("composite").input("color").input("bloom").output("final", kColor)).ok());
    EXPECT_TRUE(graph.connect(port("shadow", "shadow_map"), port("deferred", "shadow_map")).ok());
    EXPECT_TRUE(graph.connect(port("geometry", "position"), port("deferred", "position")).ok());
    EXPECT_TRUE(graph.connect(port("geometry", "normal"), port("deferred", "normal")).ok());
    EXPECT_TRUE(graph.connect(port("geometry", "albedo"), port("deferred", "albedo")).ok());
    EXPECT_TRUE(graph.connect(port("deferred", "high_pass"), port("blur", "previous_pass")).ok());
    EXPECT_TRUE(graph.connect(port("deferred", "color"), port("composite", "color")).ok());
    EXPECT_TRUE(graph.connect(port("blur", "color"), port("composite", "bloom")).ok());
    EXPECT_TRUE(graph.mark_output(port("composite", "final")).ok());
    return graph;
}

// In declared order: the tests name passes by their positions.
Plan plan_of(FrameGraph& graph, AllocatorKind allocator = AllocatorKind::Interval) {
    PlanOptions options;
    options.frame = {16, 8};
    options.allocator = allocator;
    options.order = PassOrder::Declared;
    auto plan = build_plan(graph, options);
    EXPECT_TRUE(plan.ok()) << plan.error().to_string();
    return plan.ok() ? std::move(*plan) : Plan{};
}

const PortSchedule& port_of(const ExecutionSchedule& schedule, std::string_view pass, std::string_view name) {
    for (const PassSchedule& p : schedule.passes) {
        if (p.name != pass) continue;
        for (const PortSchedule& port : p.ports) {
            if (port.name == name) return port;
        }
    }
    ADD_FAILURE() << "no port " << pass << "." << name;
    static const PortSchedule none;
    return none;
}

// (slot, load, store) of one port, for compact expectations.
struct Actions {
    TextureSlot texture;
    bool first_write;
    LoadOp load;
    StoreOp store;
    friend bool operator==(const Actions&, const Actions&) = default;
};
std::ostream& operator<<(std::ostream& out, const Actions& a) {
    return out << describe_slot(a.texture) << (a.first_write ? " first-write" : "") << " load " << static_cast<int>(a.load)
               << " store " << static_cast<int>(a.store);
}
Actions actions(const ExecutionSchedule& s, std::string_view pass, std::string_view port) {
    const PortSchedule& p = port_of(s, pass, port);
    return {p.texture, p.first_write, p.load, p.store};
}

TEST(ExecutionSchedule, Figure2TexturesTransitionsAndLoadStore) {
    FrameGraph graph = figure2();
    const Plan plan = plan_of(graph);
    auto built = build_execution_schedule(plan, {}, {});
    ASSERT_TRUE(built.ok()) << built.error().to_string();
    const ExecutionSchedule& s = *built;
    ASSERT_EQ(s.passes.size(), 5u);
    // Interval plan (see tests/framegraph/figure2_test.cpp): shadow t0; position t1, normal t2,
    // albedo t3; color t4; high_pass t5; blur.color reuses t1, composite.final reuses t2.
    EXPECT_EQ(actions(s, "shadow", "shadow_map"), (Actions{plan_texture(0), true, LoadOp::Clear, StoreOp::Store}));
    EXPECT_EQ(actions(s, "geometry", "position"), (Actions{plan_texture(1), true, LoadOp::Clear, StoreOp::Store}));
    EXPECT_EQ(actions(s, "geometry", "normal"), (Actions{plan_texture(2), true, LoadOp::Clear, StoreOp::Store}));
    EXPECT_EQ(actions(s, "geometry", "albedo"), (Actions{plan_texture(3), true, LoadOp::Clear, StoreOp::Store}));
    EXPECT_EQ(actions(s, "deferred", "position"), (Actions{plan_texture(1), false, LoadOp::Load, StoreOp::Store}));
    EXPECT_EQ(actions(s, "deferred", "color"), (Actions{plan_texture(4), true, LoadOp::Clear, StoreOp::Store}));
    EXPECT_EQ(actions(s, "deferred", "high_pass"), (Actions{plan_texture(5), true, LoadOp::Clear, StoreOp::Store}));
    EXPECT_EQ(actions(s, "blur", "color"), (Actions{plan_texture(1), true, LoadOp::Clear, StoreOp::Store}));
    EXPECT_EQ(actions(s, "composite", "final"), (Actions{plan_texture(2), true, LoadOp::Clear, StoreOp::Store}));

    // Inputs are sampled: ShaderRead, and DepthRead for the depth map; attachments need nothing.
    EXPECT_TRUE(s.passes[0].before.empty());
    EXPECT_TRUE(s.passes[1].before.empty());
    EXPECT_EQ(s.passes[2].before, (std::vector<Transition>{{plan_texture(1), ResourceState::ShaderRead},
                                                           {plan_texture(2), ResourceState::ShaderRead},
                                                           {plan_texture(3), ResourceState::ShaderRead},
                                                           {plan_texture(0), ResourceState::DepthRead}}));
    EXPECT_EQ(s.passes[3].before, (std::vector<Transition>{{plan_texture(5), ResourceState::ShaderRead}}));
    EXPECT_EQ(s.passes[4].before, (std::vector<Transition>{{plan_texture(4), ResourceState::ShaderRead},
                                                           {plan_texture(1), ResourceState::ShaderRead}}));
    for (const PassSchedule& p : s.passes) {
        EXPECT_TRUE(p.after.empty()) << p.name;
        EXPECT_TRUE(p.copies.empty()) << p.name;
    }
    EXPECT_EQ(s.texture_needed, std::vector<bool>(6, true));
    EXPECT_TRUE(s.histories.empty());
}

// base → tint (inout) → read → final (graph output); scratch writes a texture nobody reads.
FrameGraph inout_graph() {
    FrameGraph graph;
    EXPECT_TRUE(graph.add_pass(Pass("base").output("color", kColor).optional_input("previous", kColor)).ok());
    EXPECT_TRUE(graph.add_pass(Pass("tint").inout("color", kColor)).ok());
    EXPECT_TRUE(graph.add_pass(Pass("read").input("color", kColor).output("final", kColor)).ok());
    EXPECT_TRUE(graph.add_pass(Pass("scratch").output("tmp", kColor).set_side_effect()).ok());
    EXPECT_TRUE(graph.add_pass(Pass("storage").input("src", kColor.with_usage(rhi::TextureUsage::Storage))
                                   .output("dst", kColor.with_usage(rhi::TextureUsage::Storage))
                                   .set_side_effect())
                    .ok());
    EXPECT_TRUE(graph.connect(port("base", "color"), port("tint", "color")).ok());
    EXPECT_TRUE(graph.connect(port("tint", "color"), port("read", "color")).ok());
    EXPECT_TRUE(graph.connect(port("read", "final"), port("storage", "src")).ok());
    EXPECT_TRUE(graph.mark_output(port("read", "final")).ok());
    return graph;
}

TEST(ExecutionSchedule, InOutLoadsAndUnreadResultsAreDiscarded) {
    FrameGraph graph = inout_graph();
    const Plan plan = plan_of(graph);
    auto built = build_execution_schedule(plan, {}, {});
    ASSERT_TRUE(built.ok()) << built.error().to_string();
    const ExecutionSchedule& s = *built;
    const TextureSlot color = s.passes[0].ports[0].texture;
    EXPECT_EQ(actions(s, "base", "color"), (Actions{color, true, LoadOp::Clear, StoreOp::Store}));
    EXPECT_EQ(actions(s, "tint", "color"), (Actions{color, false, LoadOp::Load, StoreOp::Store}));
    EXPECT_EQ(actions(s, "read", "color"), (Actions{color, false, LoadOp::Load, StoreOp::Store}));
    EXPECT_TRUE(port_of(s, "base", "previous").texture.empty());
    // Nobody reads scratch.tmp and storage.dst: their contents die with the pass.
    EXPECT_EQ(port_of(s, "scratch", "tmp").store, StoreOp::DontCare);
    EXPECT_EQ(port_of(s, "storage", "dst").store, StoreOp::DontCare);
    // A graph output is always stored.
    EXPECT_EQ(port_of(s, "read", "final").store, StoreOp::Store);
    // Storage ports move into Storage before their pass, reading or writing.
    const PassSchedule& storage = s.passes.back();
    ASSERT_EQ(storage.name, "storage");
    EXPECT_EQ(storage.before, (std::vector<Transition>{{port_of(s, "storage", "src").texture, ResourceState::Storage},
                                                       {port_of(s, "storage", "dst").texture, ResourceState::Storage}}));
}

TEST(ExecutionSchedule, ImportedOutputReplacesItsTextureAndGetsItsFinalState) {
    FrameGraph graph = inout_graph();
    const Plan plan = plan_of(graph);
    const std::vector<ImportBinding> imports{{port("read", "final"), ResourceState::CopySrc}};
    auto built = build_execution_schedule(plan, imports, {});
    ASSERT_TRUE(built.ok()) << built.error().to_string();
    const ExecutionSchedule& s = *built;
    const TextureSlot import0{TextureSlot::Kind::Import, 0};
    EXPECT_EQ(actions(s, "read", "final"), (Actions{import0, true, LoadOp::Clear, StoreOp::Store}));
    EXPECT_EQ(port_of(s, "storage", "src").texture, import0);
    // Final state after the last use (the storage pass, last in the order).
    ASSERT_EQ(s.passes.back().name, "storage");
    EXPECT_EQ(s.passes.back().after, (std::vector<Transition>{{import0, ResourceState::CopySrc}}));
    const auto final_texture = plan.texture_of("read", "final");
    ASSERT_TRUE(final_texture.has_value());
    uint32_t needed = 0;
    for (bool n : s.texture_needed) needed += n ? 1 : 0;
    // The final texture is only created when another resource shares it.
    const bool shared = plan.textures[*final_texture].resources.size() > 1;
    EXPECT_EQ(s.texture_needed[*final_texture], shared);
    EXPECT_EQ(needed, plan.textures.size() - (shared ? 0 : 1));
}

TEST(ExecutionSchedule, ImportedInputOnAnUnconnectedPort) {
    FrameGraph graph = inout_graph();
    const Plan plan = plan_of(graph);
    const std::vector<ImportBinding> imports{{port("base", "previous"), ResourceState::ShaderRead}};
    auto built = build_execution_schedule(plan, imports, {});
    ASSERT_TRUE(built.ok()) << built.error().to_string();
    const TextureSlot import0{TextureSlot::Kind::Import, 0};
    EXPECT_EQ(port_of(*built, "base", "previous").texture, import0);
    EXPECT_EQ(built->passes[0].before, (std::vector<Transition>{{import0, ResourceState::ShaderRead}}));
    EXPECT_EQ(built->passes[0].after, (std::vector<Transition>{{import0, ResourceState::ShaderRead}}));
}

TEST(ExecutionSchedule, HistoryIsCopiedAfterTheSourcesLastUse) {
    FrameGraph graph = inout_graph();
    const Plan plan = plan_of(graph);
    const std::vector<HistoryBinding> histories{{port("base", "previous"), port("read", "final")}};
    auto built = build_execution_schedule(plan, {}, histories);
    ASSERT_TRUE(built.ok()) << built.error().to_string();
    const ExecutionSchedule& s = *built;
    ASSERT_EQ(s.histories.size(), 1u);
    const HistoryTexture& h = s.histories[0];
    EXPECT_EQ(h.source, "read.final");
    EXPECT_EQ(h.spec, plan.resources[h.resource].spec);
    // read.final is last used by "storage", the last pass; "base" reads before that: one texture.
    EXPECT_EQ(h.copy_after, plan.order.size() - 1);
    EXPECT_EQ(h.textures, 1u);
    EXPECT_EQ(h.readers, std::vector<std::string>{"base.previous"});
    const TextureSlot history0{TextureSlot::Kind::History, 0};
    EXPECT_EQ(port_of(s, "base", "previous").texture, history0);
    EXPECT_EQ(s.passes[0].before, (std::vector<Transition>{{history0, ResourceState::ShaderRead}}));
    const auto final_texture = plan.texture_of("read", "final");
    EXPECT_EQ(s.passes.back().copies, (std::vector<HistoryCopy>{{0, plan_texture(*final_texture)}}));
}

TEST(ExecutionSchedule, HistoryReadAfterTheCopyNeedsTwoTextures) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("source").output("color", kColor)).ok());
    ASSERT_TRUE(graph.add_pass(Pass("mid").input("color").output("out", kColor)).ok());
    ASSERT_TRUE(graph.add_pass(Pass("late").input("color").optional_input("previous", kColor).output("out", kColor)).ok());
    ASSERT_TRUE(graph.connect(port("source", "color"), port("mid", "color")).ok());
    ASSERT_TRUE(graph.connect(port("mid", "out"), port("late", "color")).ok());
    ASSERT_TRUE(graph.mark_output(port("late", "out")).ok());
    const Plan plan = plan_of(graph);
    const std::vector<HistoryBinding> histories{{port("late", "previous"), port("source", "color")}};
    auto built = build_execution_schedule(plan, {}, histories);
    ASSERT_TRUE(built.ok()) << built.error().to_string();
    ASSERT_EQ(built->histories.size(), 1u);
    EXPECT_EQ(built->histories[0].copy_after, 1u);  // source.color's last reader is "mid"
    EXPECT_EQ(built->histories[0].textures, 2u);
}

TEST(ExecutionSchedule, BindingErrorsNameThePort) {
    FrameGraph graph = inout_graph();
    ASSERT_TRUE(graph.add_pass(Pass("unused").output("x", kColor)).ok());
    const Plan plan = plan_of(graph);
    auto expect_error = [&](std::vector<ImportBinding> imports, std::vector<HistoryBinding> histories, const std::string& needle) {
        auto built = build_execution_schedule(plan, imports, histories);
        ASSERT_FALSE(built.ok()) << needle;
        EXPECT_EQ(built.error().code, ErrorCode::Graph);
        EXPECT_NE(built.error().message.find(needle), std::string::npos) << built.error().message;
    };
    expect_error({{port("nope", "color")}}, {}, "unknown pass 'nope'");
    expect_error({{port("read", "colour")}}, {}, "pass 'read' has no port 'colour'");
    expect_error({{port("unused", "x")}}, {}, "pass 'unused' is culled");
    expect_error({{port("read", "final")}, {port("storage", "src")}}, {}, "already imported through read.final");
    expect_error({}, {{port("read", "color"), port("read", "final")}}, "history reader read.color is connected");
    expect_error({}, {{port("tint", "color"), port("read", "final")}}, "history reader tint.color is an inout port");
    expect_error({}, {{port("base", "previous"), port("read", "nothing")}}, "history source read.nothing");
}

}  // namespace
}  // namespace loom::fg

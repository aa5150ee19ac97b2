// The paper's Figure 2 / Listing 6 pipeline: shadow map, G-buffer, deferred shading composed
// from three port sets, bloom blur, composite. Seven colour outputs share one spec; the paper's
// port colouring needs five textures for them, the depth map is allocated separately.
#include <memory>

#include <gtest/gtest.h>

#include "loom/framegraph/framegraph.hpp"

namespace loom::fg {
namespace {

using rhi::Format;

const TextureSpec kColor = TextureSpec::of(Format::RGBA16Float).with_scale(1.0f);
const TextureSpec kShadow = TextureSpec::of(Format::Depth32F).with_size(2048, 2048);

// Listing 3: deferred shading reads the G-buffer and writes a colour texture.
PortSet deferred_ports() {
    return PortSet("deferred").input("position", kColor).input("normal", kColor).input("albedo", kColor).output("color", kColor);
}
// Listing 4: a shadow-receiving pass reads a shadow map and writes colour.
PortSet shadow_receiver_ports() { return PortSet("shadow-render").input("shadow_map", kShadow).output("color", kColor); }
// Listing 5: a high-pass splits bright colours into their own output.
PortSet high_pass_ports() { return PortSet("high-pass-render").output("high_pass", kColor); }

FrameGraph figure2() {
    FrameGraph graph;
    EXPECT_TRUE(graph.add_pass(Pass("shadow").output("shadow_map", kShadow)).ok());
    EXPECT_TRUE(graph.add_pass(Pass("geometry").output("position", kColor).output("normal", kColor).output("albedo", kColor)).ok());
    EXPECT_TRUE(graph.add_pass(Pass("deferred").add(deferred_ports()).add(shadow_receiver_ports()).add(high_pass_ports())).ok());
    EXPECT_TRUE(graph.add_pass(Pass("blur").input("previous_pass", kColor).output("color", kColor)).ok());
    EXPECT_TRUE(graph.add_pass(Pass("composite").input("color", kColor).input("bloom", kColor).output("final", kColor)).ok());
    // Listing 6, connection for connection.
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

Plan plan_with(AllocatorKind allocator) {
    FrameGraph graph = figure2();
    PlanOptions options;
    options.frame = {1920, 1080};
    options.allocator = allocator;
    auto plan = build_plan(graph, options);
    EXPECT_TRUE(plan.ok()) << plan.error().to_string();
    return plan.ok() ? std::move(*plan) : Plan{};
}

uint32_t texture(const Plan& plan, std::string_view pass, std::string_view port_name) {
    auto t = plan.texture_of(pass, port_name);
    EXPECT_TRUE(t.has_value()) << pass << "." << port_name;
    return t.value_or(UINT32_MAX);
}

// 1920x1080 RGBA16Float = 16,588,800 bytes, rounded up to 64 KiB pages.
constexpr uint64_t kColorBytes = 254ull * 65536;
constexpr uint64_t kShadowBytes = 2048ull * 2048 * 4;

TEST(Figure2, DeferredPassIsComposedFromThreePortSets) {
    FrameGraph graph = figure2();
    const Pass& deferred = graph.pass(*graph.find_pass("deferred"));
    std::vector<std::string> names;
    for (const Port& p : deferred.ports()) names.push_back(p.name);
    EXPECT_EQ(names, (std::vector<std::string>{"position", "normal", "albedo", "color", "shadow_map", "high_pass"}));
    const Port* color = deferred.find_port("color");
    ASSERT_NE(color, nullptr);
    EXPECT_EQ(color->kind, PortKind::Output);
    EXPECT_EQ(color->port_sets, (std::vector<std::string>{"deferred", "shadow-render"}));
    EXPECT_EQ(deferred.find_port("high_pass")->port_sets, (std::vector<std::string>{"high-pass-render"}));
}

TEST(Figure2, OrderAndLifetimes) {
    const Plan plan = plan_with(AllocatorKind::Paper);
    std::vector<std::string> order;
    for (const PlanPass& p : plan.order) order.push_back(p.name);
    EXPECT_EQ(order, (std::vector<std::string>{"shadow", "geometry", "deferred", "blur", "composite"}));
    EXPECT_TRUE(plan.culled.empty());

    ASSERT_EQ(plan.resources.size(), 8u);
    auto life = [&](std::string_view pass, std::string_view name) { return plan.resource_of(pass, name)->lifetime; };
    EXPECT_EQ(life("shadow", "shadow_map"), (Lifetime{0, 2}));
    EXPECT_EQ(life("geometry", "position"), (Lifetime{1, 2}));
    EXPECT_EQ(life("geometry", "normal"), (Lifetime{1, 2}));
    EXPECT_EQ(life("geometry", "albedo"), (Lifetime{1, 2}));
    EXPECT_EQ(life("deferred", "color"), (Lifetime{2, 4}));
    EXPECT_EQ(life("deferred", "high_pass"), (Lifetime{2, 3}));
    EXPECT_EQ(life("blur", "color"), (Lifetime{3, 4}));
    EXPECT_EQ(life("composite", "final"), (Lifetime{4, 4}));
    EXPECT_TRUE(plan.resource_of("composite", "final")->graph_output);
}

TEST(Figure2, PaperColouringUsesFiveColourTexturesAsInThePaper) {
    const Plan plan = plan_with(AllocatorKind::Paper);
    EXPECT_EQ(plan.summary.naive_textures, 8u);  // 7 colour outputs + the depth map
    EXPECT_EQ(plan.summary.textures, 6u);        // 5 colour textures + the depth map
    EXPECT_EQ(plan.summary.lower_bound_textures, 6u);
    ASSERT_EQ(plan.spec_classes.size(), 2u);
    EXPECT_EQ(plan.spec_classes[0].spec.format, Format::Depth32F);
    EXPECT_EQ(plan.spec_classes[1].spec.format, Format::RGBA16Float);
    EXPECT_EQ(plan.spec_classes[1].resources.size(), 7u);
    EXPECT_EQ(plan.spec_classes[1].peak_live, 5u);

    // The reverse walk: the graph output takes colour 0, composite's sources 1 and 2, blur's
    // source reuses colour 0, the G-buffer takes 2, 3 and 4. Textures are numbered by first use.
    EXPECT_EQ(texture(plan, "shadow", "shadow_map"), 0u);
    EXPECT_EQ(texture(plan, "geometry", "position"), 1u);
    EXPECT_EQ(texture(plan, "blur", "color"), 1u);
    EXPECT_EQ(texture(plan, "geometry", "normal"), 2u);
    EXPECT_EQ(texture(plan, "geometry", "albedo"), 3u);
    EXPECT_EQ(texture(plan, "deferred", "color"), 4u);
    EXPECT_EQ(texture(plan, "deferred", "high_pass"), 5u);
    EXPECT_EQ(texture(plan, "composite", "final"), 5u);
    // Inputs see the texture of the output feeding them.
    EXPECT_EQ(texture(plan, "deferred", "position"), 1u);
    EXPECT_EQ(texture(plan, "blur", "previous_pass"), 5u);
    EXPECT_EQ(texture(plan, "composite", "bloom"), 1u);

    EXPECT_EQ(plan.summary.bytes, kShadowBytes + 5 * kColorBytes);
    EXPECT_EQ(plan.summary.naive_bytes, kShadowBytes + 7 * kColorBytes);
    EXPECT_EQ(plan.summary.lower_bound_bytes, kShadowBytes + 5 * kColorBytes);
}

TEST(Figure2, IntervalColouringAlsoUsesFiveColourTextures) {
    const Plan plan = plan_with(AllocatorKind::Interval);
    EXPECT_EQ(plan.summary.textures, 6u);
    EXPECT_EQ(plan.summary.naive_textures, 8u);
    EXPECT_EQ(texture(plan, "shadow", "shadow_map"), 0u);
    EXPECT_EQ(texture(plan, "geometry", "position"), 1u);
    EXPECT_EQ(texture(plan, "geometry", "normal"), 2u);
    EXPECT_EQ(texture(plan, "geometry", "albedo"), 3u);
    EXPECT_EQ(texture(plan, "deferred", "color"), 4u);
    EXPECT_EQ(texture(plan, "deferred", "high_pass"), 5u);
    // Blur starts when the G-buffer has ended: it takes the lowest free texture, position's;
    // the final colour takes normal's.
    EXPECT_EQ(texture(plan, "blur", "color"), 1u);
    EXPECT_EQ(texture(plan, "composite", "final"), 2u);
    EXPECT_EQ(plan.summary.bytes, kShadowBytes + 5 * kColorBytes);
}

TEST(Figure2, HeapPlacementReachesThePeakOfLiveBytes) {
    const Plan plan = plan_with(AllocatorKind::Heap);
    EXPECT_EQ(plan.summary.textures, 8u);  // one placed texture per resource
    ASSERT_EQ(plan.heaps.size(), 1u);
    EXPECT_EQ(plan.summary.bytes, plan.heaps[0]);
    EXPECT_EQ(plan.summary.lower_bound_bytes, kShadowBytes + 5 * kColorBytes);
    EXPECT_EQ(plan.summary.bytes, plan.summary.lower_bound_bytes);
    for (const PlanTexture& t : plan.textures) {
        ASSERT_TRUE(t.placement.has_value()) << t.name;
        EXPECT_EQ(t.placement->offset % t.alignment, 0u) << t.name;
        EXPECT_LE(t.placement->offset + t.bytes, plan.heaps[0]) << t.name;
    }
    // Resources alive at the same time never share bytes.
    for (const PlanResource& a : plan.resources) {
        for (const PlanResource& b : plan.resources) {
            if (&a == &b || !a.lifetime.overlaps(b.lifetime)) continue;
            const HeapRange& ra = *plan.textures[a.texture].placement;
            const HeapRange& rb = *plan.textures[b.texture].placement;
            const bool disjoint = ra.offset + a.bytes <= rb.offset || rb.offset + b.bytes <= ra.offset;
            EXPECT_TRUE(disjoint) << a.name << " and " << b.name;
        }
    }
}

TEST(Figure2, UsageFollowsHowPortsUseEachTexture) {
    const Plan plan = plan_with(AllocatorKind::Interval);
    using rhi::TextureUsage;
    EXPECT_EQ(plan.resource_of("shadow", "shadow_map")->spec.usage,
              TextureUsage::DepthStencilAttachment | TextureUsage::Sampled);
    EXPECT_EQ(plan.resource_of("geometry", "position")->spec.usage,
              TextureUsage::ColorAttachment | TextureUsage::Sampled);
    // The graph output is written and then read back or presented.
    EXPECT_EQ(plan.resource_of("composite", "final")->spec.usage,
              TextureUsage::ColorAttachment | TextureUsage::CopySrc);
    // A texture's usage is the union of its tenants'.
    const PlanTexture& shared = plan.textures[*plan.texture_of("composite", "final")];
    EXPECT_EQ(shared.spec.usage, TextureUsage::ColorAttachment | TextureUsage::Sampled | TextureUsage::CopySrc);
    EXPECT_EQ(plan.find_pass("deferred")->ports[0].usage, TextureUsage::Sampled);
}

TEST(Figure2, ReplanningAnUnchangedGraphReusesThePlan) {
    FrameGraph graph = figure2();
    PlanOptions options;
    options.allocator = AllocatorKind::Paper;
    auto first = graph.plan(options);
    ASSERT_TRUE(first.ok()) << first.error().to_string();
    auto second = graph.plan(options);
    ASSERT_TRUE(second.ok());
    EXPECT_EQ(first->get(), second->get());
    EXPECT_EQ(graph.plans_built(), 1u);

    // A different frame size or allocator plans again.
    options.frame = {1280, 720};
    auto resized = graph.plan(options);
    ASSERT_TRUE(resized.ok());
    EXPECT_NE(resized->get(), first->get());
    EXPECT_EQ(graph.plans_built(), 2u);
    EXPECT_EQ((*resized)->resources[1].spec.extent, (Extent2D{1280, 720}));

    // A change to the graph plans again.
    ASSERT_TRUE(graph.add_pass(Pass("debug_view").input("color", kColor).set_side_effect()).ok());
    ASSERT_TRUE(graph.connect(port("deferred", "color"), port("debug_view", "color")).ok());
    auto changed = graph.plan(options);
    ASSERT_TRUE(changed.ok());
    EXPECT_EQ(graph.plans_built(), 3u);
    EXPECT_EQ((*changed)->order.size(), 6u);
}

TEST(Figure2, PlansCompareAndHash) {
    const Plan a = plan_with(AllocatorKind::Paper);
    const Plan b = plan_with(AllocatorKind::Paper);
    const Plan c = plan_with(AllocatorKind::Interval);
    EXPECT_EQ(a, b);
    EXPECT_EQ(plan_hash(a), plan_hash(b));
    EXPECT_NE(a, c);
    EXPECT_NE(plan_hash(a), plan_hash(c));
}

}  // namespace
}  // namespace loom::fg

// Scheduling, culling, in-place modification, lifetimes, usage, optional ports, spec sharing,
// heaps and memory models: the planner's decisions, checked value by value.
#include <gtest/gtest.h>

#include "loom/framegraph/framegraph.hpp"

namespace loom::fg {
namespace {

using rhi::ChannelKind;
using rhi::Format;
using rhi::TextureUsage;

std::vector<std::string> order_of(const Plan& plan) {
    std::vector<std::string> names;
    for (const PlanPass& p : plan.order) names.push_back(p.name);
    return names;
}

Plan must_plan(const FrameGraph& graph, PlanOptions options = {}) {
    auto plan = build_plan(graph, options);
    EXPECT_TRUE(plan.ok()) << plan.error().to_string();
    return plan.ok() ? std::move(*plan) : Plan{};
}

TEST(Schedule, TiesAreBrokenByDeclarationOrder) {
    FrameGraph graph;
    for (const char* name : {"c", "a", "b"}) ASSERT_TRUE(graph.add_pass(Pass(name).output("out").set_side_effect()).ok());
    EXPECT_EQ(order_of(must_plan(graph)), (std::vector<std::string>{"c", "a", "b"}));
}

TEST(Schedule, DependenciesComeFirstWhateverTheDeclarationOrder) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("present").input("color").output("final")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("tonemap").input("hdr").output("color")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("other").output("x").set_side_effect()).ok());
    ASSERT_TRUE(graph.add_pass(Pass("light").output("hdr")).ok());
    ASSERT_TRUE(graph.connect(port("tonemap", "color"), port("present", "color")).ok());
    ASSERT_TRUE(graph.connect(port("light", "hdr"), port("tonemap", "hdr")).ok());
    ASSERT_TRUE(graph.mark_output(port("present", "final")).ok());
    // "other" is ready from the start but declared after tonemap's chain head... light is
    // declared last, so the smallest ready index runs first each time.
    EXPECT_EQ(order_of(must_plan(graph)), (std::vector<std::string>{"other", "light", "tonemap", "present"}));
}

TEST(Cull, PassesWhoseResultsNobodyNeedsAreCulled) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("scene").output("color")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("debug_blur").input("color").output("blurred")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("debug_view").input("blurred").output("view")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("stats").input("color").output("histogram")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("final").input("color").output("out")).ok());
    ASSERT_TRUE(graph.connect(port("scene", "color"), port("debug_blur", "color")).ok());
    ASSERT_TRUE(graph.connect(port("debug_blur", "blurred"), port("debug_view", "blurred")).ok());
    ASSERT_TRUE(graph.connect(port("scene", "color"), port("stats", "color")).ok());
    ASSERT_TRUE(graph.connect(port("scene", "color"), port("final", "color")).ok());
    ASSERT_TRUE(graph.mark_output(port("final", "out")).ok());

    Plan plan = must_plan(graph);
    EXPECT_EQ(order_of(plan), (std::vector<std::string>{"scene", "final"}));
    EXPECT_EQ(plan.culled, (std::vector<std::string>{"debug_blur", "debug_view", "stats"}));
    EXPECT_EQ(plan.resources.size(), 2u);
    // Culled readers do not extend lifetimes.
    EXPECT_EQ(plan.resource_of("scene", "color")->lifetime, (Lifetime{0, 1}));
    EXPECT_EQ(plan.resource_of("scene", "color")->ports, (std::vector<std::string>{"scene.color", "final.color"}));

    // A side effect keeps a pass and what it needs.
    ASSERT_TRUE(graph.set_side_effect("stats").ok());
    plan = must_plan(graph);
    EXPECT_EQ(order_of(plan), (std::vector<std::string>{"scene", "stats", "final"}));
    EXPECT_EQ(plan.culled, (std::vector<std::string>{"debug_blur", "debug_view"}));
    EXPECT_EQ(plan.resource_of("scene", "color")->lifetime, (Lifetime{0, 2}));
}

// scene → color; tint modifies it in place; histogram reads the colour before tint; present
// reads the tinted colour.
FrameGraph in_place_graph() {
    FrameGraph graph;
    EXPECT_TRUE(graph.add_pass(Pass("scene").output("color", TextureSpec::of(Format::RGBA16Float))).ok());
    EXPECT_TRUE(graph.add_pass(Pass("tint").inout("color")).ok());
    EXPECT_TRUE(graph.add_pass(Pass("histogram").input("color").output("bins", TextureSpec::of(Format::R32Uint).with_size(256, 1))).ok());
    EXPECT_TRUE(graph.add_pass(Pass("present").input("color").input("bins").output("final", TextureSpec::of(Format::RGBA8Unorm))).ok());
    EXPECT_TRUE(graph.connect(port("scene", "color"), port("tint", "color")).ok());
    EXPECT_TRUE(graph.connect(port("scene", "color"), port("histogram", "color")).ok());
    EXPECT_TRUE(graph.connect(port("tint", "color"), port("present", "color")).ok());
    EXPECT_TRUE(graph.connect(port("histogram", "bins"), port("present", "bins")).ok());
    EXPECT_TRUE(graph.mark_output(port("present", "final")).ok());
    return graph;
}

TEST(InOut, ModifiesTheSameTextureAfterEveryReaderOfThePreviousContents) {
    const Plan plan = must_plan(in_place_graph());
    // histogram is declared after tint but reads the colour before tint changes it.
    EXPECT_EQ(order_of(plan), (std::vector<std::string>{"scene", "histogram", "tint", "present"}));
    const PlanResource* color = plan.resource_of("scene", "color");
    ASSERT_NE(color, nullptr);
    EXPECT_EQ(plan.resource_of("tint", "color"), color);
    EXPECT_EQ(plan.resource_of("present", "color"), color);
    EXPECT_EQ(plan.resource_of("histogram", "color"), color);
    EXPECT_EQ(color->lifetime, (Lifetime{0, 3}));
    EXPECT_EQ(color->ports, (std::vector<std::string>{"scene.color", "tint.color", "histogram.color", "present.color"}));
    // The inout port writes as an attachment; its spec came from scene.color.
    EXPECT_EQ(plan.find_pass("tint")->ports[0].usage, TextureUsage::ColorAttachment);
    EXPECT_EQ(color->spec.format, Format::RGBA16Float);
    EXPECT_EQ(plan.summary.naive_textures, 3u);
}

TEST(InOut, ChainedModificationsShareOneTexture) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("scene").output("color")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("decals").inout("color")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("particles").inout("color")).ok());
    ASSERT_TRUE(graph.connect(port("scene", "color"), port("decals", "color")).ok());
    ASSERT_TRUE(graph.connect(port("decals", "color"), port("particles", "color")).ok());
    ASSERT_TRUE(graph.mark_output(port("particles", "color")).ok());
    for (AllocatorKind allocator : allocator_kinds()) {
        PlanOptions options;
        options.allocator = allocator;
        const Plan plan = must_plan(graph, options);
        EXPECT_EQ(order_of(plan), (std::vector<std::string>{"scene", "decals", "particles"})) << allocator_name(allocator);
        ASSERT_EQ(plan.resources.size(), 1u) << allocator_name(allocator);
        EXPECT_EQ(plan.summary.textures, 1u) << allocator_name(allocator);
        EXPECT_TRUE(plan.resources[0].graph_output);
        EXPECT_EQ(plan.resources[0].lifetime, (Lifetime{0, 2}));
    }
}

TEST(InOut, AnUnconnectedOptionalInOutStartsAFreshTexture) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("overlay").declare("canvas", PortKind::InOut, TextureSpec::of(Format::RGBA8Unorm), true)).ok());
    ASSERT_TRUE(graph.mark_output(port("overlay", "canvas")).ok());
    const Plan plan = must_plan(graph);
    ASSERT_EQ(plan.resources.size(), 1u);
    EXPECT_EQ(plan.resources[0].name, "overlay.canvas");
    EXPECT_EQ(plan.resources[0].spec.format, Format::RGBA8Unorm);

    FrameGraph required;
    ASSERT_TRUE(required.add_pass(Pass("overlay").inout("canvas")).ok());
    ASSERT_TRUE(required.mark_output(port("overlay", "canvas")).ok());
    EXPECT_EQ(build_plan(required, {}).error().message, "required inout overlay.canvas is not connected");
}

TEST(Lifetimes, UnreadOutputsAndGraphOutputs) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("gbuffer").output("albedo").output("velocity").optional_output("debug")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("light").input("albedo").output("color")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("ui").output("overlay").set_side_effect()).ok());
    ASSERT_TRUE(graph.connect(port("gbuffer", "albedo"), port("light", "albedo")).ok());
    ASSERT_TRUE(graph.mark_output(port("light", "color")).ok());
    // Declared: the memory order runs the UI first, where its overlay overlaps nothing.
    PlanOptions declared;
    declared.order = PassOrder::Declared;
    const Plan plan = must_plan(graph, declared);
    EXPECT_EQ(order_of(plan), (std::vector<std::string>{"gbuffer", "light", "ui"}));
    // A required output nobody reads is still written: it lives during its pass only.
    EXPECT_EQ(plan.resource_of("gbuffer", "velocity")->lifetime, (Lifetime{0, 0}));
    // An optional output nobody reads gets no texture.
    EXPECT_EQ(plan.resource_of("gbuffer", "debug"), nullptr);
    EXPECT_FALSE(plan.find_pass("gbuffer")->ports[2].resource.has_value());
    // A graph output lives until the last pass, even though light is not last.
    EXPECT_EQ(plan.resource_of("light", "color")->lifetime, (Lifetime{1, 2}));
    EXPECT_EQ(plan.resources.size(), 4u);
    EXPECT_EQ(plan.graph_outputs, (std::vector<std::string>{"light.color"}));
}

TEST(Usage, StorageRequestsReplaceAttachmentAndSampledAccess) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("compute").output("field", TextureSpec::of(Format::RGBA32Float).with_usage(TextureUsage::Storage))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("reader").input("field", TextureSpec{}.with_usage(TextureUsage::Storage)).input("again").output("out")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("depth").output("z", TextureSpec::of(Format::Depth24Stencil8))).ok());
    ASSERT_TRUE(graph.connect(port("compute", "field"), port("reader", "field")).ok());
    ASSERT_TRUE(graph.connect(port("compute", "field"), port("reader", "again")).ok());
    ASSERT_TRUE(graph.mark_output(port("reader", "out")).ok());
    ASSERT_TRUE(graph.mark_output(port("depth", "z")).ok());
    const Plan plan = must_plan(graph);
    EXPECT_EQ(plan.resource_of("compute", "field")->spec.usage, TextureUsage::Storage | TextureUsage::Sampled);
    EXPECT_EQ(plan.find_pass("compute")->ports[0].usage, TextureUsage::Storage);
    EXPECT_EQ(plan.find_pass("reader")->ports[0].usage, TextureUsage::Storage);
    EXPECT_EQ(plan.find_pass("reader")->ports[1].usage, TextureUsage::Sampled);
    EXPECT_EQ(plan.resource_of("depth", "z")->spec.usage, TextureUsage::DepthStencilAttachment | TextureUsage::CopySrc);
}

TEST(Formats, CoveringChoiceIsRecordedInThePlan) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("light").output("hdr", TextureSpec::color(3, 16, ChannelKind::Float))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("post").input("hdr").output("ldr")).ok());
    ASSERT_TRUE(graph.connect(port("light", "hdr"), port("post", "hdr")).ok());
    ASSERT_TRUE(graph.mark_output(port("post", "ldr")).ok());
    const Plan plan = must_plan(graph);
    const PlanResource* hdr = plan.resource_of("light", "hdr");
    EXPECT_EQ(hdr->spec.format, Format::RGBA16Float);
    EXPECT_EQ(hdr->spec.format_match, FormatMatch::Covering);
    EXPECT_EQ(hdr->requested_format, color_features(3, 16, ChannelKind::Float));
    const PlanResource* ldr = plan.resource_of("post", "ldr");
    EXPECT_EQ(ldr->spec.format, Format::RGBA8Unorm);
    EXPECT_EQ(ldr->spec.format_match, FormatMatch::Default);
    EXPECT_FALSE(ldr->requested_format.has_value());
}

// Five passes in a row, each reading the previous one's output: narrow (R16Float), wide,
// wide (RGBA16Float), narrow, narrow. Only neighbours in the chain are alive together.
FrameGraph mixed_chain() {
    FrameGraph graph;
    const TextureSpec narrow = TextureSpec::of(Format::R16Float);
    const TextureSpec wide = TextureSpec::of(Format::RGBA16Float);
    EXPECT_TRUE(graph.add_pass(Pass("p0").output("out", narrow)).ok());
    EXPECT_TRUE(graph.add_pass(Pass("p1").input("in").output("out", wide)).ok());
    EXPECT_TRUE(graph.add_pass(Pass("p2").input("in").output("out", wide)).ok());
    EXPECT_TRUE(graph.add_pass(Pass("p3").input("in").output("out", narrow)).ok());
    EXPECT_TRUE(graph.add_pass(Pass("p4").input("in").output("out", narrow)).ok());
    for (int i = 0; i < 4; ++i) {
        // Appended, not "p" + ...: GCC 12 at -O3 warns falsely on that (-Wrestrict, bug 105651).
        std::string from(1, 'p');
        from += static_cast<char>('0' + i);
        std::string to(1, 'p');
        to += static_cast<char>('1' + i);
        EXPECT_TRUE(graph.connect(port(from, "out"), port(to, "in")).ok());
    }
    EXPECT_TRUE(graph.mark_output(port("p4", "out")).ok());
    return graph;
}

constexpr uint64_t kKiB = 1024;

TEST(SpecSharingMode, JoinableSpecsMayShareATextureOfTheJoinedSpec) {
    PlanOptions options;
    options.frame = {256, 256};  // R16Float: 128 KiB; RGBA16Float: 512 KiB
    options.allocator = AllocatorKind::Interval;
    const Plan equal = must_plan(mixed_chain(), options);
    ASSERT_EQ(equal.spec_classes.size(), 2u);
    // Two narrow ones overlap (p3, p4) and two wide ones (p1, p2): two textures of each.
    EXPECT_EQ(equal.summary.textures, 4u);
    EXPECT_EQ(equal.summary.bytes, 2 * 128 * kKiB + 2 * 512 * kKiB);

    options.sharing = SpecSharing::Joinable;
    const Plan joinable = must_plan(mixed_chain(), options);
    ASSERT_EQ(joinable.spec_classes.size(), 1u);
    EXPECT_EQ(joinable.spec_classes[0].spec.format, Format::RGBA16Float);
    EXPECT_EQ(joinable.summary.textures, 2u);  // never more than two alive at once
    EXPECT_EQ(joinable.summary.lower_bound_textures, 2u);
    // Each texture gets the join of its tenants: both hold a wide resource here.
    EXPECT_EQ(joinable.summary.bytes, 2 * 512 * kKiB);
    for (const PlanTexture& t : joinable.textures) EXPECT_EQ(t.spec.format, Format::RGBA16Float);
    EXPECT_EQ(joinable.textures[*joinable.texture_of("p0", "out")].resources,
              (std::vector<uint32_t>{0, 2, 4}));  // p0.out, p2.out, p4.out

    PlanOptions paper = options;
    paper.allocator = AllocatorKind::Paper;
    EXPECT_EQ(must_plan(mixed_chain(), paper).summary.textures, 2u);
}

TEST(SpecSharingMode, SharingJoinableSpecsCanCostBytes) {
    // RGBA8Unorm and R16Unorm join to R16 G8 B8 A8, which only RGBA16Unorm covers.
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("a").output("color", TextureSpec::of(Format::RGBA8Unorm)).set_side_effect()).ok());
    ASSERT_TRUE(graph.add_pass(Pass("b").output("depth", TextureSpec::of(Format::R16Unorm)).set_side_effect()).ok());
    PlanOptions options;
    options.frame = {256, 256};
    const Plan equal = must_plan(graph, options);
    EXPECT_EQ(equal.summary.textures, 2u);
    EXPECT_EQ(equal.summary.bytes, 256 * kKiB + 128 * kKiB);
    options.sharing = SpecSharing::Joinable;
    const Plan joinable = must_plan(graph, options);
    EXPECT_EQ(joinable.summary.textures, 1u);
    EXPECT_EQ(joinable.textures[0].spec.format, Format::RGBA16Unorm);
    EXPECT_EQ(joinable.textures[0].spec.format_match, FormatMatch::Covering);
    EXPECT_EQ(joinable.summary.bytes, 512 * kKiB);
}

TEST(Heap, CappedHeapsSplitIntoSeveral) {
    PlanOptions options;
    options.frame = {256, 256};
    options.allocator = AllocatorKind::Heap;
    const Plan one = must_plan(mixed_chain(), options);
    ASSERT_EQ(one.heaps.size(), 1u);
    EXPECT_EQ(one.summary.bytes, one.summary.lower_bound_bytes);
    EXPECT_EQ(one.summary.lower_bound_bytes, 1024 * kKiB);  // p1.out and p2.out at p2

    options.max_heap_bytes = 512 * 1024;
    const Plan capped = must_plan(mixed_chain(), options);
    EXPECT_GE(capped.heaps.size(), 2u);
    for (uint64_t size : capped.heaps) EXPECT_LE(size, options.max_heap_bytes);
    for (const PlanTexture& t : capped.textures) {
        ASSERT_TRUE(t.placement.has_value());
        EXPECT_LE(t.placement->offset + t.bytes, capped.heaps[t.placement->heap]);
    }
}

// Sizes as a device might report them: exact bytes, 256-byte alignment; counts its calls.
class CountingMemoryModel final : public MemoryModel {
public:
    Result<rhi::MemoryRequirements> requirements(const rhi::TextureDesc& desc) override {
        ++calls;
        if (desc.format == Format::RGB9E5Float) return make_error(ErrorCode::Unsupported, desc.name + ": RGB9E5Float");
        return rhi::MemoryRequirements{align_up(DefaultMemoryModel::texture_bytes(desc), 256), 256};
    }
    int calls = 0;
};

TEST(MemoryModels, ThePlanUsesTheModelItIsGiven) {
    auto model = std::make_shared<CountingMemoryModel>();
    PlanOptions options;
    options.frame = {100, 100};
    options.memory_model = model;
    options.allocator = AllocatorKind::Heap;
    const Plan plan = must_plan(mixed_chain(), options);
    EXPECT_GT(model->calls, 0);
    EXPECT_EQ(plan.resource_of("p0", "out")->bytes, 20224u);  // 100 x 100 x 2 = 20000, aligned to 256
    EXPECT_EQ(plan.resource_of("p1", "out")->alignment, 256u);
    EXPECT_EQ(plan.resource_of("p1", "out")->bytes, 80128u);  // 100 x 100 x 8 = 80000, aligned
    for (const PlanTexture& t : plan.textures) EXPECT_EQ(t.placement->offset % 256, 0u);

    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("sky").output("radiance", TextureSpec::of(Format::RGB9E5Float))).ok());
    ASSERT_TRUE(graph.mark_output(port("sky", "radiance")).ok());
    auto failed = build_plan(graph, options);
    ASSERT_FALSE(failed.ok());
    EXPECT_EQ(failed.error().code, ErrorCode::Unsupported);
    EXPECT_NE(failed.error().message.find("sky.radiance"), std::string::npos);
}

TEST(MemoryModels, DefaultModelSumsMipsLayersAndSamples) {
    rhi::TextureDesc desc;
    desc.format = Format::RGBA8Unorm;
    desc.width = 256;
    desc.height = 128;
    desc.mip_levels = 3;  // 256x128 + 128x64 + 64x32
    desc.depth_or_layers = 2;
    EXPECT_EQ(DefaultMemoryModel::texture_bytes(desc), (256u * 128 + 128 * 64 + 64 * 32) * 4 * 2);
    desc.mip_levels = 1;
    desc.samples = 4;
    EXPECT_EQ(DefaultMemoryModel::texture_bytes(desc), 256u * 128 * 4 * 2 * 4);
    DefaultMemoryModel model;
    auto requirements = model.requirements(desc);
    ASSERT_TRUE(requirements.ok());
    EXPECT_EQ(requirements->alignment, 65536u);
    EXPECT_EQ(requirements->size, 1048576u);
}

TEST(PlanData, EdgesAndTextureDescriptions) {
    const Plan plan = must_plan(in_place_graph());
    ASSERT_EQ(plan.edges.size(), 4u);
    // scene.color → tint.color, in connection order.
    EXPECT_EQ(plan.edges[0], (PlanEdge{0, 0, 2, 0, 0}));
    const PlanTexture& bins = plan.textures[*plan.texture_of("histogram", "bins")];
    const rhi::TextureDesc desc = to_texture_desc(bins.spec, bins.name);
    EXPECT_EQ(desc.format, Format::R32Uint);
    EXPECT_EQ(desc.width, 256u);
    EXPECT_EQ(desc.height, 1u);
    EXPECT_EQ(desc.usage, TextureUsage::ColorAttachment | TextureUsage::Sampled);
}

}  // namespace
}  // namespace loom::fg

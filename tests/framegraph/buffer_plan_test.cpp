// Buffers, pass kinds and subresource ranges in the planner: joins and their errors, resolved
// sizes, usages, lifetimes, sharing, heap placement, summaries and the execution schedule's
// transitions, checked value by value.
#include <gtest/gtest.h>

#include "loom/framegraph/framegraph.hpp"

namespace loom::fg {
namespace {

using rhi::BufferUsage;
using rhi::Format;
using rhi::ResourceState;
using rhi::TextureUsage;

// The tests pin positions of the order the passes are declared in.
PlanOptions declared_options() {
    PlanOptions options;
    options.order = PassOrder::Declared;
    return options;
}

Plan must_plan(const FrameGraph& graph, PlanOptions options = declared_options()) {
    auto plan = build_plan(graph, options);
    EXPECT_TRUE(plan.ok()) << plan.error().to_string();
    return plan.ok() ? std::move(*plan) : Plan{};
}

Error must_fail(const FrameGraph& graph, PlanOptions options = declared_options()) {
    auto plan = build_plan(graph, options);
    EXPECT_FALSE(plan.ok());
    return plan.ok() ? Error{} : plan.error();
}

// ---- specs -------------------------------------------------------------------------------------

TEST(BufferSpecs, SizesEvaluateAgainstTheFrame) {
    EXPECT_EQ(BufferSize::absolute(4096).evaluate({1920, 1080}), 4096u);
    EXPECT_EQ(BufferSize::per_pixel(4).evaluate({1920, 1080}), 1920u * 1080u * 4u);
    EXPECT_EQ(BufferSize::per_pixel(16, 0.5f).evaluate({1920, 1080}), 960u * 540u * 16u);
    // 1920/16 = 120 tiles across, ceil(1080/16) = 68 down.
    EXPECT_EQ(BufferSize::per_tile(16, 16, 1024).evaluate({1920, 1080}), 120u * 68u * 1024u);
    EXPECT_EQ(BufferSize::per_pixel(uint64_t{1} << 40).evaluate({65536, 65536}), std::nullopt);
}

TEST(BufferSpecs, JoinTakesTheLargestAlignmentAndEveryUsage) {
    const BufferSpec a = BufferSpec::of_size(256).with_usage(BufferUsage::Storage).with_alignment(16);
    const BufferSpec b = BufferSpec{}.with_usage(BufferUsage::Indirect).with_alignment(64);
    auto joined = join_buffer_specs(a, b);
    ASSERT_TRUE(joined.ok()) << joined.error().to_string();
    EXPECT_EQ(joined->size, BufferSize::absolute(256));
    EXPECT_EQ(joined->usage, BufferUsage::Storage | BufferUsage::Indirect);
    EXPECT_EQ(joined->alignment, 64u);
}

TEST(BufferSpecs, SizesJoinWhenEqualForTheFrame) {
    JoinContext context;
    context.frame = Extent2D{64, 32};
    context.a_name = "cull.lights";
    context.b_name = "shade.lights";
    auto same = join_buffer_specs(BufferSpec::sized(BufferSize::per_pixel(4)), BufferSpec::of_size(64 * 32 * 4), context);
    ASSERT_TRUE(same.ok());
    EXPECT_EQ(same->size, BufferSize::absolute(64 * 32 * 4));  // the absolute one is kept

    auto differ = join_buffer_specs(BufferSpec::sized(BufferSize::per_tile(16, 16, 1024)), BufferSpec::of_size(4096), context);
    ASSERT_FALSE(differ.ok());
    EXPECT_EQ(differ.error().code, ErrorCode::Join);
    EXPECT_EQ(differ.error().message,
              "cannot join cull.lights and shade.lights: buffer size 8192 bytes (1024 bytes per 16x16 tile) vs 4096 bytes "
              "(frame 64x32)");
}

TEST(BufferSpecs, ResolveRefusesMissingZeroAndHugeSizesAndBadAlignments) {
    const Extent2D frame{64, 64};
    auto missing = resolve_buffer(BufferSpec{}.with_usage(BufferUsage::Storage), frame, "cull.lights");
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().message.find("buffer cull.lights: no port gives its size"), std::string::npos);
    EXPECT_FALSE(resolve_buffer(BufferSpec::of_size(0), frame, "x").ok());
    EXPECT_FALSE(resolve_buffer(BufferSpec::of_size(kMaxBufferBytes + 1), frame, "x").ok());
    EXPECT_FALSE(resolve_buffer(BufferSpec::of_size(64).with_alignment(48), frame, "x").ok());
    EXPECT_FALSE(resolve_buffer(BufferSpec::of_size(64).with_alignment(kMaxBufferAlignment * 2), frame, "x").ok());
    EXPECT_FALSE(resolve_buffer(BufferSpec::sized(BufferSize::per_tile(0, 16, 4)), frame, "x").ok());
    auto fine = resolve_buffer(BufferSpec::of_size(100).with_alignment(256), frame, "x");
    ASSERT_TRUE(fine.ok());
    EXPECT_EQ(*fine, (ResolvedBufferSpec{100, BufferUsage::None, 256}));
}

// ---- declarations and connections --------------------------------------------------------------

TEST(BufferPorts, TextureAndBufferPortsDoNotConnect) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("cull").set_kind(PassKind::Compute).buffer_output("lights", BufferSpec::of_size(64))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("shade").input("lights").output("color")).ok());
    Status status = graph.connect(port("cull", "lights"), port("shade", "lights"));
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().message,
              "connect cull.lights -> shade.lights: cull.lights is a buffer port but shade.lights is a texture port");
}

TEST(BufferPorts, PortSetsDeclaringOnePortAsTextureAndBufferConflict) {
    PortSet a("lighting");
    a.input("lights");
    PortSet b("clustered");
    b.buffer_input("lights");
    Pass pass("shade");
    pass.add(a).add(b);
    ASSERT_FALSE(pass.status().ok());
    EXPECT_EQ(pass.status().error().message,
              "pass 'shade': port 'lights' is declared as a texture port by port set 'lighting' and as a buffer port by "
              "port set 'clustered'");
}

TEST(BufferPorts, MergedDeclarationsJoinBufferSpecs) {
    PortSet a("indirect");
    a.buffer_input("args", BufferSpec{}.with_usage(BufferUsage::Indirect).with_alignment(4));
    PortSet b("sized");
    b.buffer_input("args", BufferSpec::of_size(20));
    Pass pass("draw");
    pass.add(a).add(b);
    ASSERT_TRUE(pass.status().ok()) << pass.status().error().to_string();
    EXPECT_EQ(pass.find_port("args")->buffer, BufferSpec::of_size(20).with_usage(BufferUsage::Indirect).with_alignment(4));
}

// A compute-built light list: cull writes a tiled light list, build_args writes indirect
// arguments from it, shade reads the list as storage and draw reads the arguments indirectly.
FrameGraph light_list_graph() {
    FrameGraph graph;
    EXPECT_TRUE(graph.add_pass(Pass("depth").output("depth", TextureSpec::of(Format::Depth32F))).ok());
    EXPECT_TRUE(graph.add_pass(Pass("cull")
                                   .set_kind(PassKind::Compute)
                                   .input("depth")
                                   .buffer_output("lights", BufferSpec::sized(BufferSize::per_tile(16, 16, 1024))))
                    .ok());
    EXPECT_TRUE(graph.add_pass(Pass("build_args")
                                   .set_kind(PassKind::Compute)
                                   .buffer_input("lights")
                                   .buffer_output("args", BufferSpec::of_size(20).with_alignment(4)))
                    .ok());
    EXPECT_TRUE(graph.add_pass(Pass("shade")
                                   .input("depth")
                                   .buffer_input("lights", BufferSpec{}.with_usage(BufferUsage::Storage))
                                   .output("color", TextureSpec::of(Format::RGBA16Float)))
                    .ok());
    EXPECT_TRUE(graph.add_pass(Pass("draw")
                                   .buffer_input("args", BufferSpec{}.with_usage(BufferUsage::Indirect))
                                   .inout("color"))
                    .ok());
    EXPECT_TRUE(graph.connect(port("depth", "depth"), port("cull", "depth")).ok());
    EXPECT_TRUE(graph.connect(port("depth", "depth"), port("shade", "depth")).ok());
    EXPECT_TRUE(graph.connect(port("cull", "lights"), port("build_args", "lights")).ok());
    EXPECT_TRUE(graph.connect(port("cull", "lights"), port("shade", "lights")).ok());
    EXPECT_TRUE(graph.connect(port("build_args", "args"), port("draw", "args")).ok());
    EXPECT_TRUE(graph.connect(port("shade", "color"), port("draw", "color")).ok());
    EXPECT_TRUE(graph.mark_output(port("draw", "color")).ok());
    return graph;
}

TEST(BufferPlans, LightListResolvesSizesUsagesAndLifetimes) {
    PlanOptions options = declared_options();
    options.frame = {64, 48};
    const Plan plan = must_plan(light_list_graph(), options);
    ASSERT_EQ(plan.order.size(), 5u);
    EXPECT_EQ(plan.order[1].kind, PassKind::Compute);
    EXPECT_EQ(plan.order[3].kind, PassKind::Graphics);

    ASSERT_EQ(plan.resources.size(), 4u);
    const PlanResource& lights = plan.resources[1];
    EXPECT_EQ(lights.name, "cull.lights");
    EXPECT_EQ(lights.type, ResourceType::Buffer);
    // 4 x 3 tiles of 1 KiB; written as storage, read as storage by build_args and shade.
    EXPECT_EQ(lights.buffer_spec, (ResolvedBufferSpec{12 * 1024, BufferUsage::Storage, 1}));
    EXPECT_EQ(lights.lifetime, (Lifetime{1, 3}));
    EXPECT_EQ(lights.bytes, 12u * 1024u);
    EXPECT_EQ(lights.alignment, MemoryModel::kDefaultBufferAlignment);
    EXPECT_EQ(lights.texture, kNoPhysical);
    const PlanResource& args = plan.resources[2];
    EXPECT_EQ(args.name, "build_args.args");
    EXPECT_EQ(args.buffer_spec, (ResolvedBufferSpec{20, BufferUsage::Storage | BufferUsage::Indirect, 4}));
    EXPECT_EQ(args.bytes, 256u);  // rounded up to the model's 256-byte alignment
    EXPECT_EQ(args.lifetime, (Lifetime{2, 4}));

    // Ports: roles by pass kind and declared use.
    EXPECT_EQ(plan.order[1].ports[1].buffer_usage, BufferUsage::Storage);   // cull writes
    EXPECT_EQ(plan.order[1].ports[0].usage, TextureUsage::Sampled);          // cull samples depth
    EXPECT_EQ(plan.order[4].ports[0].buffer_usage, BufferUsage::Indirect);  // draw reads arguments
    EXPECT_EQ(plan.order[4].ports[0].bytes, (BufferRange{0, 20}));

    ASSERT_EQ(plan.buffers.size(), 2u);
    EXPECT_EQ(plan.buffers[0].name, "b0");
    EXPECT_EQ(plan.buffers[0].resources, (std::vector<uint32_t>{1}));
    EXPECT_EQ(plan.buffers[1].resources, (std::vector<uint32_t>{2}));
    EXPECT_EQ(lights.buffer, 0u);
    EXPECT_EQ(args.buffer, 1u);
    EXPECT_EQ(plan.buffer_of("draw", "args"), 1u);
    EXPECT_EQ(plan.texture_of("draw", "args"), std::nullopt);
    EXPECT_EQ(plan.textures.size(), 2u);

    EXPECT_EQ(plan.summary.buffers, 2u);
    EXPECT_EQ(plan.summary.buffer_bytes, 12u * 1024u + 256u);
    EXPECT_EQ(plan.summary.naive_buffers, 2u);
    EXPECT_EQ(plan.summary.lower_bound_buffers, 2u);
    EXPECT_EQ(plan.summary.naive_textures, 2u);
    uint64_t texture_bytes = 0;
    for (const PlanTexture& t : plan.textures) texture_bytes += t.bytes;
    EXPECT_EQ(plan.summary.bytes, texture_bytes + 12u * 1024u + 256u);
}

TEST(BufferPlans, BuffersOfOneSizeWhoseLifetimesDoNotOverlapShareOneBuffer) {
    // a -> b -> c, each pass writing a 4 KiB buffer the next reads: a's and c's buffers share.
    FrameGraph graph;
    const BufferSpec spec = BufferSpec::of_size(4096);
    ASSERT_TRUE(graph.add_pass(Pass("a").set_kind(PassKind::Compute).buffer_output("out", spec)).ok());
    ASSERT_TRUE(graph.add_pass(Pass("b").set_kind(PassKind::Compute).buffer_input("in").buffer_output("out", spec)).ok());
    ASSERT_TRUE(graph.add_pass(Pass("c").set_kind(PassKind::Compute).buffer_input("in").buffer_output("out", spec)).ok());
    ASSERT_TRUE(graph.add_pass(Pass("d").buffer_input("in").output("color")).ok());
    ASSERT_TRUE(graph.connect(port("a", "out"), port("b", "in")).ok());
    ASSERT_TRUE(graph.connect(port("b", "out"), port("c", "in")).ok());
    ASSERT_TRUE(graph.connect(port("c", "out"), port("d", "in")).ok());
    ASSERT_TRUE(graph.mark_output(port("d", "color")).ok());

    const Plan plan = must_plan(graph);
    ASSERT_EQ(plan.buffers.size(), 2u);
    EXPECT_EQ(plan.buffers[0].resources, (std::vector<uint32_t>{0, 2}));
    EXPECT_EQ(plan.buffers[1].resources, (std::vector<uint32_t>{1}));
    EXPECT_EQ(plan.summary.naive_buffers, 3u);
    EXPECT_EQ(plan.summary.lower_bound_buffers, 2u);
    EXPECT_EQ(plan.summary.buffer_bytes, 2u * 4096u);
    // One spec class for the three buffers, one for the texture.
    ASSERT_EQ(plan.spec_classes.size(), 2u);
    EXPECT_EQ(plan.spec_classes[0].type, ResourceType::Buffer);
    EXPECT_EQ(plan.spec_classes[0].peak_live, 2u);
}

TEST(BufferPlans, HeapsPlaceBuffersBesideTexturesAndTheBoundCountsThem) {
    PlanOptions options = declared_options();
    options.frame = {64, 48};
    options.allocator = AllocatorKind::Heap;
    const Plan plan = must_plan(light_list_graph(), options);
    ASSERT_EQ(plan.heaps.size(), 1u);
    ASSERT_EQ(plan.buffers.size(), 2u);
    for (const PlanBuffer& b : plan.buffers) {
        ASSERT_TRUE(b.placement.has_value()) << b.name;
        EXPECT_EQ(b.placement->offset % b.alignment, 0u) << b.name;
    }
    // Everything is alive at position 3 (depth, lights, args, color): the bound is their sum.
    uint64_t all = 0;
    for (const PlanResource& r : plan.resources) all += r.bytes;
    EXPECT_EQ(plan.summary.lower_bound_bytes, all);
    EXPECT_EQ(plan.summary.bytes, plan.heaps[0]);
    EXPECT_GE(plan.summary.bytes, plan.summary.lower_bound_bytes);
    // No two live resources overlap in the heap.
    auto range_of = [&](uint32_t r) {
        const PlanResource& resource = plan.resources[r];
        const HeapRange at = resource.type == ResourceType::Buffer ? *plan.buffers[resource.buffer].placement
                                                                   : *plan.textures[resource.texture].placement;
        return std::pair{at.offset, at.offset + resource.bytes};
    };
    for (uint32_t i = 0; i < plan.resources.size(); ++i) {
        for (uint32_t j = i + 1; j < plan.resources.size(); ++j) {
            if (!plan.resources[i].lifetime.overlaps(plan.resources[j].lifetime)) continue;
            const auto a = range_of(i);
            const auto b = range_of(j);
            EXPECT_TRUE(a.second <= b.first || b.second <= a.first) << plan.resources[i].name << " " << plan.resources[j].name;
        }
    }
}

TEST(BufferPlans, UnsizedBuffersAndSeveralReadUsesAreNamedErrors) {
    FrameGraph unsized;
    ASSERT_TRUE(unsized.add_pass(Pass("cull").set_kind(PassKind::Compute).buffer_output("lights")).ok());
    ASSERT_TRUE(unsized.add_pass(Pass("shade").buffer_input("lights").output("color")).ok());
    ASSERT_TRUE(unsized.connect(port("cull", "lights"), port("shade", "lights")).ok());
    ASSERT_TRUE(unsized.mark_output(port("shade", "color")).ok());
    const Error error = must_fail(unsized);
    EXPECT_EQ(error.code, ErrorCode::Graph);
    EXPECT_NE(error.message.find("buffer cull.lights: no port gives its size"), std::string::npos) << error.message;
    EXPECT_EQ(error.subjects, (std::vector<std::string>{"cull.lights", "shade.lights"}));

    FrameGraph twice;
    ASSERT_TRUE(twice.add_pass(Pass("fill").set_kind(PassKind::Compute).buffer_output("geometry", BufferSpec::of_size(64))).ok());
    ASSERT_TRUE(twice.add_pass(Pass("draw")
                                   .buffer_input("geometry", BufferSpec{}.with_usage(BufferUsage::Vertex | BufferUsage::Indirect))
                                   .output("color"))
                    .ok());
    ASSERT_TRUE(twice.connect(port("fill", "geometry"), port("draw", "geometry")).ok());
    ASSERT_TRUE(twice.mark_output(port("draw", "color")).ok());
    const Error several = must_fail(twice);
    EXPECT_EQ(several.message,
              "port draw.geometry reads its buffer in several ways (vertex|indirect); a port reads a buffer one way: declare "
              "one input port per use");
    EXPECT_EQ(several.subjects, (std::vector<std::string>{"draw.geometry"}));
}

TEST(BufferPlans, SizeConflictsNameBothPorts) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("fill").set_kind(PassKind::Compute).buffer_output("data", BufferSpec::of_size(64))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("use").buffer_input("data", BufferSpec::of_size(128)).output("color")).ok());
    ASSERT_TRUE(graph.connect(port("fill", "data"), port("use", "data")).ok());
    ASSERT_TRUE(graph.mark_output(port("use", "color")).ok());
    const Error error = must_fail(graph);
    EXPECT_EQ(error.code, ErrorCode::Join);
    EXPECT_EQ(error.message, "cannot join fill.data and use.data: buffer size 64 bytes vs 128 bytes (frame 1920x1080)");
    EXPECT_EQ(error.subjects, (std::vector<std::string>{"use.data", "fill.data"}));
}

// ---- pass kinds --------------------------------------------------------------------------------

TEST(PassKinds, RolesFollowTheKind) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("render").output("color", TextureSpec::of(Format::RGBA8Unorm))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("blur").set_kind(PassKind::Compute).input("color").output("blurred")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("copy").set_kind(PassKind::Copy).input("blurred").output("copied")).ok());
    ASSERT_TRUE(graph.connect(port("render", "color"), port("blur", "color")).ok());
    ASSERT_TRUE(graph.connect(port("blur", "blurred"), port("copy", "blurred")).ok());
    ASSERT_TRUE(graph.mark_output(port("copy", "copied")).ok());
    const Plan plan = must_plan(graph);
    EXPECT_EQ(plan.order[0].ports[0].usage, TextureUsage::ColorAttachment);
    EXPECT_EQ(plan.order[1].ports[0].usage, TextureUsage::Sampled);
    EXPECT_EQ(plan.order[1].ports[1].usage, TextureUsage::Storage);
    EXPECT_EQ(plan.order[2].ports[0].usage, TextureUsage::CopySrc);
    EXPECT_EQ(plan.order[2].ports[1].usage, TextureUsage::CopyDst);
    EXPECT_EQ(plan.resources[1].spec.usage, TextureUsage::Storage | TextureUsage::CopySrc);
    EXPECT_EQ(plan.resources[2].spec.usage, TextureUsage::CopyDst | TextureUsage::CopySrc);  // a graph output

    auto schedule = build_execution_schedule(plan, {}, {});
    ASSERT_TRUE(schedule.ok()) << schedule.error().to_string();
    const TextureSlot color{TextureSlot::Kind::Plan, plan.resources[0].texture};
    const TextureSlot blurred{TextureSlot::Kind::Plan, plan.resources[1].texture};
    const TextureSlot copied{TextureSlot::Kind::Plan, plan.resources[2].texture};
    const rhi::TextureRange whole{};  // each port uses its texture's one mip and layer
    EXPECT_EQ(schedule->passes[1].before, (std::vector<Transition>{{color, ResourceState::ShaderRead, whole},
                                                                   {blurred, ResourceState::Storage, whole}}));
    EXPECT_EQ(schedule->passes[2].before, (std::vector<Transition>{{blurred, ResourceState::CopySrc, whole},
                                                                   {copied, ResourceState::CopyDst, whole}}));
}

TEST(PassKinds, BufferTransitionsFollowEachPortsRole) {
    FrameGraph graph;
    const BufferSpec spec = BufferSpec::of_size(256);
    ASSERT_TRUE(graph.add_pass(Pass("fill").set_kind(PassKind::Compute).buffer_output("data", spec)).ok());
    ASSERT_TRUE(graph.add_pass(Pass("refine").set_kind(PassKind::Compute).buffer_inout("data")).ok());
    ASSERT_TRUE(graph.add_pass(Pass("draw")
                                   .buffer_input("vertices", BufferSpec{}.with_usage(BufferUsage::Vertex))
                                   .buffer_input("args", BufferSpec{}.with_usage(BufferUsage::Indirect))
                                   .buffer_input("params", BufferSpec{}.with_usage(BufferUsage::Uniform))
                                   .output("color"))
                    .ok());
    ASSERT_TRUE(graph.add_pass(Pass("save").set_kind(PassKind::Copy).buffer_input("data").buffer_output("copy", spec)).ok());
    ASSERT_TRUE(graph.connect(port("fill", "data"), port("refine", "data")).ok());
    for (const char* input : {"vertices", "args", "params"}) {
        ASSERT_TRUE(graph.connect(port("refine", "data"), port("draw", input)).ok());
    }
    ASSERT_TRUE(graph.connect(port("refine", "data"), port("save", "data")).ok());
    ASSERT_TRUE(graph.mark_output(port("draw", "color")).ok());
    ASSERT_TRUE(graph.mark_output(port("save", "copy")).ok());
    const Plan plan = must_plan(graph);
    EXPECT_EQ(plan.resources[0].buffer_spec.usage, BufferUsage::Storage | BufferUsage::Vertex | BufferUsage::Indirect |
                                                       BufferUsage::Uniform | BufferUsage::CopySrc);

    auto schedule = build_execution_schedule(plan, {}, {});
    ASSERT_TRUE(schedule.ok()) << schedule.error().to_string();
    const BufferSlot data{BufferSlot::Kind::Plan, plan.resources[0].buffer};
    const BufferSlot copy{BufferSlot::Kind::Plan, plan.buffer_of("save", "copy").value()};
    // Storage before both compute passes: the second is a write-after-write the backends order.
    EXPECT_EQ(schedule->passes[0].buffers_before, (std::vector<BufferTransition>{{data, ResourceState::Storage}}));
    EXPECT_EQ(schedule->passes[1].buffers_before, (std::vector<BufferTransition>{{data, ResourceState::Storage}}));
    EXPECT_EQ(schedule->passes[2].buffers_before,
              (std::vector<BufferTransition>{{data, ResourceState::VertexBuffer},
                                             {data, ResourceState::IndirectArgument},
                                             {data, ResourceState::ShaderRead}}));
    EXPECT_EQ(schedule->passes[3].buffers_before,
              (std::vector<BufferTransition>{{data, ResourceState::CopySrc}, {copy, ResourceState::CopyDst}}));
    EXPECT_TRUE(schedule->passes[2].before.empty() || schedule->passes[2].before.size() == 0u);
}

// ---- subresource ranges ------------------------------------------------------------------------

// A down-sampling pyramid: "base" renders mip 0, then down_k reads mip k-1 and writes mip k of
// the same texture in place.
FrameGraph pyramid_graph(uint32_t levels) {
    FrameGraph graph;
    const TextureSpec spec = TextureSpec::of(Format::RGBA16Float).with_size(64, 64).with_mips(levels);
    EXPECT_TRUE(graph.add_pass(Pass("base").output("pyramid", spec, mip(0))).ok());
    std::string previous = "base";
    for (uint32_t k = 1; k < levels; ++k) {
        const std::string name = "down" + std::to_string(k);
        EXPECT_TRUE(graph.add_pass(Pass(name).set_kind(PassKind::Compute).input("src", {}, mip(k - 1)).inout("pyramid", {}, mip(k)))
                        .ok());
        EXPECT_TRUE(graph.connect(port(previous, "pyramid"), port(name, "src")).ok());
        EXPECT_TRUE(graph.connect(port(previous, "pyramid"), port(name, "pyramid")).ok());
        previous = name;
    }
    EXPECT_TRUE(graph.add_pass(Pass("bloom").input("pyramid").output("color")).ok());
    EXPECT_TRUE(graph.connect(port(previous, "pyramid"), port("bloom", "pyramid")).ok());
    EXPECT_TRUE(graph.mark_output(port("bloom", "color")).ok());
    return graph;
}

TEST(Subresources, ReadingMipKMinusOneWhileWritingMipKIsNeitherACycleNorAHazard) {
    const Plan plan = must_plan(pyramid_graph(4));
    EXPECT_EQ(plan.order.size(), 5u);
    ASSERT_EQ(plan.resources.size(), 2u);
    const PlanResource& pyramid = plan.resources[0];
    EXPECT_EQ(pyramid.spec.mips, 4u);
    EXPECT_EQ(pyramid.lifetime, (Lifetime{0, 4}));
    EXPECT_EQ(pyramid.spec.usage, TextureUsage::ColorAttachment | TextureUsage::Sampled | TextureUsage::Storage);
    EXPECT_EQ(plan.order[2].ports[0].range, mip_of_layer(1, 0));  // down2 reads mip 1 (of the one layer)
    EXPECT_EQ(plan.order[2].ports[1].range, mip_of_layer(2, 0));
    EXPECT_EQ(plan.order[4].ports[0].range, (SubresourceRange{0, 4, 0, 1}));  // bloom reads them all

    auto schedule = build_execution_schedule(plan, {}, {});
    ASSERT_TRUE(schedule.ok()) << schedule.error().to_string();
    const TextureSlot t{TextureSlot::Kind::Plan, pyramid.texture};
    EXPECT_EQ(schedule->passes[2].before, (std::vector<Transition>{{t, ResourceState::ShaderRead, mip_of_layer(1, 0)},
                                                                   {t, ResourceState::Storage, mip_of_layer(2, 0)}}));
    // bloom reads every mip: the whole texture moves.
    EXPECT_EQ(schedule->passes[4].before, (std::vector<Transition>{{t, ResourceState::ShaderRead, {}}}));
    // The first write clears; the in-place writes load (their mip's earlier contents are the
    // texture's, undefined until written).
    EXPECT_EQ(schedule->passes[0].ports[0].load, rhi::LoadOp::Clear);
    EXPECT_EQ(schedule->passes[2].ports[1].load, rhi::LoadOp::Load);
}

TEST(Subresources, OverlappingRangesInOnePassAreStillAnError) {
    FrameGraph graph;
    const TextureSpec spec = TextureSpec::of(Format::RGBA8Unorm).with_size(16, 16).with_mips(3);
    ASSERT_TRUE(graph.add_pass(Pass("base").output("t", spec)).ok());
    ASSERT_TRUE(graph.add_pass(Pass("bad").input("src", {}, mips(0, 2)).inout("t", {}, mip(1))).ok());
    ASSERT_TRUE(graph.connect(port("base", "t"), port("bad", "src")).ok());
    ASSERT_TRUE(graph.connect(port("base", "t"), port("bad", "t")).ok());
    ASSERT_TRUE(graph.mark_output(port("bad", "t")).ok());
    const Status status = graph.validate();
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().message,
              "pass 'bad' reads base.t through bad.src while modifying it in place through bad.t (one pass may read and "
              "modify one resource only in disjoint ranges)");
}

TEST(Subresources, RangesBeyondTheTextureAreNamed) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("base").output("t", TextureSpec::of(Format::RGBA8Unorm).with_mips(2))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("read").input("t", {}, mip(2)).output("color")).ok());
    ASSERT_TRUE(graph.connect(port("base", "t"), port("read", "t")).ok());
    ASSERT_TRUE(graph.mark_output(port("read", "color")).ok());
    const Error error = must_fail(graph);
    EXPECT_EQ(error.message, "port read.t uses mip 2 of texture base.t, which has 2 mips and 1 layers");
    EXPECT_EQ(error.subjects, (std::vector<std::string>{"read.t"}));
}

TEST(Subresources, CascadesWrittenLayerByLayerAndSampledAsAnArray) {
    FrameGraph graph;
    const TextureSpec spec = TextureSpec::of(Format::Depth32F).with_size(256, 256).with_layers(4);
    ASSERT_TRUE(graph.add_pass(Pass("cascade0").output("shadow", spec, layer(0))).ok());
    for (uint32_t i = 1; i < 4; ++i) {
        const std::string name = "cascade" + std::to_string(i);
        ASSERT_TRUE(graph.add_pass(Pass(name).inout("shadow", {}, layer(i))).ok());
        ASSERT_TRUE(graph.connect(port("cascade" + std::to_string(i - 1), "shadow"), port(name, "shadow")).ok());
    }
    ASSERT_TRUE(graph.add_pass(Pass("light").input("shadow").output("color")).ok());
    ASSERT_TRUE(graph.connect(port("cascade3", "shadow"), port("light", "shadow")).ok());
    ASSERT_TRUE(graph.mark_output(port("light", "color")).ok());
    const Plan plan = must_plan(graph);
    ASSERT_EQ(plan.resources.size(), 2u);
    EXPECT_EQ(plan.resources[0].spec.layers, 4u);
    for (uint32_t i = 0; i < 4; ++i) EXPECT_EQ(plan.order[i].ports[0].range, mip_of_layer(0, i)) << i;
    EXPECT_EQ(plan.order[4].ports[0].range, (SubresourceRange{0, 1, 0, 4}));
    auto schedule = build_execution_schedule(plan, {}, {});
    ASSERT_TRUE(schedule.ok());
    const TextureSlot t{TextureSlot::Kind::Plan, plan.resources[0].texture};
    EXPECT_EQ(schedule->passes[4].before, (std::vector<Transition>{{t, ResourceState::DepthRead, {}}}));
}

TEST(Subresources, CubeMapsHaveSixSquareFacesWrittenOneByOne) {
    FrameGraph graph;
    const TextureSpec spec = TextureSpec::of(Format::RGBA16Float).with_size(64, 64).with_cube();
    ASSERT_TRUE(graph.add_pass(Pass("face0").output("cube", spec, layer(0))).ok());
    for (uint32_t i = 1; i < 6; ++i) {
        ASSERT_TRUE(graph.add_pass(Pass("face" + std::to_string(i)).inout("cube", {}, layer(i))).ok());
        ASSERT_TRUE(graph.connect(port("face" + std::to_string(i - 1), "cube"), port("face" + std::to_string(i), "cube")).ok());
    }
    ASSERT_TRUE(graph.add_pass(Pass("sky").input("cube").output("color")).ok());
    ASSERT_TRUE(graph.connect(port("face5", "cube"), port("sky", "cube")).ok());
    ASSERT_TRUE(graph.mark_output(port("sky", "color")).ok());
    const Plan plan = must_plan(graph);
    const ResolvedSpec& cube = plan.resources[0].spec;
    EXPECT_TRUE(cube.cube);
    EXPECT_EQ(cube.layers, 6u);
    EXPECT_EQ(to_texture_desc(cube, "sky").dimension, rhi::TextureDimension::Cube);
    EXPECT_EQ(describe_resolved(cube), "RGBA16Float 64x64 cube");
    EXPECT_EQ(plan.order[6].ports[0].range, (SubresourceRange{0, 1, 0, 6}));

    FrameGraph oblong;
    ASSERT_TRUE(oblong.add_pass(Pass("sky").output("cube", TextureSpec::of(Format::RGBA8Unorm).with_size(64, 32).with_cube())).ok());
    ASSERT_TRUE(oblong.mark_output(port("sky", "cube")).ok());
    EXPECT_EQ(must_fail(oblong).message,
              "sky.cube: a cube map has 6 square single-sampled faces, not 6 layers of 64x32 with 1 samples");
}

TEST(Subresources, DisjointByteRangesOfOneBufferInOnePass) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("fill").set_kind(PassKind::Compute).buffer_output("data", BufferSpec::of_size(1024))).ok());
    ASSERT_TRUE(graph.add_pass(Pass("scan")
                                   .set_kind(PassKind::Compute)
                                   .buffer_input("src", {}, BufferRange{0, 512})
                                   .buffer_inout("data", {}, BufferRange{512, 0}))
                    .ok());
    ASSERT_TRUE(graph.add_pass(Pass("use").buffer_input("data").output("color")).ok());
    ASSERT_TRUE(graph.connect(port("fill", "data"), port("scan", "src")).ok());
    ASSERT_TRUE(graph.connect(port("fill", "data"), port("scan", "data")).ok());
    ASSERT_TRUE(graph.connect(port("scan", "data"), port("use", "data")).ok());
    ASSERT_TRUE(graph.mark_output(port("use", "color")).ok());
    const Plan plan = must_plan(graph);
    EXPECT_EQ(plan.order[1].ports[0].bytes, (BufferRange{0, 512}));
    EXPECT_EQ(plan.order[1].ports[1].bytes, (BufferRange{512, 512}));

    FrameGraph beyond;
    ASSERT_TRUE(beyond.add_pass(Pass("fill").set_kind(PassKind::Compute).buffer_output("data", BufferSpec::of_size(64))).ok());
    ASSERT_TRUE(beyond.add_pass(Pass("use").buffer_input("data", {}, BufferRange{32, 64}).output("color")).ok());
    ASSERT_TRUE(beyond.connect(port("fill", "data"), port("use", "data")).ok());
    ASSERT_TRUE(beyond.mark_output(port("use", "color")).ok());
    EXPECT_EQ(must_fail(beyond).message, "port use.data uses bytes 32+64 of buffer fill.data, which has 64 bytes");
}

// ---- imports -----------------------------------------------------------------------------------

TEST(BufferImports, ImportsReplaceThePlanBufferAndReachTheirFinalState) {
    PlanOptions options = declared_options();
    options.frame = {64, 48};
    const Plan plan = must_plan(light_list_graph(), options);
    const std::vector<ImportBinding> buffers{{port("cull", "lights"), ResourceState::ShaderRead}};
    auto schedule = build_execution_schedule(plan, {}, {}, buffers);
    ASSERT_TRUE(schedule.ok()) << schedule.error().to_string();
    EXPECT_EQ(schedule->buffer_needed, (std::vector<bool>{false, true}));
    const BufferSlot imported{BufferSlot::Kind::Import, 0};
    EXPECT_EQ(schedule->passes[1].ports[1].buffer, imported);
    EXPECT_EQ(schedule->passes[3].buffers_after, (std::vector<BufferTransition>{{imported, ResourceState::ShaderRead}}));

    // An imported buffer on an unconnected optional input is read as the port says.
    FrameGraph optional;
    ASSERT_TRUE(optional.add_pass(Pass("draw")
                                      .optional_buffer_input("extra", BufferSpec{}.with_usage(BufferUsage::Vertex))
                                      .output("color"))
                    .ok());
    ASSERT_TRUE(optional.mark_output(port("draw", "color")).ok());
    const Plan optional_plan = must_plan(optional);
    EXPECT_EQ(optional_plan.order[0].ports[0].buffer_usage, BufferUsage::Vertex);
    const std::vector<ImportBinding> extra{{port("draw", "extra"), ResourceState::VertexBuffer}};
    auto extra_schedule = build_execution_schedule(optional_plan, {}, {}, extra);
    ASSERT_TRUE(extra_schedule.ok()) << extra_schedule.error().to_string();
    EXPECT_EQ(extra_schedule->passes[0].buffers_before, (std::vector<BufferTransition>{{imported, ResourceState::VertexBuffer}}));

    const std::vector<ImportBinding> wrong{{port("shade", "color"), ResourceState::ShaderRead}};
    auto texture_port = build_execution_schedule(plan, {}, {}, wrong);
    ASSERT_FALSE(texture_port.ok());
    EXPECT_EQ(texture_port.error().message,
              "buffer import shade.color: a texture port takes a texture (Executor::import_texture), not a buffer");
    auto buffer_port = build_execution_schedule(plan, buffers, {});
    ASSERT_FALSE(buffer_port.ok());
    EXPECT_EQ(buffer_port.error().message,
              "import cull.lights: a buffer port takes a buffer (Executor::import_buffer), not a texture");
}

}  // namespace
}  // namespace loom::fg

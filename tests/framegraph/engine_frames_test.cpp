// The three engine frames of samples/plan/graphs (GTA V, DOOM 2016, Unreal's deferred renderer)
// planned at 1920x1080 with every allocator: the figures each reaches are pinned, and the heap
// allocator must reach the lower bound on all three. DOOM and Unreal run passes on async
// compute: their semaphores are pinned too, and the paper's allocator refuses them.
//
// Sizes are the DefaultMemoryModel's: textures in 64 KiB pages, buffers in 256-byte steps. A
// 1920x1080 RGBA8 (or RG16, RGB10A2, R11G11B10, D24S8) target is 127 pages, 8323072 bytes; an
// RGBA16F or D32FS8 one 254 pages, 16646144 bytes.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "loom/framegraph/framegraph.hpp"

namespace loom::fg {
namespace {

constexpr uint64_t kTarget8 = 8323072;    // 1920x1080 at 4 bytes a texel
constexpr uint64_t kTarget16 = 16646144;  // 1920x1080 at 8 bytes a texel

struct Frame {
    GraphFile file;
    Result<Plan> paper = Plan{};
    Plan interval;
    Plan heap;
};

Result<Plan> try_plan(const GraphFile& file, AllocatorKind allocator) {
    PlanOptions options;
    options.frame = file.frame;
    options.allocator = allocator;
    // In declared order, as the engines run them (the memory order's figures are pinned in
    // pass_order_test.cpp).
    options.order = PassOrder::Declared;
    return build_plan(file.graph, options);
}

Plan plan_with(const GraphFile& file, AllocatorKind allocator) {
    auto plan = try_plan(file, allocator);
    EXPECT_TRUE(plan.ok()) << file.source << " " << allocator_name(allocator) << ": " << plan.error().to_string();
    return plan.ok() ? std::move(*plan) : Plan{};
}

Frame load_frame(const std::string& name) {
    auto file = load_graph_file(std::string(LOOM_SAMPLE_GRAPHS) + "/" + name);
    EXPECT_TRUE(file.ok()) << file.error().to_string();
    if (!file.ok()) return {};
    Frame frame{std::move(*file), Plan{}, {}, {}};
    frame.paper = try_plan(frame.file, AllocatorKind::Paper);
    frame.interval = plan_with(frame.file, AllocatorKind::Interval);
    frame.heap = plan_with(frame.file, AllocatorKind::Heap);
    return frame;
}

// The paper's colouring cannot keep apart the resources of passes running at once on two
// queues; it names the first async pass.
void expect_paper_refuses(const Frame& frame, std::string_view first_async_pass) {
    ASSERT_FALSE(frame.paper.ok());
    EXPECT_EQ(frame.paper.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(frame.paper.error().message.find("async compute pass '" + std::string(first_async_pass) + "'"),
              std::string::npos)
        << frame.paper.error().message;
}

// What every allocator must agree on, and what each reaches.
struct Figures {
    std::size_t passes = 0;
    PlanSummary pooled;        // interval (and paper): one texture per spec class and live member
    uint64_t heap_bytes = 0;   // one heap
};

void expect_figures(const Frame& frame, const Figures& want) {
    EXPECT_EQ(frame.file.frame, (Extent2D{1920, 1080}));
    std::vector<const Plan*> plans{&frame.interval, &frame.heap};
    if (frame.paper.ok()) plans.push_back(&*frame.paper);
    for (const Plan* plan : plans) {
        EXPECT_EQ(plan->order.size(), want.passes) << plan->allocator;
        EXPECT_TRUE(plan->culled.empty()) << plan->allocator;
        // The bounds and the naive figures are the graph's, whatever the allocator.
        EXPECT_EQ(plan->summary.naive_bytes, want.pooled.naive_bytes) << plan->allocator;
        EXPECT_EQ(plan->summary.naive_textures, want.pooled.naive_textures) << plan->allocator;
        EXPECT_EQ(plan->summary.naive_buffers, want.pooled.naive_buffers) << plan->allocator;
        EXPECT_EQ(plan->summary.lower_bound_bytes, want.pooled.lower_bound_bytes) << plan->allocator;
        EXPECT_EQ(plan->summary.lower_bound_textures, want.pooled.lower_bound_textures) << plan->allocator;
        EXPECT_EQ(plan->summary.lower_bound_buffers, want.pooled.lower_bound_buffers) << plan->allocator;
        EXPECT_EQ(plan->summary.buffer_bytes, want.pooled.buffer_bytes) << plan->allocator;
    }
    if (frame.paper.ok()) {
        EXPECT_EQ(frame.paper->summary, want.pooled);
    }
    EXPECT_EQ(frame.interval.summary, want.pooled);
    // The heap places every resource on its own; it reaches the bound, in one heap.
    const PlanSummary& heap = frame.heap.summary;
    EXPECT_EQ(heap.bytes, want.heap_bytes);
    EXPECT_EQ(heap.bytes, heap.lower_bound_bytes);
    EXPECT_EQ(frame.heap.heaps, std::vector<uint64_t>{want.heap_bytes});
    EXPECT_EQ(heap.textures, want.pooled.naive_textures);
    EXPECT_EQ(heap.buffers, want.pooled.naive_buffers);
}

const PlanPass& pass(const Plan& plan, std::string_view name) {
    const PlanPass* found = plan.find_pass(name);
    EXPECT_NE(found, nullptr) << name;
    static const PlanPass kNone;
    return found != nullptr ? *found : kNone;
}

TEST(EngineFrames, Gta5) {
    const Frame frame = load_frame("gta5_frame.json");
    Figures want;
    want.passes = 51;
    want.pooled.naive_textures = 28;
    want.pooled.naive_buffers = 2;
    want.pooled.naive_bytes = 198115584;
    // Interval and paper: a texture per spec class and member alive at once; two RGBA16F HDR
    // targets (the lit image and its SSS blur, refraction copy or smoothed copy), four RGBA8
    // targets (the G-buffer colours, later the LDR chain), two half-size R8 AO targets, and one
    // of everything else.
    want.pooled.textures = 20;
    want.pooled.buffers = 2;
    want.pooled.bytes = 118489344;
    want.pooled.lower_bound_textures = 20;
    want.pooled.lower_bound_buffers = 2;
    want.pooled.buffer_bytes = 262144 + 256;
    // The peak is the sun's deferred pass: the four RGBA8 G-buffer targets, the D32FS8 depth,
    // the four 1024x1024 D32F cascades (16 MiB), the new RGBA16F HDR target, the full-size R8
    // sun shadow mask, the half-size R8 AO, the 240x120 reflection and the two 128x128 layers
    // of the paraboloid map (256 KiB each). The culling buffer died at the G-buffer pass.
    want.pooled.lower_bound_bytes = 4 * kTarget8 + kTarget16 + 16777216 + kTarget16 + 2097152 + 524288 + 262144 + 262144;
    ASSERT_EQ(want.pooled.lower_bound_bytes, 86507520u);
    want.heap_bytes = 86507520;
    expect_figures(frame, want);
    // Direct3D 11 has one queue: nothing runs on async compute, and the paper plans it too.
    EXPECT_TRUE(frame.interval.queue_syncs.empty());
    EXPECT_TRUE(frame.paper.ok());

    // The cascades are one texture of 4 layers, each drawn by its own pass; the environment
    // cube is drawn face by face; the luminance is reduced mip by mip in compute.
    const Plan& plan = frame.interval;
    const PlanResource* cascades = plan.resource_of("shadow_cascade0", "cascades");
    ASSERT_NE(cascades, nullptr);
    EXPECT_EQ(cascades->spec.layers, 4u);
    EXPECT_EQ(plan.resource_of("shadow_cascade3", "cascades"), cascades);
    EXPECT_EQ(plan.resource_of("sun_shadow_mask", "cascades"), cascades);
    EXPECT_TRUE(plan.resource_of("env_cube_nz", "env_cube")->spec.cube);
    EXPECT_EQ(pass(plan, "luminance3").kind, PassKind::Compute);
    EXPECT_EQ(pass(plan, "copy_refraction").kind, PassKind::Copy);
    EXPECT_EQ(plan.resource_of("luminance3", "luminance")->spec.mips, 4u);
}

TEST(EngineFrames, Doom2016) {
    const Frame frame = load_frame("doom2016_frame.json");
    Figures want;
    want.passes = 39;
    want.pooled.naive_textures = 20;
    want.pooled.naive_buffers = 5;
    want.pooled.naive_bytes = 437674496;
    want.pooled.textures = 16;
    want.pooled.buffers = 5;
    want.pooled.bytes = 379412992;
    want.pooled.lower_bound_textures = 16;
    want.pooled.lower_bound_buffers = 5;
    want.pooled.buffer_bytes = 24576 + 786432 + 4194304 + 256 + 256;
    // The 256 MiB shadow atlas outweighs the rest. Its last reader is the particle lighting
    // on async compute, which may run until the graphics queue next waits for that queue,
    // before the reflections pass: the atlas stays reserved over the opaque pass and SSR (it
    // would be free after the opaque pass on one queue, and the bound 17694720 bytes lower).
    // The peak is SSR: the atlas, depth, velocity, the particle lighting atlas (8 MiB), the
    // HDR, normal and specular targets of the opaque pass, SSR's RGBA16F output, the two
    // half-size R8 AO targets, the cluster grid and items, the particles and their draw
    // arguments.
    want.pooled.lower_bound_bytes = 268435456 + 3 * kTarget8 + 8388608 + kTarget16 + kTarget8 + kTarget16 +
                                    2 * 524288 + 24576 + 786432 + 4194304 + 256;
    ASSERT_EQ(want.pooled.lower_bound_bytes, 349462784u);
    want.heap_bytes = 349462784;
    expect_figures(frame, want);
    expect_paper_refuses(frame, "particle_simulate");

    const Plan& plan = frame.interval;
    // Particle simulation waits for the velocity pass (depth); the opaque pass, which draws
    // into that depth, waits for the simulation to have read it; SSAO waits for the opaque
    // pass's normals, and the reflections pass for the blurred AO (and with it for the
    // particle lighting before it on the async queue).
    const std::vector<QueueSync> syncs{{Queue::Graphics, Queue::AsyncCompute, 6, 7},
                                       {Queue::AsyncCompute, Queue::Graphics, 7, 9},
                                       {Queue::Graphics, Queue::AsyncCompute, 9, 10},
                                       {Queue::AsyncCompute, Queue::Graphics, 11, 13}};
    EXPECT_EQ(plan.queue_syncs, syncs);
    EXPECT_EQ(plan.order[7].name, "particle_simulate");
    EXPECT_EQ(plan.order[13].name, "reflections");
    const PlanResource* atlas = plan.resource_of("shadow_atlas3", "atlas");
    EXPECT_EQ(atlas->lifetime, (Lifetime{1, 9}));
    EXPECT_EQ(atlas->occupancy, (Lifetime{1, 12}));
    for (const char* async : {"particle_simulate", "particle_light", "ssao", "ssao_blur"}) {
        EXPECT_EQ(pass(plan, async).queue, Queue::AsyncCompute) << async;
    }
    EXPECT_EQ(plan.resource_of("shadow_atlas3", "atlas")->spec.layers, 4u);
    EXPECT_EQ(pass(plan, "cluster_upload").kind, PassKind::Copy);
    for (const char* compute : {"particle_simulate", "particle_light", "ssao", "ssao_blur", "luminance2", "exposure"}) {
        EXPECT_EQ(pass(plan, compute).kind, PassKind::Compute) << compute;
    }
    // Glass samples the whole blurred chain; the particles are drawn from compute-built arguments.
    EXPECT_EQ(plan.resource_of("glass", "blur_chain")->spec.mips, 5u);
    EXPECT_EQ(plan.resource_of("particles", "draw_args")->buffer_spec.usage,
              rhi::BufferUsage::Storage | rhi::BufferUsage::Indirect);
}

TEST(EngineFrames, UnrealDeferred) {
    const Frame frame = load_frame("unreal_deferred_frame.json");
    Figures want;
    want.passes = 58;
    want.pooled.naive_textures = 53;
    want.pooled.naive_buffers = 6;
    want.pooled.naive_bytes = 332742400;
    // Seven RGBA8 targets alive at once (the three DBuffer targets and GBuffer B-E at the base
    // pass), three RGBA16F ones (scene colour, translucency, the distorted colour), three
    // 120x68x64 froxel volumes, and two of each bloom level (its down-sample and its blur).
    want.pooled.textures = 36;
    want.pooled.buffers = 6;
    want.pooled.bytes = 226967296;
    want.pooled.lower_bound_textures = 36;
    want.pooled.lower_bound_buffers = 6;
    // 30x17 light grid cells of 32 slices: 8 bytes of counts and 32 16-bit light indices each.
    want.pooled.buffer_bytes = 81920 + 262144 + 30 * 17 * 32 * 8 + 30 * 17 * 32 * 32 * 2 + 4096 + 256;
    // The base pass is the peak: depth, the three DBuffer targets it reads, scene colour and
    // the five GBuffer targets it writes (GBuffer A is RGB10A2), the three D16 cascades
    // (24 MiB) and the point light's D16 cube (12 MiB) waiting for the lights, the HZB
    // (1024x1024 R16F, 10 mips), the light grid, the instance list and the draw arguments.
    // The buffers add 1519104 bytes, not a whole number of pages: the heap reaches the bound
    // only if they sit together above every page-aligned texture alive there.
    want.pooled.lower_bound_bytes = kTarget16 + 3 * kTarget8 + kTarget16 + 5 * kTarget8 + 25165824 + 12582912 +
                                    2818048 + 130560 + 1044480 + 262144 + 81920;
    ASSERT_EQ(want.pooled.lower_bound_bytes, 141962752u);
    want.heap_bytes = 141962752;
    expect_figures(frame, want);
    expect_paper_refuses(frame, "ao_half");
    // SSAO in compute on the async queue waits for its half-size setup and runs beside the
    // shadow projections, the lights, the volumetric fog and SSR until the reflection
    // environment reads it: its textures are reserved over those passes, which stay below the
    // base pass's peak, so the figures are those of a single queue.
    const std::vector<QueueSync> syncs{{Queue::Graphics, Queue::AsyncCompute, 13, 14},
                                       {Queue::AsyncCompute, Queue::Graphics, 15, 25}};
    EXPECT_EQ(frame.interval.queue_syncs, syncs);
    EXPECT_EQ(frame.interval.order[25].name, "reflection_environment");
    EXPECT_EQ(frame.interval.resource_of("ao_setup", "setup")->occupancy, (Lifetime{13, 24}));

    // The HZB is built 4 mips per dispatch into one 10-mip texture; the cascades are layers.
    const Plan& plan = frame.interval;
    const PlanResource* hzb = plan.resource_of("hzb_mips8_9", "hzb");
    ASSERT_NE(hzb, nullptr);
    EXPECT_EQ(hzb->spec.mips, 10u);
    EXPECT_EQ(hzb->spec.extent, (Extent2D{1024, 1024}));
    EXPECT_EQ(plan.resource_of("ssr", "hzb"), hzb);
    EXPECT_EQ(plan.resource_of("shadow_csm2", "csm")->spec.layers, 3u);
    EXPECT_TRUE(plan.resource_of("shadow_point_cube", "cube")->spec.cube);
    EXPECT_EQ(plan.resource_of("light_grid", "culled_light_data")->buffer_spec.size, 30u * 17 * 32 * 32 * 2);
}

}  // namespace
}  // namespace loom::fg

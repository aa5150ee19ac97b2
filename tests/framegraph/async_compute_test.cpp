// Async compute in the planner: which semaphores and queue-ownership transfers a plan emits for
// given graphs, exactly; how far async passes widen the memory occupancy of their resources;
// the errors; and, on a random corpus with async passes, that every dependency, transfer and
// shared piece of memory is ordered by the emitted semaphores.
#include <algorithm>
#include <cstdio>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "loom/framegraph/framegraph.hpp"
#include "random_graph.hpp"

namespace loom::fg {
namespace {

using rhi::Format;
constexpr Queue G = Queue::Graphics;
constexpr Queue A = Queue::AsyncCompute;

// In declared order: the tests pin positions, semaphores and occupancies of the order the
// passes are declared in (the memory order is checked against it at the end).
PlanOptions options_with(AllocatorKind allocator) {
    PlanOptions options;
    options.frame = {1920, 1080};
    options.allocator = allocator;
    options.order = PassOrder::Declared;
    return options;
}

Plan must_plan(const FrameGraph& graph, AllocatorKind allocator = AllocatorKind::Interval) {
    auto plan = build_plan(graph, options_with(allocator));
    EXPECT_TRUE(plan.ok()) << plan.error().to_string();
    return plan.ok() ? std::move(*plan) : Plan{};
}

void add(FrameGraph& graph, Pass pass) {
    auto added = graph.add_pass(std::move(pass));
    ASSERT_TRUE(added.ok()) << added.error().to_string();
}

void connect(FrameGraph& graph, const std::string& from, const std::string& to) {
    auto connected = graph.connect(*parse_port_ref(from), *parse_port_ref(to));
    ASSERT_TRUE(connected.ok()) << connected.error().to_string();
}

Pass async_pass(std::string name) {
    Pass pass(std::move(name));
    pass.set_kind(PassKind::Compute).set_queue(A);
    return pass;
}

uint32_t resource_index(const Plan& plan, const std::string& name) {
    for (uint32_t r = 0; r < plan.resources.size(); ++r) {
        if (plan.resources[r].name == name) return r;
    }
    ADD_FAILURE() << "no resource " << name;
    return 0;
}

// A depth prepass feeds SSAO on the async queue and the G-buffer pass on the graphics queue;
// shadows and the G-buffer run while SSAO does; lighting reads all three.
FrameGraph ssao_frame() {
    FrameGraph graph;
    add(graph, Pass("depth").output("depth", TextureSpec::of(Format::Depth32F)));
    add(graph, async_pass("ssao").input("depth").output("ao", TextureSpec::of(Format::R8Unorm).with_scale(0.5f)));
    add(graph, Pass("shadows").output("shadow", TextureSpec::of(Format::Depth32F).with_size(2048, 2048)));
    add(graph, Pass("gbuffer").input("depth").output("albedo", TextureSpec::of(Format::RGBA8Unorm)));
    add(graph, Pass("lighting").input("albedo").input("shadow").input("ao").output("hdr", TextureSpec::of(Format::RGBA16Float)));
    add(graph, Pass("tonemap").input("hdr").output("final", TextureSpec::of(Format::RGBA8Unorm)));
    connect(graph, "depth.depth", "ssao.depth");
    connect(graph, "depth.depth", "gbuffer.depth");
    connect(graph, "ssao.ao", "lighting.ao");
    connect(graph, "shadows.shadow", "lighting.shadow");
    connect(graph, "gbuffer.albedo", "lighting.albedo");
    connect(graph, "lighting.hdr", "tonemap.hdr");
    EXPECT_TRUE(graph.mark_output(*parse_port_ref("tonemap.final")).ok());
    return graph;
}

TEST(AsyncCompute, SsaoWaitsForDepthAndLightingWaitsForSsao) {
    const Plan plan = must_plan(ssao_frame());
    ASSERT_EQ(plan.order.size(), 6u);
    EXPECT_EQ(plan.order[1].name, "ssao");
    EXPECT_EQ(plan.order[1].queue, A);
    EXPECT_EQ(plan.order[4].name, "lighting");
    // Depth -> SSAO, SSAO -> lighting; lighting's wait also ends the async queue's frame, so
    // no wait is added at the end of the frame.
    EXPECT_EQ(plan.queue_syncs, (std::vector<QueueSync>{{G, A, 0, 1}, {A, G, 1, 4}}));
    // The AO moves from the async queue to graphics; depth is read by both queues (SSAO and
    // the G-buffer pass may run at once), so it is shared, not transferred.
    const uint32_t ao = resource_index(plan, "ssao.ao");
    EXPECT_EQ(plan.ownership_transfers, (std::vector<OwnershipTransfer>{{ao, A, G, 1, 4}}));
    EXPECT_TRUE(plan.resources[resource_index(plan, "depth.depth")].queue_shared);
    EXPECT_FALSE(plan.resources[ao].queue_shared);
    // SSAO may run from after depth (0) until lighting (4) starts: positions 1-3, which its
    // resources' lifetimes already cover.
    for (const PlanResource& r : plan.resources) EXPECT_EQ(r.occupancy, r.lifetime) << r.name;
}

// SSAO writes raw AO that a blur reads, both compute passes on `compute_queue`; graphics passes
// at positions 3 and 4 make a texture of raw AO's shape.
FrameGraph ssao_chain_frame(Queue compute_queue) {
    FrameGraph graph;
    const TextureSpec half = TextureSpec::of(Format::R16Float).with_scale(0.5f);
    add(graph, Pass("depth").output("depth", TextureSpec::of(Format::Depth32F)));
    add(graph, Pass("ssao").set_kind(PassKind::Compute).set_queue(compute_queue).input("depth").output("raw", half));
    add(graph, Pass("blur").set_kind(PassKind::Compute).set_queue(compute_queue).input("raw").output("ao", half));
    add(graph, Pass("scratch_write").output("scratch", half));
    add(graph, Pass("scratch_read").input("scratch").output("color", TextureSpec::of(Format::RGBA8Unorm)));
    add(graph, Pass("lighting").input("ao").input("color").output("hdr", TextureSpec::of(Format::RGBA16Float)));
    connect(graph, "depth.depth", "ssao.depth");
    connect(graph, "ssao.raw", "blur.raw");
    connect(graph, "blur.ao", "lighting.ao");
    connect(graph, "scratch_write.scratch", "scratch_read.scratch");
    connect(graph, "scratch_read.color", "lighting.color");
    EXPECT_TRUE(graph.mark_output(*parse_port_ref("lighting.hdr")).ok());
    return graph;
}

TEST(AsyncCompute, ATemporaryOfAnAsyncChainIsHeldWhileTheGraphicsQueueRunsBeside) {
    // On one queue raw AO (1-2) and scratch (3-4) would share a texture; with async compute
    // the blur may still run at 3 and 4, so they must not.
    const Plan plan = must_plan(ssao_chain_frame(A));
    ASSERT_EQ(plan.order[3].name, "scratch_write");
    ASSERT_EQ(plan.order[5].name, "lighting");
    EXPECT_EQ(plan.queue_syncs, (std::vector<QueueSync>{{G, A, 0, 1}, {A, G, 2, 5}}));
    const PlanResource& raw = plan.resources[resource_index(plan, "ssao.raw")];
    const PlanResource& scratch = plan.resources[resource_index(plan, "scratch_write.scratch")];
    EXPECT_EQ(raw.lifetime, (Lifetime{1, 2}));
    EXPECT_EQ(raw.occupancy, (Lifetime{1, 4}));  // until lighting, which waits for the blur, starts
    EXPECT_EQ(scratch.occupancy, (Lifetime{3, 4}));
    EXPECT_NE(raw.texture, scratch.texture);
    EXPECT_EQ(plan.summary.textures, 6u);
    EXPECT_EQ(plan.summary.lower_bound_textures, 6u);

    // The same graph on one queue: raw AO and scratch share a texture.
    const Plan one_queue = must_plan(ssao_chain_frame(G));
    EXPECT_TRUE(one_queue.queue_syncs.empty());
    EXPECT_EQ(one_queue.resources[resource_index(one_queue, "ssao.raw")].texture,
              one_queue.resources[resource_index(one_queue, "scratch_write.scratch")].texture);
    EXPECT_EQ(one_queue.summary.textures, 5u);

    // In a heap the two never overlap either.
    const Plan heap = must_plan(ssao_chain_frame(A), AllocatorKind::Heap);
    const auto& raw_at = *heap.textures[heap.resources[resource_index(heap, "ssao.raw")].texture].placement;
    const auto& scratch_at = *heap.textures[heap.resources[resource_index(heap, "scratch_write.scratch")].texture].placement;
    const uint64_t bytes = heap.resources[resource_index(heap, "ssao.raw")].bytes;
    EXPECT_TRUE(raw_at.heap != scratch_at.heap || raw_at.offset + bytes <= scratch_at.offset ||
                scratch_at.offset + bytes <= raw_at.offset);
}

TEST(AsyncCompute, AGraphOutputMadeOnTheAsyncQueueReturnsToGraphicsAtTheEndOfTheFrame) {
    // A luminance histogram built on the async queue and read back after the frame; nothing in
    // the frame waits for it, so the end of the frame does.
    FrameGraph graph;
    add(graph, Pass("scene").output("hdr", TextureSpec::of(Format::RGBA16Float)));
    add(graph, async_pass("histogram").input("hdr").buffer_output("bins", BufferSpec::of_size(1024)));
    add(graph, Pass("tonemap").input("hdr").output("final", TextureSpec::of(Format::RGBA8Unorm)));
    connect(graph, "scene.hdr", "histogram.hdr");
    connect(graph, "scene.hdr", "tonemap.hdr");
    ASSERT_TRUE(graph.mark_output(*parse_port_ref("histogram.bins")).ok());
    ASSERT_TRUE(graph.mark_output(*parse_port_ref("tonemap.final")).ok());

    const Plan plan = must_plan(graph);
    ASSERT_EQ(plan.order[1].name, "histogram");
    const auto end = static_cast<uint32_t>(plan.order.size());
    EXPECT_EQ(plan.queue_syncs, (std::vector<QueueSync>{{G, A, 0, 1}, {A, G, 1, end}}));
    const uint32_t bins = resource_index(plan, "histogram.bins");
    EXPECT_EQ(plan.ownership_transfers, (std::vector<OwnershipTransfer>{{bins, A, G, 1, end}}));
    // The histogram may run until the frame ends: its HDR input is held to the end too.
    EXPECT_EQ(plan.resources[resource_index(plan, "scene.hdr")].occupancy, (Lifetime{0, 2}));
    EXPECT_TRUE(plan.resources[resource_index(plan, "scene.hdr")].queue_shared);

    const std::string table = plan_to_table(plan);
    EXPECT_NE(table.find("queue syncs\n"
                         "  signal         after        wait           before\n"
                         "  graphics       0 scene      async_compute  1 histogram\n"
                         "  async_compute  1 histogram  graphics       frame end\n"),
              std::string::npos)
        << table;
    EXPECT_NE(table.find("  histogram.bins  async_compute  1 histogram    graphics  frame end\n"), std::string::npos)
        << table;
    EXPECT_NE(table.find("  1  histogram [compute, async]"), std::string::npos) << table;
}

TEST(AsyncCompute, ImportedContentsReadFirstOnTheAsyncQueueComeFromGraphicsAtTheStartOfTheFrame) {
    // An async pass modifies in place a buffer nothing in the frame produced (an unconnected
    // optional inout: imported contents, e.g. particle state from the last frame).
    FrameGraph graph;
    add(graph, async_pass("simulate").declare_buffer("particles", PortKind::InOut, BufferSpec::of_size(4096), true));
    add(graph, Pass("draw").buffer_input("particles", BufferSpec{}.with_usage(rhi::BufferUsage::Vertex))
                   .output("color", TextureSpec::of(Format::RGBA8Unorm)));
    connect(graph, "simulate.particles", "draw.particles");
    ASSERT_TRUE(graph.mark_output(*parse_port_ref("draw.color")).ok());

    const Plan plan = must_plan(graph);
    ASSERT_EQ(plan.order[0].name, "simulate");
    EXPECT_EQ(plan.queue_syncs, (std::vector<QueueSync>{{G, A, kFrameStart, 0}, {A, G, 0, 1}}));
    const uint32_t particles = resource_index(plan, "simulate.particles");
    EXPECT_EQ(plan.ownership_transfers,
              (std::vector<OwnershipTransfer>{{particles, G, A, kFrameStart, 0}, {particles, A, G, 0, 1}}));
}

TEST(AsyncCompute, AWaitAlreadyCoveredByAnEarlierOneIsLeftOut) {
    // Two async passes read what graphics pass 0 made; only the first waits for it. A third
    // reads what graphics made later and waits again.
    FrameGraph graph;
    add(graph, Pass("g0").output("a", TextureSpec::of(Format::RGBA8Unorm)).output("b", TextureSpec::of(Format::RGBA8Unorm)));
    add(graph, async_pass("c1").input("a").output("x", TextureSpec::of(Format::R32Float)));
    add(graph, Pass("g2").input("b").output("c", TextureSpec::of(Format::RGBA8Unorm)));
    add(graph, async_pass("c3").input("b").input("x").output("y", TextureSpec::of(Format::R32Float)));
    add(graph, async_pass("c4").input("c").input("y").output("z", TextureSpec::of(Format::R32Float)));
    add(graph, Pass("g5").input("z").output("final", TextureSpec::of(Format::RGBA8Unorm)));
    connect(graph, "g0.a", "c1.a");
    connect(graph, "g0.b", "g2.b");
    connect(graph, "g0.b", "c3.b");
    connect(graph, "c1.x", "c3.x");
    connect(graph, "g2.c", "c4.c");
    connect(graph, "c3.y", "c4.y");
    connect(graph, "c4.z", "g5.z");
    ASSERT_TRUE(graph.mark_output(*parse_port_ref("g5.final")).ok());

    const Plan plan = must_plan(graph);
    std::vector<std::string> names;
    for (const PlanPass& pass : plan.order) names.push_back(pass.name);
    ASSERT_EQ(names, (std::vector<std::string>{"g0", "c1", "g2", "c3", "c4", "g5"}));
    // c3 needs g0 (covered by c1's wait); c4 needs g2.
    EXPECT_EQ(plan.queue_syncs, (std::vector<QueueSync>{{G, A, 0, 1}, {G, A, 2, 4}, {A, G, 4, 5}}));
    // g0.b is read by g2 and c3: shared. Nothing else moves but c4.z (async -> graphics) and
    // g2.c (graphics -> async).
    EXPECT_TRUE(plan.resources[resource_index(plan, "g0.b")].queue_shared);
    EXPECT_EQ(plan.ownership_transfers,
              (std::vector<OwnershipTransfer>{{resource_index(plan, "g0.a"), G, A, 0, 1},
                                              {resource_index(plan, "g2.c"), G, A, 2, 4},
                                              {resource_index(plan, "c4.z"), A, G, 4, 5}}));
}

TEST(AsyncCompute, AGraphicsPassModifyingWhatAnAsyncPassReadsWaitsForIt) {
    // The async pass reads the colour before the graphics pass draws over it in place.
    FrameGraph graph;
    add(graph, Pass("scene").output("color", TextureSpec::of(Format::RGBA8Unorm)));
    add(graph, async_pass("analyse").input("color").buffer_output("stats", BufferSpec::of_size(256)));
    add(graph, Pass("overlay").inout("color").buffer_input("stats", BufferSpec{}.with_usage(rhi::BufferUsage::Uniform)));
    connect(graph, "scene.color", "analyse.color");
    connect(graph, "scene.color", "overlay.color");
    connect(graph, "analyse.stats", "overlay.stats");
    ASSERT_TRUE(graph.mark_output(*parse_port_ref("overlay.color")).ok());

    const Plan plan = must_plan(graph);
    EXPECT_EQ(plan.queue_syncs, (std::vector<QueueSync>{{G, A, 0, 1}, {A, G, 1, 2}}));
    EXPECT_TRUE(plan.resources[resource_index(plan, "scene.color")].queue_shared);
}

TEST(AsyncCompute, PlansWithoutAsyncPassesHaveNoSyncs) {
    FrameGraph graph;
    add(graph, Pass("a").set_kind(PassKind::Compute).output("x", TextureSpec::of(Format::RGBA8Unorm)));
    add(graph, Pass("b").input("x").output("y", TextureSpec::of(Format::RGBA8Unorm)));
    connect(graph, "a.x", "b.x");
    ASSERT_TRUE(graph.mark_output(*parse_port_ref("b.y")).ok());
    for (AllocatorKind allocator : allocator_kinds()) {
        const Plan plan = must_plan(graph, allocator);
        EXPECT_TRUE(plan.queue_syncs.empty());
        EXPECT_TRUE(plan.ownership_transfers.empty());
        for (const PlanResource& r : plan.resources) {
            EXPECT_EQ(r.occupancy, r.lifetime);
            EXPECT_FALSE(r.queue_shared);
        }
    }
}

TEST(AsyncCompute, OnlyComputeAndCopyPassesRunOnTheAsyncQueue) {
    FrameGraph graph;
    Pass draw("draw");
    draw.set_queue(A).output("color", TextureSpec::of(Format::RGBA8Unorm));
    add(graph, std::move(draw));
    ASSERT_TRUE(graph.mark_output(*parse_port_ref("draw.color")).ok());
    auto plan = build_plan(graph, options_with(AllocatorKind::Interval));
    ASSERT_FALSE(plan.ok());
    EXPECT_EQ(plan.error().code, ErrorCode::Graph);
    EXPECT_NE(plan.error().message.find("pass 'draw' is a graphics pass: only compute and copy passes run on the async "
                                        "compute queue"),
              std::string::npos)
        << plan.error().message;
}

TEST(AsyncCompute, ThePaperAllocatorRefusesAsyncPlans) {
    auto plan = build_plan(ssao_frame(), options_with(AllocatorKind::Paper));
    ASSERT_FALSE(plan.ok());
    EXPECT_EQ(plan.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(plan.error().message.find("async compute pass 'ssao'): use 'interval' or 'heap'"), std::string::npos)
        << plan.error().message;
}

TEST(AsyncCompute, GraphFilesNameTheQueue) {
    auto file = parse_graph_json(R"({"description": "two queues",
        "passes": [{"name": "a", "kind": "compute", "queue": "async_compute", "outputs": [{"name": "x", "format": "R32F"}]},
                   {"name": "b", "queue": "graphics", "inputs": [{"name": "x"}], "outputs": [{"name": "y", "format": "RGBA8"}]}],
        "connections": [["a.x", "b.x"]], "outputs": ["b.y"]})");
    ASSERT_TRUE(file.ok()) << file.error().to_string();
    EXPECT_EQ(file->graph.pass(PassId{0}).queue(), A);
    EXPECT_EQ(file->graph.pass(PassId{1}).queue(), G);
    auto bad = parse_graph_json(R"({"passes": [{"name": "a", "queue": "compute", "outputs": [{"name": "x"}]}]})");
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.error().message.find("/passes/0/queue"), std::string::npos) << bad.error().message;
    EXPECT_NE(bad.error().message.find("must be one of graphics, async_compute"), std::string::npos)
        << bad.error().message;
    auto description = parse_graph_json(R"({"description": 3, "passes": []})");
    ASSERT_FALSE(description.ok());
    EXPECT_NE(description.error().message.find("/description"), std::string::npos) << description.error().message;
}

TEST(AsyncCompute, JsonExportListsSyncsTransfersAndOccupancy) {
    const Plan plan = must_plan(ssao_frame());
    const std::string json = plan_to_json(plan, -1);
    EXPECT_NE(json.find(R"("queue_syncs":[{"from":"graphics","signal_after":0,"signal_pass":"depth","to":"async_compute","wait_before":1,"wait_pass":"ssao"})"),
              std::string::npos)
        << json;
    EXPECT_NE(json.find(R"("ownership_transfers":[{"acquire_before":4,"acquire_pass":"lighting","from":"async_compute","release_after":1,"release_pass":"ssao","resource":1,"resource_name":"ssao.ao","to":"graphics"}])"),
              std::string::npos)
        << json;
    EXPECT_NE(json.find(R"("name":"ssao","ports")"), std::string::npos) << json;
    EXPECT_NE(json.find(R"("queue":"async_compute")"), std::string::npos) << json;
    EXPECT_NE(json.find(R"("occupancy":[0,3],"ports":["depth.depth","ssao.depth","gbuffer.depth"],"queue_shared":true)"),
              std::string::npos)
        << json;
    // The hash covers the syncs.
    Plan changed = plan;
    changed.queue_syncs[1].wait_before = 3;
    EXPECT_NE(plan_hash(plan), plan_hash(changed));
}

// ---- the random corpus with async passes --------------------------------------------------------

// Where a use happens: a position in the order (-1 the start of the frame, the order's length
// its end, both on the graphics queue) and its queue.
struct At {
    int64_t position = 0;
    Queue queue = G;
};

// Vulkan's rule: on one queue, submission order (with the barriers the executor records); across
// queues, a semaphore signalled after `a` (or later) on a's queue and waited before `b` (or
// earlier) on b's.
bool happens_before(const Plan& plan, At a, At b) {
    if (a.queue == b.queue) return a.position < b.position;
    for (const QueueSync& sync : plan.queue_syncs) {
        const int64_t signal = sync.signal_after == kFrameStart ? -1 : int64_t{sync.signal_after};
        if (sync.from == a.queue && sync.to == b.queue && signal >= a.position && sync.wait_before <= b.position) {
            return true;
        }
    }
    return false;
}

std::vector<At> uses_of(const Plan& plan, uint32_t resource) {
    std::vector<At> uses;
    for (uint32_t at = 0; at < plan.order.size(); ++at) {
        for (const PlanPort& port : plan.order[at].ports) {
            if (port.resource == resource) uses.push_back(At{at, plan.order[at].queue});
        }
    }
    return uses;
}

// Resources sharing memory (one texture or buffer, or overlapping heap bytes) never run at once.
void expect_memory_reuse_ordered(const Plan& plan, uint64_t seed) {
    auto same_memory = [&](const PlanResource& a, const PlanResource& b) {
        if (a.type != b.type && plan.heaps.empty()) return false;
        if (plan.heaps.empty()) return a.type == ResourceType::Buffer ? a.buffer == b.buffer : a.texture == b.texture;
        auto place = [&](const PlanResource& r) {
            return r.type == ResourceType::Buffer ? *plan.buffers[r.buffer].placement : *plan.textures[r.texture].placement;
        };
        const HeapRange pa = place(a);
        const HeapRange pb = place(b);
        return pa.heap == pb.heap && pa.offset < pb.offset + b.bytes && pb.offset < pa.offset + a.bytes;
    };
    for (uint32_t a = 0; a < plan.resources.size(); ++a) {
        for (uint32_t b = a + 1; b < plan.resources.size(); ++b) {
            if (!same_memory(plan.resources[a], plan.resources[b])) continue;
            const bool a_first = plan.resources[a].occupancy.last < plan.resources[b].occupancy.first;
            ASSERT_TRUE(a_first || plan.resources[b].occupancy.last < plan.resources[a].occupancy.first)
                << "seed " << seed << " " << plan.allocator << ": " << plan.resources[a].name << " and "
                << plan.resources[b].name << " share memory while held at once";
            const std::vector<At> earlier = uses_of(plan, a_first ? a : b);
            const std::vector<At> later = uses_of(plan, a_first ? b : a);
            for (const At& u : earlier) {
                for (const At& v : later) {
                    ASSERT_TRUE(happens_before(plan, u, v))
                        << "seed " << seed << " " << plan.allocator << ": " << plan.resources[a].name << " and "
                        << plan.resources[b].name << " share memory, uses at " << u.position << " and " << v.position;
                }
            }
        }
    }
}

void expect_dependencies_and_transfers_ordered(const Plan& plan, uint64_t seed) {
    for (const PlanEdge& e : plan.edges) {
        ASSERT_TRUE(happens_before(plan, At{e.from_pass, plan.order[e.from_pass].queue}, At{e.to_pass, plan.order[e.to_pass].queue}))
            << "seed " << seed << ": " << plan.order[e.from_pass].name << " -> " << plan.order[e.to_pass].name;
    }
    const auto end = static_cast<int64_t>(plan.order.size());
    for (const OwnershipTransfer& t : plan.ownership_transfers) {
        EXPECT_NE(t.from, t.to);
        EXPECT_FALSE(plan.resources[t.resource].queue_shared);
        const int64_t release = t.release_after == kFrameStart ? -1 : int64_t{t.release_after};
        ASSERT_TRUE(happens_before(plan, At{release, t.from}, At{t.acquire_before, t.to}))
            << "seed " << seed << ": transfer of " << plan.resources[t.resource].name;
    }
    for (uint32_t at = 0; at < plan.order.size(); ++at) {
        if (plan.order[at].queue != A) continue;
        ASSERT_TRUE(happens_before(plan, At{-1, G}, At{at, A})) << "seed " << seed;
        ASSERT_TRUE(happens_before(plan, At{at, A}, At{end, G})) << "seed " << seed;
    }
    // No wait is covered by an earlier one on its queue: signals grow wait after wait.
    int64_t last_signal[2] = {-2, -2};
    for (const QueueSync& sync : plan.queue_syncs) {
        const int64_t signal = sync.signal_after == kFrameStart ? -1 : int64_t{sync.signal_after};
        int64_t& last = last_signal[sync.to == G ? 0 : 1];
        EXPECT_GT(signal, last) << "seed " << seed;
        last = signal;
    }
}

testing::RandomGraphOptions async_options(uint64_t seed) {
    testing::RandomGraphOptions options;
    options.passes = 2 + static_cast<uint32_t>(seed % 39);
    options.window = 2 + static_cast<uint32_t>(seed % 7);
    options.async_percent = 30;
    options.buffer_percent = seed % 2 == 0 ? 25 : 0;
    options.subresource_percent = seed % 3 == 0 ? 20 : 0;
    return options;
}

TEST(AsyncComputeRandomGraphs, EverySharedPieceOfMemoryDependencyAndTransferIsOrderedBySemaphores) {
    uint32_t with_syncs = 0;
    uint32_t with_transfers = 0;
    uint32_t widened = 0;
    for (uint64_t seed = 1; seed <= 400; ++seed) {
        const FrameGraph graph = testing::random_graph(seed, async_options(seed));
        for (AllocatorKind allocator : {AllocatorKind::Interval, AllocatorKind::Heap}) {
            auto plan = build_plan(graph, options_with(allocator));
            ASSERT_TRUE(plan.ok()) << "seed " << seed << ": " << plan.error().to_string();
            expect_memory_reuse_ordered(*plan, seed);
            expect_dependencies_and_transfers_ordered(*plan, seed);
            EXPECT_GE(plan->summary.bytes, plan->summary.lower_bound_bytes) << "seed " << seed;
            if (allocator == AllocatorKind::Interval) {
                EXPECT_EQ(plan->summary.textures, plan->summary.lower_bound_textures) << "seed " << seed;
                with_syncs += plan->queue_syncs.empty() ? 0 : 1;
                with_transfers += plan->ownership_transfers.empty() ? 0 : 1;
                for (const PlanResource& r : plan->resources) widened += r.occupancy != r.lifetime ? 1 : 0;
            }
        }
    }
    // The corpus exercises what it checks.
    EXPECT_GT(with_syncs, 300u);
    EXPECT_GT(with_transfers, 200u);
    EXPECT_GT(widened, 200u);
}

// The memory order moves passes of both queues: its plans keep every rule above, and hold at their
// peak no more bytes than the declared order's.
TEST(AsyncComputeRandomGraphs, MemoryOrderKeepsTheSemaphoreRulesAndNeverHoldsMore) {
    uint32_t reordered = 0;
    uint32_t lower = 0;
    for (uint64_t seed = 1; seed <= 400; ++seed) {
        const FrameGraph graph = testing::random_graph(seed, async_options(seed));
        for (AllocatorKind allocator : {AllocatorKind::Interval, AllocatorKind::Heap}) {
            PlanOptions options = options_with(allocator);
            const Plan declared = must_plan(graph, allocator);
            options.order = PassOrder::Memory;
            auto plan = build_plan(graph, options);
            ASSERT_TRUE(plan.ok()) << "seed " << seed << ": " << plan.error().to_string();
            expect_memory_reuse_ordered(*plan, seed);
            expect_dependencies_and_transfers_ordered(*plan, seed);
            ASSERT_LE(plan->summary.lower_bound_bytes, declared.summary.lower_bound_bytes) << "seed " << seed;
            if (allocator == AllocatorKind::Heap) {
                reordered += plan->order != declared.order ? 1 : 0;
                lower += plan->summary.lower_bound_bytes < declared.summary.lower_bound_bytes ? 1 : 0;
            }
        }
    }
    EXPECT_GT(reordered, 100u);
    EXPECT_GT(lower, 100u);
    std::printf("memory order with async compute: %u of 400 plans reordered, %u hold fewer bytes at their peak\n",
                reordered, lower);
}

}  // namespace
}  // namespace loom::fg

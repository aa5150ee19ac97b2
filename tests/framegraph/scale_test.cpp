// Exact plans of large graphs: a pass with 10,000 ports, 10,000 outputs feeding 10,000
// inputs, 2,000 resources alive at once under a heap budget, a 10,000-pass chain streamed as
// JSON. The shapes of tests/bench/scale_graph.py, small enough to plan in a test.
#include <gtest/gtest.h>

#include <set>
#include <sstream>
#include <string>

#include "loom/framegraph/framegraph.hpp"

namespace loom::fg {
namespace {

using rhi::Format;

TextureSpec small_texture() { return TextureSpec::of(Format::RGBA8Unorm).with_size(16, 16); }

PlanOptions options_for(AllocatorKind allocator, uint64_t max_heap_bytes = 0) {
    PlanOptions options;
    options.frame = {64, 64};
    options.allocator = allocator;
    options.max_heap_bytes = max_heap_bytes;
    return options;
}

// Appended rather than `prefix + std::to_string(i)`, which GCC 12 at -O3 warns about falsely
// (-Wrestrict, GCC bug 105651).
std::string numbered(const char* prefix, uint32_t i) {
    std::string name(prefix);
    name += std::to_string(i);
    return name;
}

TEST(Scale, PassWithTenThousandPortsMergesAndPlansEveryPort) {
    constexpr uint32_t kPorts = 10000;
    PortSet extra("extra");
    extra.output("o5", small_texture()).output("o9999");  // merge into ports declared by the pass
    Pass wide("wide");
    for (uint32_t i = 0; i < kPorts; ++i) wide.output(numbered("o", i), small_texture());
    wide.add(extra);
    ASSERT_TRUE(wide.status().ok());
    ASSERT_EQ(wide.ports().size(), kPorts);
    EXPECT_EQ(wide.port_index("o9999"), 9999u);
    EXPECT_EQ(wide.port_index("o10000"), std::nullopt);
    EXPECT_EQ(wide.ports()[5].port_sets, (std::vector<std::string>{"wide", "extra"}));

    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(std::move(wide)).ok());
    for (uint32_t i = 0; i < kPorts; ++i) ASSERT_TRUE(graph.mark_output(port("wide", numbered("o", i))).ok());
    ASSERT_TRUE(graph.mark_output(port("wide", "o7")).ok());  // marking twice lists it once
    EXPECT_EQ(graph.outputs().size(), kPorts);

    auto plan = build_plan(graph, options_for(AllocatorKind::Interval));
    ASSERT_TRUE(plan.ok()) << plan.error().to_string();
    EXPECT_EQ(plan->resources.size(), kPorts);
    EXPECT_EQ(plan->summary.textures, kPorts);  // all live to the end of the frame
    EXPECT_EQ(plan->resources[9999].name, "wide.o9999");
    EXPECT_EQ(plan->order.at(0).ports.at(9999).resource, 9999u);
}

TEST(Scale, FiveThousandResourcesOfFiftyShapesFormFiftyClasses) {
    constexpr uint32_t kPorts = 5000;
    Pass wide("wide");
    for (uint32_t i = 0; i < kPorts; ++i) {
        wide.output(numbered("o", i), TextureSpec::of(Format::RGBA8Unorm).with_size(1 + i % 50, 1));
    }
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(std::move(wide)).ok());
    for (uint32_t i = 0; i < kPorts; ++i) ASSERT_TRUE(graph.mark_output(port("wide", numbered("o", i))).ok());
    auto plan = build_plan(graph, options_for(AllocatorKind::Interval));
    ASSERT_TRUE(plan.ok()) << plan.error().to_string();
    ASSERT_EQ(plan->spec_classes.size(), 50u);
    EXPECT_EQ(plan->resources[1234].spec_class, 34u);
    EXPECT_EQ(plan->spec_classes[34].spec.extent.width, 35u);
    EXPECT_EQ(plan->spec_classes[34].resources.size(), 100u);
    EXPECT_EQ(plan->spec_classes[34].resources[1], 84u);
    EXPECT_EQ(plan->spec_classes[34].peak_live, 100u);
    EXPECT_EQ(plan->summary.textures, kPorts);
}

TEST(Scale, TenThousandOutputsFeedTenThousandInputs) {
    constexpr uint32_t kPorts = 10000;
    Pass producer("producer");
    Pass consumer("consumer");
    for (uint32_t i = 0; i < kPorts; ++i) {
        producer.output(numbered("o", i), small_texture());
        consumer.input(numbered("i", i));
    }
    consumer.output("final", small_texture());
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(std::move(producer)).ok());
    ASSERT_TRUE(graph.add_pass(std::move(consumer)).ok());
    // Connected in reverse, so that port i of one side meets port kPorts - 1 - i of the other.
    for (uint32_t i = 0; i < kPorts; ++i) {
        ASSERT_TRUE(graph.connect(port("producer", numbered("o", i)), port("consumer", numbered("i", kPorts - 1 - i))).ok());
    }
    ASSERT_TRUE(graph.mark_output(port("consumer", "final")).ok());
    auto second = graph.connect(port("producer", "o0"), port("consumer", numbered("i", kPorts - 1)));
    ASSERT_FALSE(second.ok());
    EXPECT_EQ(second.error().message, "connect producer.o0 -> consumer.i9999: consumer.i9999 is already connected to "
                                      "producer.o0; an input takes one source");

    auto plan = build_plan(graph, options_for(AllocatorKind::Interval));
    ASSERT_TRUE(plan.ok()) << plan.error().to_string();
    EXPECT_EQ(plan->resources.size(), kPorts + 1);
    EXPECT_EQ(plan->edges.size(), kPorts);
    EXPECT_EQ(plan->summary.textures, kPorts + 1);  // all alive while the consumer runs
    const PlanEdge& edge = plan->edges[1234];
    EXPECT_EQ(edge.from_port, 1234u);
    EXPECT_EQ(edge.to_port, kPorts - 1 - 1234);
    EXPECT_EQ(plan->resources[edge.resource].name, "producer.o1234");
    EXPECT_EQ(plan->resources[edge.resource].ports,
              (std::vector<std::string>{"producer.o1234", "consumer.i8765"}));
}

// 2,000 producers whose outputs one last pass reads: 2,001 resources alive at once.
FrameGraph live_graph(uint32_t producers) {
    FrameGraph graph;
    Pass reader("reader");
    for (uint32_t i = 0; i < producers; ++i) {
        EXPECT_TRUE(graph.add_pass(Pass(numbered("p", i)).output("out", small_texture())).ok());
        reader.input(numbered("i", i));
    }
    reader.output("final", small_texture());
    EXPECT_TRUE(graph.add_pass(std::move(reader)).ok());
    for (uint32_t i = 0; i < producers; ++i) {
        EXPECT_TRUE(graph.connect(port(numbered("p", i), "out"), port("reader", numbered("i", i))).ok());
    }
    EXPECT_TRUE(graph.mark_output(port("reader", "final")).ok());
    return graph;
}

TEST(Scale, TwoThousandLiveResourcesUnderATinyHeapBudgetGetAHeapEach) {
    const FrameGraph graph = live_graph(2000);
    auto plan = build_plan(graph, options_for(AllocatorKind::Heap, 1));
    ASSERT_TRUE(plan.ok()) << plan.error().to_string();
    ASSERT_EQ(plan->resources.size(), 2001u);
    const uint64_t bytes = plan->resources[0].bytes;
    ASSERT_EQ(plan->heaps.size(), 2001u);
    std::set<uint32_t> heaps;
    for (const PlanTexture& texture : plan->textures) {
        ASSERT_TRUE(texture.placement.has_value());
        EXPECT_EQ(texture.placement->offset, 0u);
        heaps.insert(texture.placement->heap);
    }
    EXPECT_EQ(heaps.size(), 2001u);
    for (uint64_t size : plan->heaps) EXPECT_EQ(size, bytes);
    EXPECT_EQ(plan->summary.bytes, 2001 * bytes);
    EXPECT_EQ(plan->summary.lower_bound_bytes, 2001 * bytes);
}

TEST(Scale, TwoThousandLiveResourcesFillHeapsOfFour) {
    const FrameGraph graph = live_graph(2000);
    auto probe = build_plan(graph, options_for(AllocatorKind::Heap, 1));
    ASSERT_TRUE(probe.ok()) << probe.error().to_string();
    const uint64_t bytes = probe->resources[0].bytes;  // every resource has the same size

    auto plan = build_plan(graph, options_for(AllocatorKind::Heap, 4 * bytes));
    ASSERT_TRUE(plan.ok()) << plan.error().to_string();
    // 2,001 resources, four to a heap: 500 full heaps and one with a single resource.
    ASSERT_EQ(plan->heaps.size(), 501u);
    std::vector<uint32_t> per_heap(501, 0);
    for (const PlanTexture& texture : plan->textures) {
        ASSERT_TRUE(texture.placement.has_value());
        EXPECT_EQ(texture.placement->offset % bytes, 0u);
        EXPECT_LT(texture.placement->offset, 4 * bytes);
        ++per_heap.at(texture.placement->heap);
    }
    for (uint32_t h = 0; h < 500; ++h) EXPECT_EQ(per_heap[h], 4u) << "heap " << h;
    EXPECT_EQ(per_heap[500], 1u);
    EXPECT_EQ(plan->summary.bytes, 2001 * bytes);
}

TEST(Scale, TenThousandPassCycleIsNamedEdgeByEdge) {
    constexpr uint32_t kPasses = 10000;
    FrameGraph graph;
    for (uint32_t i = 0; i < kPasses; ++i) {
        ASSERT_TRUE(graph.add_pass(Pass(numbered("p", i)).input("in").output("out", small_texture())).ok());
    }
    for (uint32_t i = 0; i < kPasses; ++i) {
        ASSERT_TRUE(graph.connect(port(numbered("p", i), "out"), port(numbered("p", (i + 1) % kPasses), "in")).ok());
    }
    ASSERT_TRUE(graph.mark_output(port("p0", "out")).ok());
    auto plan = build_plan(graph, options_for(AllocatorKind::Interval));
    ASSERT_FALSE(plan.ok());
    const std::string& message = plan.error().message;
    EXPECT_EQ(message.rfind("cycle: p0 -> p1 -> p2 -> ", 0), 0u) << message.substr(0, 200);
    EXPECT_NE(message.find(" -> p9999 -> p0 (p0.out feeds p1.in; p1.out feeds p2.in; "), std::string::npos);
    const std::string ending = "; p9999.out feeds p0.in)";
    ASSERT_GE(message.size(), ending.size());
    EXPECT_EQ(message.substr(message.size() - ending.size()), ending);
}

// Every texture as large as half the 64-bit address space and a bit.
class HugeMemoryModel final : public MemoryModel {
public:
    Result<rhi::MemoryRequirements> requirements(const rhi::TextureDesc&) override {
        rhi::MemoryRequirements out;
        out.size = (uint64_t{1} << 63) + 4096;
        out.alignment = 4096;
        return out;
    }
};

TEST(Scale, HeapOffsetsThatOverflowAreAnErrorNotAWrap) {
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("a").output("x", small_texture()).output("y", small_texture())).ok());
    ASSERT_TRUE(graph.mark_output(port("a", "x")).ok());
    ASSERT_TRUE(graph.mark_output(port("a", "y")).ok());
    PlanOptions options = options_for(AllocatorKind::Heap);
    options.memory_model = std::make_shared<HugeMemoryModel>();
    auto plan = build_plan(graph, options);
    // a.y cannot follow a.x in one heap (the offset would pass 2^64), so it gets a second
    // heap; the two heaps together do not fit in 64 bits.
    ASSERT_FALSE(plan.ok());
    EXPECT_EQ(plan.error().message, "heap allocator: the heaps together exceed 2^64 bytes");
}

TEST(Scale, TenThousandPassChainStreamsTheSameJson) {
    constexpr uint32_t kPasses = 10000;
    FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(Pass("p0").output("out", small_texture())).ok());
    for (uint32_t i = 1; i < kPasses; ++i) {
        ASSERT_TRUE(graph.add_pass(Pass(numbered("p", i)).input("in").output("out")).ok());
        ASSERT_TRUE(graph.connect(port(numbered("p", i - 1), "out"), port(numbered("p", i), "in")).ok());
    }
    ASSERT_TRUE(graph.mark_output(port(numbered("p", kPasses - 1), "out")).ok());
    auto plan = build_plan(graph, options_for(AllocatorKind::Interval));
    ASSERT_TRUE(plan.ok()) << plan.error().to_string();
    EXPECT_EQ(plan->order.size(), kPasses);
    EXPECT_EQ(plan->resources.size(), kPasses);
    EXPECT_EQ(plan->summary.textures, 3u);  // p0's texture, then two alternating; the last is an output

    std::ostringstream streamed;
    write_plan_json(streamed, *plan);
    EXPECT_EQ(streamed.str(), plan_to_json(*plan));
    EXPECT_NE(streamed.str().find("\"from\": \"p9998.out\""), std::string::npos);
}

}  // namespace
}  // namespace loom::fg

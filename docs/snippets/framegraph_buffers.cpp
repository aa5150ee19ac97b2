// docs/framegraph.md, "Buffers", "Pass kinds" and "Subresource ranges": the bloom pyramid, the
// hierarchical-Z chain and the compute-built light list in C++. plan_buffer_examples() (run by
// snippets_test.cpp) plans each and checks that it is the plan of its JSON twin in
// samples/plan/graphs/, which the guide quotes, so the two forms cannot drift apart.
#include <string>
#include <string_view>
#include <vector>

#include "loom/framegraph/framegraph.hpp"
#include "snippets.hpp"

using namespace loom;

namespace loom::docs {
namespace {

// [docs:light-list]
// cull (compute) writes a light list of 1 KiB per 16x16 tile; build_args (compute) turns it into
// indirect draw arguments; shade reads the list as a storage buffer and draw reads the arguments.
Status build_light_list(fg::FrameGraph& graph) {
    using fg::BufferSize, fg::BufferSpec, fg::PassKind;
    LOOM_TRY(graph.add_pass(fg::Pass("depth").output("depth", fg::TextureSpec::of(rhi::Format::Depth32F))));
    LOOM_TRY(graph.add_pass(fg::Pass("cull").set_kind(PassKind::Compute).input("depth")
                                .buffer_output("lights", BufferSpec::sized(BufferSize::per_tile(16, 16, 1024)))));
    LOOM_TRY(graph.add_pass(fg::Pass("build_args").set_kind(PassKind::Compute).buffer_input("lights")
                                .buffer_output("args", BufferSpec::of_size(20).with_alignment(4))));
    LOOM_TRY(graph.add_pass(fg::Pass("shade").input("depth")
                                .buffer_input("lights", BufferSpec{}.with_usage(rhi::BufferUsage::Storage))
                                .output("color", fg::TextureSpec::of(rhi::Format::RGBA16Float))));
    LOOM_TRY(graph.add_pass(fg::Pass("draw")
                                .buffer_input("args", BufferSpec{}.with_usage(rhi::BufferUsage::Indirect))
                                .inout("color")));
    LOOM_TRY(graph.connect(fg::port("depth", "depth"), fg::port("cull", "depth")));
    LOOM_TRY(graph.connect(fg::port("depth", "depth"), fg::port("shade", "depth")));
    LOOM_TRY(graph.connect(fg::port("cull", "lights"), fg::port("build_args", "lights")));
    LOOM_TRY(graph.connect(fg::port("cull", "lights"), fg::port("shade", "lights")));
    LOOM_TRY(graph.connect(fg::port("build_args", "args"), fg::port("draw", "args")));
    LOOM_TRY(graph.connect(fg::port("shade", "color"), fg::port("draw", "color")));
    return graph.mark_output(fg::port("draw", "color"));
}
// [/docs:light-list]

// [docs:hzb]
// hzb0 (compute) copies depth into mip 0 of a half-size R32F chain; hzbK reduces mip K-1 into
// mip K of the same texture; cull reads the whole chain and writes indirect draws.
Status build_hzb(fg::FrameGraph& graph) {
    using fg::PassKind;
    LOOM_TRY(graph.add_pass(fg::Pass("prepass").output("depth", fg::TextureSpec::of(rhi::Format::Depth32F))));
    const auto chain = fg::TextureSpec::of(rhi::Format::R32Float).with_scale(0.5f).with_mips(5);
    LOOM_TRY(graph.add_pass(fg::Pass("hzb0").set_kind(PassKind::Compute).input("depth").output("hzb", chain, fg::mip(0))));
    LOOM_TRY(graph.connect(fg::port("prepass", "depth"), fg::port("hzb0", "depth")));
    for (uint32_t k = 1; k < 5; ++k) {
        const std::string name = "hzb" + std::to_string(k);
        const std::string previous = "hzb" + std::to_string(k - 1);
        LOOM_TRY(graph.add_pass(fg::Pass(name).set_kind(PassKind::Compute)
                                    .input("src", {}, fg::mip(k - 1))
                                    .inout("hzb", {}, fg::mip(k))));
        LOOM_TRY(graph.connect(fg::port(previous, "hzb"), fg::port(name, "src")));
        LOOM_TRY(graph.connect(fg::port(previous, "hzb"), fg::port(name, "hzb")));
    }
    LOOM_TRY(graph.add_pass(fg::Pass("cull").set_kind(PassKind::Compute).input("hzb")
                                .buffer_output("draws", fg::BufferSpec::of_size(20480).with_alignment(16))));
    LOOM_TRY(graph.add_pass(fg::Pass("draw")
                                .buffer_input("draws", fg::BufferSpec{}.with_usage(rhi::BufferUsage::Indirect))
                                .output("color", fg::TextureSpec::of(rhi::Format::RGBA16Float))
                                .inout("depth")));
    LOOM_TRY(graph.connect(fg::port("hzb4", "hzb"), fg::port("cull", "hzb")));
    LOOM_TRY(graph.connect(fg::port("cull", "draws"), fg::port("draw", "draws")));
    LOOM_TRY(graph.connect(fg::port("prepass", "depth"), fg::port("draw", "depth")));
    return graph.mark_output(fg::port("draw", "color"));
}
// [/docs:hzb]

// [docs:bloom]
// bright writes mip 0 of a half-size 4-mip pyramid; down1..3 each read mip K-1 and write mip K
// in place, up2..0 read mip K+1 and add it onto mip K; composite reads mip 0.
Status build_bloom(fg::FrameGraph& graph) {
    const auto hdr = fg::TextureSpec::of(rhi::Format::RGBA16Float);
    LOOM_TRY(graph.add_pass(fg::Pass("scene").output("hdr", hdr)));
    LOOM_TRY(graph.add_pass(fg::Pass("bright").input("hdr").output("pyramid", hdr.with_scale(0.5f).with_mips(4), fg::mip(0))));
    LOOM_TRY(graph.connect(fg::port("scene", "hdr"), fg::port("bright", "hdr")));
    std::string previous = "bright";
    auto step = [&](const std::string& name, uint32_t read, uint32_t write) -> Status {
        LOOM_TRY(graph.add_pass(fg::Pass(name).input("src", {}, fg::mip(read)).inout("pyramid", {}, fg::mip(write))));
        LOOM_TRY(graph.connect(fg::port(previous, "pyramid"), fg::port(name, "src")));
        LOOM_TRY(graph.connect(fg::port(previous, "pyramid"), fg::port(name, "pyramid")));
        previous = name;
        return {};
    };
    for (uint32_t k = 1; k < 4; ++k) {
        LOOM_TRY(step("down" + std::to_string(k), k - 1, k));
    }
    for (uint32_t k = 3; k-- > 0;) {
        LOOM_TRY(step("up" + std::to_string(k), k + 1, k));
    }
    LOOM_TRY(graph.add_pass(fg::Pass("composite").input("hdr").input("bloom", {}, fg::mip(0))
                                .output("final", fg::TextureSpec::of(rhi::Format::RGBA8Unorm))));
    LOOM_TRY(graph.connect(fg::port("scene", "hdr"), fg::port("composite", "hdr")));
    LOOM_TRY(graph.connect(fg::port(previous, "pyramid"), fg::port("composite", "bloom")));
    return graph.mark_output(fg::port("composite", "final"));
}
// [/docs:bloom]

// [docs:async]
// SSAO and its blur run on the async compute queue while the graphics queue draws shadows and
// the G-buffer; lighting reads the blurred AO.
Status build_async_ssao(fg::FrameGraph& graph) {
    using fg::PassKind;
    using fg::Queue;
    using rhi::Format;
    LOOM_TRY(graph.add_pass(fg::Pass("depth").output("depth", fg::TextureSpec::of(Format::Depth32F))));
    LOOM_TRY(graph.add_pass(fg::Pass("ssao").set_kind(PassKind::Compute).set_queue(Queue::AsyncCompute)
                                .input("depth").output("raw", fg::TextureSpec::of(Format::R16Float).with_scale(0.5f))));
    LOOM_TRY(graph.add_pass(fg::Pass("ssao_blur").set_kind(PassKind::Compute).set_queue(Queue::AsyncCompute)
                                .input("raw").output("ao", fg::TextureSpec::of(Format::R8Unorm).with_scale(0.5f))));
    LOOM_TRY(graph.add_pass(fg::Pass("shadows").output("shadow", fg::TextureSpec::of(Format::Depth32F).with_size(2048, 2048))));
    LOOM_TRY(graph.add_pass(fg::Pass("gbuffer").input("depth").output("albedo", fg::TextureSpec::of(Format::RGBA8Unorm))));
    LOOM_TRY(graph.add_pass(fg::Pass("lighting").input("albedo").input("shadow").input("ao")
                                .output("hdr", fg::TextureSpec::of(Format::RGBA16Float))));
    LOOM_TRY(graph.add_pass(fg::Pass("tonemap").input("hdr").output("final", fg::TextureSpec::of(Format::RGBA8Unorm))));
    LOOM_TRY(graph.connect(fg::port("depth", "depth"), fg::port("ssao", "depth")));
    LOOM_TRY(graph.connect(fg::port("ssao", "raw"), fg::port("ssao_blur", "raw")));
    LOOM_TRY(graph.connect(fg::port("depth", "depth"), fg::port("gbuffer", "depth")));
    LOOM_TRY(graph.connect(fg::port("gbuffer", "albedo"), fg::port("lighting", "albedo")));
    LOOM_TRY(graph.connect(fg::port("shadows", "shadow"), fg::port("lighting", "shadow")));
    LOOM_TRY(graph.connect(fg::port("ssao_blur", "ao"), fg::port("lighting", "ao")));
    LOOM_TRY(graph.connect(fg::port("lighting", "hdr"), fg::port("tonemap", "hdr")));
    return graph.mark_output(fg::port("tonemap", "final"));
}
// [/docs:async]

Status check(bool condition, const std::string& what) {
    return condition ? Status{} : Status(Error{ErrorCode::InvalidState, "docs/framegraph.md buffer example: " + what});
}

}  // namespace

Status plan_buffer_examples(const std::string& graphs_dir) {
    struct Example {
        const char* file;
        Status (*build)(fg::FrameGraph&);
        bool async = false;  // the paper allocator refuses plans with async passes
    };
    for (const Example& example : {Example{"light_list.json", build_light_list}, Example{"hzb_chain.json", build_hzb},
                                   Example{"bloom_pyramid.json", build_bloom},
                                   Example{"async_ssao.json", build_async_ssao, true}}) {
        fg::FrameGraph graph;
        LOOM_TRY(example.build(graph));
        auto file = fg::load_graph_file(graphs_dir + "/" + example.file);
        if (!file) return file.take_error();
        for (fg::AllocatorKind allocator : fg::allocator_kinds()) {
            if (example.async && allocator == fg::AllocatorKind::Paper) continue;
            fg::PlanOptions options;
            options.frame = file->frame;
            options.allocator = allocator;
            auto from_code = fg::build_plan(graph, options);
            if (!from_code) return from_code.take_error();
            auto from_json = fg::build_plan(file->graph, options);
            if (!from_json) return from_json.take_error();
            LOOM_TRY(check(*from_code == *from_json,
                           std::string("the C++ graph plans as ") + example.file + " does with " +
                                            std::string(fg::allocator_name(allocator))));
        }
    }
    // The figures the guide quotes, at 1920x1080 with the default memory model.
    fg::FrameGraph lights;
    LOOM_TRY(build_light_list(lights));
    auto plan = fg::build_plan(lights, {});
    if (!plan) return plan.take_error();
    LOOM_TRY(check(plan->summary.buffers == 2 && plan->summary.buffer_bytes == 8355840 + 256,
                   "two buffers: 120x68 tiles of 1 KiB and the arguments in 256 bytes"));
    LOOM_TRY(check(plan->buffer_of("draw", "args") == 1u, "draw reads b1"));
    fg::FrameGraph hzb;
    LOOM_TRY(build_hzb(hzb));
    fg::PlanOptions heap;
    heap.allocator = fg::AllocatorKind::Heap;
    auto placed = fg::build_plan(hzb, heap);
    if (!placed) return placed.take_error();
    LOOM_TRY(check(placed->summary.bytes == 24989696 && placed->summary.lower_bound_bytes == 24989696,
                   "the HZB chain and the colour share heap bytes"));
    fg::FrameGraph async;
    LOOM_TRY(build_async_ssao(async));
    auto two_queues = fg::build_plan(async, {});
    if (!two_queues) return two_queues.take_error();
    using fg::Queue;
    LOOM_TRY(check(two_queues->queue_syncs == std::vector<fg::QueueSync>{{Queue::Graphics, Queue::AsyncCompute, 0, 1},
                                                                        {Queue::AsyncCompute, Queue::Graphics, 2, 5}},
                   "ssao waits for depth, lighting for the blur"));
    const fg::PlanResource* raw = two_queues->resource_of("ssao", "raw");
    LOOM_TRY(check(raw && raw->lifetime == fg::Lifetime{1, 2} && raw->occupancy == fg::Lifetime{1, 4},
                   "the raw AO is held while shadows and the G-buffer may run beside the blur"));
    LOOM_TRY(check(two_queues->resource_of("depth", "depth")->queue_shared, "both queues read the depth"));
    return {};
}

}  // namespace loom::docs

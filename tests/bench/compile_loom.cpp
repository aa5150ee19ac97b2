// The side-by-side compile benchmark's graphs in loom.
#include "compile_libraries.hpp"

#include <array>

#include "loom/framegraph/framegraph.hpp"

namespace loom::bench {
namespace {

using namespace loom::fg;

constexpr std::array<rhi::Format, kFormats> kPalette{rhi::Format::RGBA8Unorm, rhi::Format::RGBA16Float,
                                                     rhi::Format::R11G11B10Float};
// Port names by index: a pass has at most 3 inputs and 2 outputs.
constexpr std::array<const char*, 3> kInputNames{"i0", "i1", "i2"};
constexpr std::array<const char*, 2> kOutputNames{"o0", "o1"};

TextureSpec spec_of(const CompileTexture& texture) {
    return TextureSpec::of(kPalette[texture.format]).with_scale(texture.halved ? 0.5f : 1.0f);
}

PlanOptions plan_options(LoomAllocatorUnderTest allocator) {
    PlanOptions options;
    options.frame = {1920, 1080};
    options.allocator = allocator == LoomAllocatorUnderTest::Heap ? AllocatorKind::Heap : AllocatorKind::Interval;
    // The declared order, as the peers keep theirs: the memory order (the default) adds its
    // search, which BM_PlanOrder measures (docs/BENCHMARKS.md, "Pass order").
    options.order = allocator == LoomAllocatorUnderTest::IntervalMemoryOrder ? PassOrder::Memory : PassOrder::Declared;
    return options;
}

uint64_t result_of(const Result<Plan>& plan) {
    // A failed plan would make the timing meaningless: stop loudly.
    if (!plan) std::abort();
    return plan->summary.bytes;
}

// FrameGraph::plan's plan, which must be one (as result_of).
std::shared_ptr<const Plan> planned(Result<std::shared_ptr<const Plan>> plan) {
    if (!plan) std::abort();
    return std::move(*plan);
}

}  // namespace

CompileNames make_compile_names(const CompileGraph& graph) {
    CompileNames names;
    names.passes.reserve(graph.passes.size());
    names.textures.reserve(graph.textures.size());
    // Appended, not "p" + std::to_string(i): GCC 12 at -O3 warns falsely (-Wrestrict) about the
    // insertion that operator+(const char*, std::string&&) inlines.
    auto numbered = [](char prefix, std::size_t i) {
        std::string name(1, prefix);
        name += std::to_string(i);
        return name;
    };
    for (std::size_t i = 0; i < graph.passes.size(); ++i) names.passes.push_back(numbered('p', i));
    for (std::size_t i = 0; i < graph.textures.size(); ++i) names.textures.push_back(numbered('t', i));
    return names;
}

uint64_t compile_in_loom_by_name(const CompileGraph& graph, const CompileNames& names, LoomAllocatorUnderTest allocator) {
    FrameGraph frame_graph;
    for (std::size_t index = 0; index < graph.passes.size(); ++index) {
        const CompilePass& pass = graph.passes[index];
        Pass declared(names.passes[index]);
        for (uint32_t r = 0; r < pass.read_count; ++r) declared.input(kInputNames[r]);
        for (uint32_t o = 0; o < pass.create_count; ++o) declared.output(kOutputNames[o], spec_of(graph.textures[pass.first_texture + o]));
        declared.set_side_effect(pass.side_effect);
        if (!frame_graph.add_pass(std::move(declared))) std::abort();
        for (uint32_t r = 0; r < pass.read_count; ++r) {
            const CompileTexture& texture = graph.textures[graph.reads[pass.first_read + r]];
            if (!frame_graph.connect(port(names.passes[texture.pass], kOutputNames[texture.output]),
                                     port(names.passes[index], kInputNames[r]))) {
                std::abort();
            }
        }
    }
    return result_of(build_plan(frame_graph, plan_options(allocator)));
}

namespace {

// Declares `graph` into `frame_graph` (empty, reserved) by handles; pass `changed_pass` declares
// its first output in the next format.
void declare_typed(FrameGraph& frame_graph, const CompileGraph& graph, const CompileNames& names,
                   std::size_t changed_pass) {
    frame_graph.reserve(static_cast<uint32_t>(graph.passes.size()),
                        static_cast<uint32_t>(graph.reads.size() + graph.textures.size()));
    std::vector<PortAddress> handles(graph.textures.size());
    for (std::size_t index = 0; index < graph.passes.size(); ++index) {
        const CompilePass& pass = graph.passes[index];
        Pass declared(names.passes[index]);
        for (uint32_t r = 0; r < pass.read_count; ++r) declared.read(handles[graph.reads[pass.first_read + r]]);
        for (uint32_t o = 0; o < pass.create_count; ++o) {
            CompileTexture texture = graph.textures[pass.first_texture + o];
            if (index == changed_pass && o == 0) texture.format = (texture.format + 1) % kFormats;
            declared.output(kOutputNames[o], spec_of(texture));
        }
        declared.set_side_effect(pass.side_effect);
        auto id = frame_graph.add_pass(std::move(declared));
        if (!id) std::abort();
        // Reads come first among the pass's ports, then the outputs in declaration order.
        for (uint32_t o = 0; o < pass.create_count; ++o) handles[pass.first_texture + o] = port_of(*id, pass.read_count + o);
    }
}

// The spec series: one graph declared once per graph size, the first output of its middle pass
// in the next format every call.
uint64_t plan_respecified(const CompileGraph& graph, const CompileNames& names, LoomGraphUse use) {
    static FrameGraph declared;
    static std::size_t declared_passes = 0;
    static uint32_t format = 0;
    static std::shared_ptr<const Plan> held;
    const PlanOptions options = plan_options(LoomAllocatorUnderTest::Interval);
    const std::size_t middle = graph.passes.size() / 2;
    const CompilePass& pass = graph.passes[middle];
    if (declared_passes != graph.passes.size()) {
        held.reset();
        declared.clear();
        declare_typed(declared, graph, names, SIZE_MAX);
        declared_passes = graph.passes.size();
        format = graph.textures[pass.first_texture].format;
        planned(declared.plan(options));
    }
    if (use != LoomGraphUse::SpecSetHeld) held.reset();
    CompileTexture texture = graph.textures[pass.first_texture];
    texture.format = format = (format + 1) % kFormats;
    const PortAddress output = port_of(PassId{static_cast<uint32_t>(middle)}, pass.read_count);
    if (!declared.set_texture_spec(output, spec_of(texture))) std::abort();
    const uint64_t resized = declared.plans_resized();
    std::shared_ptr<const Plan> plan = planned(declared.plan(options));
    // The series measures planning from the previous plan: one planned anew would make it meaningless.
    if (declared.plans_resized() != resized + 1) std::abort();
    if (use == LoomGraphUse::SpecSetHeld) held = plan;
    return plan->summary.bytes;
}

// The allocator series: the graph planned once per graph size and allocator, then only the
// allocator run on the plan's problem, as the planner gives it (no pass lists: neither the
// interval nor the heap allocator reads them).
uint64_t allocate_only(const CompileGraph& graph, const CompileNames& names, LoomAllocatorUnderTest allocator) {
    static std::size_t planned_passes = 0;
    static LoomAllocatorUnderTest planned_allocator = allocator;
    static Plan plan;
    static AllocationProblem problem;
    const PlanOptions options = plan_options(allocator);
    if (planned_passes != graph.passes.size() || planned_allocator != allocator) {
        FrameGraph declared;
        declare_typed(declared, graph, names, SIZE_MAX);
        auto built = build_plan(declared, options);
        if (!built) std::abort();
        plan = std::move(*built);
        problem = {};
        problem.spec_class_count = static_cast<uint32_t>(plan.spec_classes.size());
        problem.max_heap_bytes = options.max_heap_bytes;
        problem.passes.resize(plan.order.size());
        for (const PlanResource& resource : plan.resources) {
            problem.resources.push_back(
                {resource.spec_class, resource.occupancy, resource.bytes, resource.alignment, resource.name});
            if (resource.graph_output) problem.graph_outputs.push_back(static_cast<uint32_t>(problem.resources.size() - 1));
        }
        planned_passes = graph.passes.size();
        planned_allocator = allocator;
    }
    const std::unique_ptr<Allocator> chosen = make_allocator(options.allocator);
    if (chosen->reads_pass_lists()) std::abort();  // the problem has none
    auto allocation = chosen->allocate(problem);
    if (!allocation) std::abort();
    return allocation->texture_count;
}

// The resize series: one graph declared once per graph size, planned at 1920x1080 and 1280x720
// in turn.
uint64_t plan_in_turn(const CompileGraph& graph, const CompileNames& names, LoomAllocatorUnderTest allocator,
                      LoomGraphUse use) {
    static FrameGraph declared;
    static std::size_t declared_passes = 0;
    // The frame size of the graph's plan (none yet, or one of another allocator: 0x0), and of
    // the last build_plan.
    static Extent2D planned_frame{};
    static LoomAllocatorUnderTest planned_allocator = allocator;
    static Extent2D replanned_frame{};
    static std::shared_ptr<const Plan> held;
    if (declared_passes != graph.passes.size()) {
        declared.clear();
        declare_typed(declared, graph, names, SIZE_MAX);
        declared_passes = graph.passes.size();
        planned_frame = {};
    }
    if (allocator != planned_allocator) planned_frame = {};
    if (use != LoomGraphUse::ResizedHeld) held.reset();
    auto other_than = [](Extent2D frame) { return frame == Extent2D{1920, 1080} ? Extent2D{1280, 720} : Extent2D{1920, 1080}; };
    PlanOptions options = plan_options(allocator);
    if (use == LoomGraphUse::Replanned) {
        options.frame = replanned_frame = other_than(replanned_frame);
        return result_of(build_plan(declared, options));
    }
    options.frame = other_than(planned_frame);
    const uint64_t resized = declared.plans_resized();
    std::shared_ptr<const Plan> plan = planned(declared.plan(options));
    // The series measures resizing: a graph that planned anew would make it meaningless.
    if (planned_frame != Extent2D{} && declared.plans_resized() != resized + 1) std::abort();
    planned_frame = options.frame;
    planned_allocator = allocator;
    if (use == LoomGraphUse::ResizedHeld) held = plan;
    return plan->summary.bytes;
}

}  // namespace

uint64_t compile_in_loom_typed(const CompileGraph& graph, const CompileNames& names, LoomAllocatorUnderTest allocator,
                               LoomGraphUse use) {
    if (use == LoomGraphUse::Resized || use == LoomGraphUse::ResizedHeld || use == LoomGraphUse::Replanned) {
        return plan_in_turn(graph, names, allocator, use);
    }
    if (use == LoomGraphUse::SpecSet || use == LoomGraphUse::SpecSetHeld) return plan_respecified(graph, names, use);
    if (use == LoomGraphUse::AllocatorOnly) return allocate_only(graph, names, allocator);
    if (use == LoomGraphUse::DeclaredOnly) {
        FrameGraph declared;
        declare_typed(declared, graph, names, SIZE_MAX);
        return declared.pass_count();
    }
    // One graph per kind of reuse, kept from call to call.
    static FrameGraph cleared;
    static FrameGraph cleared_planned;
    static FrameGraph redeclared;
    static FrameGraph changing;
    static uint64_t changing_calls = 0;
    FrameGraph fresh;
    FrameGraph& frame_graph = use == LoomGraphUse::Fresh            ? fresh
                              : use == LoomGraphUse::Cleared        ? cleared
                              : use == LoomGraphUse::ClearedPlanned ? cleared_planned
                              : use == LoomGraphUse::Redeclared     ? redeclared
                                                                     : changing;
    const bool redeclare = use == LoomGraphUse::Redeclared || use == LoomGraphUse::RedeclaredChanging;
    if (redeclare) {
        frame_graph.redeclare();
    } else {
        frame_graph.clear();
    }
    // The changing graph's middle pass declares its first output in the next format every other call.
    const std::size_t changed_pass =
        use == LoomGraphUse::RedeclaredChanging && changing_calls++ % 2 == 1 ? graph.passes.size() / 2 : SIZE_MAX;
    declare_typed(frame_graph, graph, names, changed_pass);
    if (use == LoomGraphUse::Fresh || use == LoomGraphUse::Cleared) {
        return result_of(build_plan(frame_graph, plan_options(allocator)));
    }
    return planned(frame_graph.plan(plan_options(allocator)))->summary.bytes;
}

}  // namespace loom::bench

#pragma once
// One function per library of the side-by-side compile benchmark (compile_bench.cpp): each
// creates a graph, declares every pass of a CompileGraph and compiles it, and returns a number
// read from the result (so that no work is optimised away). The peers' functions are compiled
// in their own files, against their own headers, only when their sources are present.

#include <cstdint>
#include <string>
#include <vector>

#include "compile_graph.hpp"

namespace loom::bench {

/// Names made once outside the timed loops, so that no library pays for formatting them:
/// passes p0, p1, ... and textures t0, t1, ...
struct CompileNames {
    std::vector<std::string> passes;
    std::vector<std::string> textures;
};
CompileNames make_compile_names(const CompileGraph& graph);

/// The loom allocators the benchmark compares.
enum class LoomAllocatorUnderTest {
    Interval,
    Heap,
    /// The interval allocator in the pass order an application gets when it sets none
    /// (PassOrder::Memory, with its search for a lower peak); the others keep the declared order.
    IntervalMemoryOrder,
};

/// loom through its string API: ports declared by name, connected by "pass.port" names.
uint64_t compile_in_loom_by_name(const CompileGraph& graph, const CompileNames& names, LoomAllocatorUnderTest allocator);

/// Which graph compile_in_loom_typed declares into, and how it plans.
enum class LoomGraphUse {
    Fresh,      ///< a new graph every call, planned by build_plan
    Cleared,    ///< one graph cleared and declared again every call (an engine frame after frame)
    /// As Cleared, planned by FrameGraph::plan, which keeps the plan until the next (what the
    /// redeclared graphs below compare with).
    ClearedPlanned,
    /// One graph redeclared (FrameGraph::redeclare) and planned by FrameGraph::plan every call:
    /// the same graph every time, which plan() answers with the previous plan...
    Redeclared,
    /// ... or with one output of the middle pass in another format every other call, so that
    /// every call differs from the one before in that pass's texture spec: plan() makes the plan
    /// from the previous one (the declared order), joining and resolving that resource again.
    RedeclaredChanging,
    /// One graph declared once and planned by FrameGraph::plan every call for another frame
    /// size than the call before (1920x1080, 1280x720 in turn): no declaring, plan() makes the
    /// plan from the previous one (the declared order only; it checks that it did). Nothing
    /// else holds the previous plan, which plan() then changes in place...
    Resized,
    /// ... or the previous plan is held (as an executor holds it), which plan() then copies.
    ResizedHeld,
    /// The same graph declared once, planned from scratch by build_plan every call at the
    /// sizes in turn: what Resized saves.
    Replanned,
    /// One graph declared once; every call gives the first output of its middle pass the next
    /// format (FrameGraph::set_texture_spec) and plans by FrameGraph::plan at one frame size:
    /// plan() makes the plan from the previous one (it checks that it did), changing it in
    /// place...
    SpecSet,
    /// ... or copying it, the previous plan held (as an executor holds it).
    SpecSetHeld,
    /// What no faster planning can save: a new graph declared (and destroyed) every call, not
    /// planned at all.
    DeclaredOnly,
    /// The allocator alone: the graph planned once, then every call runs the allocator on the
    /// plan's allocation problem (the resources with their classes, lifetimes and bytes).
    AllocatorOnly,
};

/// loom through its typed API: reads by the handle of the write (Pass::read), outputs by
/// port_of, the graph reserved up front.
uint64_t compile_in_loom_typed(const CompileGraph& graph, const CompileNames& names, LoomAllocatorUnderTest allocator,
                               LoomGraphUse use);

#ifdef LOOM_BENCH_SKAARJ
/// skaarj1989/FrameGraph: addCallbackPass, create + write, read, compile().
uint64_t compile_in_skaarj(const CompileGraph& graph, const CompileNames& names);
#endif

#ifdef LOOM_BENCH_ACDEMIRALP
/// acdemiralp/fg: add_render_task, create, read, compile().
uint64_t compile_in_acdemiralp(const CompileGraph& graph, const CompileNames& names);
#endif

}  // namespace loom::bench

// Frame-graph compile, side by side: the same seeded graphs (compile_graph.hpp: layers of passes,
// each reading 1-3 earlier textures and creating 1-2, nothing culled) created, declared and
// compiled in loom and, where their sources were found at configure time, in
// skaarj1989/FrameGraph and acdemiralp/fg, in one process on a warm heap. Each benchmark reports
// per_pass (seconds per pass; Google Benchmark prints it in the unit it chooses) and
// allocs_per_pass (heap allocations per pass, counted by this program's operator new) and
// peak_bytes (the most bytes the program's operator new had handed out at once during the
// untimed first run, less what the run freed of earlier memory: the graph, its plan and every
// scratch array; for a reused graph, net of the previous frame's passes it frees). The heap is
// kept warm for every library alike (warm_heap.hpp).
// docs/BENCHMARKS.md, "Frame-graph compile vs peers", has the table and the command.
//
//   loom_framegraph_compile_bench [google benchmark flags]

#include <atomic>
#include <cstdlib>
#include <new>

#include <malloc.h>

#include <benchmark/benchmark.h>

#include "compile_libraries.hpp"
#include "warm_heap.hpp"

namespace {

// Every allocation of the program, counted (relaxed: the benchmark is single-threaded; the
// counter only has to be exact between two reads on the benchmark's thread).
std::atomic<uint64_t> g_allocations{0};
// During the untimed run only (the calls cost about 8 ns an allocation, which would weigh on the
// lightest library's timings most): bytes handed out less bytes freed since the run began (as
// malloc_usable_size counts them, so that frees, which may not know the size, subtract what was
// added), and the most at once.
std::atomic<bool> g_tracking_bytes{false};
std::atomic<int64_t> g_live_bytes{0};
std::atomic<int64_t> g_peak_bytes{0};

void* counted(void* p) {
    if (!p) throw std::bad_alloc();
    g_allocations.fetch_add(1, std::memory_order_relaxed);
    if (!g_tracking_bytes.load(std::memory_order_relaxed)) return p;
    const auto bytes = static_cast<int64_t>(malloc_usable_size(p));
    const int64_t live = g_live_bytes.fetch_add(bytes, std::memory_order_relaxed) + bytes;
    if (live > g_peak_bytes.load(std::memory_order_relaxed)) g_peak_bytes.store(live, std::memory_order_relaxed);
    return p;
}

void* counted_allocation(std::size_t size) { return counted(std::malloc(size == 0 ? 1 : size)); }

void* counted_aligned_allocation(std::size_t size, std::align_val_t alignment) {
    const auto align = static_cast<std::size_t>(alignment);
    return counted(std::aligned_alloc(align, (size + align - 1) / align * align));
}

void release(void* p) noexcept {
    if (p && g_tracking_bytes.load(std::memory_order_relaxed)) {
        g_live_bytes.fetch_sub(static_cast<int64_t>(malloc_usable_size(p)), std::memory_order_relaxed);
    }
    std::free(p);
}

}  // namespace

void* operator new(std::size_t size) { return counted_allocation(size); }
void* operator new[](std::size_t size) { return counted_allocation(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
    try { return counted_allocation(size); } catch (...) { return nullptr; }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
    try { return counted_allocation(size); } catch (...) { return nullptr; }
}
void* operator new(std::size_t size, std::align_val_t alignment) { return counted_aligned_allocation(size, alignment); }
void* operator new[](std::size_t size, std::align_val_t alignment) { return counted_aligned_allocation(size, alignment); }
void operator delete(void* p) noexcept { release(p); }
void operator delete[](void* p) noexcept { release(p); }
void operator delete(void* p, std::size_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t) noexcept { release(p); }
void operator delete(void* p, std::align_val_t) noexcept { release(p); }
void operator delete[](void* p, std::align_val_t) noexcept { release(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { release(p); }

namespace {

using namespace loom::bench;

// Runs `compile` on the graph of state.range(0) passes: one untimed run first (the warm heap),
// then the timed loop, counting the allocations of the timed runs.
template <typename Compile>
void run_compile(benchmark::State& state, Compile compile) {
    const auto passes = static_cast<uint32_t>(state.range(0));
    const CompileGraph graph = make_compile_graph(passes);
    const CompileNames names = make_compile_names(graph);
    g_live_bytes.store(0, std::memory_order_relaxed);
    g_peak_bytes.store(0, std::memory_order_relaxed);
    g_tracking_bytes.store(true, std::memory_order_relaxed);
    benchmark::DoNotOptimize(compile(graph, names));
    g_tracking_bytes.store(false, std::memory_order_relaxed);
    const int64_t peak_bytes = g_peak_bytes.load(std::memory_order_relaxed);
    const uint64_t allocations_before = g_allocations.load(std::memory_order_relaxed);
    for (auto _ : state) benchmark::DoNotOptimize(compile(graph, names));
    const uint64_t allocations = g_allocations.load(std::memory_order_relaxed) - allocations_before;
    const double pass_runs = static_cast<double>(passes) * static_cast<double>(state.iterations());
    state.counters["per_pass"] = benchmark::Counter(passes, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.counters["allocs_per_pass"] = static_cast<double>(allocations) / pass_runs;
    state.counters["peak_bytes"] =
        benchmark::Counter(static_cast<double>(peak_bytes), benchmark::Counter::kDefaults, benchmark::Counter::OneK::kIs1024);
}

void BM_CompileLoomByName(benchmark::State& state, LoomAllocatorUnderTest allocator) {
    run_compile(state, [allocator](const CompileGraph& g, const CompileNames& n) { return compile_in_loom_by_name(g, n, allocator); });
}

void BM_CompileLoomTyped(benchmark::State& state, LoomAllocatorUnderTest allocator, LoomGraphUse use) {
    run_compile(state, [allocator, use](const CompileGraph& g, const CompileNames& n) {
        return compile_in_loom_typed(g, n, allocator, use);
    });
}

#ifdef LOOM_BENCH_SKAARJ
void BM_CompileSkaarj(benchmark::State& state) { run_compile(state, compile_in_skaarj); }
#endif
#ifdef LOOM_BENCH_ACDEMIRALP
void BM_CompileAcdemiralp(benchmark::State& state) { run_compile(state, compile_in_acdemiralp); }
#endif

// 1k, 10k and 100k passes.
void sizes(benchmark::internal::Benchmark* b) { b->RangeMultiplier(10)->Range(1000, 100000)->Unit(benchmark::kMillisecond); }

BENCHMARK_CAPTURE(BM_CompileLoomByName, interval, LoomAllocatorUnderTest::Interval)->Apply(sizes);
BENCHMARK_CAPTURE(BM_CompileLoomByName, heap, LoomAllocatorUnderTest::Heap)->Apply(sizes);
BENCHMARK_CAPTURE(BM_CompileLoomTyped, interval, LoomAllocatorUnderTest::Interval, LoomGraphUse::Fresh)->Apply(sizes);
BENCHMARK_CAPTURE(BM_CompileLoomTyped, interval_reused, LoomAllocatorUnderTest::Interval, LoomGraphUse::Cleared)->Apply(sizes);
// Not side by side with the peers, which plan every graph afresh: what an engine that declares
// its graph every frame pays in loom when the graph stays the same (redeclared) and when one
// pass of it differs from the frame before (redeclared_changing), against a graph cleared and
// planned by FrameGraph::plan (cleared_planned), which holds its plan as they do.
BENCHMARK_CAPTURE(BM_CompileLoomTyped, interval_cleared_planned, LoomAllocatorUnderTest::Interval,
                  LoomGraphUse::ClearedPlanned)
    ->Apply(sizes);
BENCHMARK_CAPTURE(BM_CompileLoomTyped, interval_redeclared, LoomAllocatorUnderTest::Interval, LoomGraphUse::Redeclared)
    ->Apply(sizes);
BENCHMARK_CAPTURE(BM_CompileLoomTyped, interval_redeclared_changing, LoomAllocatorUnderTest::Interval,
                  LoomGraphUse::RedeclaredChanging)
    ->Apply(sizes);
// The same two with the default pass order (PassOrder::Memory), whose search a redeclared graph
// that repeats skips too; 1k and 10k passes.
BENCHMARK_CAPTURE(BM_CompileLoomTyped, memory_order_cleared_planned, LoomAllocatorUnderTest::IntervalMemoryOrder,
                  LoomGraphUse::ClearedPlanned)
    ->RangeMultiplier(10)
    ->Range(1000, 10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CompileLoomTyped, memory_order_redeclared, LoomAllocatorUnderTest::IntervalMemoryOrder,
                  LoomGraphUse::Redeclared)
    ->RangeMultiplier(10)
    ->Range(1000, 10000)
    ->Unit(benchmark::kMillisecond);
// A graph declared once and planned for another frame size every call (a window resized, a
// dynamic resolution): plan() makes the plan from the previous one (resized), also when the
// previous plan is held and must be copied (resized_held), against planning it from scratch
// (replanned); the declared order, in which a frame size changes no more than sizes and memory.
BENCHMARK_CAPTURE(BM_CompileLoomTyped, interval_resized, LoomAllocatorUnderTest::Interval, LoomGraphUse::Resized)
    ->Apply(sizes);
BENCHMARK_CAPTURE(BM_CompileLoomTyped, interval_resized_held, LoomAllocatorUnderTest::Interval,
                  LoomGraphUse::ResizedHeld)
    ->Apply(sizes);
BENCHMARK_CAPTURE(BM_CompileLoomTyped, interval_replanned, LoomAllocatorUnderTest::Interval, LoomGraphUse::Replanned)
    ->Apply(sizes);
// A graph declared once whose middle pass's first output takes the next format every call
// (set_texture_spec): plan() makes the plan from the previous one, in place (spec_set) or copied
// from a held plan (spec_set_held); interval_cleared_planned is the graph declared and planned anew.
BENCHMARK_CAPTURE(BM_CompileLoomTyped, interval_spec_set, LoomAllocatorUnderTest::Interval, LoomGraphUse::SpecSet)
    ->Apply(sizes);
BENCHMARK_CAPTURE(BM_CompileLoomTyped, interval_spec_set_held, LoomAllocatorUnderTest::Interval,
                  LoomGraphUse::SpecSetHeld)
    ->Apply(sizes);
// Parts that bound what planning faster could reach, side by side with the peers: declaring a
// graph without planning it, and each allocator alone on the plan's allocation problem.
BENCHMARK_CAPTURE(BM_CompileLoomTyped, declared_only, LoomAllocatorUnderTest::Interval, LoomGraphUse::DeclaredOnly)
    ->Apply(sizes);
BENCHMARK_CAPTURE(BM_CompileLoomTyped, interval_allocator_only, LoomAllocatorUnderTest::Interval,
                  LoomGraphUse::AllocatorOnly)
    ->Apply(sizes);
BENCHMARK_CAPTURE(BM_CompileLoomTyped, heap_allocator_only, LoomAllocatorUnderTest::Heap, LoomGraphUse::AllocatorOnly)
    ->Apply(sizes);
// The heap allocator places by bytes, so a resize allocates again: 1k and 10k passes.
BENCHMARK_CAPTURE(BM_CompileLoomTyped, heap_resized, LoomAllocatorUnderTest::Heap, LoomGraphUse::Resized)
    ->RangeMultiplier(10)
    ->Range(1000, 10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CompileLoomTyped, heap_replanned, LoomAllocatorUnderTest::Heap, LoomGraphUse::Replanned)
    ->RangeMultiplier(10)
    ->Range(1000, 10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CompileLoomTyped, heap, LoomAllocatorUnderTest::Heap, LoomGraphUse::Fresh)->Apply(sizes);
#ifdef LOOM_BENCH_SKAARJ
BENCHMARK(BM_CompileSkaarj)->Apply(sizes);
#endif
#ifdef LOOM_BENCH_ACDEMIRALP
// acdemiralp/fg finds each resource's last user by a linear search over the tasks, so its cost
// per pass grows with the graph; at 100k passes one run takes seconds.
BENCHMARK(BM_CompileAcdemiralp)->Apply(sizes);
#endif

}  // namespace

int main(int argc, char** argv) {
    loom::bench::keep_heap_warm();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}

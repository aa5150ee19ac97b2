// Frame-graph benchmarks: the cost of building and planning random graphs of 100 to 10,000
// passes with each allocator, of re-planning an unchanged graph, and the memory each
// allocator needs on a corpus of random graphs relative to the lower bound (peak live bytes).
// The Scale* cases grow one dimension to 1k, 10k and 100k: ports on a pass, connected
// outputs and inputs, resources alive at once under a heap budget, passes written as JSON.
// BM_EngineFrame plans the three engine frames of samples/plan/graphs with each allocator.
// BM_PlanOrder and BM_EngineFrameOrder plan the same graphs in declared and in memory order
// (PassOrder): the cost of the memory order's search (docs/BENCHMARKS.md, "Pass order").
// BM_LoadGraphJson parses the JSON text of the compile benchmark's layered graphs
// (compile_graph.hpp) into a FrameGraph, without planning (issue 16: 10,000 passes in 30 ms).
//
//   loom_framegraph_bench [--corpus=N] [google benchmark flags]
//
// --corpus sets how many random graphs the *Corpus benchmarks plan (default 1000).

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <ostream>
#include <streambuf>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "compile_graph.hpp"
#include "loom/framegraph/framegraph.hpp"
#include "loom/framegraph/graph_file.hpp"
#include "random_graph.hpp"
#include "warm_heap.hpp"

namespace {

using namespace loom::fg;

uint32_t g_corpus = 1000;

testing::RandomGraphOptions big_graph_options(uint32_t passes) {
    testing::RandomGraphOptions options;
    options.passes = passes;
    options.window = 8;
    // A real frame has a handful of graph outputs (they live to the end of the frame) and
    // some side-effect passes (presentation, readback) that keep most passes alive.
    options.graph_output_percent = 0;
    options.side_effect_percent = 10;
    // Passes declared in frame order, as renderers do; shuffled declarations make the
    // declaration-order tie break scatter producers and readers far apart.
    options.shuffle_declarations = false;
    return options;
}

PlanOptions options_for(AllocatorKind allocator, PassOrder order = PassOrder::Declared) {
    PlanOptions options;
    options.frame = {1920, 1080};
    options.allocator = allocator;
    options.order = order;
    return options;
}

// The mean number of resources alive at a position of the order: how much an allocator must
// keep apart at each step.
double mean_live(const Plan& plan) {
    if (plan.order.empty()) return 0.0;
    uint64_t total = 0;
    for (const PlanResource& r : plan.resources) total += uint64_t{r.lifetime.last} - r.lifetime.first + 1;
    return static_cast<double>(total) / static_cast<double>(plan.order.size());
}

// Building the graph (passes, connections, outputs) and planning it from scratch.
void BM_BuildAndPlan(benchmark::State& state, AllocatorKind allocator) {
    const auto passes = static_cast<uint32_t>(state.range(0));
    const PlanOptions options = options_for(allocator);
    uint64_t resources = 0;
    for (auto _ : state) {
        FrameGraph graph = testing::random_graph(7, big_graph_options(passes));
        auto plan = build_plan(graph, options);
        if (!plan) {
            state.SkipWithError(plan.error().message.c_str());
            return;
        }
        resources = plan->resources.size();
        benchmark::DoNotOptimize(plan->summary);
    }
    state.counters["passes"] = passes;
    state.counters["resources"] = static_cast<double>(resources);
    state.SetComplexityN(passes);
}

// Plans `graph` in the timed loop, then reports from one more (untimed) plan: resources,
// buffers, the mean number alive at a position, bytes over the lower bound and over one object
// per resource, and the time per pass.
void plan_repeatedly(benchmark::State& state, const FrameGraph& graph, const PlanOptions& options, uint32_t passes) {
    for (auto _ : state) {
        auto plan = build_plan(graph, options);
        if (!plan) {
            state.SkipWithError(plan.error().message.c_str());
            return;
        }
        benchmark::DoNotOptimize(plan->summary);
    }
    if (auto plan = build_plan(graph, options)) {
        const PlanSummary& summary = plan->summary;
        state.counters["resources"] = static_cast<double>(plan->resources.size());
        state.counters["buffers"] = static_cast<double>(summary.naive_buffers);
        state.counters["mean_live"] = mean_live(*plan);
        state.counters["bytes_over_bound"] = static_cast<double>(summary.bytes) / static_cast<double>(summary.lower_bound_bytes);
        state.counters["bytes_over_naive"] = static_cast<double>(summary.bytes) / static_cast<double>(summary.naive_bytes);
        state.counters["lower_bound_MiB"] = static_cast<double>(summary.lower_bound_bytes) / (1024.0 * 1024.0);
    }
    state.counters["per_pass"] = benchmark::Counter(passes, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.SetComplexityN(passes);
}

// Planning only: the graph is built once outside the loop.
void BM_Plan(benchmark::State& state, AllocatorKind allocator) {
    const auto passes = static_cast<uint32_t>(state.range(0));
    plan_repeatedly(state, testing::random_graph(7, big_graph_options(passes)), options_for(allocator), passes);
}

// Planning in declared or in memory order: compare the two per_pass times (and lower bounds) in
// the same run.
void BM_PlanOrder(benchmark::State& state, AllocatorKind allocator, PassOrder order) {
    const auto passes = static_cast<uint32_t>(state.range(0));
    plan_repeatedly(state, testing::random_graph(7, big_graph_options(passes)), options_for(allocator, order), passes);
}

// Planning graphs of the same shape with buffers and subresource ranges: a quarter of the
// outputs after each pass's first are buffers (absolute, per-pixel and per-tile sizes) and a
// fifth of the textures are mip chains or layer arrays whose ports use one subresource at a
// time. Compare its per_pass time with BM_Plan's (texture-only graphs) in the same run.
void BM_PlanMixed(benchmark::State& state, AllocatorKind allocator, uint32_t buffer_percent, uint32_t subresource_percent) {
    const auto passes = static_cast<uint32_t>(state.range(0));
    testing::RandomGraphOptions graph_options = big_graph_options(passes);
    graph_options.buffer_percent = buffer_percent;
    graph_options.subresource_percent = subresource_percent;
    plan_repeatedly(state, testing::random_graph(7, graph_options), options_for(allocator), passes);
}

// The cost of async compute in planning: the same graphs (a third of the passes compute
// passes) with those passes on the async compute queue or on the graphics queue; the queues
// phase (syncs, transfers, occupancies) runs only in the first. Compare the two per_pass times
// in the same run.
void BM_PlanAsync(benchmark::State& state, AllocatorKind allocator, bool async_queue) {
    const auto passes = static_cast<uint32_t>(state.range(0));
    testing::RandomGraphOptions graph_options = big_graph_options(passes);
    graph_options.async_percent = 33;
    graph_options.async_queue = async_queue;
    plan_repeatedly(state, testing::random_graph(7, graph_options), options_for(allocator), passes);
}

// The engine frames among the sample graphs (samples/plan/graphs: GTA V, DOOM 2016, Unreal's
// deferred renderer), read once and planned at their 1920x1080 (docs/BENCHMARKS.md, "Engine
// frames").
void BM_EngineFrameOrder(benchmark::State& state, const char* file, AllocatorKind allocator, PassOrder order) {
    auto loaded = load_graph_file(std::string(LOOM_SAMPLE_GRAPHS) + "/" + file);
    if (!loaded) {
        state.SkipWithError(loaded.error().message.c_str());
        return;
    }
    PlanOptions options = options_for(allocator, order);
    options.frame = loaded->frame;
    plan_repeatedly(state, loaded->graph, options, static_cast<uint32_t>(loaded->graph.pass_count()));
}

void BM_EngineFrame(benchmark::State& state, const char* file, AllocatorKind allocator) {
    BM_EngineFrameOrder(state, file, allocator, PassOrder::Declared);
}

// Building only, for reference.
void BM_Build(benchmark::State& state) {
    const auto passes = static_cast<uint32_t>(state.range(0));
    for (auto _ : state) {
        FrameGraph graph = testing::random_graph(7, big_graph_options(passes));
        benchmark::DoNotOptimize(graph.pass_count());
    }
    state.SetComplexityN(passes);
}

// Re-planning an unchanged graph: FrameGraph::plan returns the cached plan.
void BM_Replan(benchmark::State& state) {
    const auto passes = static_cast<uint32_t>(state.range(0));
    FrameGraph graph = testing::random_graph(7, big_graph_options(passes));
    const PlanOptions options = options_for(AllocatorKind::Interval);
    if (!graph.plan(options)) {
        state.SkipWithError("plan failed");
        return;
    }
    for (auto _ : state) benchmark::DoNotOptimize(graph.plan(options));
}

double quantile(std::vector<double> values, double q) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const auto index = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1) + 0.5);
    return values[index];
}

// Bytes over the lower bound (peak live bytes) for each allocator on the same random graphs,
// side by side; the counters are quantiles of the ratio over the corpus.
void BM_BytesOverLowerBoundCorpus(benchmark::State& state) {
    std::vector<FrameGraph> graphs;
    for (uint32_t seed = 1; seed <= g_corpus; ++seed) {
        testing::RandomGraphOptions options;
        options.passes = 4 + seed % 60;
        options.window = 2 + seed % 7;
        graphs.push_back(testing::random_graph(seed, options));
    }
    std::vector<double> heap, interval, paper, naive;
    uint32_t heap_optimal = 0;
    for (auto _ : state) {
        heap.clear();
        interval.clear();
        paper.clear();
        naive.clear();
        heap_optimal = 0;
        for (const FrameGraph& graph : graphs) {
            auto heap_plan = build_plan(graph, options_for(AllocatorKind::Heap));
            auto interval_plan = build_plan(graph, options_for(AllocatorKind::Interval));
            auto paper_plan = build_plan(graph, options_for(AllocatorKind::Paper));
            if (!heap_plan || !interval_plan || !paper_plan) {
                state.SkipWithError("plan failed");
                return;
            }
            const auto bound = static_cast<double>(heap_plan->summary.lower_bound_bytes);
            heap.push_back(static_cast<double>(heap_plan->summary.bytes) / bound);
            interval.push_back(static_cast<double>(interval_plan->summary.bytes) / bound);
            paper.push_back(static_cast<double>(paper_plan->summary.bytes) / bound);
            naive.push_back(static_cast<double>(heap_plan->summary.naive_bytes) / bound);
            heap_optimal += heap_plan->summary.bytes == heap_plan->summary.lower_bound_bytes ? 1 : 0;
        }
    }
    state.counters["graphs"] = static_cast<double>(graphs.size());
    state.counters["heap_at_bound_%"] = 100.0 * heap_optimal / static_cast<double>(graphs.size());
    // Cumulative distribution of the heap ratio.
    for (const auto& [name, limit] : {std::pair{"heap_le_1.01_%", 1.01}, std::pair{"heap_le_1.05_%", 1.05},
                                      std::pair{"heap_le_1.10_%", 1.10}}) {
        const auto within = std::count_if(heap.begin(), heap.end(), [&](double r) { return r <= limit; });
        state.counters[name] = 100.0 * static_cast<double>(within) / static_cast<double>(graphs.size());
    }
    for (const auto& [name, values] : {std::pair{"heap", &heap}, std::pair{"interval", &interval},
                                       std::pair{"paper", &paper}, std::pair{"naive", &naive}}) {
        state.counters[std::string(name) + "_p50"] = quantile(*values, 0.5);
        state.counters[std::string(name) + "_p90"] = quantile(*values, 0.9);
        state.counters[std::string(name) + "_max"] = quantile(*values, 1.0);
        double sum = 0.0;
        for (double v : *values) sum += v;
        state.counters[std::string(name) + "_mean"] = values->empty() ? 0.0 : sum / static_cast<double>(values->size());
    }
}


// ---- scale: the shapes of tests/bench/scale_graph.py, at 1k, 10k and 100k -----------------

TextureSpec scale_texture() { return TextureSpec::of(loom::rhi::Format::RGBA8Unorm).with_size(16, 16); }

std::string numbered(const char* prefix, int64_t i) {
    std::string out = prefix;  // appended: GCC 12 -O3 -Wrestrict false positive (bug 105651)
    out += std::to_string(i);
    return out;
}

void plan_or_skip(benchmark::State& state, const FrameGraph& graph, const PlanOptions& options) {
    auto plan = build_plan(graph, options);
    if (!plan) {
        state.SkipWithError(plan.error().message.c_str());
        return;
    }
    state.counters["resources"] = static_cast<double>(plan->resources.size());
    benchmark::DoNotOptimize(plan->summary);
}

// One pass with N outputs, every one a graph output: declaring, marking and planning.
void BM_ScaleWidePass(benchmark::State& state) {
    const int64_t ports = state.range(0);
    for (auto _ : state) {
        Pass wide("wide");
        for (int64_t i = 0; i < ports; ++i) wide.output(numbered("o", i), scale_texture());
        FrameGraph graph;
        if (!graph.add_pass(std::move(wide))) return state.SkipWithError("add_pass");
        for (int64_t i = 0; i < ports; ++i) {
            if (!graph.mark_output(port("wide", numbered("o", i)))) return state.SkipWithError("mark_output");
        }
        plan_or_skip(state, graph, options_for(AllocatorKind::Interval));
    }
    state.SetComplexityN(ports);
}

// N outputs of one pass connected to the N inputs of another, then planned.
void BM_ScaleConnect(benchmark::State& state) {
    const int64_t ports = state.range(0);
    for (auto _ : state) {
        Pass producer("producer");
        Pass consumer("consumer");
        for (int64_t i = 0; i < ports; ++i) {
            producer.output(numbered("o", i), scale_texture());
            consumer.input(numbered("i", i));
        }
        consumer.output("final", scale_texture());
        FrameGraph graph;
        if (!graph.add_pass(std::move(producer)) || !graph.add_pass(std::move(consumer))) {
            return state.SkipWithError("add_pass");
        }
        for (int64_t i = 0; i < ports; ++i) {
            if (!graph.connect(port("producer", numbered("o", i)), port("consumer", numbered("i", i)))) {
                return state.SkipWithError("connect");
            }
        }
        if (!graph.mark_output(port("consumer", "final"))) return state.SkipWithError("mark_output");
        plan_or_skip(state, graph, options_for(AllocatorKind::Interval));
    }
    state.SetComplexityN(ports);
}

// N producers read by one last pass: N + 1 resources alive at once, planned by the heap
// allocator with a 1-byte budget (every resource in a heap of its own). Planning only.
void BM_ScaleLiveHeap(benchmark::State& state) {
    const int64_t producers = state.range(0);
    FrameGraph graph;
    Pass reader("reader");
    for (int64_t i = 0; i < producers; ++i) {
        if (!graph.add_pass(Pass(numbered("p", i)).output("out", scale_texture()))) return state.SkipWithError("add_pass");
        reader.input(numbered("i", i));
    }
    reader.output("final", scale_texture());
    if (!graph.add_pass(std::move(reader))) return state.SkipWithError("add_pass");
    for (int64_t i = 0; i < producers; ++i) {
        if (!graph.connect(port(numbered("p", i), "out"), port("reader", numbered("i", i)))) {
            return state.SkipWithError("connect");
        }
    }
    if (!graph.mark_output(port("reader", "final"))) return state.SkipWithError("mark_output");
    PlanOptions options = options_for(AllocatorKind::Heap);
    options.max_heap_bytes = 1;
    for (auto _ : state) plan_or_skip(state, graph, options);
    state.SetComplexityN(producers);
}

// Counts what is written and keeps nothing, so only the writer's own memory shows.
class CountingBuffer final : public std::streambuf {
public:
    [[nodiscard]] uint64_t count() const { return count_; }

protected:
    int_type overflow(int_type c) override {
        if (!traits_type::eq_int_type(c, traits_type::eof())) ++count_;
        return traits_type::not_eof(c);
    }
    std::streamsize xsputn(const char*, std::streamsize n) override {
        count_ += static_cast<uint64_t>(n);
        return n;
    }

private:
    uint64_t count_ = 0;
};

// A chain of N passes planned once; the benchmark is writing the plan as JSON.
void BM_ScalePlanJson(benchmark::State& state) {
    const int64_t passes = state.range(0);
    FrameGraph graph;
    if (!graph.add_pass(Pass("p0").output("out", scale_texture()))) return state.SkipWithError("add_pass");
    for (int64_t i = 1; i < passes; ++i) {
        if (!graph.add_pass(Pass(numbered("p", i)).input("in").output("out")) ||
            !graph.connect(port(numbered("p", i - 1), "out"), port(numbered("p", i), "in"))) {
            return state.SkipWithError("add_pass/connect");
        }
    }
    if (!graph.mark_output(port(numbered("p", passes - 1), "out"))) return state.SkipWithError("mark_output");
    auto plan = build_plan(graph, options_for(AllocatorKind::Interval));
    if (!plan) return state.SkipWithError(plan.error().message.c_str());
    uint64_t bytes = 0;
    for (auto _ : state) {
        CountingBuffer buffer;
        std::ostream out(&buffer);
        write_plan_json(out, *plan);
        bytes = buffer.count();
    }
    state.counters["json_bytes"] = static_cast<double>(bytes);
    state.SetBytesProcessed(static_cast<int64_t>(bytes) * state.iterations());
    state.SetComplexityN(passes);
}

// The graph file of make_compile_graph(passes): pass p<i> with inputs i0.. (connected to the
// outputs they read) and outputs o0/o1 in one of three formats at full or half the frame size;
// the last layer has side effects. Written the way a tool or a person writes graph files, one
// object per port with its own keys.
std::string layered_graph_json(uint32_t passes) {
    static constexpr const char* kFormats[] = {"RGBA16F", "RGBA8", "R32F"};
    const loom::bench::CompileGraph graph = loom::bench::make_compile_graph(passes);
    std::string text = "{\"frame\": {\"width\": 1920, \"height\": 1080},\n \"passes\": [";
    std::string connections;
    for (uint32_t index = 0; index < graph.passes.size(); ++index) {
        const loom::bench::CompilePass& pass = graph.passes[index];
        const std::string name = std::to_string(index);
        text += index == 0 ? "\n  " : ",\n  ";
        text += "{\"name\": \"p" + name + "\"";
        if (pass.read_count > 0) {
            text += ", \"inputs\": [";
            for (uint32_t r = 0; r < pass.read_count; ++r) {
                const loom::bench::CompileTexture& read = graph.textures[graph.reads[pass.first_read + r]];
                text += (r == 0 ? "" : ", ") + std::string("{\"name\": \"i") + std::to_string(r) + "\"}";
                connections += connections.empty() ? "\n  " : ",\n  ";
                connections += "[\"p" + std::to_string(read.pass) + ".o" + std::to_string(read.output) + "\", \"p" + name + ".i" +
                               std::to_string(r) + "\"]";
            }
            text += "]";
        }
        text += ", \"outputs\": [";
        for (uint32_t o = 0; o < pass.create_count; ++o) {
            const loom::bench::CompileTexture& created = graph.textures[pass.first_texture + o];
            text += (o == 0 ? "" : ", ") + std::string("{\"name\": \"o") + std::to_string(o) + "\", \"format\": \"" +
                    kFormats[created.format] + "\", \"scale\": " + (created.halved ? "0.5" : "1.0") + "}";
        }
        text += "]";
        if (pass.side_effect) text += ", \"side_effect\": true";
        text += "}";
    }
    text += "],\n \"connections\": [" + connections + "]}\n";
    return text;
}

void BM_LoadGraphJson(benchmark::State& state) {
    const auto passes = static_cast<uint32_t>(state.range(0));
    const std::string text = layered_graph_json(passes);
    for (auto _ : state) {
        auto file = parse_graph_json(text, "layered.json");
        // A graph that does not load would make the timing meaningless: stop loudly.
        if (!file || file->graph.pass_count() != passes) std::abort();
        benchmark::DoNotOptimize(file->graph);
    }
    state.counters["per_pass"] = benchmark::Counter(passes, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.counters["json_bytes"] = static_cast<double>(text.size());
    state.SetBytesProcessed(static_cast<int64_t>(text.size()) * state.iterations());
    state.SetComplexityN(passes);
}

}  // namespace

BENCHMARK(BM_LoadGraphJson)->RangeMultiplier(10)->Range(100, 10000)->Unit(benchmark::kMillisecond)->Complexity();
BENCHMARK_CAPTURE(BM_BuildAndPlan, paper, AllocatorKind::Paper)->RangeMultiplier(10)->Range(100, 10000)->Unit(benchmark::kMillisecond)->Complexity();
BENCHMARK_CAPTURE(BM_BuildAndPlan, interval, AllocatorKind::Interval)->RangeMultiplier(10)->Range(100, 10000)->Unit(benchmark::kMillisecond)->Complexity();
BENCHMARK_CAPTURE(BM_BuildAndPlan, heap, AllocatorKind::Heap)->RangeMultiplier(10)->Range(100, 10000)->Unit(benchmark::kMillisecond)->Complexity();
BENCHMARK_CAPTURE(BM_Plan, paper, AllocatorKind::Paper)->RangeMultiplier(10)->Range(100, 10000)->Unit(benchmark::kMillisecond)->Complexity();
BENCHMARK_CAPTURE(BM_Plan, interval, AllocatorKind::Interval)->RangeMultiplier(10)->Range(100, 10000)->Unit(benchmark::kMillisecond)->Complexity();
BENCHMARK_CAPTURE(BM_Plan, heap, AllocatorKind::Heap)->RangeMultiplier(10)->Range(100, 10000)->Unit(benchmark::kMillisecond)->Complexity();
BENCHMARK_CAPTURE(BM_PlanMixed, interval, AllocatorKind::Interval, 25, 20)->RangeMultiplier(10)->Range(100, 10000)->Unit(benchmark::kMillisecond)->Complexity();
BENCHMARK_CAPTURE(BM_PlanMixed, heap, AllocatorKind::Heap, 25, 20)->RangeMultiplier(10)->Range(100, 10000)->Unit(benchmark::kMillisecond)->Complexity();
BENCHMARK_CAPTURE(BM_PlanAsync, interval_one_queue, AllocatorKind::Interval, false)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PlanAsync, interval_async, AllocatorKind::Interval, true)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PlanAsync, heap_one_queue, AllocatorKind::Heap, false)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PlanAsync, heap_async, AllocatorKind::Heap, true)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PlanMixed, heap_buffers_only, AllocatorKind::Heap, 25, 0)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PlanMixed, heap_subresources_only, AllocatorKind::Heap, 0, 20)->Arg(10000)->Unit(benchmark::kMillisecond);
// The paper's allocator refuses plans with async compute passes (DOOM's and Unreal's frames).
BENCHMARK_CAPTURE(BM_EngineFrame, gta5_paper, "gta5_frame.json", AllocatorKind::Paper)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_EngineFrame, gta5_interval, "gta5_frame.json", AllocatorKind::Interval)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_EngineFrame, gta5_heap, "gta5_frame.json", AllocatorKind::Heap)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_EngineFrame, doom2016_interval, "doom2016_frame.json", AllocatorKind::Interval)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_EngineFrame, doom2016_heap, "doom2016_frame.json", AllocatorKind::Heap)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_EngineFrame, unreal_interval, "unreal_deferred_frame.json", AllocatorKind::Interval)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_EngineFrame, unreal_heap, "unreal_deferred_frame.json", AllocatorKind::Heap)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_PlanOrder, interval_declared, AllocatorKind::Interval, PassOrder::Declared)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PlanOrder, interval_memory, AllocatorKind::Interval, PassOrder::Memory)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PlanOrder, heap_declared, AllocatorKind::Heap, PassOrder::Declared)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PlanOrder, heap_memory, AllocatorKind::Heap, PassOrder::Memory)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_EngineFrameOrder, gta5_heap_memory, "gta5_frame.json", AllocatorKind::Heap, PassOrder::Memory)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_EngineFrameOrder, doom2016_heap_memory, "doom2016_frame.json", AllocatorKind::Heap, PassOrder::Memory)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_EngineFrameOrder, unreal_heap_memory, "unreal_deferred_frame.json", AllocatorKind::Heap, PassOrder::Memory)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Build)->RangeMultiplier(10)->Range(100, 10000)->Unit(benchmark::kMillisecond)->Complexity();
BENCHMARK(BM_Replan)->RangeMultiplier(10)->Range(100, 10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BytesOverLowerBoundCorpus)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ScaleWidePass)->RangeMultiplier(10)->Range(1000, 100000)->Unit(benchmark::kMillisecond)->Complexity();
BENCHMARK(BM_ScaleConnect)->RangeMultiplier(10)->Range(1000, 100000)->Unit(benchmark::kMillisecond)->Complexity();
BENCHMARK(BM_ScaleLiveHeap)->RangeMultiplier(10)->Range(1000, 100000)->Unit(benchmark::kMillisecond)->Complexity();
BENCHMARK(BM_ScalePlanJson)->RangeMultiplier(10)->Range(1000, 100000)->Unit(benchmark::kMillisecond)->Complexity();

int main(int argc, char** argv) {
    loom::bench::keep_heap_warm();
    // Our own flag first; Google Benchmark rejects flags it does not know.
    std::vector<char*> rest;
    for (int i = 0; i < argc; ++i) {
        if (std::strncmp(argv[i], "--corpus=", 9) == 0) {
            g_corpus = static_cast<uint32_t>(std::max(1L, std::strtol(argv[i] + 9, nullptr, 10)));
        } else {
            rest.push_back(argv[i]);
        }
    }
    int rest_count = static_cast<int>(rest.size());
    benchmark::Initialize(&rest_count, rest.data());
    if (benchmark::ReportUnrecognizedArguments(rest_count, rest.data())) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}

// The memory order (PassOrder::Memory) measured: peak live bytes in declared order, in memory
// order and at the exact optimum (where the exact solver finishes), and plan times, on
//   - the sample graphs (samples/plan/graphs: the engine frames and the smaller examples),
//   - random corpora: small graphs (6-25 passes, against the exact optimum), the property tests'
//     corpus (2-40 passes, shuffled declarations, with buffers and subresources), graphs with
//     async compute passes, and big graphs declared in frame order (1,000 and 10,000 passes).
// Prints Markdown tables (docs/BENCHMARKS.md, "Pass order"); --csv DIR also writes
// engine_frames.csv and small_corpus.csv there for tests/bench/plot_pass_order.py.
//
//   loom_pass_order_report [--graphs DIR] [--corpus N] [--repetitions N] [--exact-states N] [--csv DIR]
//
// Peaks are PlanSummary::lower_bound_bytes of heap-allocator plans (with async compute: the
// held bytes); the exact optimum is over lifetimes alone (for a frame with async compute it is
// a lower bound of what any order holds). Plan times are the median CPU time of --repetitions
// plans (of this thread: other work on a shared machine does not count).

#include <algorithm>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include "loom/framegraph/framegraph.hpp"
#include "plan_order.hpp"
#include "random_graph.hpp"

namespace {

using namespace loom::fg;
namespace fs = std::filesystem;

struct Options {
    std::string graphs = LOOM_SAMPLE_GRAPHS;
    uint32_t corpus = 1000;
    uint32_t repetitions = 21;
    uint64_t exact_states = 4'000'000;
    std::string csv;
};

Options parse(int argc, char** argv) {
    Options options;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "%s needs a value\n", arg.c_str());
                std::exit(2);
            }
            return argv[++i];
        };
        if (arg == "--graphs") {
            options.graphs = value();
        } else if (arg == "--corpus") {
            options.corpus = static_cast<uint32_t>(std::stoul(value()));
        } else if (arg == "--repetitions") {
            options.repetitions = std::max(1u, static_cast<uint32_t>(std::stoul(value())));
        } else if (arg == "--exact-states") {
            options.exact_states = std::stoull(value());
        } else if (arg == "--csv") {
            options.csv = value();
        } else {
            std::fprintf(stderr,
                         "usage: loom_pass_order_report [--graphs DIR] [--corpus N] [--repetitions N] "
                         "[--exact-states N] [--csv DIR]\n");
            std::exit(2);
        }
    }
    return options;
}

PlanOptions plan_options(PassOrder order, AllocatorKind allocator = AllocatorKind::Heap, Extent2D frame = {1920, 1080}) {
    PlanOptions options;
    options.frame = frame;
    options.allocator = allocator;
    options.order = order;
    return options;
}

Plan must_plan(const FrameGraph& graph, const PlanOptions& options) {
    auto plan = build_plan(graph, options);
    if (!plan) {
        std::fprintf(stderr, "plan failed: %s\n", plan.error().to_string().c_str());
        std::exit(1);
    }
    return std::move(*plan);
}

// This thread's CPU time in microseconds: on a shared machine it counts only the planning.
double thread_microseconds() {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) * 1e6 + static_cast<double>(now.tv_nsec) / 1e3;
}

// The median CPU time of planning, in microseconds.
double plan_microseconds(const FrameGraph& graph, const PlanOptions& options, uint32_t repetitions) {
    std::vector<double> times;
    for (uint32_t i = 0; i < repetitions; ++i) {
        const double start = thread_microseconds();
        auto plan = build_plan(graph, options);
        const double end = thread_microseconds();
        if (!plan) std::exit(1);
        times.push_back(end - start);
    }
    std::sort(times.begin(), times.end());
    return times[times.size() / 2];
}

std::string mib(uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", static_cast<double>(bytes) / (1024.0 * 1024.0));
    return text;
}

std::string percent_change(uint64_t after, uint64_t before) {
    char text[32];
    std::snprintf(text, sizeof text, "%+.1f %%", 100.0 * (static_cast<double>(after) / static_cast<double>(before) - 1.0));
    return text;
}

std::vector<uint32_t> identity(uint32_t n) {
    std::vector<uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    return order;
}

// ---- the sample graphs -------------------------------------------------------------------------

void sample_graphs(const Options& options, std::ofstream* csv) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(options.graphs)) {
        if (entry.path().extension() == ".json") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    std::printf("### Sample graphs\n\n");
    std::printf("| graph | passes | declared | memory | change | exact (lifetimes) | exact states | interval: declared | "
                "interval: memory | plan: declared | plan: memory |\n");
    std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    if (csv) *csv << "graph,passes,declared_bytes,memory_bytes,exact_bytes,declared_us,memory_us\n";
    for (const fs::path& path : files) {
        auto file = load_graph_file(path);
        if (!file) {
            std::fprintf(stderr, "%s\n", file.error().to_string().c_str());
            std::exit(1);
        }
        const Plan declared = must_plan(file->graph, plan_options(PassOrder::Declared, AllocatorKind::Heap, file->frame));
        const Plan memory = must_plan(file->graph, plan_options(PassOrder::Memory, AllocatorKind::Heap, file->frame));
        const Plan interval_declared = must_plan(file->graph, plan_options(PassOrder::Declared, AllocatorKind::Interval, file->frame));
        const Plan interval_memory = must_plan(file->graph, plan_options(PassOrder::Memory, AllocatorKind::Interval, file->frame));
        auto problem = detail::order_problem_of(file->graph, plan_options(PassOrder::Declared, AllocatorKind::Heap, file->frame));
        if (!problem) std::exit(1);
        const auto exact = detail::exact_memory_order(*problem, options.exact_states,
                                                      detail::order_cost(*problem, identity(problem->pass_count())).peak);
        const double declared_us =
            plan_microseconds(file->graph, plan_options(PassOrder::Declared, AllocatorKind::Heap, file->frame), options.repetitions);
        const double memory_us =
            plan_microseconds(file->graph, plan_options(PassOrder::Memory, AllocatorKind::Heap, file->frame), options.repetitions);
        const uint64_t before = declared.summary.lower_bound_bytes;
        const uint64_t after = memory.summary.lower_bound_bytes;
        std::printf("| `%s` | %zu | %llu (%s MiB) | %llu (%s MiB) | %s | %s | %s | %s MiB | %s MiB | %.0f µs | %.0f µs |\n",
                    path.filename().string().c_str(), declared.order.size(), static_cast<unsigned long long>(before),
                    mib(before).c_str(), static_cast<unsigned long long>(after), mib(after).c_str(),
                    percent_change(after, before).c_str(),
                    exact ? (std::to_string(exact->peak) + " (" + mib(exact->peak) + " MiB)").c_str() : "not finished",
                    exact ? std::to_string(exact->states).c_str() : "-", mib(interval_declared.summary.bytes).c_str(),
                    mib(interval_memory.summary.bytes).c_str(), declared_us, memory_us);
        if (csv) {
            *csv << path.stem().string() << "," << declared.order.size() << "," << before << "," << after << ","
                 << (exact ? std::to_string(exact->peak) : "") << "," << declared_us << "," << memory_us << "\n";
        }
        std::fflush(stdout);
    }
    std::printf("\n");
}

// ---- random corpora ----------------------------------------------------------------------------

testing::RandomGraphOptions small_options(uint64_t seed) {
    testing::RandomGraphOptions options;
    options.passes = 6 + static_cast<uint32_t>(seed % 20);
    options.window = 2 + static_cast<uint32_t>(seed % 7);
    return options;
}

void small_corpus(const Options& options, std::ofstream* csv) {
    uint32_t solved = 0;
    uint32_t optimal = 0;
    uint32_t declared_optimal = 0;
    uint32_t worse = 0;
    double gap_sum = 0.0;
    double worst_gap = 0.0;
    double ratio_sum = 0.0;
    double exact_ratio_sum = 0.0;
    uint64_t worst_seed = 0;
    double heuristic_us = 0.0;
    if (csv) *csv << "seed,passes,declared_bytes,memory_bytes,exact_bytes\n";
    for (uint64_t seed = 1; seed <= options.corpus; ++seed) {
        const FrameGraph graph = testing::random_graph(seed, small_options(seed));
        auto problem = detail::order_problem_of(graph, plan_options(PassOrder::Declared));
        if (!problem) std::exit(1);
        const double start = thread_microseconds();
        const std::vector<uint32_t> order = detail::memory_order(*problem);
        heuristic_us += thread_microseconds() - start;
        const uint64_t declared = detail::order_cost(*problem, identity(problem->pass_count())).peak;
        const uint64_t memory = detail::order_cost(*problem, order).peak;
        worse += memory > declared ? 1 : 0;
        ratio_sum += static_cast<double>(memory) / static_cast<double>(declared);
        const auto exact = detail::exact_memory_order(*problem, options.exact_states, memory);
        if (csv) {
            *csv << seed << "," << problem->pass_count() << "," << declared << "," << memory << ","
                 << (exact ? std::to_string(exact->peak) : "") << "\n";
        }
        if (!exact) continue;
        ++solved;
        optimal += exact->peak == memory ? 1 : 0;
        declared_optimal += exact->peak == declared ? 1 : 0;
        exact_ratio_sum += static_cast<double>(exact->peak) / static_cast<double>(declared);
        const double gap = static_cast<double>(memory) / static_cast<double>(exact->peak) - 1.0;
        gap_sum += gap;
        if (gap > worst_gap) {
            worst_gap = gap;
            worst_seed = seed;
        }
    }
    std::printf("### Small random graphs (6-25 passes before culling), against the exact optimum\n\n");
    std::printf("| graphs | solved exactly | memory order optimal | declared order optimal | mean gap | worst gap | "
                "memory / declared (mean) | exact / declared (mean) | memory worse than declared | heuristic time (mean) |\n");
    std::printf("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    std::printf("| %u | %u | %u (%.1f %%) | %u (%.1f %%) | %.3f %% | %.2f %% (seed %llu) | %.3f | %.3f | %u | %.1f µs |\n\n",
                options.corpus, solved, optimal, 100.0 * optimal / solved, declared_optimal,
                100.0 * declared_optimal / solved, 100.0 * gap_sum / solved, 100.0 * worst_gap,
                static_cast<unsigned long long>(worst_seed), ratio_sum / options.corpus, exact_ratio_sum / solved, worse,
                heuristic_us / options.corpus);
}

struct CorpusFigures {
    uint32_t graphs = 0;
    uint32_t lower = 0;
    uint32_t worse = 0;
    // What the allocators make of it: bytes higher (lower) in memory order than in declared.
    uint32_t heap_worse = 0;
    uint32_t heap_better = 0;
    uint32_t interval_worse = 0;
    uint32_t interval_better = 0;
    double interval_ratio_sum = 0.0;
    double ratio_sum = 0.0;
    double best_ratio = 1.0;
    double declared_us = 0.0;
    double memory_us = 0.0;
};

void corpus_row(const char* name, const CorpusFigures& f) {
    std::printf("| %s | %u | %u (%.1f %%) | %u | %.3f | %.3f | %u / %u | %u / %u (%.3f) | %.1f µs | %.1f µs |\n", name,
                f.graphs, f.lower, 100.0 * f.lower / f.graphs, f.worse, f.ratio_sum / f.graphs, f.best_ratio,
                f.heap_better, f.heap_worse, f.interval_better, f.interval_worse, f.interval_ratio_sum / f.graphs,
                f.declared_us / f.graphs, f.memory_us / f.graphs);
}

template <class MakeOptions>
CorpusFigures plan_corpus(uint32_t count, MakeOptions make_options) {
    const AllocatorKind allocator = AllocatorKind::Heap;
    CorpusFigures figures;
    for (uint64_t seed = 1; seed <= count; ++seed) {
        const FrameGraph graph = testing::random_graph(seed, make_options(seed));
        const PlanOptions declared_options = plan_options(PassOrder::Declared, allocator);
        const PlanOptions memory_options = plan_options(PassOrder::Memory, allocator);
        const Plan declared_plan = must_plan(graph, declared_options);
        const Plan memory_plan = must_plan(graph, memory_options);
        const uint64_t declared = declared_plan.summary.lower_bound_bytes;
        const uint64_t memory = memory_plan.summary.lower_bound_bytes;
        figures.heap_worse += memory_plan.summary.bytes > declared_plan.summary.bytes ? 1 : 0;
        figures.heap_better += memory_plan.summary.bytes < declared_plan.summary.bytes ? 1 : 0;
        const uint64_t interval_declared =
            must_plan(graph, plan_options(PassOrder::Declared, AllocatorKind::Interval)).summary.bytes;
        const uint64_t interval_memory = must_plan(graph, plan_options(PassOrder::Memory, AllocatorKind::Interval)).summary.bytes;
        figures.interval_worse += interval_memory > interval_declared ? 1 : 0;
        figures.interval_better += interval_memory < interval_declared ? 1 : 0;
        figures.interval_ratio_sum += static_cast<double>(interval_memory) / static_cast<double>(interval_declared);
        figures.declared_us += plan_microseconds(graph, declared_options, 3);
        figures.memory_us += plan_microseconds(graph, memory_options, 3);
        ++figures.graphs;
        figures.lower += memory < declared ? 1 : 0;
        figures.worse += memory > declared ? 1 : 0;
        const double ratio = static_cast<double>(memory) / static_cast<double>(declared);
        figures.ratio_sum += ratio;
        figures.best_ratio = std::min(figures.best_ratio, ratio);
    }
    return figures;
}

void corpora(const Options& options) {
    std::printf("### Random corpora, memory order against declared order (heap allocator's lower bound)\n\n");
    std::printf("| corpus | graphs | memory order lower | memory order higher | memory / declared (mean) | "
                "memory / declared (best) | heap bytes lower / higher | interval bytes lower / higher (mean ratio) | "
                "plan: declared (mean) | plan: memory (mean) |\n");
    std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    corpus_row("property tests' (2-40 passes)", plan_corpus(options.corpus, [](uint64_t seed) {
                   testing::RandomGraphOptions o;
                   o.passes = 2 + static_cast<uint32_t>(seed % 39);
                   o.window = 2 + static_cast<uint32_t>(seed % 7);
                   return o;
               }));
    corpus_row("with buffers and subresources (2-40 passes)", plan_corpus(options.corpus, [](uint64_t seed) {
                   testing::RandomGraphOptions o;
                   o.passes = 2 + static_cast<uint32_t>(seed % 39);
                   o.window = 2 + static_cast<uint32_t>(seed % 7);
                   o.buffer_percent = 25;
                   o.subresource_percent = 20;
                   return o;
               }));
    corpus_row("with async compute (2-40 passes, 30 % async)", plan_corpus(options.corpus, [](uint64_t seed) {
                   testing::RandomGraphOptions o;
                   o.passes = 2 + static_cast<uint32_t>(seed % 39);
                   o.window = 2 + static_cast<uint32_t>(seed % 7);
                   o.async_percent = 30;
                   return o;
               }));
    corpus_row("frame order (40-200 passes)", plan_corpus(options.corpus / 5, [](uint64_t seed) {
                   testing::RandomGraphOptions o;
                   o.passes = 40 + static_cast<uint32_t>(seed % 161);
                   o.window = 8;
                   o.graph_output_percent = 0;
                   o.side_effect_percent = 10;
                   o.shuffle_declarations = false;
                   return o;
               }));
    std::printf("\n");
}

// The benchmarks' big graphs (tests/bench/framegraph_bench.cpp, big_graph_options).
void big_graphs(const Options& options) {
    std::printf("### Big graphs in frame order (the benchmarks' graphs, seed 7)\n\n");
    std::printf("| passes | declared | memory | change | heap: declared | heap: memory | interval: declared | "
                "interval: memory | plan (interval): declared | plan (interval): memory | overhead |\n");
    std::printf("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (uint32_t passes : {1000u, 10000u}) {
        testing::RandomGraphOptions o;
        o.passes = passes;
        o.window = 8;
        o.graph_output_percent = 0;
        o.side_effect_percent = 10;
        o.shuffle_declarations = false;
        const FrameGraph graph = testing::random_graph(7, o);
        const Plan declared = must_plan(graph, plan_options(PassOrder::Declared, AllocatorKind::Interval));
        const Plan memory = must_plan(graph, plan_options(PassOrder::Memory, AllocatorKind::Interval));
        const uint64_t before = declared.summary.lower_bound_bytes;
        const uint64_t after = memory.summary.lower_bound_bytes;
        const uint64_t heap_before = must_plan(graph, plan_options(PassOrder::Declared, AllocatorKind::Heap)).summary.bytes;
        const uint64_t heap_after = must_plan(graph, plan_options(PassOrder::Memory, AllocatorKind::Heap)).summary.bytes;
        const uint32_t repetitions = std::max(3u, options.repetitions / 3);
        const double declared_us = plan_microseconds(graph, plan_options(PassOrder::Declared, AllocatorKind::Interval), repetitions);
        const double memory_us = plan_microseconds(graph, plan_options(PassOrder::Memory, AllocatorKind::Interval), repetitions);
        std::printf("| %u | %s MiB | %s MiB | %s | %s MiB | %s MiB | %s MiB | %s MiB | %.2f ms | %.2f ms | %+.0f %% |\n",
                    passes, mib(before).c_str(), mib(after).c_str(), percent_change(after, before).c_str(),
                    mib(heap_before).c_str(), mib(heap_after).c_str(), mib(declared.summary.bytes).c_str(),
                    mib(memory.summary.bytes).c_str(), declared_us / 1000.0, memory_us / 1000.0,
                    100.0 * (memory_us / declared_us - 1.0));
        std::fflush(stdout);
    }
    std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
    const Options options = parse(argc, argv);
    std::optional<std::ofstream> engine_csv;
    std::optional<std::ofstream> corpus_csv;
    if (!options.csv.empty()) {
        fs::create_directories(options.csv);
        engine_csv.emplace(fs::path(options.csv) / "engine_frames.csv");
        corpus_csv.emplace(fs::path(options.csv) / "small_corpus.csv");
    }
    sample_graphs(options, engine_csv ? &*engine_csv : nullptr);
    small_corpus(options, corpus_csv ? &*corpus_csv : nullptr);
    corpora(options);
    big_graphs(options);
    return 0;
}

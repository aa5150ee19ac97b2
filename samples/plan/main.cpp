// loom-plan GRAPH.json [--allocator paper|interval|heap | --compare] [--sharing equal|joinable]
//                      [--frame WxH] [--max-heap BYTES] [--order declared|memory] [--json] [--dot FILE]
//                      [--inspect FILE]
//
// Plans a frame graph described in JSON and prints the plan: a readable table by default, or
// one JSON object with --json. --dot also writes the plan as a Graphviz graph, --inspect the
// inspector input (the plan, its barriers and every allocator's figures) that loom-inspect
// turns into a page. --compare plans
// with every allocator instead and prints their memory side by side with the naive figures and
// the lower bound. --order picks the pass order (the graph file's "order" by default). Exit
// status 0 on success, 1 for a bad graph or file, 2 for bad arguments; errors are one line on
// stderr.

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <optional>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

#include "loom/framegraph/framegraph.hpp"
#include "inspect_input.hpp"
#include "plan_arguments.hpp"

namespace {

// Prints one line, with any newline in the message flattened, and returns the exit status.
int fail(int status, std::string_view message) {
    std::string line(message);
    for (char& c : line) {
        if (c == '\n' || c == '\r') c = ' ';
    }
    std::cerr << "loom-plan: " << line << "\n";
    return status;
}

// --compare: every allocator's figures beside the naive ones and the lower bound (which are the
// graph's, the same in every plan). An allocator that refuses the graph (paper, for async
// compute) says why on its row; any other error stops with it.
int compare(const loom::fg::GraphFile& file, loom::fg::PlanOptions options, bool json) {
    using loom::fg::format_bytes;
    struct Row {
        std::string name;
        std::optional<loom::fg::PlanSummary> summary;
        std::string refused;
    };
    std::vector<Row> rows;
    std::optional<loom::fg::PlanSummary> any;
    for (loom::fg::AllocatorKind allocator : loom::fg::allocator_kinds()) {
        options.allocator = allocator;
        const std::string name(loom::fg::allocator_name(allocator));
        auto plan = loom::fg::build_plan(file.graph, options);
        if (plan) {
            rows.push_back({name, plan->summary, {}});
            any = plan->summary;
        } else if (plan.error().code == loom::ErrorCode::InvalidArgument) {
            rows.push_back({name, std::nullopt, plan.error().message});
        } else {
            return fail(1, loom::fg::locate_in_graph_file(file, plan.take_error()).to_string());
        }
    }
    if (!any) return fail(2, "no allocator accepts the graph: " + rows.front().refused);
    const loom::fg::PlanSummary& graph = *any;
    auto ratio = [&](uint64_t bytes) {
        char text[32];
        std::snprintf(text, sizeof text, "%.3f", static_cast<double>(bytes) / static_cast<double>(graph.lower_bound_bytes));
        return std::string(text);
    };
    if (json) {
        std::cout << "{\"frame\": [" << options.frame.width << ", " << options.frame.height << "], \"order\": \""
                  << loom::fg::pass_order_name(options.order) << "\", \"lower_bound_bytes\": "
                  << graph.lower_bound_bytes << ", \"naive_bytes\": " << graph.naive_bytes << ", \"allocators\": {";
        for (std::size_t i = 0; i < rows.size(); ++i) {
            std::cout << (i ? ", " : "") << "\"" << rows[i].name << "\": ";
            if (rows[i].summary) {
                std::cout << "{\"bytes\": " << rows[i].summary->bytes << ", \"textures\": " << rows[i].summary->textures
                          << ", \"buffers\": " << rows[i].summary->buffers << "}";
            } else {
                std::cout << "null";
            }
        }
        std::cout << "}}\n";
        return std::cout.good() ? 0 : 1;
    }
    std::cout << "memory at " << options.frame.width << "x" << options.frame.height << ", sharing "
              << loom::fg::spec_sharing_name(options.sharing) << ", order " << loom::fg::pass_order_name(options.order)
              << "\n";
    std::vector<std::vector<std::string>> table{{"", "textures", "buffers", "bytes", "", "bytes / lower bound"}};
    auto figures = [&](std::string name, uint32_t textures, uint32_t buffers, uint64_t bytes) {
        table.push_back({std::move(name), std::to_string(textures), std::to_string(buffers), std::to_string(bytes),
                         format_bytes(bytes), ratio(bytes)});
    };
    figures("naive", graph.naive_textures, graph.naive_buffers, graph.naive_bytes);
    for (const Row& row : rows) {
        if (row.summary) {
            figures(row.name, row.summary->textures, row.summary->buffers, row.summary->bytes);
        } else {
            table.push_back({row.name, "refuses: " + row.refused});
        }
    }
    figures("lower bound", graph.lower_bound_textures, graph.lower_bound_buffers, graph.lower_bound_bytes);
    // Columns as wide as their widest cell (a refusal runs on past the others).
    std::vector<std::size_t> width(table.front().size(), 0);
    for (const auto& row : table) {
        if (row.size() != width.size()) continue;
        for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
    }
    for (const auto& row : table) {
        std::string line = "  ";
        for (std::size_t c = 0; c < row.size(); ++c) {
            line += row[c];
            if (c + 1 < row.size()) line += std::string(width[c] - std::min(width[c], row[c].size()) + 2, ' ');
        }
        while (!line.empty() && line.back() == ' ') line.pop_back();
        std::cout << line << "\n";
    }
    return std::cout.good() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    // The plan is streamed in many small pieces; iostreams need not keep stdio's order.
    std::ios::sync_with_stdio(false);
    const std::vector<std::string> words(argv + (argc > 0 ? 1 : 0), argv + argc);
    auto parsed = loom::plan::parse_arguments(words);
    if (!parsed) return fail(2, parsed.error().message);
    loom::plan::Arguments& args = *parsed;
    if (args.help) {
        std::cout << loom::plan::kUsage << "\n";
        return 0;
    }

    auto file = loom::fg::load_graph_file(args.graph);
    if (!file) return fail(1, file.error().to_string());
    args.options.frame = args.frame.value_or(file->frame);
    args.options.order = args.order.value_or(file->order);
    if (args.compare) return compare(*file, args.options, args.json);

    auto plan = loom::fg::build_plan(file->graph, args.options);
    if (!plan) {
        // A bad option (an empty frame, paper with async compute) is an argument error, not a
        // graph error (nor located in the file).
        if (plan.error().code == loom::ErrorCode::InvalidArgument) return fail(2, plan.error().to_string());
        // A planning error names passes and ports; say where the file declares them.
        return fail(1, loom::fg::locate_in_graph_file(*file, plan.take_error()).to_string());
    }

    if (!args.dot.empty()) {
        std::ofstream dot(args.dot, std::ios::binary);
        loom::fg::write_plan_dot(dot, *plan);
        if (!dot) return fail(1, "Io: cannot write " + args.dot);
    }
    if (!args.inspect.empty()) {
        loom::inspect::RunRecord run;
        run.source = "loom-plan " + args.graph;
        // A graph file binds no imports or histories: the schedule of the plan alone.
        auto schedule = loom::fg::build_execution_schedule(*plan, {}, {});
        if (!schedule) return fail(1, loom::fg::locate_in_graph_file(*file, schedule.take_error()).to_string());
        run.schedule = &*schedule;
        auto allocators = loom::inspect::compare_allocators(file->graph, args.options);
        if (!allocators) return fail(1, loom::fg::locate_in_graph_file(*file, allocators.take_error()).to_string());
        run.allocators = std::move(*allocators);
        if (auto written = loom::inspect::write_input_file(args.inspect, *plan, run); !written) {
            return fail(1, written.error().to_string());
        }
    }
    if (args.json) {
        loom::fg::write_plan_json(std::cout, *plan);
        std::cout << "\n";
    } else {
        loom::fg::write_plan_table(std::cout, *plan);
    }
    return std::cout.good() ? 0 : 1;
}

// loom-plan GRAPH.json [--allocator paper|interval|heap] [--sharing equal|joinable]
//                      [--frame WxH] [--max-heap BYTES] [--json] [--dot FILE]
//
// Plans a frame graph described in JSON and prints the plan: a readable table by default, or
// one JSON object with --json. --dot also writes the plan as a Graphviz graph. Exit status 0
// on success, 1 for a bad graph or file, 2 for bad arguments; errors are one line on stderr.

#include <fstream>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

#include "loom/framegraph/framegraph.hpp"
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

    auto plan = loom::fg::build_plan(file->graph, args.options);
    if (!plan) {
        // A bad allocator name is an argument error, not a graph error (nor located in the file).
        if (plan.error().code == loom::ErrorCode::InvalidArgument) return fail(2, plan.error().to_string());
        // A planning error names passes and ports; say where the file declares them.
        return fail(1, loom::fg::locate_in_graph_file(*file, plan.take_error()).to_string());
    }

    if (!args.dot.empty()) {
        std::ofstream dot(args.dot, std::ios::binary);
        loom::fg::write_plan_dot(dot, *plan);
        if (!dot) return fail(1, "Io: cannot write " + args.dot);
    }
    if (args.json) {
        loom::fg::write_plan_json(std::cout, *plan);
        std::cout << "\n";
    } else {
        loom::fg::write_plan_table(std::cout, *plan);
    }
    return std::cout.good() ? 0 : 1;
}

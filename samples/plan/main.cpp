// loom-plan GRAPH.json [--allocator paper|interval|heap] [--sharing equal|joinable]
//                      [--frame WxH] [--max-heap BYTES] [--json] [--dot FILE]
//
// Plans a frame graph described in JSON and prints the plan: a readable table by default, or
// one JSON object with --json. --dot also writes the plan as a Graphviz graph. Exit status 0
// on success, 1 for a bad graph or file, 2 for bad arguments; errors are one line on stderr.

#include <charconv>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>

#include "loom/framegraph/framegraph.hpp"

namespace {

constexpr std::string_view kUsage =
    "usage: loom-plan GRAPH.json [--allocator paper|interval|heap] [--sharing equal|joinable] [--frame WxH] "
    "[--max-heap BYTES] [--json] [--dot FILE]";

struct Arguments {
    std::string graph;
    loom::fg::PlanOptions options;
    std::optional<loom::fg::Extent2D> frame;
    bool json = false;
    bool help = false;
    std::string dot;
};

// Prints one line, with any newline in the message flattened, and returns the exit status.
int fail(int status, std::string_view message) {
    std::string line(message);
    for (char& c : line) {
        if (c == '\n' || c == '\r') c = ' ';
    }
    std::cerr << "loom-plan: " << line << "\n";
    return status;
}

bool parse_number(std::string_view text, uint64_t& out) {
    auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), out);
    return error == std::errc{} && end == text.data() + text.size();
}

std::optional<loom::fg::Extent2D> parse_frame(std::string_view text) {
    const auto x = text.find('x');
    if (x == std::string_view::npos) return std::nullopt;
    uint64_t width = 0;
    uint64_t height = 0;
    if (!parse_number(text.substr(0, x), width) || !parse_number(text.substr(x + 1), height)) return std::nullopt;
    if (width == 0 || height == 0 || width > loom::fg::kMaxTextureExtent || height > loom::fg::kMaxTextureExtent) {
        return std::nullopt;
    }
    return loom::fg::Extent2D{static_cast<uint32_t>(width), static_cast<uint32_t>(height)};
}

// Parses argv; on error returns the message.
std::optional<std::string> parse_arguments(int argc, char** argv, Arguments& args) {
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        auto value = [&]() -> std::optional<std::string_view> {
            if (i + 1 >= argc) return std::nullopt;
            return std::string_view(argv[++i]);
        };
        if (arg == "--json") {
            args.json = true;
        } else if (arg == "--allocator" || arg == "--sharing" || arg == "--frame" || arg == "--max-heap" ||
                   arg == "--dot") {
            auto v = value();
            if (!v) return std::string(arg) + " needs a value";
            if (arg == "--allocator") {
                args.options.allocator = std::string(*v);
            } else if (arg == "--sharing") {
                if (*v == "equal") {
                    args.options.sharing = loom::fg::SpecSharing::Equal;
                } else if (*v == "joinable") {
                    args.options.sharing = loom::fg::SpecSharing::Joinable;
                } else {
                    return "--sharing must be equal or joinable, not '" + std::string(*v) + "'";
                }
            } else if (arg == "--frame") {
                args.frame = parse_frame(*v);
                if (!args.frame) return "--frame must be WxH (e.g. 1920x1080) with each side in 1.." +
                           std::to_string(loom::fg::kMaxTextureExtent) + ", not '" + std::string(*v) + "'";
            } else if (arg == "--max-heap") {
                if (!parse_number(*v, args.options.max_heap_bytes)) {
                    return "--max-heap must be a byte count, not '" + std::string(*v) + "'";
                }
            } else {
                args.dot = std::string(*v);
            }
        } else if (arg == "--help" || arg == "-h") {
            args.help = true;
        } else if (arg.starts_with("-")) {
            return "unknown option '" + std::string(arg) + "'";
        } else if (args.graph.empty()) {
            args.graph = std::string(arg);
        } else {
            return "more than one graph file given ('" + args.graph + "', '" + std::string(arg) + "')";
        }
    }
    if (args.graph.empty() && !args.help) return "no graph file given; " + std::string(kUsage);
    return std::nullopt;
}

}  // namespace

int main(int argc, char** argv) {
    // The plan is streamed in many small pieces; iostreams need not keep stdio's order.
    std::ios::sync_with_stdio(false);
    Arguments args;
    if (auto problem = parse_arguments(argc, argv, args)) return fail(2, *problem);
    if (args.help) {
        std::cout << kUsage << "\n";
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

// loom-inspect INPUT [--out FILE.html] [--title TEXT] [--timings FILE] [--allocations FILE]
//              [--allocator NAME] [--sharing equal|joinable] [--frame WxH] [--order declared|memory]
//              [--max-heap BYTES] [--no-compare]
//
// Writes one self-contained HTML page that shows a plan as pictures: the pass graph, the
// resources' lifetimes, the memory map, memory against the naive figure and the lower bound,
// per-pass timings, and each pass's ports and barriers (docs/inspector.md). INPUT is an
// inspector input (any sample's --inspect FILE), a plan (loom-plan --json) or a graph file,
// which is planned here with the planning options. Exit status 0 on success, 1 for a bad input
// file, 2 for bad arguments; errors are one line on stderr.

#include <iostream>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "input_files.hpp"
#include "inspect_page.hpp"
#include "plan_arguments.hpp"

namespace {

constexpr std::string_view kUsage =
    "usage: loom-inspect INPUT [--out FILE.html] [--title TEXT] [--timings FILE] [--allocations FILE]\n"
    "                    [--allocator paper|interval|heap] [--sharing equal|joinable] [--frame WxH]\n"
    "                    [--order declared|memory] [--max-heap BYTES] [--no-compare]\n"
    "INPUT: an inspector input (a sample's --inspect FILE), a plan (loom-plan --json) or a graph file\n"
    "(planned here with the planning options, and with every allocator for the memory comparison\n"
    "unless --no-compare). --out defaults to inspect.html.";

int fail(int status, std::string_view message) {
    std::string line(message);
    for (char& c : line) {
        if (c == '\n' || c == '\r') c = ' ';
    }
    std::cerr << "loom-inspect: " << line << "\n";
    return status;
}

struct Arguments {
    std::string input;
    std::string out = "inspect.html";
    std::string title;
    std::string timings;
    std::string allocations;
    loom::inspect::GraphPlanning planning;
    bool help = false;
};

loom::Result<Arguments> parse(std::span<const std::string> words) {
    auto bad = [](std::string message) { return loom::make_error(loom::ErrorCode::InvalidArgument, std::move(message)); };
    Arguments args;
    for (std::size_t i = 0; i < words.size(); ++i) {
        const std::string& word = words[i];
        if (word == "--help" || word == "-h") {
            args.help = true;
        } else if (word == "--no-compare") {
            args.planning.compare = false;
        } else if (word.starts_with("--")) {
            if (i + 1 >= words.size()) return bad(word + " needs a value");
            const std::string& value = words[++i];
            if (word == "--out") {
                args.out = value;
            } else if (word == "--title") {
                args.title = value;
            } else if (word == "--timings") {
                args.timings = value;
            } else if (word == "--allocations") {
                args.allocations = value;
            } else if (word == "--allocator") {
                auto kind = loom::fg::parse_allocator(value);
                if (!kind) return bad("--allocator: " + kind.error().message);
                args.planning.options.allocator = *kind;
            } else if (word == "--sharing") {
                if (value != "equal" && value != "joinable") return bad("--sharing must be equal or joinable, not '" + value + "'");
                args.planning.options.sharing = value == "equal" ? loom::fg::SpecSharing::Equal : loom::fg::SpecSharing::Joinable;
            } else if (word == "--frame") {
                args.planning.frame = loom::plan::parse_frame(value);
                if (!args.planning.frame) return bad("--frame must be WxH (e.g. 1920x1080), not '" + value + "'");
            } else if (word == "--order") {
                args.planning.order = loom::fg::parse_pass_order(value);
                if (!args.planning.order) return bad("--order must be declared or memory, not '" + value + "'");
            } else if (word == "--max-heap") {
                try {
                    std::size_t used = 0;
                    args.planning.options.max_heap_bytes = std::stoull(value, &used);
                    if (used != value.size() || value.starts_with("-")) throw std::invalid_argument(value);
                } catch (const std::exception&) {
                    return bad("--max-heap must be a byte count, not '" + value + "'");
                }
            } else {
                return bad("unknown option '" + word + "'");
            }
        } else if (args.input.empty()) {
            args.input = word;
        } else {
            return bad("more than one input given ('" + args.input + "', '" + word + "')");
        }
    }
    if (args.input.empty() && !args.help) return bad("no input given; " + std::string(kUsage.substr(0, kUsage.find('\n'))));
    return args;
}

}  // namespace

int main(int argc, char** argv) {
    const std::vector<std::string> words(argv + (argc > 0 ? 1 : 0), argv + argc);
    auto parsed = parse(words);
    if (!parsed) return fail(2, parsed.error().message);
    const Arguments& args = *parsed;
    if (args.help) {
        std::cout << kUsage << "\n";
        return 0;
    }
    auto input = loom::inspect::read_input(args.input, args.planning);
    if (!input) {
        // An unknown allocator name is an argument error, not one of the file.
        const int status = input.error().code == loom::ErrorCode::InvalidArgument ? 2 : 1;
        return fail(status, input.error().to_string());
    }
    if (!args.timings.empty()) {
        if (auto added = loom::inspect::add_timings(*input, args.timings); !added) return fail(1, added.error().to_string());
    }
    if (!args.allocations.empty()) {
        if (auto added = loom::inspect::add_allocations(*input, args.allocations); !added) {
            return fail(1, added.error().to_string());
        }
    }
    const std::string title = args.title.empty() ? std::filesystem::path(args.input).filename().string() : args.title;
    if (auto written = loom::inspect::write_page_file(args.out, *input, title); !written) {
        return fail(1, written.error().to_string());
    }
    std::cout << "loom-inspect: wrote " << args.out << "\n";
    return 0;
}

#pragma once
// The command line of loom-plan, parsed apart from main() so that the tool, its tests and the
// command-line fuzz harness (fuzz/command_line_fuzzer.cpp) run the same parser.

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "loom/framegraph/framegraph.hpp"
#include "loom/rhi/result.hpp"

namespace loom::plan {

/// The one-line usage text (--help prints it; a missing graph file quotes it).
inline constexpr std::string_view kUsage =
    "usage: loom-plan GRAPH.json [--allocator paper|interval|heap | --compare] [--sharing equal|joinable] "
    "[--frame WxH] [--max-heap BYTES] [--order declared|memory] [--json] [--dot FILE] [--inspect FILE]";

/// What the command line asks for.
struct Arguments {
    std::string graph;
    fg::PlanOptions options;
    /// --frame; the graph file's frame size when absent.
    std::optional<fg::Extent2D> frame;
    /// --order; the graph file's "order" when absent.
    std::optional<fg::PassOrder> order;
    bool json = false;
    bool help = false;
    /// --compare: the memory figures of every allocator side by side instead of one plan.
    bool compare = false;
    /// --dot's file; empty: no DOT output.
    std::string dot;
    /// --inspect's file: the inspector input for loom-inspect (the plan, its barriers and every
    /// allocator's figures); empty: none.
    std::string inspect;
};

/// "WxH" with each side in 1..fg::kMaxTextureExtent, or nullopt.
std::optional<fg::Extent2D> parse_frame(std::string_view text);

/// Parses `args` (without the program name). Errors are InvalidArgument with a message naming
/// the argument (an unknown allocator name among them).
Result<Arguments> parse_arguments(std::span<const std::string> args);

}  // namespace loom::plan

#pragma once
// The files loom-inspect reads, turned into one inspector input document (the format
// inspect_input.hpp writes): an inspector input as it is, a plan JSON (loom-plan --json) as the
// plan of an input, a graph file planned here; then timings and allocations from files of their
// own. Every file is checked for the members the page uses, so that a wrong or damaged file
// is an error naming the file and the JSON pointer at fault instead of a broken page.

#include <filesystem>
#include <optional>
#include <string_view>

#include <nlohmann/json.hpp>

#include "loom/framegraph/framegraph.hpp"
#include "loom/rhi/result.hpp"

namespace loom::inspect {

/// How a graph file given to loom-inspect is planned.
struct GraphPlanning {
    fg::PlanOptions options;
    /// The graph file's frame size when empty.
    std::optional<fg::Extent2D> frame;
    /// The graph file's "order" when empty.
    std::optional<fg::PassOrder> order;
    /// Also plan with every allocator for the page's memory comparison.
    bool compare = true;
};

/// The inspector input for `path`. Errors: Io (unreadable), Parse (not JSON, or a plan or input
/// lacking a member the page needs: "FILE: /passes/3/name: expected a string"), and a graph
/// file's own errors, located in the file as loom-plan reports them.
Result<nlohmann::json> read_input(const std::filesystem::path& path, const GraphPlanning& planning);

/// read_input of `text` as the contents of `path` (which is not read, only named in errors): for
/// an input made in memory (write_input's text), checked as loom-inspect checks a file.
Result<nlohmann::json> parse_input(const std::string& text, const std::filesystem::path& path,
                                   const GraphPlanning& planning);

/// Adds the per-pass timings of `path` to `input`: a file holding {"timings": [...]} (an
/// inspector input too) or the array alone, each entry {"pass", "cpu_ms", "gpu_ms" (or null)}.
/// Errors name the file and entry, also for a pass the plan does not have.
Status add_timings(nlohmann::json& input, const std::filesystem::path& path);

/// Adds the device's allocations of `path` to `input`: a file holding {"allocations": {...}}
/// (an inspector input too) or the object alone, its members byte and object counts.
Status add_allocations(nlohmann::json& input, const std::filesystem::path& path);

}  // namespace loom::inspect

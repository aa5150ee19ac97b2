#pragma once
// The inspector's input: a plan with what a run adds to it (the barriers and load/store
// actions around each pass, per-pass timings, what the device allocated, every allocator's
// figures), as one JSON document that loom-inspect turns into a page. Samples write it with
// --inspect FILE; docs/inspector.md describes the format.

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "loom/framegraph/framegraph.hpp"
#include "loom/rhi/result.hpp"

namespace loom::inspect {

/// The "format" member that marks an inspector input (a plain plan JSON has none).
inline constexpr const char* kInputFormat = "loom-inspect-input";
/// Its "version"; loom-inspect refuses other versions.
inline constexpr int kInputVersion = 1;

/// One allocator's figures for the same graph (or why it refused it).
struct AllocatorFigures {
    std::string allocator;
    /// Empty when the allocator refused the graph.
    std::optional<fg::PlanSummary> summary;
    /// Why it refused (empty when it planned).
    std::string refused;
};

/// Plans `graph` with every allocator (allocator_kinds()) and `options` otherwise. An allocator
/// that refuses the graph with InvalidArgument (paper, for async compute) gets a row saying
/// why; any other planning error is returned.
Result<std::vector<AllocatorFigures>> compare_allocators(const fg::FrameGraph& graph, fg::PlanOptions options);

/// What a run adds to the plan; every member is optional.
struct RunRecord {
    /// Who wrote the input ("loom-deferred on vulkan, llvmpipe"); the page's subtitle.
    std::string source;
    /// The barriers and load/store actions the executor records around each pass.
    const fg::ExecutionSchedule* schedule = nullptr;
    /// Per-pass timings of the latest frame, in plan order.
    std::vector<fg::PassTiming> timings;
    /// What the executor and the device created for the plan.
    std::optional<fg::ExecutionStats> allocations;
    /// Every allocator's figures for the same graph (compare_allocators).
    std::vector<AllocatorFigures> allocators;
};

/// Writes the inspector input for `plan` and `run` as one JSON object (the plan streamed with
/// write_plan_json, so that a large plan is never held as a second document).
void write_input(std::ostream& out, const fg::Plan& plan, const RunRecord& run);

/// write_input into the file `path`; Io error naming the file when it cannot be written.
Status write_input_file(const std::filesystem::path& path, const fg::Plan& plan, const RunRecord& run);

/// What `executor`'s latest frame adds to its plan (executor.plan()): its schedule, per-pass
/// timings and what it created, with every allocator's figures for `graph` planned with
/// `options` (the options the frame was planned with; the allocator is replaced). The record
/// points into the executor: valid until its next frame. InvalidState before the first frame;
/// planning errors of the comparison.
Result<RunRecord> executor_run_record(const fg::Executor& executor, const fg::FrameGraph& graph,
                                      const fg::PlanOptions& options, std::string source);

/// The inspector input of `executor`'s latest frame (its plan and executor_run_record) into
/// `path`. Errors: executor_run_record's; Io naming the file.
Status write_executor_input(const std::filesystem::path& path, const fg::Executor& executor, const fg::FrameGraph& graph,
                            const fg::PlanOptions& options, std::string source);

}  // namespace loom::inspect

#pragma once
// loom-compare's reports: one JSON object (--json, and report.json) and a self-contained HTML
// page (report.html, the pictures and inspector pages beside it), failures first.

#include <string>
#include <vector>

#include "case_result.hpp"
#include "compare_options.hpp"
#include "loom/rhi/device.hpp"

namespace loom::compare {

/// What the reports say about the run as a whole.
struct RunInfo {
    const Options* options = nullptr;
    std::vector<rhi::Backend> backends;
    RunSummary summary;
};

/// {"cases": [...], "summary": {"cases", "passed", "failed", ...}} as indented JSON text. PSNR
/// is null for identical pictures (JSON has no infinity).
std::string report_json(const std::vector<CaseResult>& cases, const RunInfo& run);

/// The HTML page: the run's summary, a table of every case, then per case (failures first) the
/// backends' pictures, the difference heat map, the metrics, the plans and the failures; the
/// table and each case link the case's inspector pages (BackendRun::inspector_file). A click
/// on a picture opens the viewer (report_viewer.hpp): the case's pictures one over the other, to
/// flip between and zoom into pixel by pixel.
std::string report_html(const std::vector<CaseResult>& cases, const RunInfo& run);

/// The cases in report order: failed ones first, otherwise as run.
std::vector<const CaseResult*> report_order(const std::vector<CaseResult>& cases);

}  // namespace loom::compare

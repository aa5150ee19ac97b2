#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include "loom/framegraph/export.hpp"
#include "loom/sample_common/html.hpp"
#include "report_viewer.hpp"

namespace loom::compare {
namespace {

using nlohmann::json;
using samples::escape_html;

json metrics_json(const std::optional<ImageMetrics>& metrics) {
    if (!metrics) return nullptr;
    return {{"max_channel_diff", metrics->max_channel_diff},
            {"pixels_above_threshold", metrics->pixels_above_threshold},
            {"pixel_count", metrics->pixel_count},
            {"psnr", std::isfinite(metrics->psnr) ? json(metrics->psnr) : json(nullptr)},
            {"identical", metrics->max_channel_diff == 0.0},
            {"diff", metrics->diff_file}};
}

json run_json(const BackendRun& run) {
    json out;
    out["backend"] = rhi::backend_name(run.backend);
    out["rendered"] = run.rendered();
    out["error"] = run.error.empty() ? json(nullptr) : json(run.error);
    out["milliseconds"] = std::round(run.milliseconds * 10.0) / 10.0;
    out["messages"] = run.messages;
    if (run.plan) {
        out["plan"] = {{"hash", plan_hash_text(*run.plan)},
                       {"passes", run.plan->order.size()},
                       {"textures", run.plan->textures.size()},
                       {"bytes", plan_texture_bytes(*run.plan)}};
        out["created"] = {{"textures", run.stats.textures}, {"bytes", run.stats.texture_bytes}};
    } else {
        out["plan"] = nullptr;
        out["created"] = nullptr;
    }
    out["image"] = run.image_file.empty() ? json(nullptr) : json(run.image_file);
    out["inspector"] = run.inspector_file.empty() ? json(nullptr) : json(run.inspector_file);
    return out;
}

json case_json(const CaseResult& c) {
    json out;
    out["scene"] = c.scene;
    out["file"] = c.file;
    out["pipeline"] = c.pipeline;
    out["id"] = c.id;
    out["passed"] = c.passed();
    out["failures"] = c.failures;
    out["error"] = c.load_error.empty() ? json(nullptr) : json(c.load_error);
    out["scene_info"] = c.scene_info;
    out["warnings"] = c.warnings;
    out["backends"] = json::array();
    for (const BackendRun& run : c.runs) out["backends"].push_back(run_json(run));
    out["image"] = metrics_json(c.image);
    out["against_deferred"] = metrics_json(c.against_deferred);
    return out;
}

std::string number(double value, int decimals) {
    char text[64];
    std::snprintf(text, sizeof(text), "%.*f", decimals, value);
    return text;
}

std::string psnr_text(const ImageMetrics& metrics) {
    return std::isfinite(metrics.psnr) ? number(metrics.psnr, 1) + " dB" : "identical";
}

/// "plan 0123abcd…: 7 passes, 8 textures, 3.2 MiB; gl created 8 (3.2 MiB), vulkan 8 (3.2 MiB)"
std::string plan_line(const CaseResult& c) {
    const BackendRun* first = nullptr;
    for (const BackendRun& run : c.runs) {
        if (run.plan) {
            first = &run;
            break;
        }
    }
    if (!first) return "no plan";
    std::string line = "plan " + plan_hash_text(*first->plan) + ": " + std::to_string(first->plan->order.size()) +
                       " passes, " + std::to_string(first->plan->textures.size()) + " textures, " +
                       fg::format_bytes(plan_texture_bytes(*first->plan)) + "; created:";
    for (const BackendRun& run : c.runs) {
        if (!run.plan) continue;
        // Appended piece by piece (GCC 12 -O3 -Wrestrict false positive, bug 105651).
        line += ' ';
        line += rhi::backend_name(run.backend);
        line += ' ';
        line += std::to_string(run.stats.textures);
        line += " (";
        line += fg::format_bytes(run.stats.texture_bytes);
        line += "), plan ";
        line += plan_hash_text(*run.plan).substr(0, 8);
        line += ';';
    }
    line.pop_back();
    return line;
}

/// Links to the case's inspector pages, one per backend that has one, named by the backend
/// (empty when none was written).
std::string inspector_links(const CaseResult& c) {
    std::string links;
    for (const BackendRun& run : c.runs) {
        if (run.inspector_file.empty()) continue;
        const std::string_view backend = rhi::backend_name(run.backend);
        links += links.empty() ? "" : " ";
        links += "<a class=\"inspector\" data-backend=\"";
        links += backend;
        links += "\" href=\"";
        links += escape_html(run.inspector_file);
        links += "\">";
        links += backend;
        links += "</a>";
    }
    return links;
}

constexpr const char* kStyle = R"(
body { font-family: sans-serif; margin: 1.5em; color: #222; }
h1 { font-size: 1.4em; }
table { border-collapse: collapse; margin-bottom: 2em; }
td, th { border: 1px solid #ccc; padding: 2px 8px; text-align: left; font-size: 0.9em; }
.pass { color: #176b1f; font-weight: bold; }
.fail { color: #b00020; font-weight: bold; }
.case { border: 1px solid #ccc; padding: 0.6em 1em; margin-bottom: 1.2em; }
.case.failed { border-color: #b00020; background: #fff5f6; }
.pictures { display: flex; flex-wrap: wrap; gap: 12px; }
figure { margin: 0; }
figure img { display: block; border: 1px solid #888; image-rendering: pixelated; max-width: 31vw; height: auto; }
figcaption { font-size: 0.85em; color: #555; }
ul { margin: 0.3em 0; }
code { font-size: 0.85em; }
)";

}  // namespace

std::vector<const CaseResult*> report_order(const std::vector<CaseResult>& cases) {
    std::vector<const CaseResult*> order;
    for (const CaseResult& c : cases) order.push_back(&c);
    std::stable_partition(order.begin(), order.end(), [](const CaseResult* c) { return !c->passed(); });
    return order;
}

std::string report_json(const std::vector<CaseResult>& cases, const RunInfo& run) {
    json out;
    out["cases"] = json::array();
    for (const CaseResult& c : cases) out["cases"].push_back(case_json(c));
    json backends = json::array();
    for (rhi::Backend backend : run.backends) backends.push_back(rhi::backend_name(backend));
    const Options& options = *run.options;
    out["summary"] = {{"cases", run.summary.cases},
                      {"passed", run.summary.passed},
                      {"failed", run.summary.failed},
                      {"seconds", std::round(run.summary.seconds * 10.0) / 10.0},
                      {"backends", backends},
                      {"size", std::to_string(options.width) + "x" + std::to_string(options.height)},
                      {"threshold", options.threshold},
                      {"max_differing", options.max_differing},
                      {"expect_errors", options.expect_errors}};
    return out.dump(2) + "\n";
}

std::string report_html(const std::vector<CaseResult>& cases, const RunInfo& run) {
    const Options& options = *run.options;
    std::ostringstream html;
    std::string backends;
    for (rhi::Backend backend : run.backends) backends += (backends.empty() ? "" : ", ") + std::string(rhi::backend_name(backend));
    html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n" << viewer::kErrorCollector
         << "<title>loom-compare: " << run.summary.failed << " failed, " << run.summary.passed << " passed</title>\n<style>"
         << kStyle << viewer::kStyle << "</style>\n</head>\n<body>\n";
    html << "<h1>loom-compare: " << run.summary.cases << " case(s), <span class=\"pass\">" << run.summary.passed
         << " passed</span>, <span class=\"" << (run.summary.failed ? "fail" : "pass") << "\">" << run.summary.failed
         << " failed</span></h1>\n";
    html << "<p>Backends: " << escape_html(backends) << ". Pictures " << options.width << "x" << options.height
         << (options.expect_errors ? "; every file must fail to load with a one-line error naming it"
                                   : "; a pixel differs when a channel differs by more than " +
                                         number(options.threshold, 1) + " levels, and " +
                                         (options.max_differing > 0.0
                                              ? "at most " + number(options.max_differing * 100.0, 3) + "% of the pixels may"
                                              : std::string("no pixel may")))
         << ". Run time " << number(run.summary.seconds, 1) << " s.</p>\n";

    const std::vector<const CaseResult*> order = report_order(cases);
    html << "<table>\n<tr><th>result</th><th>scene</th><th>pipeline</th><th>max diff</th><th>pixels above</th>"
            "<th>PSNR</th><th>inspector</th><th>first failure / error</th></tr>\n";
    for (const CaseResult* c : order) {
        html << "<tr><td class=\"" << (c->passed() ? "pass\">pass" : "fail\">FAIL") << "</td><td><a href=\"#"
             << escape_html(c->id) << "\">" << escape_html(c->scene) << "</a></td><td>" << escape_html(c->pipeline) << "</td>";
        if (c->image) {
            html << "<td>" << number(c->image->max_channel_diff, 0) << "</td><td>" << c->image->pixels_above_threshold
                 << " / " << c->image->pixel_count << "</td><td>" << psnr_text(*c->image) << "</td>";
        } else {
            html << "<td></td><td></td><td></td>";
        }
        html << "<td>" << inspector_links(*c) << "</td>";
        const std::string note = !c->failures.empty() ? c->failures.front() : c->load_error;
        html << "<td><code>" << escape_html(note) << "</code></td></tr>\n";
    }
    html << "</table>\n";

    for (const CaseResult* c : order) {
        html << "<div class=\"case" << (c->passed() ? "" : " failed") << "\" id=\"" << escape_html(c->id) << "\">\n<h2>"
             << "<span class=\"" << (c->passed() ? "pass\">pass" : "fail\">FAIL") << "</span> " << escape_html(c->scene)
             << " — " << escape_html(c->pipeline) << "</h2>\n";
        html << "<p><code>" << escape_html(c->file) << "</code>";
        if (!c->scene_info.empty()) html << "<br>" << escape_html(c->scene_info);
        html << "</p>\n";
        if (!c->failures.empty()) {
            html << "<ul>\n";
            for (const std::string& failure : c->failures) html << "<li class=\"fail\">" << escape_html(failure) << "</li>\n";
            html << "</ul>\n";
        }
        if (!c->load_error.empty()) html << "<p>Error: <code>" << escape_html(c->load_error) << "</code></p>\n";
        // Marked for the viewer (report_viewer.hpp): the case, and each picture's key and label.
        html << "<div class=\"pictures\" data-case=\"" << escape_html(c->id) << "\" data-title=\""
             << escape_html(c->scene + " — " + c->pipeline) << "\">\n";
        for (const BackendRun& backend_run : c->runs) {
            if (backend_run.image_file.empty()) continue;
            const std::string_view backend = rhi::backend_name(backend_run.backend);
            html << "<figure data-image=\"" << backend << "\" data-label=\"" << backend << "\" data-backend><a href=\""
                 << escape_html(backend_run.image_file) << "\"><img src=\"" << escape_html(backend_run.image_file) << "\" alt=\""
                 << backend << "\"></a><figcaption>" << backend << ", " << number(backend_run.milliseconds, 0)
                 << " ms</figcaption></figure>\n";
        }
        if (c->image && !c->image->diff_file.empty()) {
            html << "<figure data-image=\"difference\" data-label=\"difference\"><a href=\"" << escape_html(c->image->diff_file)
                 << "\"><img src=\"" << escape_html(c->image->diff_file)
                 << "\" alt=\"difference\"></a><figcaption>difference (black: equal, bright: largest)</figcaption></figure>\n";
        }
        if (c->against_deferred && !c->against_deferred->diff_file.empty()) {
            html << "<figure data-image=\"against-deferred\" data-label=\"forward against deferred\"><a href=\""
                 << escape_html(c->against_deferred->diff_file) << "\"><img src=\"" << escape_html(c->against_deferred->diff_file)
                 << "\" alt=\"forward against deferred\"></a><figcaption>forward against deferred</figcaption></figure>\n";
        }
        html << "</div>\n";
        if (c->image) {
            html << "<p>Largest channel difference " << number(c->image->max_channel_diff, 0) << ", "
                 << c->image->pixels_above_threshold << " of " << c->image->pixel_count << " pixels above the threshold, PSNR "
                 << psnr_text(*c->image) << ".</p>\n";
        }
        if (c->against_deferred) {
            html << "<p>Against the deferred pipeline: largest channel difference "
                 << number(c->against_deferred->max_channel_diff, 0) << ", " << c->against_deferred->pixels_above_threshold
                 << " of " << c->against_deferred->pixel_count << " pixels above " << number(kPipelineThreshold, 0)
                 << " levels (at most " << number(kPipelineMaxDiffering * 100.0, 1) << "% may be), PSNR "
                 << psnr_text(*c->against_deferred) << ".</p>\n";
        }
        if (!c->runs.empty()) html << "<p>" << escape_html(plan_line(*c)) << "</p>\n";
        if (const std::string links = inspector_links(*c); !links.empty()) {
            html << "<p>Inspector (the plan, barriers, timings and memory of the frame): " << links << "</p>\n";
        }
        std::vector<std::string> notes = c->warnings;
        for (const BackendRun& backend_run : c->runs) {
            for (const std::string& message : backend_run.messages) {
                notes.push_back(std::string(rhi::backend_name(backend_run.backend)) + ": " + message);
            }
        }
        if (!notes.empty()) {
            html << "<ul>\n";
            for (const std::string& note : notes) html << "<li><code>" << escape_html(note) << "</code></li>\n";
            html << "</ul>\n";
        }
        html << "</div>\n";
    }
    html << viewer::kBody << "</body>\n</html>\n";
    return html.str();
}

}  // namespace loom::compare

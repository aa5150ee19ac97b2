// loom-compare: every glTF scene × pipeline on every compiled-in backend, headless; the plans
// and the final pictures compared across the backends; an HTML report with the pictures and
// difference heat maps, and the same results as JSON. Exits 1 when any case fails.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "case_runner.hpp"
#include "compare_options.hpp"
#include "report.hpp"
#include "scene_files.hpp"

namespace {

constexpr int kUsageError = 2;

int usage_error(const std::string& message) {
    std::fprintf(stderr, "loom-compare: %s (see --help)\n", message.c_str());
    return kUsageError;
}

loom::Status write_text(const std::filesystem::path& path, const std::string& text) {
    std::ofstream file(path, std::ios::binary);
    file << text;
    if (!file) return loom::make_error(loom::ErrorCode::Io, "cannot write " + path.string());
    return {};
}

}  // namespace

int main(int argc, char** argv) {
    using namespace loom::compare;
    std::vector<std::string> args(argv + 1, argv + argc);
    auto options = parse_options(args);
    if (!options) return usage_error(options.error().message);
    if (options->help) {
        std::printf("%s", usage().c_str());
        return EXIT_SUCCESS;
    }
    if (options->scenes.empty()) {
        const std::filesystem::path data = std::filesystem::path(LOOM_COMPARE_DATA_DIR) / "gltf";
        std::error_code ec;
        if (!std::filesystem::is_directory(data, ec)) {
            return usage_error("no --scenes given and the default data directory " + data.string() + " does not exist");
        }
        options->scenes.push_back(data);
    }
    auto files = find_scene_files(options->scenes);
    if (!files) return usage_error(files.error().message);
    if (files->empty()) return usage_error("no .gltf or .glb file found");

    const auto start = std::chrono::steady_clock::now();
    auto runner = CaseRunner::create(*options);
    if (!runner) {
        std::fprintf(stderr, "loom-compare: %s\n", runner.error().to_string().c_str());
        return EXIT_FAILURE;
    }
    std::vector<CaseResult> cases;
    for (const SceneFile& file : *files) {
        for (CaseResult& result : (*runner)->run(file)) {
            std::fprintf(stderr, "%-4s %s [%s]%s%s\n", result.passed() ? "ok" : "FAIL", result.scene.c_str(),
                         result.pipeline.c_str(), result.passed() ? "" : ": ",
                         result.passed() ? "" : result.failures.front().c_str());
            cases.push_back(std::move(result));
        }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    RunInfo run{&*options, (*runner)->backends(), summarize(cases, seconds)};
    runner->reset();  // the devices, before writing

    std::error_code ec;
    std::filesystem::create_directories(options->out, ec);
    const std::string json = report_json(cases, run);
    for (auto [name, text] : {std::pair{"report.html", report_html(cases, run)}, std::pair{"report.json", json}}) {
        if (auto written = write_text(options->out / name, text); !written) {
            std::fprintf(stderr, "loom-compare: %s\n", written.error().to_string().c_str());
            return EXIT_FAILURE;
        }
    }
    if (options->json) std::printf("%s", json.c_str());
    std::fprintf(stderr, "loom-compare: %u case(s), %u passed, %u failed in %.1f s; report: %s\n", run.summary.cases,
                 run.summary.passed, run.summary.failed, seconds, (options->out / "report.html").string().c_str());
    return run.summary.failed == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

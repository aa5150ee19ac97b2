#include "case_runner.hpp"

#include <chrono>
#include <cstdio>
#include <cmath>
#include <utility>

#include "inspect_page.hpp"
#include "log_router.hpp"
#include "loom/gltf/gltf.hpp"
#include "loom/image_io/image_io.hpp"
#include "loom/renderer/gltf_scene.hpp"
#include "loom/rhi/log.hpp"

namespace loom::compare {
namespace {

using Clock = std::chrono::steady_clock;

double milliseconds_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::string safe_id(const std::string& text) {
    std::string id;
    for (char c : text) {
        const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '-';
        id += keep ? c : '_';
    }
    return id;
}

/// What compare_images found, as the reports keep it (the heat map's file is added when written).
ImageMetrics metrics_of(const rhi::ImageComparison& comparison) {
    ImageMetrics metrics;
    metrics.max_channel_diff = comparison.max_channel_diff;
    metrics.pixels_above_threshold = comparison.pixels_above_threshold;
    metrics.pixel_count = comparison.pixel_count;
    metrics.psnr = comparison.psnr;
    return metrics;
}

/// One line of an error message (the importer's are one line already; a backend's may not be).
std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

/// The inspector page of `pipeline`'s latest frame on `device`, as loom-deferred --inspect and
/// loom-inspect make it, to cases/<id>/<backend>.inspector.html beside the case's pictures; named
/// in `run` when written, a failure of `result` naming the file when not.
void write_inspector_page(const std::filesystem::path& out, CaseResult& result, BackendRun& run,
                          renderer::DeferredPipeline& pipeline, const rhi::Device& device) {
    const std::string backend(rhi::backend_name(run.backend));
    const std::filesystem::path file = std::filesystem::path("cases") / result.id / (backend + ".inspector.html");
    std::error_code ignored;  // a directory that cannot be made is the page's Io error below
    std::filesystem::create_directories((out / file).parent_path(), ignored);
    // Compared on the options the frame was planned with, so the figures match the plan's.
    const fg::PlanOptions planned = pipeline.executor().effective_options(pipeline.options());
    const std::string source = "loom-compare on " + backend + ", " + device.capabilities().device_name;
    const std::string title = result.scene + " — " + result.pipeline + " on " + backend;
    if (Status written =
            inspect::write_executor_page(out / file, pipeline.executor(), pipeline.graph(), planned, source, title);
        !written) {
        result.failures.push_back(backend + " inspector page " + file.generic_string() + ": " +
                                  first_line(written.error().to_string()));
        return;
    }
    run.inspector_file = file.generic_string();
}

}  // namespace

Result<std::unique_ptr<CaseRunner>> CaseRunner::create(const Options& options) {
    std::unique_ptr<CaseRunner> runner(new CaseRunner(options));
    runner->library_ = std::make_shared<passes::ShaderLibrary>();
    for (rhi::Backend backend : rhi::compiled_backends()) {
        rhi::DeviceDesc desc;
        desc.backend = backend;
        desc.headless = true;
        desc.debug = true;
        auto device = rhi::create_device(desc);
        if (!device) {
            return make_error(device.error().code, std::string(rhi::backend_name(backend)) + ": " + device.error().message);
        }
        runner->devices_.push_back(std::move(*device));
    }
    if (runner->devices_.empty()) return make_error(ErrorCode::Unsupported, "no backend compiled in");
    return runner;
}

CaseRunner::~CaseRunner() = default;

std::vector<rhi::Backend> CaseRunner::backends() const {
    std::vector<rhi::Backend> out;
    for (const auto& device : devices_) out.push_back(device->backend());
    return out;
}

CaseResult CaseRunner::new_case(const SceneFile& file, const std::string& pipeline) {
    CaseResult result;
    result.scene = file.name;
    result.file = file.path.string();
    result.pipeline = pipeline;
    const std::string base = safe_id(file.name) + "." + pipeline;
    result.id = base;
    for (int n = 2; !used_ids_.insert(result.id).second; ++n) result.id = base + "-" + std::to_string(n);
    return result;
}

CaseResult CaseRunner::expect_error(const SceneFile& file) {
    CaseResult result = new_case(file, "load");
    LogRouter router;
    std::vector<std::string> messages;
    router.route(&messages);
    auto scene = gltf::load(file.path);
    router.route(nullptr);
    for (const std::string& message : messages) result.failures.push_back("logged while loading: " + message);
    if (scene) {
        result.warnings = scene->warnings;  // the JSON report lists them: what the importer let through
        result.failures.push_back("loaded without an error (" + std::to_string(scene->draw_items.size()) +
                                  " draw items); an invalid file must be rejected");
        return result;
    }
    result.load_error = scene.error().to_string();
    // A clean error: one line that names the file.
    if (result.load_error.find('\n') != std::string::npos) result.failures.push_back("the error is not one line");
    if (result.load_error.find(file.path.filename().string()) == std::string::npos) {
        result.failures.push_back("the error does not name the file " + file.path.filename().string());
    }
    return result;
}

std::vector<CaseResult> CaseRunner::run(const SceneFile& file) {
    if (options_.expect_errors) return {expect_error(file)};

    LogRouter router;
    std::vector<std::string> load_messages;
    router.route(&load_messages);
    auto prepared = renderer::load_gltf_scene(file.path);
    router.route(nullptr);
    if (!prepared) {
        CaseResult result = new_case(file, "load");
        result.load_error = prepared.error().to_string();
        result.failures.push_back("does not load: " + result.load_error);
        return {result};
    }
    const scene::Scene& scene = (*prepared)->scene;
    auto viewpoint = renderer::SceneViewpoint::choose(scene);
    if (!viewpoint) {
        CaseResult result = new_case(file, "load");
        result.failures.push_back(viewpoint.error().to_string());
        return {result};
    }

    std::vector<CaseResult> results;
    for (PipelineKind pipeline : options_.pipelines) {
        CaseResult result = new_case(file, std::string(pipeline_name(pipeline)));
        result.warnings = scene.warnings;
        for (const auto& device : devices_) result.runs.emplace_back(device->backend());
        for (const std::string& message : load_messages) result.failures.push_back("logged while loading: " + message);
        results.push_back(std::move(result));
    }
    // images[case][backend]
    std::vector<std::vector<rhi::Image>> images(results.size(), std::vector<rhi::Image>(devices_.size()));

    for (std::size_t b = 0; b < devices_.size(); ++b) {
        rhi::Device& device = *devices_[b];
        std::vector<std::string> upload_messages;
        router.route(&upload_messages);
        const Clock::time_point upload_start = Clock::now();
        auto gpu = renderer::GpuScene::create(device, *prepared);
        const double upload_ms = milliseconds_since(upload_start);
        for (std::size_t c = 0; c < results.size(); ++c) {
            BackendRun& run = results[c].runs[b];
            run.messages = upload_messages;
            run.milliseconds = upload_ms;
            if (!gpu) {
                run.error = "upload: " + first_line(gpu.error().to_string());
                continue;
            }
            router.route(&run.messages);
            const Clock::time_point start = Clock::now();
            renderer::PipelineScene content = renderer::gltf_pipeline_scene(*gpu, *viewpoint);
            if (b == 0) results[c].scene_info = renderer::describe_gltf_scene(scene, content, *viewpoint);
            renderer::PipelineSettings settings;
            settings.forward = options_.pipelines[c] == PipelineKind::Forward;
            settings.capture = false;
            settings.library = library_;
            auto pipeline = renderer::DeferredPipeline::create(device, std::move(content), settings);
            Status status = pipeline ? (*pipeline)->render({options_.width, options_.height}) : Status(pipeline.error());
            if (status) status = device.wait_idle();
            if (status) {
                auto image = device.read_texture((*pipeline)->final_texture());
                if (image) {
                    images[c][b] = std::move(*image);
                } else {
                    status = image.error();
                }
            }
            if (pipeline && (*pipeline)->executor().plan()) {
                run.plan = *(*pipeline)->executor().plan();
                run.stats = (*pipeline)->executor().stats();
            }
            if (!status) run.error = first_line(status.error().to_string());
            run.milliseconds += milliseconds_since(start);
            // After the timing: the page is the report's, not the frame's.
            if (options_.inspector_pages && run.plan)
                write_inspector_page(options_.out, results[c], run, **pipeline, device);
        }
        // The pipelines are gone; what the scene's buffers and textures say on their way out
        // belongs to every case of this backend.
        std::vector<std::string> teardown;
        router.route(&teardown);
        if (gpu) gpu->reset();
        if (Status idle = device.wait_idle(); !idle) teardown.push_back(idle.error().to_string());
        router.route(nullptr);
        for (CaseResult& result : results) {
            result.runs[b].messages.insert(result.runs[b].messages.end(), teardown.begin(), teardown.end());
        }
    }

    for (std::size_t c = 0; c < results.size(); ++c) {
        const std::optional<rhi::Image> heatmap = compare(results[c], images[c]);
        if (Status written = write_pictures(results[c], images[c], heatmap); !written) {
            results[c].failures.push_back("pictures: " + written.error().to_string());
        }
    }
    // The two pipelines against each other, when both ran.
    std::optional<std::size_t> deferred, forward;
    for (std::size_t c = 0; c < results.size(); ++c) {
        if (options_.pipelines[c] == PipelineKind::Deferred) deferred = c;
        if (options_.pipelines[c] == PipelineKind::Forward) forward = c;
    }
    if (deferred && forward) compare_pipelines(results[*deferred], images[*deferred], results[*forward], images[*forward]);
    return results;
}

void CaseRunner::compare_pipelines(const CaseResult& deferred, const std::vector<rhi::Image>& deferred_images,
                                   CaseResult& forward, const std::vector<rhi::Image>& forward_images) {
    rhi::ImageCompareOptions compare_options;
    compare_options.threshold = kPipelineThreshold;
    for (std::size_t b = 0; b < forward.runs.size(); ++b) {
        if (!deferred.runs[b].rendered() || !forward.runs[b].rendered()) continue;
        if (deferred_images[b].empty() || forward_images[b].empty()) continue;
        const std::string backend(rhi::backend_name(forward.runs[b].backend));
        auto comparison = rhi::compare_images(deferred_images[b], forward_images[b], compare_options);
        if (!comparison) {
            forward.failures.push_back("forward against deferred on " + backend + ": " + comparison.error().to_string());
            continue;
        }
        const auto allowed =
            static_cast<uint64_t>(std::floor(kPipelineMaxDiffering * static_cast<double>(comparison->pixel_count)));
        if (comparison->pixels_above_threshold > allowed) {
            forward.failures.push_back("forward differs from deferred on " + backend + ": " + comparison->summary() +
                                       " (allowed: " + std::to_string(allowed) + " pixels above " +
                                       std::to_string(static_cast<int>(kPipelineThreshold)) + ")");
        }
        if (forward.against_deferred) continue;
        ImageMetrics metrics = metrics_of(*comparison);
        if (comparison->heatmap) {
            const std::filesystem::path file = std::filesystem::path("cases") / forward.id / "vs-deferred.png";
            if (Status written = image_io::write_png(*comparison->heatmap, options_.out / file); written) {
                metrics.diff_file = file.generic_string();
            } else {
                forward.failures.push_back("pictures: " + written.error().to_string());
            }
        }
        forward.against_deferred = metrics;
    }
}

std::optional<rhi::Image> CaseRunner::compare(CaseResult& result, const std::vector<rhi::Image>& images) {
    std::vector<std::size_t> rendered;
    for (std::size_t b = 0; b < result.runs.size(); ++b) {
        const BackendRun& run = result.runs[b];
        const std::string backend(rhi::backend_name(run.backend));
        if (!run.error.empty()) result.failures.push_back(backend + " did not render: " + run.error);
        if (!run.messages.empty()) {
            result.failures.push_back(backend + " logged " + std::to_string(run.messages.size()) +
                                      " error/API message(s), the first: " + first_line(run.messages.front()));
        }
        if (!run.rendered()) continue;
        rendered.push_back(b);
        // What the backend created is the plan: one texture per plan texture, its bytes.
        const uint64_t bytes = plan_texture_bytes(*run.plan);
        if (run.stats.textures != run.plan->textures.size() || run.stats.texture_bytes != bytes) {
            result.failures.push_back(backend + " created " + std::to_string(run.stats.textures) + " textures (" +
                                      std::to_string(run.stats.texture_bytes) + " bytes) for a plan of " +
                                      std::to_string(run.plan->textures.size()) + " (" + std::to_string(bytes) +
                                      " bytes)");
        }
    }
    if (rendered.size() < 2) return std::nullopt;
    const BackendRun& a = result.runs[rendered[0]];
    const std::string a_name(rhi::backend_name(a.backend));
    for (std::size_t i = 1; i < rendered.size(); ++i) {
        const BackendRun& b = result.runs[rendered[i]];
        const std::string b_name(rhi::backend_name(b.backend));
        if (fg::plan_hash(*a.plan) != fg::plan_hash(*b.plan) || !(*a.plan == *b.plan)) {
            result.failures.push_back("plans differ: " + a_name + " " + plan_hash_text(*a.plan) + ", " + b_name + " " +
                                      plan_hash_text(*b.plan));
        }
        if (a.stats.textures != b.stats.textures || a.stats.texture_bytes != b.stats.texture_bytes) {
            result.failures.push_back("created resources differ: " + a_name + " " + std::to_string(a.stats.textures) +
                                      " textures (" + std::to_string(a.stats.texture_bytes) + " bytes), " + b_name +
                                      " " + std::to_string(b.stats.textures) + " (" +
                                      std::to_string(b.stats.texture_bytes) + " bytes)");
        }
    }
    // The pictures: the first two backends (GL and Vulkan when both are compiled in).
    rhi::ImageCompareOptions compare_options;
    compare_options.threshold = options_.threshold;
    auto comparison = rhi::compare_images(images[rendered[0]], images[rendered[1]], compare_options);
    if (!comparison) {
        result.failures.push_back("pictures: " + comparison.error().to_string());
        return std::nullopt;
    }
    ImageMetrics metrics = metrics_of(*comparison);
    const auto allowed = static_cast<uint64_t>(std::floor(options_.max_differing * static_cast<double>(metrics.pixel_count)));
    if (metrics.pixels_above_threshold > allowed) {
        char allowance[96];
        std::snprintf(allowance, sizeof(allowance), " (allowed: %llu pixels above %g)",
                      static_cast<unsigned long long>(allowed), options_.threshold);
        result.failures.push_back("pictures differ: " + comparison->summary() + allowance);
    }
    result.image = metrics;
    return std::move(comparison->heatmap);
}

Status CaseRunner::write_pictures(CaseResult& result, const std::vector<rhi::Image>& images,
                                  const std::optional<rhi::Image>& heatmap) {
    const std::filesystem::path relative = std::filesystem::path("cases") / result.id;
    std::error_code ec;
    std::filesystem::create_directories(options_.out / relative, ec);
    if (ec) return make_error(ErrorCode::Io, (options_.out / relative).string() + ": " + ec.message());
    for (std::size_t b = 0; b < result.runs.size(); ++b) {
        if (images[b].empty()) continue;
        const std::filesystem::path file = relative / (std::string(rhi::backend_name(result.runs[b].backend)) + ".png");
        LOOM_TRY(image_io::write_png(images[b], options_.out / file));
        result.runs[b].image_file = file.generic_string();
    }
    if (heatmap && result.image) {
        const std::filesystem::path file = relative / "diff.png";
        LOOM_TRY(image_io::write_png(*heatmap, options_.out / file));
        result.image->diff_file = file.generic_string();
    }
    return {};
}

}  // namespace loom::compare

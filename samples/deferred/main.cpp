// loom-deferred: the paper's Figure 2 pipeline (shadow map → G-buffer → deferred lighting with
// shadows and high pass → blur → composite with bloom and tone mapping) on one frame graph, on
// GL or Vulkan. Headless it writes the final frame, every intermediate texture (the paper's
// Figures 3-7), the plan as JSON and DOT, and prints what the plan and the device used. The
// scene is the built-in procedural one or a glTF file (--scene FILE).
#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <fstream>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <string>

#include "loom/image_io/image_io.hpp"
#include "loom/renderer/deferred_pipeline.hpp"
#include "loom/renderer/gltf_scene.hpp"
#include "loom/framegraph/export.hpp"
#include "loom/framegraph/plan.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/image.hpp"
#include "loom/sample_common/options.hpp"
#include "loom/sample_common/output.hpp"
#include "inspect_input.hpp"
#include "animation_playback.hpp"
#include "deferred_controls.hpp"
#include "procedural_scene.hpp"
#include "soak.hpp"
#include "soak_plot.hpp"
#include "visualize.hpp"

namespace {

constexpr const char* kName = "loom-deferred";

int fail(const std::string& message) {
    std::fprintf(stderr, "%s: %s\n", kName, message.c_str());
    return EXIT_FAILURE;
}
int fail(const loom::Error& error) { return fail(error.to_string()); }

struct Options {
    loom::samples::CommonOptions common;
    uint64_t frames = 1;
    /// --allocator; none: the one that needs the fewest bytes on the device (choose_allocator).
    std::optional<loom::fg::AllocatorKind> allocator;
    loom::fg::PassOrder order = loom::fg::kDefaultPassOrder;
    bool forward = false;
    /// A glTF file; empty: the built-in scene.
    std::filesystem::path scene;
    std::optional<uint32_t> camera;
    /// --time SECONDS: the file's animations posed at that time (scene::pose); none: the static pose.
    std::optional<float> time;
    /// --animate N: frames of the animation run (0: none).
    uint32_t animate = 0;
    /// --soak N: frames of the soak run (0: no soak run).
    uint64_t soak = 0;
    uint32_t resize_every = 100;
    uint32_t rebuild_every = 10;
    /// --inspect FILE: the inspector input of the last frame (headless); empty: none.
    std::filesystem::path inspect;
    /// --overlay: the frame overlay shown from the first frame (--window; F1 toggles it).
    bool overlay = false;
    /// --screenshot FILE: the back buffer of the last frame as a PNG (--window); empty: none.
    std::filesystem::path screenshot;
};

const char* kUsage =
    "usage: loom-deferred [options]\n"
    "Renders the paper's Figure 2 pipeline (shadow map, G-buffer, deferred lighting with shadows\n"
    "and high pass, separable blur, composite with bloom and tone mapping) on a procedural scene\n"
    "or a glTF 2.0 file (.gltf or .glb).\n"
    "Headless, it writes into --out DIR: final.png, one PNG per pass output (<pass>.<port>.png),\n"
    "geometry.material.png and figure3-gbuffer.png, plan.json, plan.dot and summary.txt.\n\n";

std::string extra_help() {
    return "  --frames N            frames to render (default 1; with --window 0 runs until closed)\n"
           "  --allocator NAME      paper, interval, heap or auto (the default: heap where the device places\n"
           "                        resources and it needs fewer bytes, as on Vulkan; interval otherwise, as on GL)\n"
           "  --scene FILE|builtin  a glTF 2.0 file (.gltf, .glb), or the built-in procedural scene (the default)\n"
           "  --camera N            the file's camera N (default: its first camera, or one framing the scene)\n"
           "  --time SECONDS        pose the file's animations at SECONDS (each in file order; default: the\n"
           "                        file's static pose)\n"
           "  --animate N           play the file's animations for N frames (headless), sampled evenly from 0 s\n"
           "                        to the end of the longest, through the retained object layer and, side by\n"
           "                        side, through per-draw objects; writes animation.png (a contact sheet of\n"
           "                        the frames), animation.csv (bytes uploaded per frame by each path) and\n"
           "                        animation.txt into --out DIR; fails unless both paths draw the same pictures\n"
           "  --order NAME          pass order: memory (the default: the lowest peak of live bytes) or\n"
           "                        declared; the same pictures\n"
           "  --pipeline NAME       deferred (Figure 2, the default) or forward (one forward pass with the\n"
           "                        same shadow-render and high-pass-render parts)\n"
           "  --soak N              soak run of N frames (headless): resize every --resize-every frames\n"
           "                        (default 100; between --size and 3/4 of it), rebuild the graph with the\n"
           "                        lit pass toggled (deferred <-> forward) every --rebuild-every frames\n"
           "                        (default 10); writes soak.csv, soak.svg and soak.txt into --out DIR and\n"
           "                        fails unless the live GPU objects repeat exactly once warmed up\n"
           "                        (docs/soak.md); N must exceed two periods (400 frames by default)\n"
           "  --inspect FILE        also write the inspector input of the last frame (plan, barriers, timings,\n"
           "                        allocations, every allocator's memory) for loom-inspect (docs/inspector.md)\n"
           "  --overlay             with --window: show the frame overlay from the start (F1 shows and hides it:\n"
           "                        passes, GPU/CPU times, memory, allocator and pass switches that re-plan)\n"
           "  --screenshot FILE     with --window: write the last frame's back buffer (overlay included) as a PNG\n";
}

loom::Result<Options> parse(int argc, char** argv) {
    loom::samples::CommonDefaults defaults;
    defaults.width = 1280;
    defaults.height = 720;
    defaults.out = "out/deferred";
    auto common = loom::samples::parse_common_options(argc, argv, defaults);
    if (!common) return common.take_error();
    Options options;
    options.common = std::move(*common);
    loom::samples::ArgumentReader args(options.common.rest);
    while (args.next()) {
        const std::string& name = args.name();
        auto take = [&] { return args.value(); };
        if (name == "--frames") {
            auto v = take();
            if (!v) return v.take_error();
            char* end = nullptr;
            const unsigned long long n = std::strtoull(v->c_str(), &end, 10);
            if (v->empty() || *end != '\0') {
                return loom::make_error(loom::ErrorCode::InvalidArgument, "--frames expects a number, got '" + *v + "'");
            }
            options.frames = n;
        } else if (name == "--soak" || name == "--resize-every" || name == "--rebuild-every") {
            auto v = take();
            if (!v) return v.take_error();
            char* end = nullptr;
            const unsigned long long n = std::strtoull(v->c_str(), &end, 10);
            const uint64_t max = name == "--soak" ? UINT64_MAX : UINT32_MAX;
            if (v->empty() || *end != '\0' || (*v)[0] == '-' || n == 0 || n > max) {
                return loom::make_error(loom::ErrorCode::InvalidArgument,
                                        name + " expects a positive number, got '" + *v + "'");
            }
            if (name == "--soak") options.soak = n;
            if (name == "--resize-every") options.resize_every = static_cast<uint32_t>(n);
            if (name == "--rebuild-every") options.rebuild_every = static_cast<uint32_t>(n);
        } else if (name == "--allocator") {
            auto v = take();
            if (!v) return v.take_error();
            if (*v != "auto") {
                auto kind = loom::fg::parse_allocator(*v);
                if (!kind) {
                    return loom::make_error(loom::ErrorCode::InvalidArgument, "--allocator: " + kind.error().message + " (or auto)");
                }
                options.allocator = *kind;
            }
        } else if (name == "--pipeline") {
            auto v = take();
            if (!v) return v.take_error();
            if (*v != "deferred" && *v != "forward") {
                return loom::make_error(loom::ErrorCode::InvalidArgument,
                                        "--pipeline expects deferred or forward, got '" + *v + "'");
            }
            options.forward = *v == "forward";
        } else if (name == "--order") {
            auto v = take();
            if (!v) return v.take_error();
            auto order = loom::fg::parse_pass_order(*v);
            if (!order) {
                return loom::make_error(loom::ErrorCode::InvalidArgument, "--order expects declared or memory, got '" + *v + "'");
            }
            options.order = *order;
        } else if (name == "--inspect") {
            auto v = take();
            if (!v) return v.take_error();
            if (v->empty()) return loom::make_error(loom::ErrorCode::InvalidArgument, "--inspect needs a file");
            options.inspect = *v;
        } else if (name == "--overlay") {
            options.overlay = true;
        } else if (name == "--screenshot") {
            auto v = take();
            if (!v) return v.take_error();
            if (v->empty()) return loom::make_error(loom::ErrorCode::InvalidArgument, "--screenshot needs a file");
            options.screenshot = *v;
        } else if (name == "--scene") {
            auto v = take();
            if (!v) return v.take_error();
            if (v->empty()) return loom::make_error(loom::ErrorCode::InvalidArgument, "--scene needs a file or 'builtin'");
            options.scene = *v == "builtin" ? std::filesystem::path() : std::filesystem::path(*v);
        } else if (name == "--camera") {
            auto v = take();
            if (!v) return v.take_error();
            char* end = nullptr;
            const unsigned long n = std::strtoul(v->c_str(), &end, 10);
            if (v->empty() || *end != '\0' || (*v)[0] == '-' || n > UINT32_MAX) {
                return loom::make_error(loom::ErrorCode::InvalidArgument, "--camera expects a camera index, got '" + *v + "'");
            }
            options.camera = static_cast<uint32_t>(n);
        } else if (name == "--animate") {
            auto v = take();
            if (!v) return v.take_error();
            char* end = nullptr;
            const unsigned long long n = std::strtoull(v->c_str(), &end, 10);
            if (v->empty() || *end != '\0' || n == 0 || n > 4096) {
                return loom::make_error(loom::ErrorCode::InvalidArgument,
                                        "--animate expects a number of frames (1 to 4096), got '" + *v + "'");
            }
            options.animate = static_cast<uint32_t>(n);
        } else if (name == "--time") {
            auto v = take();
            if (!v) return v.take_error();
            char* end = nullptr;
            const float seconds = std::strtof(v->c_str(), &end);
            if (v->empty() || *end != '\0' || !std::isfinite(seconds) || seconds < 0.0f) {
                return loom::make_error(loom::ErrorCode::InvalidArgument,
                                        "--time expects seconds (a number, 0 or more), got '" + *v + "'");
            }
            options.time = seconds;
        } else {
            return args.unknown();
        }
    }
    if (!options.inspect.empty() && (options.common.window || options.soak != 0)) {
        return loom::make_error(loom::ErrorCode::InvalidArgument, "--inspect writes the headless frame's input (leave out --window and --soak)");
    }
    if ((options.overlay || !options.screenshot.empty()) && !options.common.window) {
        return loom::make_error(loom::ErrorCode::InvalidArgument,
                                std::string(options.overlay ? "--overlay" : "--screenshot") + " needs --window");
    }
    if (!options.screenshot.empty() && options.frames == 0) {
        return loom::make_error(loom::ErrorCode::InvalidArgument, "--screenshot needs a last frame (--frames N, not 0)");
    }
    if (options.camera && options.scene.empty()) {
        return loom::make_error(loom::ErrorCode::InvalidArgument, "--camera needs a glTF scene (--scene FILE)");
    }
    if (options.time && options.scene.empty()) {
        return loom::make_error(loom::ErrorCode::InvalidArgument, "--time needs a glTF scene (--scene FILE)");
    }
    if (options.animate != 0) {
        if (options.scene.empty()) {
            return loom::make_error(loom::ErrorCode::InvalidArgument, "--animate needs a glTF scene (--scene FILE)");
        }
        if (options.common.window || options.soak != 0 || options.time || !options.inspect.empty()) {
            return loom::make_error(loom::ErrorCode::InvalidArgument,
                                    "--animate runs headless on its own (leave out --window, --soak, --time and --inspect)");
        }
    }
    if (options.soak != 0) {
        if (options.common.window) {
            return loom::make_error(loom::ErrorCode::InvalidArgument, "--soak runs headless (leave out --window)");
        }
        loom::deferred::SoakSettings soak;
        soak.resize_every = options.resize_every;
        soak.rebuild_every = options.rebuild_every;
        const uint64_t period = loom::deferred::soak_period(soak);
        if (period > UINT64_MAX / 2 || options.soak <= 2 * period) {
            return loom::make_error(loom::ErrorCode::InvalidArgument,
                                    "--soak " + std::to_string(options.soak) + " is too short: the check compares each frame after a " +
                                        "warm-up period with one period earlier, so it needs more than two periods (" +
                                        std::to_string(period) + " frames each with these settings)");
        }
    }
    if (!options.common.window && options.frames == 0) {
        return loom::make_error(loom::ErrorCode::InvalidArgument, "--frames 0 only makes sense with --window");
    }
    return options;
}

std::string file_name(const std::string& texture) { return texture + ".png"; }

/// The pipeline settings the options choose (allocator, lit pass); the callers add the rest.
loom::renderer::PipelineSettings pipeline_settings(const Options& options) {
    loom::renderer::PipelineSettings settings;
    settings.allocator = options.allocator.value_or(loom::fg::AllocatorKind::Interval);
    settings.order = options.order;
    settings.forward = options.forward;
    return settings;
}

/// Without --allocator: the pipeline rebuilt with the allocator that needs the fewest bytes for
/// a frame of --size on this device (Executor::cheapest_allocator: heap on Vulkan where it
/// saves memory, interval on GL).
loom::Status choose_allocator(loom::renderer::DeferredPipeline& pipeline, const Options& options) {
    if (options.allocator) return {};
    loom::fg::PlanOptions planned;
    planned.frame = {options.common.width, options.common.height};
    planned.order = options.order;
    auto kind = pipeline.executor().cheapest_allocator(pipeline.graph(), planned);
    if (!kind) return kind.take_error();
    if (*kind == pipeline.settings().allocator) return {};
    loom::renderer::PipelineSettings settings = pipeline.settings();
    settings.allocator = *kind;
    return pipeline.rebuild(settings);
}

/// The pipeline on the scene the options name (built-in, or a glTF file seen from its camera).
/// `scene_line` says what was loaded, for the summary.
loom::Result<std::unique_ptr<loom::renderer::DeferredPipeline>> load_pipeline(loom::rhi::Device& device,
                                                                             const Options& options,
                                                                             const loom::renderer::PipelineSettings& settings,
                                                                             std::string& scene_line) {
    using namespace loom;
    if (options.scene.empty()) {
        scene_line = "scene: builtin (procedural)";
        return deferred::create_procedural_pipeline(device, deferred::procedural_scene(), settings);
    }
    auto loaded = renderer::load_gltf_scene(options.scene);
    if (!loaded) return loaded.take_error();
    std::shared_ptr<const renderer::PreparedScene> prepared = *loaded;
    std::string pose_line;
    if (options.time) {
        // The geometry and images stay; the nodes and draw items move.
        auto posed = std::make_shared<renderer::PreparedScene>(*prepared);
        for (const scene::Animation& animation : posed->scene.animations) scene::pose(posed->scene, animation, *options.time);
        pose_line = "; posed at " + std::to_string(*options.time) + " s (" +
                    std::to_string(posed->scene.animations.size()) + " animation(s))";
        prepared = std::move(posed);
    }
    const scene::Scene& scene = prepared->scene;
    auto viewpoint = renderer::SceneViewpoint::choose(scene, options.camera);
    if (!viewpoint) return viewpoint.take_error();
    auto gpu = renderer::GpuScene::create(device, prepared);
    if (!gpu) return gpu.take_error();
    renderer::PipelineScene content = renderer::gltf_pipeline_scene(*gpu, *viewpoint);
    scene_line = "scene: " + options.scene.string() + ": " + renderer::describe_gltf_scene(scene, content, *viewpoint) +
                 "; textures with mipmaps: " + fg::format_bytes((*gpu)->texture_bytes()) + pose_line;
    for (const std::string& warning : scene.warnings) scene_line += "\n  warning: " + warning;
    return renderer::DeferredPipeline::create(device, std::move(content), settings);
}

/// load_pipeline, then choose_allocator.
loom::Result<std::unique_ptr<loom::renderer::DeferredPipeline>> make_pipeline(loom::rhi::Device& device,
                                                                             const Options& options,
                                                                             const loom::renderer::PipelineSettings& settings,
                                                                             std::string& scene_line) {
    auto pipeline = load_pipeline(device, options, settings, scene_line);
    if (!pipeline) return pipeline.take_error();
    LOOM_TRY(choose_allocator(**pipeline, options));
    return pipeline;
}

/// The plan, what the device created for it, and the timings of the latest frame.
std::string summary(const loom::renderer::DeferredPipeline& pipeline, loom::fg::Executor& executor,
                    loom::rhi::Device& device, const Options& options, const std::string& scene_line) {
    using loom::fg::format_bytes;
    const auto plan = executor.plan();
    std::ostringstream out;
    const auto& caps = device.capabilities();
    out << kName << ": " << loom::rhi::backend_name(device.backend()) << ", " << caps.device_name << ", "
        << plan->frame.width << "x" << plan->frame.height << ", allocator " << plan->allocator
        << (options.allocator ? "" : " (auto)")
        << ", " << loom::fg::pass_order_name(plan->pass_order) << " order, " << options.frames
        << " frame(s)\n";
    out << scene_line << "\n";
    char hash[32];
    std::snprintf(hash, sizeof(hash), "%016" PRIx64, loom::fg::plan_hash(*plan));
    out << "plan " << hash << ": " << plan->order.size() << " passes, " << plan->resources.size() << " resources -> "
        << plan->summary.textures << " textures (naive " << plan->summary.naive_textures << ", lower bound "
        << plan->summary.lower_bound_textures << "), " << format_bytes(plan->summary.bytes) << " (naive "
        << format_bytes(plan->summary.naive_bytes) << ", lower bound " << format_bytes(plan->summary.lower_bound_bytes)
        << ")\n";
    for (const auto& cls : plan->spec_classes) {
        uint32_t textures = 0;
        for (const auto& texture : plan->textures) {
            if (loom::fg::same_texture_shape(texture.spec, cls.spec)) ++textures;
        }
        std::string names;
        for (uint32_t r : cls.resources) names += (names.empty() ? "" : ", ") + plan->resources[r].name;
        out << "  " << loom::fg::describe_resolved(cls.spec) << ": " << textures << " texture(s) for "
            << cls.resources.size() << " output(s): " << names << "\n";
    }
    if (options.scene.empty()) {
        out << "  (the paper, with a one-pass blur: 5 colour textures for 7 outputs, plus the depth map)\n";
    }
    const loom::fg::ExecutionStats stats = executor.stats();
    out << "created: " << stats.textures << " textures for the plan's " << stats.plan_textures << " ("
        << stats.placed_textures << " placed in " << stats.heaps << " heap(s), " << format_bytes(stats.heap_bytes)
        << "), " << format_bytes(stats.texture_bytes) << " in unplaced textures; device total: "
        << stats.device.textures << " textures, " << stats.device.buffers << " buffers, " << stats.device.pipelines
        << " pipelines, " << format_bytes(stats.device.total_bytes()) << "\n";
    out << "programs: composed " << pipeline.library().requests() << " stages, compiled "
        << pipeline.library().compilations() << "\n";
    out << "timings of the latest frame (ms):\n";
    out << "  pass              gpu       cpu\n";
    double gpu_total = 0.0, cpu_total = 0.0;
    for (const auto& timing : executor.timings()) {
        char line[128];
        if (timing.gpu_ms) {
            std::snprintf(line, sizeof(line), "  %-14s %8.3f  %8.3f\n", timing.pass.c_str(), *timing.gpu_ms, timing.cpu_ms);
            gpu_total += *timing.gpu_ms;
        } else {
            std::snprintf(line, sizeof(line), "  %-14s %8s  %8.3f\n", timing.pass.c_str(), "n/a", timing.cpu_ms);
        }
        cpu_total += timing.cpu_ms;
        out << line;
    }
    char total[128];
    std::snprintf(total, sizeof(total), "  %-14s %8.3f  %8.3f\n", "total", gpu_total, cpu_total);
    out << total;
    return out.str();
}

loom::Status write_text(const std::filesystem::path& path, const std::string& text) {
    std::ofstream file(path, std::ios::binary);
    file << text;
    if (!file) return loom::make_error(loom::ErrorCode::Io, "cannot write " + path.string());
    return {};
}

/// Reads back every intermediate and the final frame and writes them as pictures.
loom::Status write_pictures(loom::rhi::Device& device, const loom::renderer::DeferredPipeline& pipeline,
                            const std::filesystem::path& dir, std::vector<std::string>& written) {
    std::map<std::string, loom::rhi::Image> images;
    for (const auto& intermediate : pipeline.intermediates()) {
        auto image = device.read_texture(intermediate.texture);
        if (!image) return image.take_error();
        images.emplace(intermediate.name, std::move(*image));
    }
    auto final_image = device.read_texture(pipeline.final_texture());
    if (!final_image) return final_image.take_error();

    loom::deferred::DisplaySettings display;
    display.scene_bounds = pipeline.scene().bounds;
    std::map<std::string, loom::rhi::Image> pictures;
    for (const auto& [name, image] : images) pictures[name] = loom::deferred::visualize(name, image, images, display);
    auto have = [&](const char* n) { return images.count(n) != 0; };
    if (have("geometry.position") && have("geometry.normal") && have("geometry.albedo") && have("geometry.emission")) {
        pictures["geometry.material"] = loom::deferred::material_map(images["geometry.position"], images["geometry.normal"],
                                                                     images["geometry.emission"]);
        // The 2x2 mosaic halves each map: only for frames of at least 2x2.
        if (final_image->width >= 2 && final_image->height >= 2) {
            pictures["figure3-gbuffer"] = loom::deferred::mosaic(pictures["geometry.position"], pictures["geometry.normal"],
                                                                 pictures["geometry.albedo"], pictures["geometry.material"]);
        }
    }
    pictures["final"] = loom::deferred::visualize("present.target", *final_image, images, display);

    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    for (const auto& [name, picture] : pictures) {
        LOOM_TRY(loom::image_io::write_png(picture, dir / file_name(name)));
        written.push_back(file_name(name));
    }
    return {};
}

int run_window(const Options& options) {
    using namespace loom;
    auto device = rhi::create_device(samples::device_desc(options.common, "loom deferred"));
    if (!device) return fail(device.error());
    rhi::Device& dev = **device;
    // The back buffer's format decides the present pass's target (and whether the composite
    // encodes sRGB itself).
    rhi::CommandList& first = dev.begin_frame();
    (void)first;
    auto desc = dev.texture_desc(dev.backbuffer());
    if (auto ended = dev.end_frame(); !ended) return fail(ended.error());
    if (!desc) return fail(desc.error());
    renderer::PipelineSettings settings = pipeline_settings(options);
    settings.capture = false;
    settings.target_format = desc->format;
    std::string scene_line;
    auto pipeline = make_pipeline(dev, options, settings, scene_line);
    if (!pipeline) return fail(pipeline.error());
    deferred::DeferredFrameControls controls(**pipeline);
    auto live = overlay::LiveOverlay::create(dev, controls, desc->format);
    if (!live) return fail(live.error());
    (*live)->overlay().set_visible(options.overlay);
    uint64_t frames = 0;
    overlay::FrameClock clock;
    while (dev.poll_window()) {
        const rhi::Extent3D size = dev.window_size();
        const double seconds = clock.begin();
        // Input first: a change re-plans before the frame is recorded.
        auto updated = (*live)->update(dev.window_input(), size, seconds, clock.frame_ms());
        if (!updated) return fail(updated.error());
        rhi::CommandList& commands = dev.begin_frame();
        const rhi::TextureHandle backbuffer = dev.backbuffer();
        const bool overlay = (*live)->overlay().visible();
        Status recorded = (*pipeline)->record(commands, backbuffer, {size.width, size.height},
                                              overlay ? rhi::ResourceState::RenderTarget : rhi::ResourceState::Present);
        if (recorded && overlay) recorded = (*live)->record(commands, backbuffer);
        const bool last_frame = options.frames != 0 && frames + 1 >= options.frames;
        if (recorded && last_frame && !options.screenshot.empty()) {
            recorded = samples::save_texture_png(dev, backbuffer, options.screenshot);
        }
        Status ended = dev.end_frame();
        clock.end();
        if (!recorded) return fail(recorded.error());
        if (!ended) return fail(ended.error());
        if (options.frames != 0 && ++frames >= options.frames) break;
    }
    if (auto idle = dev.wait_idle(); !idle) return fail(idle.error());
    std::printf("%s", summary(**pipeline, (*pipeline)->executor(), dev, options, scene_line).c_str());
    if ((*live)->replans() != 0) std::printf("overlay: re-planned %u time(s)\n", (*live)->replans());
    if (!options.screenshot.empty()) std::printf("wrote the last frame to %s\n", options.screenshot.string().c_str());
    return EXIT_SUCCESS;
}

/// The soak run (docs/soak.md): its CSV, plot and verdict into --out; fails when the live
/// objects do not repeat.
int run_soak(const Options& options) {
    using namespace loom;
    auto device = rhi::create_device(samples::device_desc(options.common, "loom deferred"));
    if (!device) return fail(device.error());
    rhi::Device& dev = **device;
    renderer::PipelineSettings settings = pipeline_settings(options);
    // No read-back copies: the soak measures what a frame keeps alive, not the capture.
    settings.capture = false;
    std::string scene_line;
    auto pipeline = make_pipeline(dev, options, settings, scene_line);
    if (!pipeline) return fail(pipeline.error());

    deferred::SoakSettings soak;
    soak.frames = options.soak;
    soak.resize_every = options.resize_every;
    soak.rebuild_every = options.rebuild_every;
    soak.size = {options.common.width, options.common.height};
    const std::filesystem::path dir = options.common.out;
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    std::ofstream csv(dir / "soak.csv", std::ios::binary);
    if (!csv) return fail("cannot write " + (dir / "soak.csv").string());
    csv << deferred::soak_csv_header();
    const uint64_t progress_every = std::max<uint64_t>(1000, options.soak / 10);
    auto samples = deferred::run_soak(dev, **pipeline, soak, [&](const deferred::SoakSample& sample) {
        csv << deferred::soak_csv_row(sample);
        if ((sample.frame + 1) % progress_every == 0) {
            std::fprintf(stderr, "%s: soak frame %" PRIu64 " of %" PRIu64 ": %" PRIu64 " textures, %" PRIu64
                                 " pipelines, resident %s\n",
                         kName, sample.frame + 1, options.soak, sample.live.textures, sample.live.pipelines,
                         fg::format_bytes(sample.resident_bytes).c_str());
        }
    });
    csv.close();
    if (!samples) return fail(samples.error());
    if (!csv) return fail("cannot write " + (dir / "soak.csv").string());

    const deferred::SoakVerdict verdict = deferred::check_soak(*samples, deferred::soak_period(soak));
    const std::string title = std::string("loom-deferred --soak ") + std::to_string(options.soak) + " on " +
                              std::string(rhi::backend_name(dev.backend())) + " (" + dev.capabilities().device_name + "), " +
                              std::to_string(soak.size.width) + "x" + std::to_string(soak.size.height);
    if (auto status = write_text(dir / "soak.svg", deferred::soak_svg(*samples, title, verdict.warm_up_frames)); !status) {
        return fail(status.error());
    }
    double total_ms = 0.0;
    for (const auto& sample : *samples) total_ms += sample.frame_ms;
    const deferred::SoakSample& last = samples->back();
    std::ostringstream text;
    text << title << "\n" << scene_line << "\n"
         << "resize every " << soak.resize_every << " frames, graph rebuilt (lit pass toggled) every "
         << soak.rebuild_every << " frames; " << samples->size() << " frames in " << (total_ms / 1000.0) << " s\n"
         << "live at the end: " << last.live.textures << " textures, " << last.live.buffers << " buffers, "
         << last.live.heaps << " heaps, " << last.live.samplers << " samplers, " << last.live.shaders << " shaders, "
         << last.live.pipelines << " pipelines, " << fg::format_bytes(last.live.total_bytes()) << "\n"
         << verdict.describe() << "\n";
    if (auto status = write_text(dir / "soak.txt", text.str()); !status) return fail(status.error());
    std::printf("%s", text.str().c_str());
    std::printf("wrote soak.csv, soak.svg and soak.txt to %s\n", dir.string().c_str());
    return verdict.steady ? EXIT_SUCCESS : EXIT_FAILURE;
}

int run_animation(const Options& options) {
    using namespace loom;
    auto device = rhi::create_device(samples::device_desc(options.common, "loom deferred"));
    if (!device) return fail(device.error());
    rhi::Device& dev = **device;
    auto loaded = renderer::load_gltf_scene(options.scene);
    if (!loaded) return fail(loaded.error());
    deferred::AnimationSettings settings;
    settings.frames = options.animate;
    settings.size = {options.common.width, options.common.height};
    settings.camera = options.camera;
    settings.pipeline = pipeline_settings(options);
    // Only the final pictures are read back.
    settings.pipeline.capture = false;
    auto run = deferred::play_animation(dev, *loaded, settings);
    if (!run) return fail(run.error());

    const std::filesystem::path dir = options.common.out;
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (auto status = image_io::write_png(run->contact_sheet, dir / "animation.png"); !status) return fail(status.error());
    if (auto status = write_text(dir / "animation.csv", deferred::animation_csv(*run)); !status) return fail(status.error());
    const std::string text = std::string(kName) + ": " + std::string(rhi::backend_name(dev.backend())) + ", " +
                             dev.capabilities().device_name + ", " + std::to_string(settings.size.width) + "x" +
                             std::to_string(settings.size.height) + "\n" + deferred::animation_summary(*run);
    if (auto status = write_text(dir / "animation.txt", text); !status) return fail(status.error());
    std::printf("%s", text.c_str());
    std::printf("wrote animation.png (%u frames, %u per row), animation.csv and animation.txt to %s\n",
                static_cast<unsigned>(run->frames.size()), run->columns, dir.string().c_str());
    for (const std::string& warning : (*loaded)->scene.warnings) std::fprintf(stderr, "%s: warning: %s\n", kName, warning.c_str());
    const bool identical = std::all_of(run->frames.begin(), run->frames.end(), [](const auto& f) { return f.identical; });
    if (!identical) return fail("the retained and immediate paths drew different pictures (see animation.csv)");
    return EXIT_SUCCESS;
}

int run_headless(const Options& options) {
    using namespace loom;
    auto device = rhi::create_device(samples::device_desc(options.common, "loom deferred"));
    if (!device) return fail(device.error());
    rhi::Device& dev = **device;
    const renderer::PipelineSettings settings = pipeline_settings(options);
    std::string scene_line;
    auto pipeline = make_pipeline(dev, options, settings, scene_line);
    if (!pipeline) return fail(pipeline.error());
    for (uint64_t i = 0; i < options.frames; ++i) {
        if (auto rendered = (*pipeline)->render({options.common.width, options.common.height}); !rendered) {
            return fail(rendered.error());
        }
    }
    if (auto idle = dev.wait_idle(); !idle) return fail(idle.error());

    const std::filesystem::path dir = options.common.out;
    std::vector<std::string> written;
    if (auto status = write_pictures(dev, **pipeline, dir, written); !status) return fail(status.error());
    const auto plan = (*pipeline)->executor().plan();
    if (auto status = write_text(dir / "plan.json", fg::plan_to_json(*plan)); !status) return fail(status.error());
    if (auto status = write_text(dir / "plan.dot", fg::plan_to_dot(*plan)); !status) return fail(status.error());
    const std::string text = summary(**pipeline, (*pipeline)->executor(), dev, options, scene_line);
    if (auto status = write_text(dir / "summary.txt", text); !status) return fail(status.error());
    if (!options.inspect.empty()) {
        // Compared on the options the frame was planned with, so the figures match the plan's.
        fg::PlanOptions planned = (*pipeline)->executor().effective_options((*pipeline)->options());
        planned.frame = plan->frame;
        const std::string source = std::string(kName) + " on " + std::string(rhi::backend_name(dev.backend())) + ", " +
                                   dev.capabilities().device_name;
        if (auto status = inspect::write_executor_input(options.inspect, (*pipeline)->executor(), (*pipeline)->graph(), planned, source);
            !status) {
            return fail(status.error());
        }
    }
    std::printf("%s", text.c_str());
    std::printf("wrote %zu pictures, plan.json, plan.dot and summary.txt to %s%s\n", written.size(), dir.string().c_str(),
                options.inspect.empty() ? "" : (" and the inspector input to " + options.inspect.string()).c_str());
    return EXIT_SUCCESS;
}

}  // namespace

int main(int argc, char** argv) {
    auto options = parse(argc, argv);
    if (!options) return fail(options.error().message + " (see --help)");
    if (options->common.help) {
        loom::samples::CommonDefaults defaults;
        defaults.width = 1280;
        defaults.height = 720;
        defaults.out = "out/deferred";
        std::printf("%s%s%s", kUsage, loom::samples::common_options_help(defaults).c_str(), extra_help().c_str());
        return EXIT_SUCCESS;
    }
    if (options->soak != 0) return run_soak(*options);
    if (options->animate != 0) return run_animation(*options);
    return options->common.window ? run_window(*options) : run_headless(*options);
}

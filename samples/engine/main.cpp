// loom-engine: an engine-style frame on one frame graph, on GL or Vulkan (docs/engine.md):
// depth prepass, hierarchical Z built level by level in compute, a tiled light list built in
// compute for many point lights, four shadow cascades in one array texture, SSAO on the async
// compute queue, forward+ shading with the sky, a bloom pyramid and tone mapping. Headless it
// writes the picture, every intermediate (each mip level and layer), the plan as JSON and DOT
// and a summary with the memory each allocator needs; with --window it shows the frame.
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "engine_frame.hpp"
#include "engine_pictures.hpp"
#include "loom/framegraph/export.hpp"
#include "loom/framegraph/planner.hpp"
#include "loom/image_io/image_io.hpp"
#include "loom/rhi/device.hpp"
#include "loom/sample_common/options.hpp"
#include "engine_controls.hpp"
#include "inspect_input.hpp"

namespace {

constexpr const char* kName = "loom-engine";

int fail(const std::string& message) {
    std::fprintf(stderr, "%s: %s\n", kName, message.c_str());
    return EXIT_FAILURE;
}
int fail(const loom::Error& error) { return fail(error.to_string()); }

struct Options {
    loom::samples::CommonOptions common;
    uint64_t frames = 1;
    loom::engine::SceneSettings scene;
    loom::engine::FrameSettings frame;
    /// --inspect FILE: the inspector input of the last frame (headless); empty: none.
    std::filesystem::path inspect;
    /// --overlay: the frame overlay shown from the first frame (--window; F1 toggles it).
    bool overlay = false;
};

const char* kUsage =
    "usage: loom-engine [options]\n"
    "Renders an engine-style frame (depth prepass, hierarchical Z and a tiled light list in compute,\n"
    "shadow cascades, SSAO on the async compute queue, forward+ shading, bloom, tone mapping) of a\n"
    "courtyard lit by many point lights, with a glTF model in the middle when one is given.\n"
    "Headless, it writes into --out DIR: final.png, one PNG per intermediate (each mip level and\n"
    "layer), light_list.png (lights per tile), intermediates.png (six stages side by side),\n"
    "plan.json, plan.dot and summary.txt.\n\n";

std::string extra_help() {
    return "  --scene FILE|builtin  a glTF 2.0 file (.gltf, .glb) for the middle of the courtyard (default builtin)\n"
           "  --lights N            point lights (default 128, at most 4096)\n"
           "  --frames N            frames to render (default 1; with --window 0 runs until closed)\n"
           "  --allocator NAME      heap (default: aliasing in bytes), interval (whole textures), or paper\n"
           "                        (needs --async off)\n"
           "  --order NAME          pass order: memory (the default: the lowest peak of live bytes) or declared\n"
           "  --async on|off        SSAO on the async compute queue (default on; serial on one-queue devices)\n"
           "  --shadow-size N       texels per side of each shadow cascade (default 1024)\n"
           "  --inspect FILE        also write the inspector input of the last frame (plan, barriers, timings,\n"
           "                        allocations, every allocator's memory) for loom-inspect (docs/inspector.md)\n"
           "  --overlay             with --window: show the frame overlay from the start (F1 shows and hides it:\n"
           "                        passes, GPU/CPU times, memory, allocator and async compute, which re-plan)\n";
}

loom::Result<uint64_t> number(const std::string& name, const std::string& text, uint64_t max) {
    char* end = nullptr;
    const unsigned long long n = std::strtoull(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || text[0] == '-' || n > max) {
        return loom::make_error(loom::ErrorCode::InvalidArgument, name + " expects a number up to " + std::to_string(max) + ", got '" + text + "'");
    }
    return static_cast<uint64_t>(n);
}

/// The shared options' defaults for this sample (parsing and --help).
loom::samples::CommonDefaults engine_defaults() {
    loom::samples::CommonDefaults defaults;
    defaults.width = 960;
    defaults.height = 540;
    defaults.out = "out/engine";
    return defaults;
}

loom::Result<Options> parse(int argc, char** argv) {
    auto common = loom::samples::parse_common_options(argc, argv, engine_defaults());
    if (!common) return common.take_error();
    Options options;
    options.common = std::move(*common);
    loom::samples::ArgumentReader args(options.common.rest);
    while (args.next()) {
        const std::string& name = args.name();
        if (name == "--overlay") {
            options.overlay = true;
            continue;
        }
        const bool known = name == "--scene" || name == "--lights" || name == "--frames" || name == "--allocator" ||
                           name == "--async" || name == "--shadow-size" || name == "--inspect" || name == "--order";
        if (!known) return args.unknown();
        auto v = args.value();
        if (!v) return v.take_error();
        if (name == "--scene") {
            if (v->empty()) return loom::make_error(loom::ErrorCode::InvalidArgument, "--scene needs a file or 'builtin'");
            options.scene.model = *v == "builtin" ? std::filesystem::path() : std::filesystem::path(*v);
        } else if (name == "--lights") {
            auto n = number(name, *v, loom::engine::kMaxLights);
            if (!n) return n.take_error();
            if (*n == 0) return loom::make_error(loom::ErrorCode::InvalidArgument, "--lights expects at least 1 light");
            options.scene.lights = static_cast<uint32_t>(*n);
        } else if (name == "--frames") {
            auto n = number(name, *v, UINT64_MAX);
            if (!n) return n.take_error();
            options.frames = *n;
        } else if (name == "--allocator") {
            auto allocator = loom::fg::parse_allocator(*v);
            if (!allocator) return loom::make_error(loom::ErrorCode::InvalidArgument, "--allocator: " + allocator.error().message);
            options.frame.allocator = *allocator;
        } else if (name == "--order") {
            auto order = loom::fg::parse_pass_order(*v);
            if (!order) {
                return loom::make_error(loom::ErrorCode::InvalidArgument, "--order expects declared or memory, got '" + *v + "'");
            }
            options.frame.order = *order;
        } else if (name == "--async") {
            if (*v != "on" && *v != "off") return loom::make_error(loom::ErrorCode::InvalidArgument, "--async expects on or off, got '" + *v + "'");
            options.frame.async_compute = *v == "on";
        } else if (name == "--inspect") {
            if (v->empty()) return loom::make_error(loom::ErrorCode::InvalidArgument, "--inspect needs a file");
            options.inspect = *v;
        } else if (name == "--shadow-size") {
            auto n = number(name, *v, 16384);
            if (!n) return n.take_error();
            options.frame.shadow_size = static_cast<uint32_t>(*n);
        }
    }
    if (options.overlay && !options.common.window) {
        return loom::make_error(loom::ErrorCode::InvalidArgument, "--overlay needs --window");
    }
    if (!options.inspect.empty() && options.common.window) {
        return loom::make_error(loom::ErrorCode::InvalidArgument, "--inspect writes the headless frame's input (leave out --window)");
    }
    if (!options.common.window && options.frames == 0) {
        return loom::make_error(loom::ErrorCode::InvalidArgument, "--frames 0 only makes sense with --window");
    }
    if (options.common.width < loom::engine::kMinFrameSide || options.common.height < loom::engine::kMinFrameSide) {
        return loom::make_error(loom::ErrorCode::InvalidArgument, "--size must be at least " + std::to_string(loom::engine::kMinFrameSide) +
                                                                      "x" + std::to_string(loom::engine::kMinFrameSide));
    }
    return options;
}

loom::Status write_text(const std::filesystem::path& path, const std::string& text) {
    std::ofstream file(path, std::ios::binary);
    file << text;
    if (!file) return loom::make_error(loom::ErrorCode::Io, "cannot write " + path.string());
    return {};
}

/// What the plan is and needs: passes by kind and queue, and the bytes of every allocator
/// beside the naive figure and the lower bound, planned for this device.
std::string memory_report(loom::engine::EngineFrame& frame, loom::fg::Extent2D size) {
    using loom::fg::format_bytes;
    std::ostringstream out;
    const auto plan = frame.executor().plan();
    uint32_t compute = 0, async = 0;
    for (const auto& pass : plan->order) {
        if (pass.kind == loom::fg::PassKind::Compute) ++compute;
        if (pass.queue == loom::fg::Queue::AsyncCompute) ++async;
    }
    char hash[32];
    std::snprintf(hash, sizeof(hash), "%016" PRIx64, loom::fg::plan_hash(*plan));
    out << "plan " << hash << ": " << plan->order.size() << " passes (" << compute << " compute, " << async
        << " of them on the async queue), " << plan->resources.size() << " resources, " << plan->queue_syncs.size()
        << " queue syncs\n";
    out << "memory (" << size.width << "x" << size.height << "):\n";
    out << "  allocator   textures  buffers        bytes   vs naive\n";
    using loom::fg::AllocatorKind;
    for (AllocatorKind kind : {AllocatorKind::Interval, AllocatorKind::Heap, AllocatorKind::Paper}) {
        const std::string allocator(loom::fg::allocator_name(kind));
        loom::fg::PlanOptions options = frame.executor().effective_options(frame.plan_options(size));
        options.allocator = kind;
        auto planned = loom::fg::build_plan(frame.graph(), options);
        char line[160];
        if (!planned) {
            out << "  " << allocator << "       refuses: " << planned.error().message << "\n";
            continue;
        }
        const auto& s = planned->summary;
        std::snprintf(line, sizeof(line), "  %-10s  %8u  %7u  %11s  %7.1f %%\n", allocator.c_str(), s.textures, s.buffers, format_bytes(s.bytes).c_str(),
                      100.0 * static_cast<double>(s.bytes) / static_cast<double>(std::max<uint64_t>(s.naive_bytes, 1)));
        out << line;
        if (kind == AllocatorKind::Interval) {
            std::snprintf(line, sizeof(line), "  %-10s  %8u  %7u  %11s  %7.1f %%\n", "naive", s.naive_textures, s.naive_buffers,
                          format_bytes(s.naive_bytes).c_str(), 100.0);
            out << line;
            std::snprintf(line, sizeof(line), "  %-10s  %8u  %7u  %11s  %7.1f %%\n", "lower bound", s.lower_bound_textures,
                          s.lower_bound_buffers, format_bytes(s.lower_bound_bytes).c_str(),
                          100.0 * static_cast<double>(s.lower_bound_bytes) / static_cast<double>(std::max<uint64_t>(s.naive_bytes, 1)));
            out << line;
        }
    }
    return out.str();
}

std::string summary(loom::engine::EngineFrame& frame, loom::rhi::Device& device, const Options& options, loom::fg::Extent2D size) {
    using loom::fg::format_bytes;
    std::ostringstream out;
    const auto& caps = device.capabilities();
    out << kName << ": " << loom::rhi::backend_name(device.backend()) << ", " << caps.device_name << ", " << size.width << "x"
        << size.height << ", allocator " << loom::fg::allocator_name(frame.settings().allocator)
        << ", " << loom::fg::pass_order_name(frame.settings().order) << " order, async compute "
        << (frame.settings().async_compute ? (caps.async_compute ? "on (two queues)" : "on (one queue: run in order)") : "off") << ", "
        << options.frames << " frame(s)\n";
    out << "scene: " << frame.scene().description << "; textures with mipmaps: " << format_bytes(frame.gpu_scene().texture_bytes()) << "\n";
    out << memory_report(frame, size);
    const loom::fg::ExecutionStats stats = frame.executor().stats();
    out << "created: " << stats.textures << " textures for the plan's " << stats.plan_textures << " and " << stats.buffers
        << " buffer(s) (" << (stats.placed_textures + stats.placed_buffers) << " placed in " << stats.heaps << " heap(s) of "
        << format_bytes(stats.heap_bytes) << "; " << format_bytes(stats.texture_bytes + stats.buffer_bytes)
        << " unplaced); device total: " << stats.device.textures << " textures, " << stats.device.buffers << " buffers, "
        << stats.device.pipelines << " pipelines, " << format_bytes(stats.device.total_bytes()) << "\n";
    out << "timings of the latest frame (ms):\n  pass                   gpu       cpu\n";
    for (const auto& timing : frame.executor().timings()) {
        char line[128];
        if (timing.gpu_ms) {
            std::snprintf(line, sizeof(line), "  %-18s %8.3f  %8.3f\n", timing.pass.c_str(), *timing.gpu_ms, timing.cpu_ms);
        } else {
            std::snprintf(line, sizeof(line), "  %-18s %8s  %8.3f\n", timing.pass.c_str(), "n/a", timing.cpu_ms);
        }
        out << line;
    }
    return out.str();
}

int run_window(Options options) {
    using namespace loom;
    auto device = rhi::create_device(samples::device_desc(options.common, "loom engine"));
    if (!device) return fail(device.error());
    rhi::Device& dev = **device;
    (void)dev.begin_frame();
    auto desc = dev.texture_desc(dev.backbuffer());
    if (auto ended = dev.end_frame(); !ended) return fail(ended.error());
    if (!desc) return fail(desc.error());
    options.frame.capture = false;
    options.frame.target_format = desc->format;
    auto scene = engine::make_engine_scene(options.scene);
    if (!scene) return fail(scene.error());
    auto frame = engine::EngineFrame::create(dev, *scene, options.frame);
    if (!frame) return fail(frame.error());
    engine::EngineFrameControls controls(**frame);
    auto live = overlay::LiveOverlay::create(dev, controls, desc->format);
    if (!live) return fail(live.error());
    (*live)->overlay().set_visible(options.overlay);
    uint64_t frames = 0;
    fg::Extent2D size{};
    overlay::FrameClock clock;
    while (dev.poll_window()) {
        const rhi::Extent3D window = dev.window_size();
        const double seconds = clock.begin();
        // Input first: a change (F1 overlay) re-plans before the frame is recorded.
        auto updated = (*live)->update(dev.window_input(), window, seconds, clock.frame_ms());
        if (!updated) return fail(updated.error());
        rhi::CommandList& commands = dev.begin_frame();
        const rhi::TextureHandle backbuffer = dev.backbuffer();
        size = {std::max(window.width, engine::kMinFrameSide), std::max(window.height, engine::kMinFrameSide)};
        const bool drawn = window.width >= engine::kMinFrameSide && window.height >= engine::kMinFrameSide;
        const bool overlay = drawn && (*live)->overlay().visible();
        // A minimised or tiny window: nothing to draw this frame.
        Status recorded = drawn ? (*frame)->record(commands, backbuffer, {window.width, window.height},
                                                   overlay ? rhi::ResourceState::RenderTarget : rhi::ResourceState::Present)
                                : Status{};
        if (recorded && overlay) recorded = (*live)->record(commands, backbuffer);
        Status ended = dev.end_frame();
        clock.end();
        if (!recorded) return fail(recorded.error());
        if (!ended) return fail(ended.error());
        if (options.frames != 0 && ++frames >= options.frames) break;
    }
    if (auto idle = dev.wait_idle(); !idle) return fail(idle.error());
    if ((*frame)->executor().plan()) std::printf("%s", summary(**frame, dev, options, size).c_str());
    if ((*live)->replans() != 0) std::printf("overlay: re-planned %u time(s)\n", (*live)->replans());
    return EXIT_SUCCESS;
}

int run_headless(const Options& options) {
    using namespace loom;
    auto device = rhi::create_device(samples::device_desc(options.common, "loom engine"));
    if (!device) return fail(device.error());
    rhi::Device& dev = **device;
    auto scene = engine::make_engine_scene(options.scene);
    if (!scene) return fail(scene.error());
    auto frame = engine::EngineFrame::create(dev, *scene, options.frame);
    if (!frame) return fail(frame.error());
    const fg::Extent2D size{options.common.width, options.common.height};
    for (uint64_t i = 0; i < options.frames; ++i) {
        if (auto rendered = (*frame)->render(size); !rendered) return fail(rendered.error());
    }
    if (auto idle = dev.wait_idle(); !idle) return fail(idle.error());

    auto images = engine::read_intermediates(dev, **frame);
    if (!images) return fail(images.error());
    const std::filesystem::path dir = options.common.out;
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    const rhi::Image& final_image = images->at("final");
    std::map<std::string, rhi::Image> pictures;
    for (const auto& [name, image] : *images) {
        pictures[name] = engine::viewable(name, image, final_image);
        if (auto written = image_io::write_png(pictures[name], dir / (name + ".png")); !written) return fail(written.error());
    }
    // Six stages of the frame side by side, each at half the frame's size.
    const rhi::Image sheet = engine::contact_sheet(
        pictures, {"depth", "hzb.mip4", "light_list", "shadow_cascades.layer1", "ssao", "bloom_up.mip0"}, 3,
        {std::max(size.width / 2, 1u), std::max(size.height / 2, 1u)});
    if (auto written = image_io::write_png(sheet, dir / "intermediates.png"); !written) return fail(written.error());
    const auto plan = (*frame)->executor().plan();
    if (auto status = write_text(dir / "plan.json", fg::plan_to_json(*plan)); !status) return fail(status.error());
    if (auto status = write_text(dir / "plan.dot", fg::plan_to_dot(*plan)); !status) return fail(status.error());
    const std::string text = summary(**frame, dev, options, size);
    if (auto status = write_text(dir / "summary.txt", text); !status) return fail(status.error());
    if (!options.inspect.empty()) {
        // Compared on the options the frame was planned with, as memory_report does.
        const fg::PlanOptions planned = (*frame)->executor().effective_options((*frame)->plan_options(size));
        const std::string source = std::string("loom-engine on ") + std::string(rhi::backend_name(dev.backend())) + ", " +
                                   dev.capabilities().device_name;
        if (auto status = inspect::write_executor_input(options.inspect, (*frame)->executor(), (*frame)->graph(), planned, source);
            !status) {
            return fail(status.error());
        }
    }
    std::printf("%s", text.c_str());
    std::printf("wrote %zu pictures, intermediates.png, plan.json, plan.dot and summary.txt to %s%s\n", images->size(),
                dir.string().c_str(), options.inspect.empty() ? "" : (" and the inspector input to " + options.inspect.string()).c_str());
    return EXIT_SUCCESS;
}

}  // namespace

int main(int argc, char** argv) {
    auto options = parse(argc, argv);
    if (!options) return fail(options.error().message + " (see --help)");
    if (options->common.help) {
        std::printf("%s%s%s", kUsage, loom::samples::common_options_help(engine_defaults()).c_str(), extra_help().c_str());
        return EXIT_SUCCESS;
    }
    return options->common.window ? run_window(*options) : run_headless(*options);
}

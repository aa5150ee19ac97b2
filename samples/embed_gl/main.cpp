// loom-embed-gl: loom inside an "engine" that owns the OpenGL context, the window and the
// render target. The engine clears its target with its own GL calls; loom, running on the
// engine's context (gl::create_gl_device_on_current_context), draws the overlay graph over it
// (the target imported with gl::import_gl_texture); the engine then shows the target in its
// window (gl::blit_to_framebuffer) or, headless, reads it back itself and writes a PNG. loom
// puts back every piece of GL state it changes, so the engine's state is its own throughout.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "gl_engine.hpp"
#include "loom/framegraph/framegraph.hpp"
#include "loom/gl/gl_embed.hpp"
#include "loom/image_io/image_io.hpp"
#include "loom/rhi/log.hpp"
#include "loom/sample_common/options.hpp"
#include "overlay_graph.hpp"

namespace {

constexpr const char* kName = "loom-embed-gl";

int fail(const std::string& message) {
    std::fprintf(stderr, "%s: %s\n", kName, message.c_str());
    return EXIT_FAILURE;
}

int fail(const loom::Error& error) { return fail(error.to_string()); }

loom::rhi::TextureDesc target_desc(const loom::samples::GlEngine& engine) {
    loom::rhi::TextureDesc desc;
    desc.name = "engine target";
    desc.format = loom::rhi::Format::RGBA8Unorm;
    desc.width = engine.width();
    desc.height = engine.height();
    desc.usage = loom::rhi::TextureUsage::ColorAttachment | loom::rhi::TextureUsage::Sampled;
    return desc;
}

int run(const loom::samples::CommonOptions& options, uint64_t max_frames) {
    using namespace loom;
    // GL errors reported through debug output (and loom's own errors) fail the run.
    int errors = 0;
    set_log_sink([&](LogLevel level, std::string_view source, std::string_view message) {
        if (level < LogLevel::Warning) return;
        std::fprintf(stderr, "[%s] %.*s\n", std::string(source).c_str(), static_cast<int>(message.size()), message.data());
        if (level == LogLevel::Error) ++errors;
    });

    // The engine: its window or headless context, current on this thread, and its target.
    auto engine = samples::GlEngine::create(options.window, options.width, options.height);
    if (!engine) return fail(engine.error());

    // loom on the engine's context.
    auto device = gl::create_gl_device_on_current_context({.debug_output = true});
    if (!device) return fail(device.error());
    rhi::Device& dev = **device;
    auto target = gl::import_gl_texture(dev, (*engine)->target(), target_desc(**engine));
    if (!target) return fail(target.error());
    auto overlay = samples::OverlayGraph::create(dev, rhi::Format::RGBA8Unorm);
    if (!overlay) return fail(overlay.error());
    rhi::TextureHandle imported = *target;
    {
        fg::Executor executor(dev);
        uint64_t frames = 0;
        const uint64_t last_frame = options.window ? max_frames : 1;
        while ((*engine)->poll()) {
            if ((*engine)->fit_target_to_window()) {
                // A new engine texture after a resize: forget the old one, import the new one.
                (void)dev.destroy(imported);
                auto reimported = gl::import_gl_texture(dev, (*engine)->target(), target_desc(**engine));
                if (!reimported) return fail(reimported.error());
                imported = *reimported;
            }
            (*engine)->clear_target();
            executor.import_texture(samples::OverlayGraph::target_port(), imported, rhi::ResourceState::ShaderRead);
            fg::PlanOptions plan;
            plan.frame = {(*engine)->width(), (*engine)->height()};
            if (auto status = executor.run_frame((*overlay)->graph(), plan); !status) return fail(status.error());
            ++frames;
            const bool last = last_frame != 0 && frames >= last_frame;
            if ((*engine)->windowed()) {
                // Shown the right way up in the window's default framebuffer.
                if (auto status = gl::blit_to_framebuffer(dev, imported, 0, 0, 0, (*engine)->width(), (*engine)->height());
                    !status) {
                    return fail(status.error());
                }
                if (last && !options.out.empty()) {
                    if (auto status = image_io::write_png((*engine)->read_window(), options.out); !status) return fail(status.error());
                }
                (*engine)->present();
            } else if (!options.out.empty()) {
                if (auto status = image_io::write_png((*engine)->read_target(), options.out); !status) return fail(status.error());
            }
            if (last) break;
        }
        std::printf("%s: %llu frame(s) at %ux%u on %s%s%s\n", kName, static_cast<unsigned long long>(frames),
                    (*engine)->width(), (*engine)->height(), dev.capabilities().device_name.c_str(),
                    options.out.empty() ? "" : ", wrote ", options.out.string().c_str());
    }
    (void)dev.destroy(imported);
    overlay->reset();
    device->reset();
    if (errors > 0) return fail(std::to_string(errors) + " error(s) logged");
    return EXIT_SUCCESS;
}

}  // namespace

int main(int argc, char** argv) {
    loom::samples::CommonDefaults defaults;
    defaults.out = "out/embed_gl.png";
    for (int i = 1; i < argc; ++i) {
        if (std::string(argv[i]) == "--backend") return fail("--backend: this sample is the OpenGL one (see loom-embed-vulkan)");
    }
    auto options = loom::samples::parse_common_options(argc, argv, defaults);
    if (!options) return fail(options.error().message + " (see --help)");
    if (options->help) {
        std::printf("usage: %s [options]\n"
                    "An OpenGL \"engine\" with its own context and render target embeds loom, which draws a\n"
                    "pattern into the top-left quadrant of the engine's target. Headless: writes the target\n"
                    "as a PNG. --window: shows it; with --frames N stops after N frames and writes the last\n"
                    "one's window contents to --out.\n\n%s"
                    "  --frames N           with --window: stop after N frames (default 0: until closed)\n",
                    kName, loom::samples::common_options_help(defaults).c_str());
        return EXIT_SUCCESS;
    }
    uint64_t max_frames = 0;
    for (std::size_t i = 0; i < options->rest.size(); ++i) {
        const std::string& arg = options->rest[i];
        if (arg == "--frames" && i + 1 < options->rest.size()) {
            const std::string& value = options->rest[++i];
            char* end = nullptr;
            max_frames = std::strtoull(value.c_str(), &end, 10);
            if (value.empty() || *end != '\0') return fail("--frames expects a number of frames, got '" + value + "'");
        } else {
            return fail("unknown argument '" + arg + "' (see --help)");
        }
    }
    // In a window without --frames the picture is only written when asked for explicitly.
    if (options->window && max_frames == 0) options->out.clear();
    return run(*options, max_frames);
}

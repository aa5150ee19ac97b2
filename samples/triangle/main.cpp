// loom-triangle: draws the built-in triangle with either backend. Headless by default (writes
// a PNG); --window shows it in a window until the window is closed.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "loom/rhi/device.hpp"
#include "loom/sample_common/options.hpp"
#include "loom/sample_common/output.hpp"
#include "loom/sample_common/window_loop.hpp"
#include "triangle_renderer.hpp"

namespace {

constexpr const char* kName = "loom-triangle";

int fail(const std::string& message) {
    std::fprintf(stderr, "%s: %s\n", kName, message.c_str());
    return EXIT_FAILURE;
}

int fail(const loom::Error& error) { return fail(error.to_string()); }

int run(const loom::samples::CommonOptions& options, uint64_t max_frames) {
    using namespace loom;
    auto device = rhi::create_device(samples::device_desc(options, "loom triangle"));
    if (!device.ok()) return fail(device.error());
    rhi::Device& dev = **device;
    const rhi::Format format = rhi::Format::RGBA8Unorm;
    auto renderer = samples::TriangleRenderer::create(dev, format);
    if (!renderer.ok()) return fail(renderer.error());

    if (options.window) {
        auto status = samples::run_window_loop(dev, [&](rhi::CommandList& list, rhi::TextureHandle backbuffer, rhi::Extent3D) {
            renderer->record(list, backbuffer);
        }, max_frames);
        return status.ok() ? EXIT_SUCCESS : fail(status.error());
    }

    rhi::TextureDesc desc;
    desc.name = "triangle target";
    desc.format = format;
    desc.width = options.width;
    desc.height = options.height;
    desc.usage = rhi::TextureUsage::ColorAttachment | rhi::TextureUsage::CopySrc;
    auto target = dev.create_texture(desc);
    if (!target.ok()) return fail(target.error());
    renderer->record(dev.begin_frame(), *target);
    if (auto status = dev.end_frame(); !status.ok()) return fail(status.error());
    if (auto status = samples::save_texture_png(dev, *target, options.out); !status.ok()) return fail(status.error());
    (void)dev.destroy(*target);
    std::printf("%s: wrote %s (%ux%u, %s, %s)\n", kName, options.out.string().c_str(), options.width, options.height,
                std::string(rhi::backend_name(options.backend)).c_str(), dev.capabilities().device_name.c_str());
    return EXIT_SUCCESS;
}

}  // namespace

int main(int argc, char** argv) {
    loom::samples::CommonDefaults defaults;
    defaults.out = "out/triangle.png";
    auto options = loom::samples::parse_common_options(argc, argv, defaults);
    if (!options.ok()) return fail(options.error().message + " (see --help)");
    if (options->help) {
        std::printf("usage: %s [options]\nDraws a coloured triangle on a dark background.\n\n%s"
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
    return run(*options, max_frames);
}

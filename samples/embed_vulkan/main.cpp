// loom-embed-vulkan: loom inside an "engine" that owns the Vulkan instance, device, queue,
// command buffers, frames in flight and window. Each frame the engine begins its command
// buffer and clears its image (a swapchain image, or headless its offscreen target) with its
// own commands; loom (vulkan::create_vulkan_device_on) records the overlay graph into the same
// command buffer (vulkan::begin_external_frame) with the image imported
// (vulkan::import_vulkan_image) and hands it back in the layout the engine asks for; the engine
// takes a screenshot when asked, submits (signalling loom's timeline value) and presents.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "loom/framegraph/framegraph.hpp"
#include "loom/image_io/image_io.hpp"
#include "loom/rhi/log.hpp"
#include "loom/sample_common/options.hpp"
#include "loom/vulkan/vulkan_embed.hpp"
#include "overlay_graph.hpp"
#include "vulkan_engine.hpp"

namespace {

constexpr const char* kName = "loom-embed-vulkan";

int fail(const std::string& message) {
    std::fprintf(stderr, "%s: %s\n", kName, message.c_str());
    return EXIT_FAILURE;
}

int fail(const loom::Error& error) { return fail(error.to_string()); }

int run(const loom::samples::CommonOptions& options, uint64_t max_frames) {
    using namespace loom;
    int errors = 0;
    set_log_sink([&](LogLevel level, std::string_view source, std::string_view message) {
        if (level < LogLevel::Warning) return;
        std::fprintf(stderr, "[%s] %.*s\n", std::string(source).c_str(), static_cast<int>(message.size()), message.data());
        if (level == LogLevel::Error) ++errors;
    });

    // The engine: instance (validation when installed), device, queue, window or offscreen image.
    auto engine = samples::VulkanEngine::create(options.window, options.width, options.height);
    if (!engine) return fail(engine.error());
    samples::VulkanEngine& eng = **engine;

    // loom on the engine's objects.
    auto device = vulkan::create_vulkan_device_on(eng.loom_desc());
    if (!device) return fail(device.error());
    rhi::Device& dev = **device;
    const rhi::Format format = eng.format() == VK_FORMAT_B8G8R8A8_UNORM ? rhi::Format::BGRA8Unorm : rhi::Format::RGBA8Unorm;
    auto overlay = samples::OverlayGraph::create(dev, format);
    if (!overlay) return fail(overlay.error());

    // The engine's images as loom textures, imported again when the swapchain changes.
    std::vector<rhi::TextureHandle> imports;
    uint64_t imported_generation = 0;
    auto forget_images = [&] {
        for (rhi::TextureHandle t : imports) (void)dev.destroy(t);
        imports.clear();
        (void)dev.wait_idle();  // loom's views of the old images go now
    };
    auto import_images = [&]() -> Status {
        forget_images();
        for (std::size_t i = 0; i < eng.images().size(); ++i) {
            vulkan::ExternalImage image;
            image.name = "engine image " + std::to_string(i);
            image.image = eng.images()[i];
            image.format = eng.format();
            image.width = eng.extent().width;
            image.height = eng.extent().height;
            image.usage = eng.image_usage();
            image.layout = VK_IMAGE_LAYOUT_UNDEFINED;
            auto texture = vulkan::import_vulkan_image(dev, image);
            if (!texture) return texture.take_error();
            imports.push_back(*texture);
        }
        imported_generation = eng.generation();
        return {};
    };

    const uint64_t last_frame = max_frames != 0 ? max_frames : (options.window ? 0 : 1);
    uint64_t frames = 0;
    {
        fg::Executor executor(dev);
        while (eng.poll()) {
            auto frame = eng.begin_frame(forget_images);
            if (!frame) return fail(frame.error());
            if (imported_generation != eng.generation()) {
                if (auto status = import_images(); !status) return fail(status.error());
            }
            ++frames;
            const bool screenshot = !options.out.empty() && frames == last_frame;
            const rhi::TextureHandle target = imports[frame->image_index];
            // The engine cleared the image: it is in TRANSFER_DST_OPTIMAL now.
            if (auto status = vulkan::set_image_layout(dev, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL); !status) {
                return fail(status.error());
            }
            auto commands = vulkan::begin_external_frame(dev, frame->cmd);
            if (!commands) return fail(commands.error());
            // Handed back ready for what the engine does next: present, or copy for a screenshot.
            const rhi::ResourceState final_state = screenshot        ? rhi::ResourceState::CopySrc
                                                   : eng.windowed() ? rhi::ResourceState::Present
                                                                    : rhi::ResourceState::ShaderRead;
            executor.import_texture(samples::OverlayGraph::target_port(), target, final_state);
            fg::PlanOptions plan;
            plan.frame = {eng.extent().width, eng.extent().height};
            const Status executed = executor.execute((*overlay)->graph(), **commands, plan);
            const Status ended = dev.end_frame();  // loom's part only: the engine submits
            if (!executed) return fail(executed.error());
            if (!ended) return fail(ended.error());
            auto signal = vulkan::external_frame_signal(dev);
            if (!signal) return fail(signal.error());
            if (auto status = eng.end_frame(*frame, *signal, vulkan::layout_for_state(final_state, false), screenshot); !status) {
                return fail(status.error());
            }
            if (last_frame != 0 && frames >= last_frame) break;
        }
        if (auto status = dev.wait_idle(); !status) return fail(status.error());
    }
    if (!options.out.empty() && frames == last_frame) {
        auto picture = eng.screenshot();
        if (!picture) return fail(picture.error());
        if (auto status = image_io::write_png(*picture, options.out); !status) return fail(status.error());
    }
    std::printf("%s: %llu frame(s) at %ux%u on %s%s%s\n", kName, static_cast<unsigned long long>(frames), eng.extent().width,
                eng.extent().height, dev.capabilities().device_name.c_str(), options.out.empty() ? "" : ", wrote ",
                options.out.string().c_str());
    for (rhi::TextureHandle t : imports) (void)dev.destroy(t);
    overlay->reset();
    device->reset();
    if (eng.validation_errors() > 0) return fail(std::to_string(eng.validation_errors()) + " validation message(s)");
    if (errors > 0) return fail(std::to_string(errors) + " error(s) logged");
    return EXIT_SUCCESS;
}

}  // namespace

int main(int argc, char** argv) {
    loom::samples::CommonDefaults defaults;
    defaults.out = "out/embed_vulkan.png";
    for (int i = 1; i < argc; ++i) {
        if (std::string(argv[i]) == "--backend") return fail("--backend: this sample is the Vulkan one (see loom-embed-gl)");
    }
    auto options = loom::samples::parse_common_options(argc, argv, defaults);
    if (!options) return fail(options.error().message + " (see --help)");
    if (options->help) {
        std::printf("usage: %s [options]\n"
                    "A Vulkan \"engine\" with its own instance, device, command buffers and window embeds loom,\n"
                    "which records a pattern into the top-left quadrant of the engine's image. Headless:\n"
                    "writes the image as a PNG. --window: presents it; with --frames N stops after N frames\n"
                    "and writes the last one to --out.\n\n%s"
                    "  --frames N           stop after N frames (default: 1 headless, until closed with --window)\n",
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

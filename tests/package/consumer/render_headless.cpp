// Renders headless through the installed (or subproject) loom on every backend it has: a frame
// graph whose first pass clears its RGBA16Float output and whose second (loom::passes' BlitPass) copies it
// into the target; reads the target back and checks a texel. Also looks up a built-in shader
// (loom::shaders). Exit status 0 when every backend drew the expected colour.
#include <cmath>
#include <cstdio>
#include <memory>

#include "every_backend.hpp"
#include "loom/framegraph/framegraph.hpp"
#include "loom/passes/blit_pass.hpp"
#include "loom/rhi/device.hpp"
#include "loom/shaders/builtin.hpp"
#if defined(CONSUMER_HAS_GL)
#include "loom/gl/gl_device.hpp"
#endif
#if defined(CONSUMER_HAS_VULKAN)
#include "loom/vulkan/vulkan_device.hpp"
#endif

namespace {

using namespace loom;

constexpr std::array<double, 4> kColor{0.2, 0.4, 0.6, 1.0};  // (51, 102, 153, 255) in RGBA8

Status render(rhi::Device& device) {
    fg::FrameGraph graph;
    LOOM_TRY(graph.add_pass(fg::Pass("clear")
                                .output("color", fg::TextureSpec::of(rhi::Format::RGBA16Float))
                                .on_execute([](fg::PassContext& ctx) {
                                    ctx.begin_render_pass({{"color", kColor}});
                                    ctx.end_render_pass();
                                    return Status{};
                                })));
    LOOM_TRY(graph.add_pass(std::make_unique<passes::BlitPass>()));
    LOOM_TRY(graph.connect(fg::port("clear", "color"), fg::port("present", "source")));
    LOOM_TRY(graph.mark_output(fg::port("present", "target")));
    fg::Executor executor(device);
    fg::PlanOptions options;
    options.frame = {32, 16};
    LOOM_TRY(executor.run_frame(graph, options));
    auto image = device.read_texture(executor.texture("present", "target"));
    if (!image) return image.take_error();
    const auto texel = image->load(20, 10);
    for (std::size_t c = 0; c < 4; ++c) {
        if (std::abs(texel[c] - kColor[c]) > 0.5 / 255.0) {
            return Error{ErrorCode::Backend, "texel (20, 10) channel " + std::to_string(c) + " is " + std::to_string(texel[c]) +
                                                 ", expected " + std::to_string(kColor[c])};
        }
    }
    return {};
}

}  // namespace

int main() {
    const consumer::LoggedErrors logged;
    if (auto shader = shaders::builtin("fullscreen.vert"); !shader) {
        std::fprintf(stderr, "render_headless: %s\n", shader.error().to_string().c_str());
        return 1;
    }
    int failures = consumer::on_every_backend("render_headless", "drew the expected colour", render);
    if (failures < 0) return 1;
#if defined(CONSUMER_HAS_GL)
    // The backend's own factory is there too.
    if (!gl::create_gl_device({})) ++failures;
#endif
#if defined(CONSUMER_HAS_VULKAN)
    rhi::DeviceDesc vulkan_desc;
    vulkan_desc.backend = rhi::Backend::Vulkan;
    if (!vulkan::create_vulkan_device(vulkan_desc)) ++failures;
#endif
    if (logged.count() > 0) std::fprintf(stderr, "render_headless: %d error(s) logged\n", logged.count());
    return failures == 0 && logged.count() == 0 ? 0 : 1;
}

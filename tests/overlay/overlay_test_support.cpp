#include "overlay_test_support.hpp"

#include <algorithm>

#include "render_helpers.hpp"

namespace loom::test {

Result<rhi::TextureHandle> cleared_target(rhi::Device& device, uint32_t width, uint32_t height,
                                          std::array<double, 4> color) {
    auto target = make_target(device, "overlay test target", rhi::Format::RGBA8Unorm, width, height);
    if (!target) return target.take_error();
    LOOM_TRY(run_frame(device, [&](rhi::CommandList& commands) {
        commands.begin_render_pass(clear_pass("clear", *target, color));
        commands.end_render_pass();
    }));
    return *target;
}

uint32_t count_pixels(const rhi::Image& image, const rhi::Rect& rect,
                      const std::function<bool(const std::array<double, 4>&)>& test) {
    uint32_t count = 0;
    const uint32_t x0 = static_cast<uint32_t>(std::max(rect.x, 0));
    const uint32_t y0 = static_cast<uint32_t>(std::max(rect.y, 0));
    const uint32_t x1 = std::min<uint32_t>(image.width, static_cast<uint32_t>(std::max(rect.x, 0)) + rect.width);
    const uint32_t y1 = std::min<uint32_t>(image.height, static_cast<uint32_t>(std::max(rect.y, 0)) + rect.height);
    for (uint32_t y = y0; y < y1; ++y) {
        for (uint32_t x = x0; x < x1; ++x) {
            if (test(image.load(x, y))) ++count;
        }
    }
    return count;
}

std::pair<float, float> centre(const rhi::Rect& rect) {
    return {static_cast<float>(rect.x) + static_cast<float>(rect.width) / 2.0f,
            static_cast<float>(rect.y) + static_cast<float>(rect.height) / 2.0f};
}

rhi::WindowInput hover_at(float x, float y) {
    rhi::WindowInput input;
    input.cursor_x = x;
    input.cursor_y = y;
    input.cursor_inside = true;
    input.focused = true;
    return input;
}

rhi::WindowInput tap_at(float x, float y) {
    rhi::WindowInput input = hover_at(x, y);
    input.buttons_pressed[static_cast<std::size_t>(rhi::MouseButton::Left)] = true;
    return input;
}

}  // namespace loom::test

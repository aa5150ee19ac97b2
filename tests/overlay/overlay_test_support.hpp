#pragma once
// Helpers of the frame-overlay tests: a target texture, a clear, pixel counts in a rectangle,
// and a click on one of the overlay's controls.

#include <functional>
#include <string>

#include "frame_overlay.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/image.hpp"

namespace loom::test {

/// An RGBA8 colour target of `width` x `height`, cleared to `color`.
Result<rhi::TextureHandle> cleared_target(rhi::Device& device, uint32_t width, uint32_t height,
                                          std::array<double, 4> color);

/// Pixels of `image` inside `rect` for which `test` holds.
uint32_t count_pixels(const rhi::Image& image, const rhi::Rect& rect,
                      const std::function<bool(const std::array<double, 4>&)>& test);

/// The centre of `rect`.
std::pair<float, float> centre(const rhi::Rect& rect);

/// Input with the pointer at (x, y) and the left button tapped (pressed and released within
/// one poll, as a quick click arrives).
rhi::WindowInput tap_at(float x, float y);
/// Input with the pointer at (x, y) and no button.
rhi::WindowInput hover_at(float x, float y);

}  // namespace loom::test

#pragma once
// CPU reference implementations of the post-process passes, written from the formulas in
// shaders/include/loom/parts/ (gaussian_blur, high_pass_render, composite, blit) and computed in
// float in the shaders' order of operations, then rounded to the output format as the GPU
// does: toward zero for half floats (llvmpipe and lavapipe truncate when they write RGBA16F
// attachments), to nearest for 8-bit unorm.

#include <vector>

#include "loom/passes/blur_pass.hpp"
#include "loom/rhi/image.hpp"

namespace loom::test {

/// One direction of the separable blur: texel-exact taps, edges clamped, `weights[i]` for offset i.
rhi::Image reference_blur(const rhi::Image& source, passes::BlurAxis axis, const std::vector<float>& weights);

/// The high pass: colour * max(l - threshold, 0) / max(l, 1e-4), l the Rec. 709 luminance; alpha 1.
rhi::Image reference_high_pass(const rhi::Image& source, float threshold);

/// The composite: ACES(exposure * (color + strength * bloom)), sRGB-encoded when `srgb`; alpha 1.
/// The output has `color`'s format.
rhi::Image reference_composite(const rhi::Image& color, const rhi::Image& bloom, float exposure, float strength,
                               bool srgb);

/// The blit: every texel converted to `format`.
rhi::Image reference_blit(const rhi::Image& source, rhi::Format format);

}  // namespace loom::test

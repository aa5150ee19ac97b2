#pragma once
// Shared by the embedding tests: the exact picture of the small "overlay" frame graph an engine
// embeds (samples/embed_gl/overlay_graph.hpp, the one samples/embed_gl and samples/embed_vulkan draw).
//
//   pattern (output "color", RGBA8Unorm, frame-sized): texel (x, y) =
//       (x % 16 / 15, y % 16 / 15, (x / 16 + y / 16) % 2, 1)        (exact in 8-bit unorm)
//   overlay (optional inout "target", input "pattern"): copies the pattern into the top-left
//       quadrant of the target (x < w / 2, y < h / 2, row 0 on top) and keeps the rest: the
//       application's texture bound to "target" shows its own clear colour around it.

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "loom/framegraph/framegraph.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/image.hpp"
#include "overlay_graph.hpp"

/// Assigns the value of a Result expression to `lhs`, or fails the test with its error.
#define LOOM_EMBED_CONCAT_INNER(a, b) a##b
#define LOOM_EMBED_CONCAT(a, b) LOOM_EMBED_CONCAT_INNER(a, b)
#define LOOM_EMBED_ASSIGN(lhs, expr)                                                            \
    auto LOOM_EMBED_CONCAT(loom_result_, __LINE__) = (expr);                                    \
    ASSERT_TRUE(LOOM_EMBED_CONCAT(loom_result_, __LINE__).ok())                                 \
        << #expr << ": " << LOOM_EMBED_CONCAT(loom_result_, __LINE__).error().to_string();       \
    lhs = std::move(*LOOM_EMBED_CONCAT(loom_result_, __LINE__))
/// Fails the test when a Status expression is an error.
#define LOOM_EMBED_OK(expr)                                                                     \
    do {                                                                                        \
        auto loom_status_ = (expr);                                                             \
        ASSERT_TRUE(loom_status_.ok()) << #expr << ": " << loom_status_.error().to_string();    \
    } while (false)

namespace loom::test {

/// RGBA8 bytes of a texel.
using Rgba8 = std::array<uint8_t, 4>;

/// The application's clear colour around the overlay: (0.2, 0.4, 0.6, 1) = (51, 102, 153, 255).
inline constexpr std::array<double, 4> kEngineClear{0.2, 0.4, 0.6, 1.0};
inline constexpr Rgba8 kEngineClearBytes{51, 102, 153, 255};

/// The pattern pass's texel (x, y).
Rgba8 expected_pattern(uint32_t x, uint32_t y);
/// The target after the overlay graph ran over a target cleared to kEngineClear.
Rgba8 expected_overlay(uint32_t x, uint32_t y, uint32_t width, uint32_t height);

/// Compares an RGBA8 image (rows top-first) with expected_overlay; on a mismatch the message
/// names the first differing texel and how many differ, and the image is written under
/// output_dir()/embed/<name>.png.
::testing::AssertionResult matches_overlay(const rhi::Image& image, const std::string& name);

/// The overlay graph both embedding samples run (samples/embed_gl/overlay_graph.hpp, compiled
/// into the tests too, so they run without the samples).
using samples::OverlayGraph;

/// Compiles GLSL 450 for `device` (runtime compiler).
Result<rhi::ShaderHandle> compile_shader(rhi::Device& device, rhi::ShaderStage stage, const std::string& name,
                                         const std::string& source);

}  // namespace loom::test

#pragma once
// Shared by the Vulkan-only tests: a validated Vulkan device through the RHI, small shaders
// and one-frame helpers.

#include <array>
#include <functional>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "loom/rhi/device.hpp"
#include "loom/shader_compiler/shader_compiler.hpp"

namespace loom::test {

/// A headless Vulkan device with validation (and synchronisation validation) on.
std::unique_ptr<rhi::Device> make_vulkan_device();

/// A pipeline drawing a full-screen triangle in the colour given as push constant (vec4),
/// into one colour attachment of `format`.
Result<rhi::PipelineHandle> make_fill_pipeline(rhi::Device& device, rhi::Format format);

/// Records and submits one frame.
Status record_frame(rhi::Device& device, const std::function<void(rhi::CommandList&)>& record);

/// A render pass over `target` that clears it to `clear` and fills it with `fill` using
/// `pipeline` (made by make_fill_pipeline) inside the given pixel rectangle.
void clear_and_fill(rhi::CommandList& list, rhi::TextureHandle target, rhi::PipelineHandle pipeline,
                    std::array<double, 4> clear, std::array<float, 4> fill, rhi::Rect rect);

}  // namespace loom::test

#define LOOM_VK_ASSIGN(lhs, expr)                                                               \
    auto LOOM_VK_CAT(loom_vk_, __LINE__) = (expr);                                              \
    ASSERT_TRUE(LOOM_VK_CAT(loom_vk_, __LINE__).ok()) << #expr << ": "                          \
                                                     << LOOM_VK_CAT(loom_vk_, __LINE__).error().to_string(); \
    lhs = std::move(*LOOM_VK_CAT(loom_vk_, __LINE__))
#define LOOM_VK_CAT_INNER(a, b) a##b
#define LOOM_VK_CAT(a, b) LOOM_VK_CAT_INNER(a, b)
#define LOOM_VK_OK(expr)                                                                        \
    do {                                                                                        \
        auto loom_vk_status_ = (expr);                                                          \
        ASSERT_TRUE(loom_vk_status_.ok()) << #expr << ": " << loom_vk_status_.error().to_string(); \
    } while (false)

#pragma once
// Factory of the Vulkan 1.3 backend. Samples and tests normally go through
// rhi::create_device(); this header is what backends/create_device.cpp calls.

#include <memory>

#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

namespace loom::vulkan {

/// Creates a Vulkan device (headless, or with a GLFW window and swapchain when
/// `desc.headless` is false). With `desc.debug` the Khronos validation layer is enabled and
/// its warnings and errors are logged at LogLevel::Error (source "vulkan").
///
/// Environment: LOOM_VK_DEVICE picks the physical device by index or by a substring of its
/// name; LOOM_VK_SYNC_VALIDATION=0 turns synchronisation validation off.
loom::Result<std::unique_ptr<loom::rhi::Device>> create_vulkan_device(const loom::rhi::DeviceDesc& desc);

}  // namespace loom::vulkan

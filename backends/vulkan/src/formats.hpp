#pragma once
// loom formats and enums as Vulkan values, and the capabilities a physical device reports.

#include <vulkan/vulkan.h>

#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/device.hpp"

namespace loom::vulkan {

/// The VkFormat of a loom format (VK_FORMAT_UNDEFINED for Undefined).
VkFormat to_vk_format(rhi::Format format);

/// Fills Capabilities::formats from vkGetPhysicalDeviceFormatProperties (optimal tiling).
void query_format_capabilities(VkPhysicalDevice physical_device, rhi::Capabilities& caps);

VkCompareOp to_vk(rhi::CompareOp op);
VkFilter to_vk(rhi::Filter filter);
VkSamplerMipmapMode to_vk_mipmap(rhi::Filter filter);
VkSamplerAddressMode to_vk(rhi::AddressMode mode);
VkBorderColor to_vk(rhi::BorderColor color);
VkFormat to_vk(rhi::VertexFormat format);
VkPrimitiveTopology to_vk(rhi::PrimitiveTopology topology);
VkCullModeFlags to_vk(rhi::CullMode mode);
VkFrontFace to_vk(rhi::FrontFace face);
VkPolygonMode to_vk(rhi::PolygonMode mode);
VkBlendFactor to_vk(rhi::BlendFactor factor);
VkBlendOp to_vk(rhi::BlendOp op);
VkColorComponentFlags to_vk(rhi::ColorMask mask);
VkAttachmentLoadOp to_vk(rhi::LoadOp op);
VkAttachmentStoreOp to_vk(rhi::StoreOp op);
VkIndexType to_vk(rhi::IndexType type);

/// The clear value of a colour attachment, converted to the attachment's channel kind.
VkClearColorValue clear_color(rhi::Format format, const std::array<double, 4>& value);

}  // namespace loom::vulkan

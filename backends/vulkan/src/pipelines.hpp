#pragma once
// Graphics and compute pipelines from loom descriptions (dynamic rendering, dynamic viewport
// and scissor), and the key under which equal descriptions share one VkPipeline.

#include <string>

#include <vulkan/vulkan.h>

#include "descriptors.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/result.hpp"
#include "objects.hpp"

namespace loom::vulkan {

class VulkanContext;

/// A byte-exact key of everything in `desc` that affects the VkPipeline (not its name).
std::string graphics_pipeline_key(const rhi::GraphicsPipelineDesc& desc);
std::string compute_pipeline_key(const rhi::ComputePipelineDesc& desc);

loom::Result<VkPipeline> build_graphics_pipeline(const VulkanContext& context, VkPipelineCache cache,
                                                 const rhi::GraphicsPipelineDesc& desc, const Shader& vertex,
                                                 const Shader& fragment, const PipelineLayout& layout);
loom::Result<VkPipeline> build_compute_pipeline(const VulkanContext& context, VkPipelineCache cache,
                                                const rhi::ComputePipelineDesc& desc, const Shader& compute,
                                                const PipelineLayout& layout);

}  // namespace loom::vulkan

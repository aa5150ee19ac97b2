#include "pipelines.hpp"

#include <algorithm>
#include <cstring>

#include "formats.hpp"
#include "loom/vulkan/context.hpp"
#include "loom/rhi/validation.hpp"

namespace loom::vulkan {
namespace {

template <class T>
void append(std::string& key, const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    key.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

using rhi::validation::in_quotes;

}  // namespace

std::string graphics_pipeline_key(const rhi::GraphicsPipelineDesc& d) {
    std::string key = "G";
    append(key, d.vertex);
    append(key, d.fragment);
    append(key, d.vertex_buffers.size());
    for (const auto& vb : d.vertex_buffers) {
        append(key, vb.stride);
        append(key, vb.step);
        append(key, vb.attributes.size());
        for (const auto& a : vb.attributes) {
            append(key, a.location);
            append(key, a.format);
            append(key, a.offset);
        }
    }
    append(key, d.topology);
    append(key, d.raster.cull);
    append(key, d.raster.front_face);
    append(key, d.raster.polygon);
    append(key, d.raster.depth_clamp);
    append(key, d.raster.depth_bias_constant);
    append(key, d.raster.depth_bias_slope);
    append(key, d.depth.test);
    append(key, d.depth.write);
    append(key, d.depth.compare);
    append(key, d.color_formats.size());
    for (auto f : d.color_formats) append(key, f);
    append(key, d.blend.size());
    for (const auto& b : d.blend) {
        append(key, b.enabled);
        append(key, b.src_color);
        append(key, b.dst_color);
        append(key, b.color_op);
        append(key, b.src_alpha);
        append(key, b.dst_alpha);
        append(key, b.alpha_op);
        append(key, b.write_mask);
    }
    append(key, d.depth_format);
    append(key, d.samples);
    return key;
}

std::string compute_pipeline_key(const rhi::ComputePipelineDesc& d) {
    std::string key = "C";
    append(key, d.compute);
    return key;
}

loom::Result<VkPipeline> build_graphics_pipeline(const VulkanContext& context, VkPipelineCache cache,
                                                 const rhi::GraphicsPipelineDesc& d, const Shader& vertex,
                                                 const Shader& fragment, const PipelineLayout& layout) {
    VkPipelineShaderStageCreateInfo stages[2]{};
    stages[0].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vertex.shader;
    stages[0].pName = vertex.module.entry_point.c_str();
    stages[1].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fragment.shader;
    stages[1].pName = fragment.module.entry_point.c_str();

    std::vector<VkVertexInputBindingDescription> bindings;
    std::vector<VkVertexInputAttributeDescription> attributes;
    for (uint32_t slot = 0; slot < d.vertex_buffers.size(); ++slot) {
        const rhi::VertexBufferLayout& vb = d.vertex_buffers[slot];
        bindings.push_back({slot, vb.stride,
                            vb.step == rhi::VertexStepMode::PerInstance ? VK_VERTEX_INPUT_RATE_INSTANCE : VK_VERTEX_INPUT_RATE_VERTEX});
        for (const rhi::VertexAttribute& a : vb.attributes) attributes.push_back({a.location, slot, to_vk(a.format), a.offset});
    }
    auto vertex_input = vk_init<VkPipelineVertexInputStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
    vertex_input.vertexBindingDescriptionCount = static_cast<uint32_t>(bindings.size());
    vertex_input.pVertexBindingDescriptions = bindings.data();
    vertex_input.vertexAttributeDescriptionCount = static_cast<uint32_t>(attributes.size());
    vertex_input.pVertexAttributeDescriptions = attributes.data();

    auto assembly = vk_init<VkPipelineInputAssemblyStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO);
    assembly.topology = to_vk(d.topology);

    auto viewport = vk_init<VkPipelineViewportStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO);
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;

    auto raster = vk_init<VkPipelineRasterizationStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
    raster.depthClampEnable = d.raster.depth_clamp;
    raster.polygonMode = to_vk(d.raster.polygon);
    raster.cullMode = to_vk(d.raster.cull);
    raster.frontFace = to_vk(d.raster.front_face);
    raster.depthBiasEnable = d.raster.depth_bias_constant != 0.0f || d.raster.depth_bias_slope != 0.0f;
    raster.depthBiasConstantFactor = d.raster.depth_bias_constant;
    raster.depthBiasSlopeFactor = d.raster.depth_bias_slope;
    raster.lineWidth = 1.0f;

    auto multisample = vk_init<VkPipelineMultisampleStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
    multisample.rasterizationSamples = static_cast<VkSampleCountFlagBits>(d.samples);

    auto depth = vk_init<VkPipelineDepthStencilStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO);
    depth.depthTestEnable = d.depth.test;
    depth.depthWriteEnable = d.depth.write;
    // GL ignores depth writes with the test off; Vulkan writes nothing either then, since
    // depth writes happen only when the test is enabled.
    depth.depthCompareOp = to_vk(d.depth.compare);

    std::vector<VkPipelineColorBlendAttachmentState> blends(d.color_formats.size());
    for (std::size_t i = 0; i < blends.size(); ++i) {
        const rhi::BlendState b = i < d.blend.size() ? d.blend[i] : rhi::BlendState{};
        VkPipelineColorBlendAttachmentState& s = blends[i];
        s.blendEnable = b.enabled;
        s.srcColorBlendFactor = to_vk(b.src_color);
        s.dstColorBlendFactor = to_vk(b.dst_color);
        s.colorBlendOp = to_vk(b.color_op);
        s.srcAlphaBlendFactor = to_vk(b.src_alpha);
        s.dstAlphaBlendFactor = to_vk(b.dst_alpha);
        s.alphaBlendOp = to_vk(b.alpha_op);
        s.colorWriteMask = to_vk(b.write_mask);
    }
    auto blend = vk_init<VkPipelineColorBlendStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO);
    blend.attachmentCount = static_cast<uint32_t>(blends.size());
    blend.pAttachments = blends.data();

    const VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    auto dynamic = vk_init<VkPipelineDynamicStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO);
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamic_states;

    std::vector<VkFormat> color_formats;
    for (rhi::Format f : d.color_formats) color_formats.push_back(to_vk_format(f));
    auto rendering = vk_init<VkPipelineRenderingCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO);
    rendering.colorAttachmentCount = static_cast<uint32_t>(color_formats.size());
    rendering.pColorAttachmentFormats = color_formats.data();
    if (d.depth_format != rhi::Format::Undefined) {
        const rhi::FormatInfo& info = rhi::format_info(d.depth_format);
        if (info.has_depth()) rendering.depthAttachmentFormat = to_vk_format(d.depth_format);
        if (info.has_stencil()) rendering.stencilAttachmentFormat = to_vk_format(d.depth_format);
    }

    auto info = vk_init<VkGraphicsPipelineCreateInfo>(VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO);
    info.pNext = &rendering;
    info.stageCount = 2;
    info.pStages = stages;
    info.pVertexInputState = &vertex_input;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend;
    info.pDynamicState = &dynamic;
    info.layout = layout.layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    if (VkResult r = vkCreateGraphicsPipelines(context.device(), cache, 1, &info, nullptr, &pipeline); r != VK_SUCCESS) {
        Error e = vk_error(r, "vkCreateGraphicsPipelines for pipeline " + in_quotes(d.name));
        e.code = ErrorCode::ShaderLink;
        return e;
    }
    context.set_name(VK_OBJECT_TYPE_PIPELINE, reinterpret_cast<uint64_t>(pipeline), d.name);
    return pipeline;
}

loom::Result<VkPipeline> build_compute_pipeline(const VulkanContext& context, VkPipelineCache cache,
                                                const rhi::ComputePipelineDesc& d, const Shader& compute,
                                                const PipelineLayout& layout) {
    auto info = vk_init<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
    info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = compute.shader;
    info.stage.pName = compute.module.entry_point.c_str();
    info.layout = layout.layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    if (VkResult r = vkCreateComputePipelines(context.device(), cache, 1, &info, nullptr, &pipeline); r != VK_SUCCESS) {
        Error e = vk_error(r, "vkCreateComputePipelines for pipeline " + in_quotes(d.name));
        e.code = ErrorCode::ShaderLink;
        return e;
    }
    context.set_name(VK_OBJECT_TYPE_PIPELINE, reinterpret_cast<uint64_t>(pipeline), d.name);
    return pipeline;
}

}  // namespace loom::vulkan

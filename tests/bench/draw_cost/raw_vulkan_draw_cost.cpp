// raw_vulkan_draw_cost: the work of loom_draw_cost --backend vulkan written directly against
// Vulkan 1.3 (dynamic rendering), the way a competent Vulkan programmer would: push constants,
// per-draw uniform data at a dynamic offset into a mapped ring, prebuilt descriptor sets. Only
// the instance and device come from loom (VulkanContext, validation off); nothing of loom runs
// inside the measured frame.
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "draw_cost_common.hpp"
#include "loom/vulkan/context.hpp"

namespace {

using namespace loom;
using draw_cost::Path;

[[noreturn]] void die(const std::string& message) {
    std::fprintf(stderr, "raw_vulkan_draw_cost: %s\n", message.c_str());
    std::exit(EXIT_FAILURE);
}

void check(VkResult result, const char* what) {
    if (result != VK_SUCCESS) die(std::string(what) + " failed (" + std::to_string(static_cast<int>(result)) + ")");
}

struct Raw {
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    VkPhysicalDeviceMemoryProperties memory{};
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    VkImage target = VK_NULL_HANDLE;
    VkImageView target_view = VK_NULL_HANDLE;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    std::array<VkPipeline, 2> pipelines{};
    VkDescriptorPool descriptor_pool = VK_NULL_HANDLE;
    std::array<VkDescriptorSet, 2> sets{};
    VkBuffer ring = VK_NULL_HANDLE;
    std::byte* ring_memory = nullptr;
    VkDeviceSize ring_alignment = 256;
    std::array<VkBuffer, 2> vertices{}, indices{};
};

uint32_t memory_type(const Raw& r, uint32_t bits, VkMemoryPropertyFlags wanted) {
    for (uint32_t i = 0; i < r.memory.memoryTypeCount; ++i) {
        if ((bits & (1u << i)) && (r.memory.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
    }
    die("no suitable memory type");
}

VkDeviceMemory bind_memory(const Raw& r, VkMemoryRequirements req, VkMemoryPropertyFlags flags) {
    VkMemoryAllocateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    info.allocationSize = req.size;
    info.memoryTypeIndex = memory_type(r, req.memoryTypeBits, flags);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    check(vkAllocateMemory(r.device, &info, nullptr, &memory), "vkAllocateMemory");
    return memory;
}

/// A host-visible buffer with `data` in it (or `size` bytes left for the caller), mapped.
VkBuffer host_buffer(const Raw& r, VkBufferUsageFlags usage, VkDeviceSize size, const void* data, std::byte** mapped = nullptr) {
    VkBufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    info.size = size;
    info.usage = usage;
    VkBuffer buffer = VK_NULL_HANDLE;
    check(vkCreateBuffer(r.device, &info, nullptr, &buffer), "vkCreateBuffer");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(r.device, buffer, &req);
    VkDeviceMemory memory = bind_memory(r, req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    check(vkBindBufferMemory(r.device, buffer, memory, 0), "vkBindBufferMemory");
    void* pointer = nullptr;
    check(vkMapMemory(r.device, memory, 0, VK_WHOLE_SIZE, 0, &pointer), "vkMapMemory");
    if (data) std::memcpy(pointer, data, size);
    if (mapped) *mapped = static_cast<std::byte*>(pointer);
    return buffer;
}

VkImage image(const Raw& r, uint32_t size, VkImageUsageFlags usage, VkImageView& view) {
    VkImageCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = VK_FORMAT_R8G8B8A8_UNORM;
    info.extent = {size, size, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    VkImage result = VK_NULL_HANDLE;
    check(vkCreateImage(r.device, &info, nullptr, &result), "vkCreateImage");
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(r.device, result, &req);
    check(vkBindImageMemory(r.device, result, bind_memory(r, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT), 0), "vkBindImageMemory");
    VkImageViewCreateInfo view_info{};
    view_info.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    view_info.image = result;
    view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view_info.format = info.format;
    view_info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    check(vkCreateImageView(r.device, &view_info, nullptr, &view), "vkCreateImageView");
    return result;
}

VkShaderModule shader_module(const Raw& r, const rhi::ShaderModule& module) {
    VkShaderModuleCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    info.codeSize = module.spirv.size() * sizeof(uint32_t);
    info.pCode = module.spirv.data();
    VkShaderModule result = VK_NULL_HANDLE;
    check(vkCreateShaderModule(r.device, &info, nullptr, &result), "vkCreateShaderModule");
    return result;
}

VkPipeline pipeline(const Raw& r, Path path, int variant) {
    auto vs = draw_cost::vertex_shader(path);
    auto fs = draw_cost::fragment_shader(path, variant);
    if (!vs.ok() || !fs.ok()) die("shader compilation failed");
    std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
    stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT,
                 shader_module(r, *vs), "main", nullptr};
    stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT,
                 shader_module(r, *fs), "main", nullptr};
    const VkVertexInputBindingDescription binding{0, 8, VK_VERTEX_INPUT_RATE_VERTEX};
    const VkVertexInputAttributeDescription attribute{0, 0, VK_FORMAT_R32G32_SFLOAT, 0};
    VkPipelineVertexInputStateCreateInfo vertex_input{};
    vertex_input.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
    if (path == Path::VertexBuffers) {
        vertex_input.vertexBindingDescriptionCount = 1;
        vertex_input.pVertexBindingDescriptions = &binding;
        vertex_input.vertexAttributeDescriptionCount = 1;
        vertex_input.pVertexAttributeDescriptions = &attribute;
    }
    VkPipelineInputAssemblyStateCreateInfo assembly{};
    assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{};
    viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{};
    raster.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_NONE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{};
    multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo depth{};
    depth.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
    VkPipelineColorBlendAttachmentState blend_attachment{};
    blend_attachment.colorWriteMask = 0xF;
    VkPipelineColorBlendStateCreateInfo blend{};
    blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
    blend.attachmentCount = 1;
    blend.pAttachments = &blend_attachment;
    const std::array<VkDynamicState, 2> dynamic_states = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{};
    dynamic.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamic_states.data();
    const VkFormat color_format = VK_FORMAT_R8G8B8A8_UNORM;
    VkPipelineRenderingCreateInfo rendering{};
    rendering.sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO;
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachmentFormats = &color_format;
    VkGraphicsPipelineCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
    info.pNext = &rendering;
    info.stageCount = 2;
    info.pStages = stages.data();
    info.pVertexInputState = &vertex_input;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend;
    info.pDynamicState = &dynamic;
    info.layout = r.layout;
    VkPipeline result = VK_NULL_HANDLE;
    check(vkCreateGraphicsPipelines(r.device, VK_NULL_HANDLE, 1, &info, nullptr, &result), "vkCreateGraphicsPipelines");
    return result;
}

void submit_and_wait(const Raw& r) {
    VkSubmitInfo submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &r.cmd;
    check(vkQueueSubmit(r.queue, 1, &submit, r.fence), "vkQueueSubmit");
    check(vkWaitForFences(r.device, 1, &r.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    check(vkResetFences(r.device, 1, &r.fence), "vkResetFences");
}

void begin_commands(const Raw& r) {
    check(vkResetCommandPool(r.device, r.pool, 0), "vkResetCommandPool");
    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(r.cmd, &begin), "vkBeginCommandBuffer");
}

void to_layout(const Raw& r, VkImage image, VkImageLayout layout, VkPipelineStageFlags2 stage, VkAccessFlags2 access) {
    VkImageMemoryBarrier2 barrier{};
    barrier.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2;
    barrier.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    barrier.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
    barrier.dstStageMask = stage;
    barrier.dstAccessMask = access;
    barrier.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    barrier.newLayout = layout;
    barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkDependencyInfo dependency{};
    dependency.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
    dependency.imageMemoryBarrierCount = 1;
    dependency.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(r.cmd, &dependency);
}

Raw create(const vulkan::VulkanContext& context, Path path, uint32_t draws) {
    Raw r;
    r.device = context.device();
    r.queue = context.queue();
    r.memory = context.memory_properties();
    VkCommandPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pool_info.queueFamilyIndex = context.queue_family();
    check(vkCreateCommandPool(r.device, &pool_info, nullptr, &r.pool), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo cmd_info{};
    cmd_info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    cmd_info.commandPool = r.pool;
    cmd_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cmd_info.commandBufferCount = 1;
    check(vkAllocateCommandBuffers(r.device, &cmd_info, &r.cmd), "vkAllocateCommandBuffers");
    VkFenceCreateInfo fence_info{};
    fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    check(vkCreateFence(r.device, &fence_info, nullptr, &r.fence), "vkCreateFence");
    r.target = image(r, 64, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, r.target_view);

    // The layout: push constants, a dynamic uniform buffer or a sampled image, as the path needs.
    VkDescriptorSetLayoutBinding binding{};
    binding.binding = 0;
    binding.descriptorCount = 1;
    if (path == Path::TransientUniforms) {
        binding.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC;
        binding.stageFlags = VK_SHADER_STAGE_VERTEX_BIT;
    } else {
        binding.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        binding.stageFlags = VK_SHADER_STAGE_FRAGMENT_BIT;
    }
    const bool has_set = path == Path::TransientUniforms || path == Path::BindGroup;
    VkDescriptorSetLayoutCreateInfo set_info{};
    set_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    set_info.bindingCount = has_set ? 1 : 0;
    set_info.pBindings = &binding;
    check(vkCreateDescriptorSetLayout(r.device, &set_info, nullptr, &r.set_layout), "vkCreateDescriptorSetLayout");
    const VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(draw_cost::DrawConstants)};
    VkPipelineLayoutCreateInfo layout_info{};
    layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &r.set_layout;
    layout_info.pushConstantRangeCount = path == Path::PushConstants ? 1 : 0;
    layout_info.pPushConstantRanges = &push;
    check(vkCreatePipelineLayout(r.device, &layout_info, nullptr, &r.layout), "vkCreatePipelineLayout");
    for (int variant = 0; variant < (path == Path::Pipeline ? 2 : 1); ++variant) {
        r.pipelines[static_cast<std::size_t>(variant)] = pipeline(r, path, variant);
    }

    if (has_set) {
        const VkDescriptorPoolSize size{binding.descriptorType, 2};
        VkDescriptorPoolCreateInfo pool{};
        pool.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
        pool.maxSets = 2;
        pool.poolSizeCount = 1;
        pool.pPoolSizes = &size;
        check(vkCreateDescriptorPool(r.device, &pool, nullptr, &r.descriptor_pool), "vkCreateDescriptorPool");
        const std::array<VkDescriptorSetLayout, 2> layouts = {r.set_layout, r.set_layout};
        VkDescriptorSetAllocateInfo alloc{};
        alloc.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
        alloc.descriptorPool = r.descriptor_pool;
        alloc.descriptorSetCount = 2;
        alloc.pSetLayouts = layouts.data();
        check(vkAllocateDescriptorSets(r.device, &alloc, r.sets.data()), "vkAllocateDescriptorSets");
    }
    if (path == Path::TransientUniforms) {
        // Each draw's constants at the next multiple of the offset alignment after the last.
        const VkDeviceSize alignment = context.properties().limits.minUniformBufferOffsetAlignment;
        r.ring_alignment = (sizeof(draw_cost::DrawConstants) + alignment - 1) / alignment * alignment;
        r.ring = host_buffer(r, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, draws * r.ring_alignment, nullptr, &r.ring_memory);
        const VkDescriptorBufferInfo range{r.ring, 0, sizeof(draw_cost::DrawConstants)};
        VkWriteDescriptorSet write{};
        write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        write.dstSet = r.sets[0];
        write.descriptorCount = 1;
        write.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC;
        write.pBufferInfo = &range;
        vkUpdateDescriptorSets(r.device, 1, &write, 0, nullptr);
    }
    if (path == Path::BindGroup) {
        VkSamplerCreateInfo sampler_info{};
        sampler_info.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
        sampler_info.magFilter = sampler_info.minFilter = VK_FILTER_LINEAR;
        VkSampler sampler = VK_NULL_HANDLE;
        check(vkCreateSampler(r.device, &sampler_info, nullptr, &sampler), "vkCreateSampler");
        begin_commands(r);
        for (std::size_t i = 0; i < 2; ++i) {
            VkImageView view = VK_NULL_HANDLE;
            const VkImage texture = image(r, 4, VK_IMAGE_USAGE_SAMPLED_BIT, view);
            to_layout(r, texture, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
            const VkDescriptorImageInfo image_info{sampler, view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
            VkWriteDescriptorSet write{};
            write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
            write.dstSet = r.sets[i];
            write.descriptorCount = 1;
            write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            write.pImageInfo = &image_info;
            vkUpdateDescriptorSets(r.device, 1, &write, 0, nullptr);
        }
        check(vkEndCommandBuffer(r.cmd), "vkEndCommandBuffer");
        submit_and_wait(r);
    }
    if (path == Path::VertexBuffers) {
        for (std::size_t i = 0; i < 2; ++i) {
            const float d = i == 0 ? 0.0f : 0.5f;
            const std::array<float, 6> positions = {-0.9f + d, -0.9f, -0.8f + d, -0.9f, -0.9f + d, -0.8f};
            const std::array<uint32_t, 3> triangle = {0, 1, 2};
            r.vertices[i] = host_buffer(r, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, sizeof positions, positions.data());
            r.indices[i] = host_buffer(r, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, sizeof triangle, triangle.data());
        }
    }
    return r;
}

void frame(const Raw& r, Path path, uint32_t draws) {
    begin_commands(r);
    to_layout(r, r.target, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
              VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    VkRenderingAttachmentInfo color{};
    color.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
    color.imageView = r.target_view;
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    VkRenderingInfo rendering{};
    rendering.sType = VK_STRUCTURE_TYPE_RENDERING_INFO;
    rendering.renderArea = {{0, 0}, {64, 64}};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachments = &color;
    vkCmdBeginRendering(r.cmd, &rendering);
    const VkViewport viewport{0, 0, 64, 64, 0, 1};
    const VkRect2D scissor{{0, 0}, {64, 64}};
    vkCmdSetViewport(r.cmd, 0, 1, &viewport);
    vkCmdSetScissor(r.cmd, 0, 1, &scissor);
    vkCmdBindPipeline(r.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.pipelines[0]);
    switch (path) {
        case Path::PushConstants:
            for (uint32_t i = 0; i < draws; ++i) {
                const draw_cost::DrawConstants c = draw_cost::draw_constants(i);
                vkCmdPushConstants(r.cmd, r.layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof c, &c);
                vkCmdDraw(r.cmd, 3, 1, 0, 0);
            }
            break;
        case Path::TransientUniforms:
            for (uint32_t i = 0; i < draws; ++i) {
                const draw_cost::DrawConstants c = draw_cost::draw_constants(i);
                const auto offset = static_cast<uint32_t>(i * r.ring_alignment);
                std::memcpy(r.ring_memory + offset, &c, sizeof c);
                vkCmdBindDescriptorSets(r.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.layout, 0, 1, &r.sets[0], 1, &offset);
                vkCmdDraw(r.cmd, 3, 1, 0, 0);
            }
            break;
        case Path::BindGroup:
            for (uint32_t i = 0; i < draws; ++i) {
                vkCmdBindDescriptorSets(r.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.layout, 0, 1, &r.sets[i & 1], 0, nullptr);
                vkCmdDraw(r.cmd, 3, 1, 0, 0);
            }
            break;
        case Path::VertexBuffers:
            for (uint32_t i = 0; i < draws; ++i) {
                const VkDeviceSize offset = 0;
                vkCmdBindVertexBuffers(r.cmd, 0, 1, &r.vertices[i & 1], &offset);
                vkCmdBindIndexBuffer(r.cmd, r.indices[i & 1], 0, VK_INDEX_TYPE_UINT32);
                vkCmdDrawIndexed(r.cmd, 3, 1, 0, 0, 0);
            }
            break;
        case Path::Pipeline:
            for (uint32_t i = 0; i < draws; ++i) {
                vkCmdBindPipeline(r.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.pipelines[i & 1]);
                vkCmdDraw(r.cmd, 3, 1, 0, 0);
            }
            break;
    }
    vkCmdEndRendering(r.cmd);
    check(vkEndCommandBuffer(r.cmd), "vkEndCommandBuffer");
    submit_and_wait(r);
}

}  // namespace

int main(int argc, char** argv) {
    auto options = draw_cost::parse_options(argc, argv, false);
    if (!options.ok()) die(options.error().message);
    vulkan::ContextOptions context_options;
    context_options.validation = false;
    context_options.synchronization_validation = false;
    auto context = vulkan::VulkanContext::create(context_options);
    if (!context.ok()) die(context.error().to_string());
    const Raw raw = create(**context, options->path, options->draws);
    for (uint32_t i = 0; i < options->warmup_frames; ++i) frame(raw, options->path, options->draws);
    draw_cost::begin_measurement();
    frame(raw, options->path, options->draws);
    draw_cost::end_measurement();
    draw_cost::report("raw-vulkan", *options);
    check(vkDeviceWaitIdle(raw.device), "vkDeviceWaitIdle");
    return EXIT_SUCCESS;
}

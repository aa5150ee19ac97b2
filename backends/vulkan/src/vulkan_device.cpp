#include "vulkan_device.hpp"

#include "formats.hpp"
#include "loom/rhi/log.hpp"
#include "loom/vulkan/vulkan_device.hpp"

namespace loom::vulkan {

loom::Result<std::unique_ptr<rhi::Device>> create_vulkan_device(const rhi::DeviceDesc& desc) {
    return VulkanDevice::create(desc);
}

namespace {
// Big enough for a 1024x1024 RGBA32F upload in one piece; larger ones use a temporary buffer.
constexpr VkDeviceSize kStagingRingSize = VkDeviceSize{16} << 20;
constexpr uint64_t kInitialUniformRing = 256 * 1024;
}  // namespace

loom::Result<std::unique_ptr<rhi::Device>> VulkanDevice::create(const rhi::DeviceDesc& desc) {
    std::unique_ptr<VulkanDevice> device(new VulkanDevice());
    if (auto status = device->init(desc); !status.ok()) return status.take_error();
    return std::unique_ptr<rhi::Device>(std::move(device));
}

loom::Result<std::unique_ptr<rhi::Device>> VulkanDevice::create_external(const ExternalDeviceDesc& desc) {
    std::unique_ptr<VulkanDevice> device(new VulkanDevice());
    auto context = VulkanContext::adopt(desc);
    if (!context.ok()) return context.take_error();
    device->context_ = std::move(*context);
    rhi::DeviceDesc device_desc;
    device_desc.backend = rhi::Backend::Vulkan;
    device_desc.debug = desc.debug_utils;
    device_desc.validation = desc.validation;
    if (auto status = device->init_device(device_desc); !status.ok()) return status.take_error();
    return std::unique_ptr<rhi::Device>(std::move(device));
}

loom::Status VulkanDevice::init(const rhi::DeviceDesc& desc) {
    debug_ = desc.debug;
    ContextOptions options;
    options.validation = desc.debug;
    if (!desc.headless) {
        auto window = Window::create(desc.window);
        if (!window.ok()) return window.take_error();
        window_ = std::move(*window);
        options.instance_extensions = Window::required_instance_extensions();
        Window* w = window_.get();
        options.create_surface = [w](VkInstance instance) { return w->create_surface(instance); };
    }
    auto context = VulkanContext::create(options);
    if (!context.ok()) return context.take_error();
    context_ = std::move(*context);
    return init_device(desc);
}

loom::Status VulkanDevice::init_device(const rhi::DeviceDesc& desc) {
    VkDevice device = context_->device();

    allocator_ = std::make_unique<MemoryAllocator>(context_->physical_device(), device);
    submissions_ = std::make_unique<SubmissionTracker>(device);
    staging_ = std::make_unique<StagingRing>(device, *allocator_, kStagingRingSize);
    LOOM_TRY(staging_->init());
    layouts_ = std::make_unique<LayoutCache>(device, context_->properties().limits.maxDescriptorSetUniformBuffersDynamic);
    auto cache_info = vk_init<VkPipelineCacheCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO);
    if (VkResult r = vkCreatePipelineCache(device, &cache_info, nullptr, &pipeline_cache_); r != VK_SUCCESS) {
        return vk_error(r, "vkCreatePipelineCache");
    }

    // ---- capabilities ---------------------------------------------------------------------
    const VkPhysicalDeviceProperties& props = context_->properties();
    caps_.backend = rhi::Backend::Vulkan;
    caps_.device_name = props.deviceName;
    caps_.api_version = "Vulkan " + std::to_string(VK_API_VERSION_MAJOR(props.apiVersion)) + "." +
                        std::to_string(VK_API_VERSION_MINOR(props.apiVersion)) + "." +
                        std::to_string(VK_API_VERSION_PATCH(props.apiVersion));
    query_format_capabilities(context_->physical_device(), caps_);
    caps_.placed_resources = true;
    // Indirect draws whose instances start past 0 need drawIndirectFirstInstance.
    caps_.draw_indirect = context_->draw_indirect_first_instance();
    caps_.timestamps = context_->timestamp_valid_bits() > 0 && props.limits.timestampPeriod > 0.0f;
    caps_.async_compute = context_->compute_queue() != context_->queue();
    caps_.polygon_mode_line = context_->fill_mode_non_solid();
    caps_.depth_clamp = context_->depth_clamp();
    caps_.max_texture_size = props.limits.maxImageDimension2D;
    caps_.max_texture_layers = props.limits.maxImageArrayLayers;
    caps_.max_texture_size_3d = props.limits.maxImageDimension3D;
    caps_.max_texture_size_cube = props.limits.maxImageDimensionCube;
    // The most samples both colour and depth attachments allow: the highest common bit.
    const VkSampleCountFlags counts =
        props.limits.framebufferColorSampleCounts & props.limits.framebufferDepthSampleCounts;
    caps_.max_samples = 1;
    for (uint32_t n = 64; n > 1; n /= 2) {
        if (counts & n) {
            caps_.max_samples = n;
            break;
        }
    }
    caps_.max_color_attachments = props.limits.maxColorAttachments;
    caps_.uniform_buffer_offset_alignment = props.limits.minUniformBufferOffsetAlignment;
    caps_.storage_buffer_offset_alignment = props.limits.minStorageBufferOffsetAlignment;

    // ---- command pools and frames in flight ------------------------------------------------
    auto pool_info = vk_init<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    pool_info.queueFamilyIndex = context_->queue_family();
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    if (VkResult r = vkCreateCommandPool(device, &pool_info, nullptr, &setup_pool_); r != VK_SUCCESS) {
        return vk_error(r, "vkCreateCommandPool");
    }
    pool_info.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    for (FrameSlot& frame : frames_) {
        if (VkResult r = vkCreateCommandPool(device, &pool_info, nullptr, &frame.command_pool); r != VK_SUCCESS) {
            return vk_error(r, "vkCreateCommandPool");
        }
        frame.descriptors = std::make_unique<FrameDescriptorPools>(device);
        auto ring = create_buffer_internal({"transient uniforms", kInitialUniformRing, rhi::BufferUsage::Uniform}, true);
        if (!ring.ok()) return ring.take_error();
        frame.uniform_ring = *ring;
        frame.uniform_ring_data = mapped_bytes(*ring);
        frame.uniform_ring_size = kInitialUniformRing;
        if (caps_.timestamps) {
            auto qi = vk_init<VkQueryPoolCreateInfo>(VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO);
            qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
            qi.queryCount = 2 * kMaxTimersPerFrame;
            if (VkResult r = vkCreateQueryPool(device, &qi, nullptr, &frame.timestamps); r != VK_SUCCESS) {
                return vk_error(r, "vkCreateQueryPool");
            }
        }
        if (window_) {
            auto si = vk_init<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
            if (VkResult r = vkCreateSemaphore(device, &si, nullptr, &frame.image_available); r != VK_SUCCESS) {
                return vk_error(r, "vkCreateSemaphore");
            }
        }
    }
    command_list_ = std::make_unique<VulkanCommandList>(*this);
    command_list_->state().set_validation(desc.validation);

    if (window_) {
        swapchain_ = std::make_unique<Swapchain>(*context_, desc.window.vsync);
        LOOM_TRY(recreate_swapchain());
    }
    if (context_->adopted()) {
        loom::log_info("vulkan", "device " + caps_.device_name + " (" + caps_.api_version + ") of the application, " +
                                     rhi::validation::checks_in_log("debug utils", desc.debug, desc.validation));
    } else {
        loom::log_info("vulkan", "device " + caps_.device_name + " (" + caps_.api_version + "), " +
                                     rhi::validation::checks_in_log("the Khronos validation layer",
                                                                    context_->validation_enabled(), desc.validation) +
                                     ", synchronisation validation " +
                                     (context_->synchronization_validation_enabled() ? "on" : "off"));
    }
    return {};
}

VulkanDevice::~VulkanDevice() { destroy_everything(); }

void VulkanDevice::destroy_everything() {
    if (!context_) return;
    VkDevice device = context_->device();
    if (submissions_) {
        (void)flush_setup();
        (void)submissions_->wait_all();
    }
    // The fences cover the submissions, not the last presents, which wait on the swapchain's
    // render-finished semaphores destroyed below: only an idle device has finished them (as in
    // recreate_swapchain; VUID-vkDestroySemaphore-semaphore-01137, seen once under load in
    // VulkanWindow.UnderXvfb).
    if (device != VK_NULL_HANDLE) (void)vkDeviceWaitIdle(device);
    backbuffers_.clear();
    textures_.clear([&](rhi::TextureHandle, Texture& t) { release_texture(t); });
    buffers_.clear([&](rhi::BufferHandle, Buffer& b) { release_buffer(b); });
    samplers_.clear([&](rhi::SamplerHandle, Sampler& s) { vkDestroySampler(device, s.sampler, nullptr); });
    shaders_.clear([&](rhi::ShaderHandle, Shader& s) { vkDestroyShaderModule(device, s.shader, nullptr); });
    pipelines_.clear([](rhi::PipelineHandle, Pipeline&) {});
    for (auto& [key, entry] : pipeline_cache_entries_) vkDestroyPipeline(device, entry.pipeline, nullptr);
    pipeline_cache_entries_.clear();
    if (submissions_) submissions_->run_all_deferred();
    heaps_.clear([&](rhi::HeapHandle, Heap& h) { allocator_->free(h.memory); });
    for (FrameSlot& frame : frames_) {
        if (frame.command_pool) vkDestroyCommandPool(device, frame.command_pool, nullptr);
        frame.descriptors.reset();
        if (frame.timestamps) vkDestroyQueryPool(device, frame.timestamps, nullptr);
        if (frame.image_available) vkDestroySemaphore(device, frame.image_available, nullptr);
        for (VkSemaphore semaphore : frame.queue_semaphores) vkDestroySemaphore(device, semaphore, nullptr);
        frame.queue_semaphores.clear();
    }
    if (setup_pool_) vkDestroyCommandPool(device, setup_pool_, nullptr);
    if (frame_timeline_) vkDestroySemaphore(device, frame_timeline_, nullptr);
    if (pipeline_cache_) vkDestroyPipelineCache(device, pipeline_cache_, nullptr);
    swapchain_.reset();
    layouts_.reset();
    staging_.reset();
    submissions_.reset();
    allocator_.reset();
    context_.reset();
    window_.reset();
}

rhi::ResourceStats VulkanDevice::resource_stats() const {
    rhi::ResourceStats s;
    auto& self = const_cast<VulkanDevice&>(*this);
    self.textures_.for_each([&](rhi::TextureHandle, const Texture& t) {
        if (t.swapchain || t.imported) return;
        ++s.textures;
        s.texture_bytes += t.bytes;
    });
    self.buffers_.for_each([&](rhi::BufferHandle, const Buffer& b) {
        if (b.internal) return;
        ++s.buffers;
        s.buffer_bytes += b.memory.size;
    });
    self.heaps_.for_each([&](rhi::HeapHandle, const Heap& h) {
        ++s.heaps;
        s.heap_bytes += h.memory.size;
    });
    s.samplers = samplers_.size();
    s.shaders = shaders_.size();
    s.pipelines = pipelines_.size();
    return s;
}

bool VulkanDevice::poll_window() { return window_ ? window_->poll() : false; }

const rhi::WindowInput& VulkanDevice::window_input() const { return window_ ? window_->input() : Device::window_input(); }

rhi::Extent3D VulkanDevice::window_size() const { return window_ ? window_->framebuffer_size() : rhi::Extent3D{0, 0, 0}; }

rhi::TextureHandle VulkanDevice::backbuffer() {
    if (!window_ || !frame_recording() || backbuffer_index_ >= backbuffers_.size()) return {};
    return backbuffers_[backbuffer_index_];
}

}  // namespace loom::vulkan

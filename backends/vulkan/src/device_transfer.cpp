// Uploads and readbacks through the staging ring, recorded in a "setup" command buffer that is
// submitted ahead of the next frame's commands (the RHI's ordering of uploads), and the one
// function that submits work to the queue.
#include <cstring>

#include "vulkan_device.hpp"
#include "loom/rhi/subresources.hpp"
#include "loom/rhi/validation.hpp"

namespace loom::vulkan {

using rhi::ResourceState;

namespace {

using rhi::validation::in_quotes;

constexpr VkDeviceSize kStagingAlignment = 16;

/// How loom's CPU layout of a depth/stencil format maps to Vulkan's per-aspect copies.
struct CopyLayout {
    uint32_t depth_bytes = 0;    ///< bytes per texel of the depth (or colour) aspect copy
    uint32_t stencil_bytes = 0;  ///< 1 when a separate stencil copy exists
};

CopyLayout copy_layout(rhi::Format format) {
    switch (format) {
        case rhi::Format::Depth24Stencil8: return {4, 1};  // X8_D24 depth + S8
        case rhi::Format::Depth32FStencil8: return {4, 1};
        case rhi::Format::Stencil8: return {0, 1};
        default: return {rhi::format_info(format).bytes_per_texel, 0};
    }
}


// loom layout -> Vulkan depth part + stencil part (both tightly packed, stencil after depth).
void split_depth_stencil(rhi::Format format, std::span<const std::byte> src, std::byte* depth, std::byte* stencil,
                         std::size_t texels) {
    for (std::size_t i = 0; i < texels; ++i) {
        if (format == rhi::Format::Depth24Stencil8) {
            uint32_t w;
            std::memcpy(&w, src.data() + 4 * i, 4);
            const uint32_t d = w & 0xFFFFFFu;
            std::memcpy(depth + 4 * i, &d, 4);
            stencil[i] = static_cast<std::byte>(w >> 24);
        } else {  // Depth32FStencil8: float, stencil byte, 3 bytes padding
            std::memcpy(depth + 4 * i, src.data() + 8 * i, 4);
            stencil[i] = src[8 * i + 4];
        }
    }
}

// Vulkan depth part + stencil part -> loom layout.
void join_depth_stencil(rhi::Format format, const std::byte* depth, const std::byte* stencil, std::byte* dst,
                        std::size_t texels) {
    for (std::size_t i = 0; i < texels; ++i) {
        if (format == rhi::Format::Depth24Stencil8) {
            uint32_t d;
            std::memcpy(&d, depth + 4 * i, 4);
            const uint32_t w = (d & 0xFFFFFFu) | (static_cast<uint32_t>(stencil[i]) << 24);
            std::memcpy(dst + 4 * i, &w, 4);
        } else {
            std::memcpy(dst + 8 * i, depth + 4 * i, 4);
            dst[8 * i + 4] = stencil[i];
            std::memset(dst + 8 * i + 5, 0, 3);
        }
    }
}

}  // namespace

// ---- setup command buffer and submission ------------------------------------------------------

void VulkanDevice::recycle_setup_buffers() {
    const uint64_t done = submissions_->completed_serial();
    for (std::size_t i = 0; i < used_setup_buffers_.size();) {
        if (used_setup_buffers_[i].serial <= done) {
            free_setup_buffers_.push_back(used_setup_buffers_[i].cmd);
            used_setup_buffers_[i] = used_setup_buffers_.back();
            used_setup_buffers_.pop_back();
        } else {
            ++i;
        }
    }
}

VkCommandBuffer VulkanDevice::setup_commands() {
    if (setup_cmd_) return setup_cmd_;
    recycle_setup_buffers();
    if (!free_setup_buffers_.empty()) {
        setup_cmd_ = free_setup_buffers_.back();
        free_setup_buffers_.pop_back();
    } else {
        auto info = vk_init<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
        info.commandPool = setup_pool_;
        info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        info.commandBufferCount = 1;
        if (vkAllocateCommandBuffers(context_->device(), &info, &setup_cmd_) != VK_SUCCESS) return VK_NULL_HANDLE;
    }
    auto begin = vk_init<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(setup_cmd_, &begin);
    setup_has_buffer_writes_ = false;
    return setup_cmd_;
}

loom::Status VulkanDevice::submit(std::span<const VkCommandBuffer> frame_commands, bool frame_part,
                                  std::span<const VkSemaphore> signals, std::span<const VkSemaphore> waits,
                                  rhi::QueueType queue) {
    const bool graphics = queue == rhi::QueueType::Graphics;
    // Uploads go first, with the next submission to the graphics queue. Where the compute queue
    // is a queue of its own, a compute submission while uploads are pending first sends them to
    // the graphics queue and waits for them there; where it is the graphics queue, they simply
    // go first in this submission.
    std::vector<VkSemaphore> all_waits(waits.begin(), waits.end());
    if (!graphics && setup_cmd_ && caps_.async_compute) {
        auto uploaded = queue_semaphore();
        if (!uploaded.ok()) return uploaded.take_error();
        LOOM_TRY(submit({}, false, std::span<const VkSemaphore>(&*uploaded, 1), {}, rhi::QueueType::Graphics));
        all_waits.push_back(*uploaded);
    }
    std::vector<VkCommandBufferSubmitInfo> buffers;
    VkCommandBuffer setup = graphics || !caps_.async_compute ? setup_cmd_ : VK_NULL_HANDLE;
    if (setup) {
        if (setup_has_buffer_writes_) {
            // Buffer uploads become visible to everything that follows.
            BarrierBatch batch;
            batch.after_transfer();
            batch.flush(setup);
        }
        if (VkResult r = vkEndCommandBuffer(setup); r != VK_SUCCESS) return vk_error(r, "vkEndCommandBuffer (uploads)");
        setup_cmd_ = VK_NULL_HANDLE;
        buffers.push_back({VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, nullptr, setup, 0});
    }
    for (VkCommandBuffer cmd : frame_commands) buffers.push_back({VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, nullptr, cmd, 0});
    std::vector<VkSemaphoreSubmitInfo> wait_infos;
    std::vector<VkSemaphoreSubmitInfo> signal_infos;
    auto semaphore_info = [](VkSemaphore semaphore) {
        auto info = vk_init<VkSemaphoreSubmitInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO);
        info.semaphore = semaphore;
        info.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;  // also covers frames split by a readback
        return info;
    };
    if (frame_part && graphics && pending_wait_) {
        wait_infos.push_back(semaphore_info(pending_wait_));
        pending_wait_ = VK_NULL_HANDLE;
    }
    for (VkSemaphore w : all_waits) wait_infos.push_back(semaphore_info(w));
    for (VkSemaphore s : signals) {
        if (s) signal_infos.push_back(semaphore_info(s));
    }
    if (buffers.empty() && wait_infos.empty() && signal_infos.empty()) return {};
    auto info = vk_init<VkSubmitInfo2>(VK_STRUCTURE_TYPE_SUBMIT_INFO_2);
    info.waitSemaphoreInfoCount = static_cast<uint32_t>(wait_infos.size());
    info.pWaitSemaphoreInfos = wait_infos.data();
    info.signalSemaphoreInfoCount = static_cast<uint32_t>(signal_infos.size());
    info.pSignalSemaphoreInfos = signal_infos.data();
    info.commandBufferInfoCount = static_cast<uint32_t>(buffers.size());
    info.pCommandBufferInfos = buffers.data();
    auto serial = submissions_->submit(graphics ? context_->queue() : context_->compute_queue(), info);
    if (!serial.ok()) return serial.take_error();
    if (setup) used_setup_buffers_.push_back({setup, *serial});
    if (frame_part) {
        current_frame().serial = *serial;
        ++epoch_;
    }
    return {};
}

loom::Status VulkanDevice::flush_setup() {
    if (!setup_cmd_) return {};
    return submit({}, false, {});
}

loom::Result<StagingRing::Span> VulkanDevice::staging(VkDeviceSize size) {
    submissions_->poll();
    staging_->release(submissions_->completed_serial());
    if (size > staging_->capacity()) {
        // Too big for the ring: a temporary host-visible buffer, freed after its submission.
        auto info = vk_init<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
        info.size = size;
        info.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
        info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
        VkDevice device = context_->device();
        VkBuffer buffer = VK_NULL_HANDLE;
        if (VkResult r = vkCreateBuffer(device, &info, nullptr, &buffer); r != VK_SUCCESS) return vk_error(r, "vkCreateBuffer (staging)");
        AllocationRequest request;
        vkGetBufferMemoryRequirements(device, buffer, &request.requirements);
        request.required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        request.kind = ResourceKind::Buffer;
        request.dedicated = true;
        auto memory = allocator_->allocate(request);
        if (!memory.ok()) {
            vkDestroyBuffer(device, buffer, nullptr);
            return memory.take_error();
        }
        vkBindBufferMemory(device, buffer, memory->memory, memory->offset);
        MemoryAllocator* allocator = allocator_.get();
        SubmissionTracker* submissions = submissions_.get();
        MemoryAllocation allocation = *memory;
        // Released when the caller is done with the span, after the submissions recorded by
        // then have completed.
        std::shared_ptr<void> keep_alive(nullptr, [device, allocator, submissions, buffer, allocation](void*) {
            submissions->defer([device, allocator, buffer, allocation] {
                vkDestroyBuffer(device, buffer, nullptr);
                allocator->free(allocation);
            });
        });
        return StagingRing::Span{buffer, 0, static_cast<std::byte*>(memory->mapped), std::move(keep_alive)};
    }
    for (;;) {
        if (auto span = staging_->allocate(size, kStagingAlignment, submissions_->pending_serial())) return *span;
        // The ring is full: submit what uses it and wait for the oldest user.
        const uint64_t oldest = staging_->oldest_serial();
        if (oldest >= submissions_->pending_serial()) LOOM_TRY(flush_setup());
        LOOM_TRY(submissions_->wait(oldest));
        staging_->release(submissions_->completed_serial());
    }
}

// ---- buffers -----------------------------------------------------------------------------------

loom::Status VulkanDevice::write_buffer(rhi::BufferHandle handle, uint64_t offset, std::span<const std::byte> data) {
    auto b = buffers_.get(handle);
    if (!b.ok()) return b.take_error();
    Buffer& buffer = **b;
    LOOM_TRY(rhi::validation::buffer_write(buffer.desc, offset, data.size()));
    if (data.empty()) return {};
    // A placed buffer written takes its bytes over from any alias that used them.
    take_over_bytes(buffer);
    auto span = staging(data.size());
    if (!span.ok()) return span.take_error();
    std::memcpy(span->data, data.data(), data.size());
    VkCommandBuffer cmd = setup_commands();
    if (!cmd) return Error{ErrorCode::Backend, "write_buffer: cannot allocate a command buffer"};
    // Earlier reads and writes of the buffer (previous frames, earlier uploads) finish first.
    BarrierBatch batch;
    batch.before_transfer();
    batch.flush(cmd);
    VkBufferCopy region{span->offset, offset, data.size()};
    vkCmdCopyBuffer(cmd, span->buffer, buffer.buffer, 1, &region);
    setup_has_buffer_writes_ = true;
    bytes_uploaded_ += data.size();
    return {};
}

loom::Result<std::vector<std::byte>> VulkanDevice::read_buffer(rhi::BufferHandle handle, uint64_t offset, uint64_t size) {
    auto b = buffers_.get(handle);
    if (!b.ok()) return b.take_error();
    Buffer& buffer = **b;
    LOOM_TRY(rhi::validation::buffer_read(buffer.desc, offset, size));
    // The frame recorded so far is submitted first, which must not cut a render pass in two.
    LOOM_TRY(command_list_->state().check_outside_render_pass("read_buffer of buffer " + in_quotes(buffer.desc.name)));
    if (size == 0) return std::vector<std::byte>{};
    if (recording_external_frame()) {
        return Error{ErrorCode::InvalidState, "read_buffer of buffer " + in_quotes(buffer.desc.name) +
                                                  " while a frame is recorded into the application's command buffer: read "
                                                  "after end_frame, once the application has submitted the frame"};
    }
    if (frame_recording()) LOOM_TRY(split_frame());
    auto span = staging(size);
    if (!span.ok()) return span.take_error();
    VkCommandBuffer cmd = setup_commands();
    if (!cmd) return Error{ErrorCode::Backend, "read_buffer: cannot allocate a command buffer"};
    BarrierBatch batch;
    batch.before_transfer();
    batch.flush(cmd);
    VkBufferCopy region{offset, span->offset, size};
    vkCmdCopyBuffer(cmd, buffer.buffer, span->buffer, 1, &region);
    batch.transfer_to_host();
    batch.flush(cmd);
    LOOM_TRY(flush_setup());
    LOOM_TRY(submissions_->wait(submissions_->last_submitted_serial()));
    std::vector<std::byte> out(size);
    std::memcpy(out.data(), span->data, size);
    return out;
}

// ---- textures ----------------------------------------------------------------------------------

loom::Status VulkanDevice::write_texture(rhi::TextureHandle handle, const rhi::TextureRegion& region,
                                         std::span<const std::byte> data) {
    auto tex = textures_.get(handle);
    if (!tex.ok()) return tex.take_error();
    Texture& t = **tex;
    auto write = rhi::validation::texture_write(t.desc, region, data.size());
    if (!write.ok()) return write.take_error();
    const std::string name = "write_texture to texture " + in_quotes(t.desc.name);
    // The API's own rule for images the application made: copies need TRANSFER_DST.
    if (t.imported && !rhi::has_all(t.desc.usage, rhi::TextureUsage::CopyDst)) {
        return Error{ErrorCode::InvalidArgument, name + ": the application's image has no TRANSFER_DST usage"};
    }
    const rhi::Extent3D full = rhi::mip_extent(t.desc, region.mip);
    const rhi::Extent3D e = write->extent;
    const std::size_t texels = std::size_t{e.width} * e.height * e.depth;
    const rhi::FormatInfo& info = rhi::format_info(t.desc.format);
    const CopyLayout layout = copy_layout(t.desc.format);
    const VkDeviceSize depth_size = VkDeviceSize{layout.depth_bytes} * texels;
    const VkDeviceSize stencil_offset = (depth_size + 3) & ~VkDeviceSize{3};
    const VkDeviceSize total = layout.stencil_bytes ? stencil_offset + texels : depth_size;
    auto span = staging(total);
    if (!span.ok()) return span.take_error();
    if (layout.stencil_bytes && layout.depth_bytes) {
        split_depth_stencil(t.desc.format, data, span->data, span->data + stencil_offset, texels);
    } else if (layout.stencil_bytes) {
        std::memcpy(span->data + stencil_offset, data.data(), texels);
    } else {
        std::memcpy(span->data, data.data(), data.size());
    }

    VkCommandBuffer cmd = setup_commands();
    if (!cmd) return Error{ErrorCode::Backend, name + ": cannot allocate a command buffer"};
    const uint32_t layer = write->layer;
    const bool whole = region.origin.x == 0 && region.origin.y == 0 && region.origin.z == 0 && e.width == full.width &&
                       e.height == full.height && e.depth == full.depth;
    BarrierBatch batch;
    transition_texture(batch, t, region.mip, 1, layer, 1, ResourceState::CopyDst, Stream::Setup, whole);
    batch.flush(cmd);
    std::vector<VkBufferImageCopy> copies;
    VkBufferImageCopy c{};
    c.imageSubresource = {0, region.mip, layer, 1};
    c.imageOffset = {static_cast<int32_t>(region.origin.x), static_cast<int32_t>(region.origin.y), static_cast<int32_t>(region.origin.z)};
    c.imageExtent = {e.width, e.height, e.depth};
    if (layout.depth_bytes) {
        c.bufferOffset = span->offset;
        c.imageSubresource.aspectMask = info.has_depth() ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
        copies.push_back(c);
    }
    if (layout.stencil_bytes) {
        c.bufferOffset = span->offset + stencil_offset;
        c.imageSubresource.aspectMask = VK_IMAGE_ASPECT_STENCIL_BIT;
        copies.push_back(c);
    }
    vkCmdCopyBufferToImage(cmd, span->buffer, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, static_cast<uint32_t>(copies.size()),
                           copies.data());
    // Uploaded textures are ready to sample (the GL backend does the same); those without
    // Sampled usage stay CopyDst.
    const ResourceState after = rhi::has_all(t.desc.usage, rhi::TextureUsage::Sampled) && t.sampled_view
                                    ? ResourceState::ShaderRead
                                    : ResourceState::CopyDst;
    transition_texture(batch, t, region.mip, 1, layer, 1, after, Stream::Setup);
    batch.flush(cmd);
    bytes_uploaded_ += data.size();
    return {};
}

loom::Result<rhi::Image> VulkanDevice::read_texture(rhi::TextureHandle handle, uint32_t mip, uint32_t layer) {
    auto tex = textures_.get(handle);
    if (!tex.ok()) return tex.take_error();
    Texture& t = **tex;
    LOOM_TRY(rhi::validation::texture_read(t.desc, mip, layer));
    const std::string name = "read_texture of texture " + in_quotes(t.desc.name);
    // The frame recorded so far is submitted first, which must not cut a render pass in two.
    LOOM_TRY(command_list_->state().check_outside_render_pass(name));
    if (t.imported && !rhi::has_all(t.desc.usage, rhi::TextureUsage::CopySrc)) {
        return Error{ErrorCode::InvalidArgument, name + ": the application's image has no TRANSFER_SRC usage"};
    }
    if (recording_external_frame()) {
        return Error{ErrorCode::InvalidState, name + " while a frame is recorded into the application's command buffer: read "
                                                     "after end_frame, once the application has submitted the frame"};
    }
    if (frame_recording()) LOOM_TRY(split_frame());
    if (t.desc.samples > 1) return read_resolved(handle);
    return read_subresource(t, mip, layer);
}

loom::Result<rhi::Image> VulkanDevice::read_resolved(rhi::TextureHandle handle) {
    // Multisampled (colour, single mip and layer: the validation layer's rules) textures are
    // resolved into a temporary single-sampled one first, as GL's read_texture does with a blit.
    rhi::TextureDesc single = (*textures_.get(handle))->desc;
    single.name += " (resolved for read_texture)";
    single.samples = 1;
    single.usage = rhi::TextureUsage::CopySrc | rhi::TextureUsage::CopyDst;
    single.placement.reset();
    auto made = create_texture(single);
    if (!made.ok()) return made.take_error();
    // Looked up after create_texture, which may move the pool's textures.
    Texture& t = **textures_.get(handle);
    Texture& resolved = **textures_.get(*made);
    VkCommandBuffer cmd = setup_commands();
    if (!cmd) {
        (void)destroy(*made);
        return Error{ErrorCode::Backend, "read_texture of texture " + in_quotes(t.desc.name) + ": cannot allocate a command buffer"};
    }
    const ResourceState before = tracked_state(t, t.subresource(0, 0), Stream::Setup);
    BarrierBatch batch;
    transition_texture(batch, t, 0, 1, 0, 1, ResourceState::CopySrc, Stream::Setup);
    transition_texture(batch, resolved, 0, 1, 0, 1, ResourceState::CopyDst, Stream::Setup, true);
    batch.flush(cmd);
    VkImageResolve region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.extent = {t.desc.width, t.desc.height, 1};
    vkCmdResolveImage(cmd, t.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, resolved.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                      &region);
    if (before != ResourceState::Undefined) transition_texture(batch, t, 0, 1, 0, 1, before, Stream::Setup);
    batch.flush(cmd);
    auto image = read_subresource(resolved, 0, 0);
    LOOM_TRY(destroy(*made));
    return image;
}

loom::Result<rhi::Image> VulkanDevice::read_subresource(Texture& t, uint32_t mip, uint32_t layer) {
    const std::string name = "read_texture of texture " + in_quotes(t.desc.name);
    const bool is3d = t.desc.dimension == rhi::TextureDimension::Tex3D;
    const rhi::Extent3D full = rhi::mip_extent(t.desc, mip);
    const std::size_t texels = std::size_t{full.width} * full.height;
    const CopyLayout layout = copy_layout(t.desc.format);
    const VkDeviceSize depth_size = VkDeviceSize{layout.depth_bytes} * texels;
    const VkDeviceSize stencil_offset = (depth_size + 3) & ~VkDeviceSize{3};
    const VkDeviceSize total = layout.stencil_bytes ? stencil_offset + texels : depth_size;
    auto span = staging(total);
    if (!span.ok()) return span.take_error();

    VkCommandBuffer cmd = setup_commands();
    if (!cmd) return Error{ErrorCode::Backend, name + ": cannot allocate a command buffer"};
    const uint32_t array_layer = is3d ? 0 : layer;
    const uint32_t sub = t.subresource(mip, array_layer);
    const ResourceState before = tracked_state(t, sub, Stream::Setup);
    BarrierBatch batch;
    transition_texture(batch, t, mip, 1, array_layer, 1, ResourceState::CopySrc, Stream::Setup);
    batch.flush(cmd);
    const rhi::FormatInfo& info = rhi::format_info(t.desc.format);
    std::vector<VkBufferImageCopy> copies;
    VkBufferImageCopy c{};
    c.imageSubresource = {0, mip, array_layer, 1};
    c.imageOffset = {0, 0, is3d ? static_cast<int32_t>(layer) : 0};
    c.imageExtent = {full.width, full.height, 1};
    if (layout.depth_bytes) {
        c.bufferOffset = span->offset;
        c.imageSubresource.aspectMask = info.has_depth() ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
        copies.push_back(c);
    }
    if (layout.stencil_bytes) {
        c.bufferOffset = span->offset + stencil_offset;
        c.imageSubresource.aspectMask = VK_IMAGE_ASPECT_STENCIL_BIT;
        copies.push_back(c);
    }
    vkCmdCopyImageToBuffer(cmd, t.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, span->buffer, static_cast<uint32_t>(copies.size()),
                           copies.data());
    batch.transfer_to_host();
    if (before != ResourceState::Undefined) transition_texture(batch, t, mip, 1, array_layer, 1, before, Stream::Setup);
    batch.flush(cmd);
    LOOM_TRY(flush_setup());
    LOOM_TRY(submissions_->wait(submissions_->last_submitted_serial()));

    rhi::Image image(full.width, full.height, t.desc.format);
    if (layout.stencil_bytes && layout.depth_bytes) {
        join_depth_stencil(t.desc.format, span->data, span->data + stencil_offset, image.pixels.data(), texels);
    } else if (layout.stencil_bytes) {
        std::memcpy(image.pixels.data(), span->data + stencil_offset, texels);
    } else {
        std::memcpy(image.pixels.data(), span->data, image.pixels.size());
        if (t.desc.format == rhi::Format::Depth24) {
            // X8_D24: the top 8 bits are undefined; loom's layout has them zero.
            for (std::size_t i = 0; i < texels; ++i) {
                uint32_t w;
                std::memcpy(&w, image.pixels.data() + 4 * i, 4);
                w &= 0xFFFFFFu;
                std::memcpy(image.pixels.data() + 4 * i, &w, 4);
            }
        }
    }
    return image;
}

}  // namespace loom::vulkan

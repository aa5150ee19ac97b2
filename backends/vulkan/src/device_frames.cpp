// Frames in flight: per-frame command buffers, descriptor pools, uniform rings and timestamp
// queries, reused once the frame's fence has signalled (never vkDeviceWaitIdle per frame);
// swapchain acquire and present on windowed devices.
#include <algorithm>
#include <cstring>

#include "loom/rhi/log.hpp"
#include "vulkan_device.hpp"

namespace loom::vulkan {

using rhi::ResourceState;

loom::Status VulkanDevice::begin_frame_commands() {
    FrameSlot& slot = current_frame();
    if (slot.used_command_buffers == slot.command_buffers.size()) {
        auto info = vk_init<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
        info.commandPool = slot.command_pool;
        info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        info.commandBufferCount = 1;
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        if (VkResult r = vkAllocateCommandBuffers(context_->device(), &info, &cmd); r != VK_SUCCESS) {
            return vk_error(r, "vkAllocateCommandBuffers");
        }
        slot.command_buffers.push_back(cmd);
    }
    const bool new_frame = slot.used_command_buffers == 0;
    VkCommandBuffer cmd = slot.command_buffers[slot.used_command_buffers++];
    auto begin = vk_init<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    if (VkResult r = vkBeginCommandBuffer(cmd, &begin); r != VK_SUCCESS) return vk_error(r, "vkBeginCommandBuffer");
    if (new_frame && slot.timestamps) vkCmdResetQueryPool(cmd, slot.timestamps, 0, 2 * kMaxTimersPerFrame);
    command_list_->begin(cmd, new_frame);
    return {};
}

loom::Status VulkanDevice::recycle_current_slot() {
    FrameSlot& slot = current_frame();
    // The frame that used this slot kFramesInFlight frames ago must be done.
    Status done = submissions_->wait(slot.serial);
    collect_timers(slot);
    slot.descriptors->reset();
    slot.uniform_ring_offset = 0;
    slot.timer_labels.clear();
    slot.used_queue_semaphores = 0;
    vkResetCommandPool(context_->device(), slot.command_pool, 0);
    slot.used_command_buffers = 0;
    staging_->release(submissions_->completed_serial());
    recycle_setup_buffers();
    return done;
}

rhi::CommandList& VulkanDevice::begin_frame() {
    if (Status idle = command_list_->state().check_begin_frame(); !idle.ok()) {
        // Recording goes on into the open frame.
        command_list_->record_error(idle.take_error());
        return *command_list_;
    }
    if (auto status = recycle_current_slot(); !status.ok()) loom::log_error("vulkan", status.error().to_string());
    external_frame_ = false;
    reset_queues();
    command_list_->state().begin_frame();
    if (swapchain_) {
        if (auto status = acquire_backbuffer(); !status.ok()) loom::log_error("vulkan", status.error().to_string());
    }
    if (auto status = begin_frame_commands(); !status.ok()) loom::log_error("vulkan", status.error().to_string());
    return *command_list_;
}

loom::Status VulkanDevice::end_frame() {
    LOOM_TRY(command_list_->state().check_recording("end_frame"));
    if (external_frame_) return end_external_frame();
    command_list_->finish();
    // The frame ends on the graphics queue, after the compute queue's part of it.
    Status joined = join_queues();
    FrameSlot& slot = current_frame();
    VkCommandBuffer cmd = command_list_->command_buffer();
    const bool presenting = swapchain_ && backbuffer_index_ != UINT32_MAX;
    if (presenting) {
        if (Texture* back = textures_.find(backbuffers_[backbuffer_index_])) {
            BarrierBatch batch;
            transition_texture(batch, *back, 0, 1, 0, 1, ResourceState::Present, Stream::Frame);
            batch.flush(cmd);
        }
    }
    Status result = joined;
    if (VkResult r = vkEndCommandBuffer(cmd); r != VK_SUCCESS && result.ok()) result = vk_error(r, "vkEndCommandBuffer");
    const VkSemaphore signal = presenting ? swapchain_->render_finished(backbuffer_index_) : VK_NULL_HANDLE;
    const std::vector<VkSemaphore> waits = std::move(batch_waits_);
    batch_waits_.clear();
    if (result.ok()) result = submit(std::span<const VkCommandBuffer>(&cmd, 1), true, std::span<const VkSemaphore>(&signal, 1), waits);
    // Even a frame without timers is "the latest frame" whose (empty) results timer_results()
    // describes once it has finished.
    slot.timers_pending = true;
    command_list_->state().end_frame();
    if (presenting && result.ok()) {
        const VkResult r = swapchain_->present(context_->queue(), backbuffer_index_);
        if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) {
            swapchain_dirty_ = true;
        } else if (r != VK_SUCCESS) {
            result = vk_error(r, "vkQueuePresentKHR");
        }
    }
    backbuffer_index_ = UINT32_MAX;
    last_frame_stats_ = command_list_->stats();
    last_frame_stats_.bytes_uploaded += bytes_uploaded_;
    bytes_uploaded_ = 0;
    ++frame_index_;
    submissions_->poll();
    if (auto error = command_list_->take_error()) return *error;
    return result;
}

loom::Status VulkanDevice::split_frame() { return submit_batch({}, batch_queue_); }

loom::Status VulkanDevice::wait_idle() {
    LOOM_TRY(flush_setup());
    LOOM_TRY(submissions_->wait_all());
    // Timer results of every finished frame, oldest first, so the newest frame's remain.
    std::array<FrameSlot*, kFramesInFlight> slots{};
    for (uint32_t i = 0; i < kFramesInFlight; ++i) slots[i] = &frames_[i];
    std::sort(slots.begin(), slots.end(), [](const FrameSlot* a, const FrameSlot* b) { return a->serial < b->serial; });
    for (FrameSlot* slot : slots) {
        if (!frame_recording() || slot != &current_frame()) collect_timers(*slot);
    }
    staging_->release(submissions_->completed_serial());
    recycle_setup_buffers();
    // Nothing recorded is pending: whatever waits for "the commands recorded so far" can go.
    if (!frame_recording() && !setup_cmd_) submissions_->run_all_deferred();
    return {};
}

void VulkanDevice::collect_timers(FrameSlot& slot) {
    if (!slot.timers_pending || !slot.timestamps || slot.serial > submissions_->completed_serial()) return;
    slot.timers_pending = false;
    const uint32_t count = static_cast<uint32_t>(slot.timer_labels.size());
    if (count == 0) {
        timer_results_.clear();
        return;
    }
    std::vector<uint64_t> values(2 * std::size_t{count});
    const VkResult r = vkGetQueryPoolResults(context_->device(), slot.timestamps, 0, 2 * count, values.size() * sizeof(uint64_t),
                                             values.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT);
    if (r != VK_SUCCESS) return;
    const uint32_t bits = context_->timestamp_valid_bits();
    const uint64_t mask = bits >= 64 ? ~uint64_t{0} : (uint64_t{1} << bits) - 1;
    const double period_ns = context_->properties().limits.timestampPeriod;
    timer_results_.clear();
    for (uint32_t i = 0; i < count; ++i) {
        const uint64_t begin = values[2 * i] & mask;
        const uint64_t end = values[2 * i + 1] & mask;
        const uint64_t ticks = (end - begin) & mask;  // wraps correctly within the valid bits
        timer_results_.push_back({slot.timer_labels[i], static_cast<double>(ticks) * period_ns / 1.0e6});
    }
}

std::vector<rhi::TimerResult> VulkanDevice::timer_results() {
    submissions_->poll();
    std::array<FrameSlot*, kFramesInFlight> slots{};
    for (uint32_t i = 0; i < kFramesInFlight; ++i) slots[i] = &frames_[i];
    std::sort(slots.begin(), slots.end(), [](const FrameSlot* a, const FrameSlot* b) { return a->serial < b->serial; });
    for (FrameSlot* slot : slots) {
        if (!frame_recording() || slot != &current_frame()) collect_timers(*slot);
    }
    return timer_results_;
}

loom::Status VulkanDevice::grow_uniform_ring(FrameSlot& slot, uint64_t size) {
    // A bigger ring for the rest of this frame (and the next ones in this slot); the old one goes
    // when this frame has finished with it.
    const uint64_t new_size = std::max(slot.uniform_ring_size * 2, size * 2);
    auto ring = create_buffer_internal({"transient uniforms", new_size, rhi::BufferUsage::Uniform}, true);
    if (!ring.ok()) return ring.take_error();
    auto old = buffers_.remove(slot.uniform_ring);
    if (old.ok()) release_buffer(*old);
    slot.uniform_ring = *ring;
    slot.uniform_ring_data = mapped_bytes(*ring);
    slot.uniform_ring_size = new_size;
    slot.uniform_ring_offset = 0;
    if (!slot.uniform_ring_data) return Error{ErrorCode::Backend, "the transient uniform ring is not mapped"};
    return {};
}

// ---- swapchain ---------------------------------------------------------------------------------

loom::Status VulkanDevice::recreate_swapchain() {
    const rhi::Extent3D size = window_->framebuffer_size();
    if (size.width == 0 || size.height == 0) return {};  // minimised: keep the old one
    // Resizes are rare: waiting for the GPU here (not per frame) is fine.
    LOOM_TRY(flush_setup());
    LOOM_TRY(submissions_->wait_all());
    // The fences cover the submissions, not the presents waiting on the render-finished
    // semaphores that the new swapchain replaces: only an idle device has finished those
    // (VUID-vkDestroySemaphore-semaphore-01137, seen under load in VulkanWindow.UnderXvfb).
    if (VkResult r = vkDeviceWaitIdle(context_->device()); r != VK_SUCCESS) return vk_error(r, "vkDeviceWaitIdle before a swapchain resize");
    for (rhi::TextureHandle h : backbuffers_) {
        auto t = textures_.remove(h);
        if (t.ok()) release_texture(*t);
    }
    backbuffers_.clear();
    LOOM_TRY(swapchain_->create(size.width, size.height));
    const auto& images = swapchain_->images();
    for (uint32_t i = 0; i < images.size(); ++i) {
        auto handle = wrap_swapchain_image(images[i], swapchain_->format(), swapchain_->extent().width,
                                           swapchain_->extent().height, i);
        if (!handle.ok()) return handle.take_error();
        backbuffers_.push_back(*handle);
    }
    swapchain_dirty_ = false;
    return {};
}

loom::Status VulkanDevice::acquire_backbuffer() {
    backbuffer_index_ = UINT32_MAX;
    const rhi::Extent3D size = window_->framebuffer_size();
    if (size.width == 0 || size.height == 0) return {};  // minimised: nothing to present
    const VkExtent2D extent = swapchain_->extent();
    if (swapchain_dirty_ || extent.width != size.width || extent.height != size.height) LOOM_TRY(recreate_swapchain());
    FrameSlot& slot = current_frame();
    uint32_t index = 0;
    VkResult r = swapchain_->acquire(slot.image_available, index);
    if (r == VK_ERROR_OUT_OF_DATE_KHR) {
        LOOM_TRY(recreate_swapchain());
        r = swapchain_->acquire(slot.image_available, index);
    }
    if (r == VK_SUBOPTIMAL_KHR) {
        swapchain_dirty_ = true;  // usable now, recreated at the next frame
    } else if (r != VK_SUCCESS) {
        return vk_error(r, "vkAcquireNextImageKHR");
    }
    backbuffer_index_ = index;
    pending_wait_ = slot.image_available;
    // A freshly acquired image has no contents worth keeping.
    Texture* back = textures_.find(backbuffers_[index]);
    if (!back) return Error{ErrorCode::Backend, "swapchain image " + std::to_string(index) + " has no texture"};
    back->states.assign(back->states.size(), ResourceState::Undefined);
    back->frame_start_states = back->states;
    return {};
}

}  // namespace loom::vulkan

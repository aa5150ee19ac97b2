// A frame on two queues: the commands recorded between set_queue, signal_queue and wait_queue
// calls become batches, each its own command buffer submitted (in recording order, so that
// every binary semaphore is signalled before it is waited) to the graphics queue or to the
// compute queue, which is a second queue of the same family where the device has one and the
// graphics queue itself elsewhere (lavapipe). Queues of one family share command pools and
// need no ownership transfers.
#include "vulkan_device.hpp"

namespace loom::vulkan {

using rhi::QueueType;

loom::Result<VkSemaphore> VulkanDevice::queue_semaphore() {
    FrameSlot& slot = current_frame();
    if (slot.used_queue_semaphores == slot.queue_semaphores.size()) {
        auto info = vk_init<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
        VkSemaphore semaphore = VK_NULL_HANDLE;
        if (VkResult r = vkCreateSemaphore(context_->device(), &info, nullptr, &semaphore); r != VK_SUCCESS) {
            return vk_error(r, "vkCreateSemaphore (queue signal)");
        }
        context_->set_name(VK_OBJECT_TYPE_SEMAPHORE, reinterpret_cast<uint64_t>(semaphore),
                           "queue signal " + std::to_string(slot.queue_semaphores.size()));
        slot.queue_semaphores.push_back(semaphore);
    }
    return slot.queue_semaphores[slot.used_queue_semaphores++];
}

loom::Status VulkanDevice::submit_batch(std::span<const VkSemaphore> signals, QueueType next) {
    VkCommandBuffer cmd = command_list_->command_buffer();
    if (VkResult r = vkEndCommandBuffer(cmd); r != VK_SUCCESS) return vk_error(r, "vkEndCommandBuffer");
    const std::vector<VkSemaphore> waits = std::move(batch_waits_);
    batch_waits_.clear();
    LOOM_TRY(submit(std::span<const VkCommandBuffer>(&cmd, 1), true, signals, waits, batch_queue_));
    batch_queue_ = next;
    return begin_frame_commands();
}

loom::Result<VkSemaphore> VulkanDevice::submit_batch_signalling(QueueType next) {
    auto semaphore = queue_semaphore();
    if (!semaphore.ok()) return semaphore.take_error();
    LOOM_TRY(submit_batch(std::span<const VkSemaphore>(&*semaphore, 1), next));
    return *semaphore;
}

loom::Status VulkanDevice::switch_queue(QueueType queue) {
    if (external_frame_ || queue == batch_queue_) return {};
    // On a queue of its own, the frame's first compute batch waits for the graphics work recorded
    // before it: the timestamp reset at the frame's start, earlier frames' use of the same
    // resources, uploads. Later compute batches wait only where the commands say, unless
    // uploads recorded since would otherwise race them.
    const bool after_graphics = caps_.async_compute && queue == QueueType::Compute && (!compute_used_ || setup_cmd_);
    if (queue == QueueType::Compute) compute_used_ = true;
    if (!after_graphics) return submit_batch({}, queue);
    auto semaphore = submit_batch_signalling(queue);
    if (!semaphore.ok()) return semaphore.take_error();
    batch_waits_.push_back(*semaphore);
    return {};
}

loom::Status VulkanDevice::signal_queue(uint32_t index) {
    if (external_frame_) return {};
    if (index != frame_signals_.size()) {
        return Error{ErrorCode::Backend, "signal_queue: signal " + std::to_string(index) + " is not the frame's next (" +
                                             std::to_string(frame_signals_.size()) + ")"};
    }
    const QueueType queue = batch_queue_;
    auto semaphore = submit_batch_signalling(queue);
    if (!semaphore.ok()) return semaphore.take_error();
    frame_signals_.push_back(BatchSignal{*semaphore, queue, false});
    return {};
}

loom::Status VulkanDevice::wait_queue(uint32_t index) {
    if (external_frame_) return {};
    if (index >= frame_signals_.size()) {
        return Error{ErrorCode::Backend, "wait_queue: signal " + std::to_string(index) + " was never made"};
    }
    // What was recorded before the wait runs without it: a batch of its own.
    LOOM_TRY(submit_batch({}, batch_queue_));
    frame_signals_[index].waited = true;
    batch_waits_.push_back(frame_signals_[index].semaphore);
    return {};
}

loom::Status VulkanDevice::join_queues() {
    if (external_frame_ || (frame_signals_.empty() && !compute_used_)) return {};
    // Every semaphore signalled in the frame is waited before it ends (a binary semaphore must
    // be unsignalled to be signalled again when the slot comes back): the compute queue's last
    // batch waits for the graphics signals nobody waited for and signals `done`; the frame's
    // last (graphics) submission waits for `done` and the compute signals nobody waited for.
    std::vector<VkSemaphore> for_compute;
    std::vector<VkSemaphore> for_graphics;
    for (BatchSignal& signal : frame_signals_) {
        if (signal.waited) continue;
        (signal.queue == QueueType::Graphics ? for_compute : for_graphics).push_back(signal.semaphore);
        signal.waited = true;
    }
    auto done = queue_semaphore();
    if (!done.ok()) return done.take_error();
    if (batch_queue_ == QueueType::Compute) {
        batch_waits_.insert(batch_waits_.end(), for_compute.begin(), for_compute.end());
        LOOM_TRY(submit_batch(std::span<const VkSemaphore>(&*done, 1), QueueType::Graphics));
    } else {
        LOOM_TRY(submit({}, true, std::span<const VkSemaphore>(&*done, 1), for_compute, QueueType::Compute));
    }
    batch_waits_.insert(batch_waits_.end(), for_graphics.begin(), for_graphics.end());
    batch_waits_.push_back(*done);
    return {};
}

void VulkanDevice::reset_queues() {
    batch_queue_ = QueueType::Graphics;
    batch_waits_.clear();
    frame_signals_.clear();
    compute_used_ = false;
}

}  // namespace loom::vulkan

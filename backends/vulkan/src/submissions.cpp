#include "submissions.hpp"

#include "loom/vulkan/context.hpp"

namespace loom::vulkan {

namespace {
// How long loom waits for a frame the application submits. Reaching it means the application
// never submitted the frame (or never signalled loom's semaphore): an error, not a hang.
constexpr uint64_t kExternalWaitNs = 20'000'000'000;
}  // namespace

SubmissionTracker::~SubmissionTracker() {
    run_all_deferred();
    for (const InFlight& f : in_flight_) {
        if (f.fence) vkDestroyFence(device_, f.fence, nullptr);
    }
    for (VkFence f : free_fences_) vkDestroyFence(device_, f, nullptr);
}

loom::Result<uint64_t> SubmissionTracker::submit(VkQueue queue, const VkSubmitInfo2& info) {
    VkFence fence = VK_NULL_HANDLE;
    if (!free_fences_.empty()) {
        fence = free_fences_.back();
        free_fences_.pop_back();
    } else {
        auto fi = vk_init<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
        if (VkResult r = vkCreateFence(device_, &fi, nullptr, &fence); r != VK_SUCCESS) return vk_error(r, "vkCreateFence");
    }
    if (VkResult r = vkQueueSubmit2(queue, 1, &info, fence); r != VK_SUCCESS) {
        free_fences_.push_back(fence);
        return vk_error(r, "vkQueueSubmit2");
    }
    const uint64_t serial = next_serial_++;
    in_flight_.push_back({serial, fence});
    return serial;
}

uint64_t SubmissionTracker::add_external(VkSemaphore timeline, uint64_t value) {
    const uint64_t serial = next_serial_++;
    in_flight_.push_back({serial, VK_NULL_HANDLE, timeline, value});
    return serial;
}

bool SubmissionTracker::finished(const InFlight& f) const {
    if (f.fence) return vkGetFenceStatus(device_, f.fence) == VK_SUCCESS;
    uint64_t reached = 0;
    return vkGetSemaphoreCounterValue(device_, f.timeline, &reached) == VK_SUCCESS && reached >= f.value;
}

void SubmissionTracker::retire(InFlight& f) {
    if (f.fence) {
        vkResetFences(device_, 1, &f.fence);
        free_fences_.push_back(f.fence);
    }
    completed_ = f.serial;
}

void SubmissionTracker::poll() {
    while (!in_flight_.empty() && finished(in_flight_.front())) {
        retire(in_flight_.front());
        in_flight_.pop_front();
    }
    run_due();
}

loom::Status SubmissionTracker::wait(uint64_t serial) {
    while (!in_flight_.empty() && in_flight_.front().serial <= serial) {
        InFlight& f = in_flight_.front();
        if (f.fence) {
            if (VkResult r = vkWaitForFences(device_, 1, &f.fence, VK_TRUE, UINT64_MAX); r != VK_SUCCESS) {
                return vk_error(r, "vkWaitForFences");
            }
        } else {
            auto info = vk_init<VkSemaphoreWaitInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_WAIT_INFO);
            info.semaphoreCount = 1;
            info.pSemaphores = &f.timeline;
            info.pValues = &f.value;
            const VkResult r = vkWaitSemaphores(device_, &info, kExternalWaitNs);
            if (r == VK_TIMEOUT) {
                return Error{ErrorCode::InvalidState,
                             "the frame the application recorded (loom's timeline semaphore value " + std::to_string(f.value) +
                                 ") did not finish within " + std::to_string(kExternalWaitNs / 1'000'000'000) +
                                 " s: submit its command buffer, signalling external_frame_signal(), before loom "
                                 "submits again (the next end_frame, a readback, wait_idle)"};
            }
            if (r != VK_SUCCESS) return vk_error(r, "vkWaitSemaphores");
        }
        retire(f);
        in_flight_.pop_front();
    }
    poll();
    return {};
}

void SubmissionTracker::defer(std::function<void()> fn) { deferred_.push_back({next_serial_, std::move(fn)}); }

void SubmissionTracker::run_due() {
    // Deferred work is appended in serial order, so the due items are at the front. An item
    // tagged with a serial not yet submitted is not due.
    while (!deferred_.empty() && deferred_.front().serial <= completed_) {
        auto fn = std::move(deferred_.front().fn);
        deferred_.pop_front();
        fn();
    }
}

void SubmissionTracker::run_all_deferred() {
    while (!deferred_.empty()) {
        auto fn = std::move(deferred_.front().fn);
        deferred_.pop_front();
        fn();
    }
}

}  // namespace loom::vulkan

#pragma once
// Queue submissions numbered by serial, each with a fence; what a serial has completed; and
// work (object destruction, ring-space release) deferred until a serial completes. This is
// how the backend knows when the GPU no longer uses something without waiting for idle.

#include <cstdint>
#include <deque>
#include <functional>
#include <vector>

#include <vulkan/vulkan.h>

#include "loom/rhi/result.hpp"

namespace loom::vulkan {

class SubmissionTracker {
public:
    explicit SubmissionTracker(VkDevice device) : device_(device) {}
    ~SubmissionTracker();
    SubmissionTracker(const SubmissionTracker&) = delete;
    SubmissionTracker& operator=(const SubmissionTracker&) = delete;

    /// The serial the next submission will get: anything recorded now is used by it.
    [[nodiscard]] uint64_t pending_serial() const { return next_serial_; }
    /// All submissions up to this serial have finished on the GPU.
    [[nodiscard]] uint64_t completed_serial() const { return completed_; }
    [[nodiscard]] uint64_t last_submitted_serial() const { return next_serial_ - 1; }

    /// Submits `info` (one batch) with a fence and returns its serial.
    loom::Result<uint64_t> submit(VkQueue queue, const VkSubmitInfo2& info);
    /// Numbers work the application submits itself (a frame recorded into its command
    /// buffer): it has completed once `timeline` reaches `value`. Returns its serial. The
    /// application submits it before loom's next submission, so serials stay in queue order.
    uint64_t add_external(VkSemaphore timeline, uint64_t value);

    /// Updates completed_serial() from the fences without waiting, then runs due work.
    void poll();
    /// Waits until `serial` has completed (and runs due deferred work).
    loom::Status wait(uint64_t serial);
    /// Waits for every submission.
    loom::Status wait_all() { return wait(last_submitted_serial()); }

    /// Runs `fn` once every submission up to pending_serial() (the commands recorded so far)
    /// has completed.
    void defer(std::function<void()> fn);
    /// Runs every deferred function now (the device is idle or being destroyed).
    void run_all_deferred();

private:
    /// A submission, finished when its fence signals, or (external work, no fence) when its
    /// timeline semaphore reaches `value`.
    struct InFlight {
        uint64_t serial;
        VkFence fence;
        VkSemaphore timeline = VK_NULL_HANDLE;
        uint64_t value = 0;
    };
    struct Deferred {
        uint64_t serial;
        std::function<void()> fn;
    };

    void run_due();
    bool finished(const InFlight& f) const;
    void retire(InFlight& f);

    VkDevice device_;
    uint64_t next_serial_ = 1;
    uint64_t completed_ = 0;
    std::deque<InFlight> in_flight_;
    std::vector<VkFence> free_fences_;
    std::deque<Deferred> deferred_;
};

}  // namespace loom::vulkan

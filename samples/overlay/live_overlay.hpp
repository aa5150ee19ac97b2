#pragma once
// The frame overlay over an application's frame graph: each update shows the executor's latest
// plan, timings and the device's memory, and when the user changes a control the frame is
// re-planned before the next frame is recorded. The application says how controls map to its
// settings through PlannedFrame; loom-deferred and loom-engine implement it.

#include <chrono>
#include <memory>
#include <string>

#include "frame_overlay.hpp"

namespace loom::overlay {

/// A frame the overlay can show and re-plan.
class PlannedFrame {
public:
    virtual ~PlannedFrame() = default;
    /// The executor whose plan and timings the overlay shows.
    [[nodiscard]] virtual fg::Executor& executor() = 0;
    /// The controls that describe the frame's settings now.
    [[nodiscard]] virtual OverlayControls controls() const = 0;
    /// Rebuilds the frame with what `controls` set. A combination the frame cannot run is an
    /// InvalidArgument error saying why, with the frame left as it was.
    virtual Status apply(const OverlayControls& controls) = 0;
};

/// The two times LiveOverlay::update takes, as a sample's window loop measures them.
class FrameClock {
public:
    /// Marks the beginning of a frame; returns the seconds since the previous frame began.
    double begin() {
        const Clock::time_point now = Clock::now();
        const double seconds = std::chrono::duration<double>(now - begun_).count();
        begun_ = now;
        return seconds;
    }
    /// Marks the end of the frame begun last (after end_frame).
    void end() { frame_ms_ = std::chrono::duration<double, std::milli>(Clock::now() - begun_).count(); }
    /// CPU time of the last frame ended, from begin() to end(), in milliseconds (0 before one).
    [[nodiscard]] double frame_ms() const { return frame_ms_; }

private:
    using Clock = std::chrono::steady_clock;
    Clock::time_point begun_ = Clock::now();
    double frame_ms_ = 0.0;
};

class LiveOverlay {
public:
    /// An overlay (hidden until F1 or set_visible) over `frame`, drawing into `target_format`.
    static Result<std::unique_ptr<LiveOverlay>> create(rhi::Device& device, PlannedFrame& frame, rhi::Format target_format);

    /// One UI frame from `input` for a target of `size`; re-plans the frame when the user
    /// changed a control (true then). A change the frame refuses is undone and its message
    /// shown in the overlay; other errors are returned. `frame_ms` is the CPU time of the
    /// previous frame, shown.
    Result<bool> update(const rhi::WindowInput& input, rhi::Extent3D size, double seconds, double frame_ms);
    /// Draws the overlay over `target` (nothing while hidden).
    Status record(rhi::CommandList& commands, rhi::TextureHandle target) { return overlay_->record(commands, target); }

    [[nodiscard]] FrameOverlay& overlay() { return *overlay_; }
    [[nodiscard]] const OverlayControls& controls() const { return controls_; }
    /// How many times a change re-planned the frame.
    [[nodiscard]] uint32_t replans() const { return replans_; }
    /// Why the latest refused change was refused (empty: none refused since the last re-plan).
    [[nodiscard]] const std::string& message() const { return message_; }

private:
    LiveOverlay(rhi::Device& device, PlannedFrame& frame) : device_(device), frame_(frame) {}

    rhi::Device& device_;
    PlannedFrame& frame_;
    std::unique_ptr<FrameOverlay> overlay_;
    OverlayControls controls_;
    uint32_t replans_ = 0;
    std::string message_;
};

}  // namespace loom::overlay

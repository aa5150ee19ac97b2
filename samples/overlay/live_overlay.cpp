#include "live_overlay.hpp"

#include "loom/rhi/log.hpp"

namespace loom::overlay {

Result<std::unique_ptr<LiveOverlay>> LiveOverlay::create(rhi::Device& device, PlannedFrame& frame, rhi::Format target_format) {
    std::unique_ptr<LiveOverlay> live(new LiveOverlay(device, frame));
    auto created = FrameOverlay::create(device, target_format);
    if (!created) return created.take_error();
    live->overlay_ = std::move(*created);
    live->controls_ = frame.controls();
    return live;
}

Result<bool> LiveOverlay::update(const rhi::WindowInput& input, rhi::Extent3D size, double seconds, double frame_ms) {
    fg::Executor& executor = frame_.executor();
    const std::shared_ptr<const fg::Plan> plan = executor.plan();
    OverlayFrame shown;
    shown.title = std::string(rhi::backend_name(device_.backend())) + " on " + device_.capabilities().device_name +
                  (plan ? ", " + std::to_string(plan->frame.width) + "x" + std::to_string(plan->frame.height) : std::string());
    shown.plan = plan.get();
    shown.timings = executor.timings();
    shown.device_bytes = device_.resource_stats().total_bytes();
    shown.frame_ms = frame_ms;
    shown.message = message_;
    const OverlayControls changed = overlay_->update(input, size, seconds, shown, controls_);
    if (changed == controls_) return false;
    if (Status applied = frame_.apply(changed); !applied) {
        if (applied.error().code != ErrorCode::InvalidArgument) return applied.take_error();
        message_ = applied.error().message;
        log_warning("overlay", "change refused: " + message_);
        return false;
    }
    controls_ = changed;
    message_.clear();
    ++replans_;
    log_info("overlay", "re-planned with allocator " + std::string(fg::allocator_name(controls_.allocator)));
    return true;
}

}  // namespace loom::overlay

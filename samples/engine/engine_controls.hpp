#pragma once
// loom-engine's frame as frame-overlay controls (samples/overlay): the allocator and whether
// SSAO runs on the async compute queue. A change rebuilds the graph (EngineFrame::replan); the
// paper allocator with async compute on is refused with a message, as on the command line.

#include "engine_frame.hpp"
#include "live_overlay.hpp"

namespace loom::engine {

/// The label of the async compute switch (OverlaySwitch::label).
inline constexpr const char* kAsyncComputeSwitch = "async compute (SSAO on the compute queue)";

class EngineFrameControls : public overlay::PlannedFrame {
public:
    explicit EngineFrameControls(EngineFrame& frame) : frame_(frame) {}
    [[nodiscard]] fg::Executor& executor() override { return frame_.executor(); }
    [[nodiscard]] overlay::OverlayControls controls() const override {
        overlay::OverlayControls controls;
        controls.allocator = frame_.settings().allocator;
        controls.switches.push_back({kAsyncComputeSwitch, {}, frame_.settings().async_compute});
        return controls;
    }
    Status apply(const overlay::OverlayControls& controls) override {
        const overlay::OverlaySwitch* async = controls.find(kAsyncComputeSwitch);
        return frame_.replan(controls.allocator, async ? async->on : frame_.settings().async_compute);
    }

private:
    EngineFrame& frame_;
};

}  // namespace loom::engine

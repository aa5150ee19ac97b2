#pragma once
// The flagship pipeline's settings as frame-overlay controls (samples/overlay): the lit pass
// (deferred or forward), the bloom's blur passes, the transparent pass and the allocator. A
// change rebuilds the pipeline's graph; the next frame plans it.

#include "live_overlay.hpp"
#include "loom/renderer/deferred_pipeline.hpp"

namespace loom::deferred {

/// Switch labels (OverlaySwitch::label) of the pipeline's controls.
inline constexpr const char* kDeferredSwitch = "deferred lighting (off: one forward pass)";
inline constexpr const char* kBloomSwitch = "bloom";
inline constexpr const char* kTransparentSwitch = "transparent objects";

/// The overlay controls that describe `settings` on a pipeline drawing `scene` (the transparent
/// switch only where the scene has blended objects).
overlay::OverlayControls pipeline_controls(const renderer::PipelineSettings& settings, const renderer::PipelineScene& scene);

/// `settings` with what `controls` set (allocator, lit pass, bloom, transparent pass).
renderer::PipelineSettings apply_controls(renderer::PipelineSettings settings, const overlay::OverlayControls& controls);

/// A DeferredPipeline as the overlay's PlannedFrame.
class DeferredFrameControls : public overlay::PlannedFrame {
public:
    explicit DeferredFrameControls(renderer::DeferredPipeline& pipeline) : pipeline_(pipeline) {}
    [[nodiscard]] fg::Executor& executor() override { return pipeline_.executor(); }
    [[nodiscard]] overlay::OverlayControls controls() const override {
        return pipeline_controls(pipeline_.settings(), pipeline_.scene());
    }
    /// Every combination runs: rebuilds the pipeline's graph.
    Status apply(const overlay::OverlayControls& controls) override {
        return pipeline_.rebuild(apply_controls(pipeline_.settings(), controls));
    }

private:
    renderer::DeferredPipeline& pipeline_;
};

}  // namespace loom::deferred

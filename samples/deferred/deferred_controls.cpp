#include "deferred_controls.hpp"

namespace loom::deferred {
overlay::OverlayControls pipeline_controls(const renderer::PipelineSettings& settings, const renderer::PipelineScene& scene) {
    overlay::OverlayControls controls;
    controls.allocator = settings.allocator;
    controls.switches.push_back({kDeferredSwitch, {"geometry", "deferred"}, !settings.forward});
    controls.switches.push_back({kBloomSwitch, {"blur-h", "blur-v"}, settings.bloom});
    if (!scene.blended.empty()) controls.switches.push_back({kTransparentSwitch, {"transparent"}, settings.transparent});
    return controls;
}

renderer::PipelineSettings apply_controls(renderer::PipelineSettings settings, const overlay::OverlayControls& controls) {
    settings.allocator = controls.allocator;
    if (const auto* s = controls.find(kDeferredSwitch)) settings.forward = !s->on;
    if (const auto* s = controls.find(kBloomSwitch)) settings.bloom = s->on;
    if (const auto* s = controls.find(kTransparentSwitch)) settings.transparent = s->on;
    return settings;
}

}  // namespace loom::deferred

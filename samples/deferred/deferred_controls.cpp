#include "deferred_controls.hpp"

namespace loom::deferred {
namespace {

const overlay::OverlaySwitch* find_switch(const overlay::OverlayControls& controls, std::string_view label) {
    for (const overlay::OverlaySwitch& s : controls.switches) {
        if (s.label == label) return &s;
    }
    return nullptr;
}

}  // namespace

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
    if (const auto* s = find_switch(controls, kDeferredSwitch)) settings.forward = !s->on;
    if (const auto* s = find_switch(controls, kBloomSwitch)) settings.bloom = s->on;
    if (const auto* s = find_switch(controls, kTransparentSwitch)) settings.transparent = s->on;
    return settings;
}

}  // namespace loom::deferred

#pragma once
// Renders the flagship pipeline (samples/deferred) in-process and reads back every texture.

#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "loom/framegraph/plan.hpp"
#include "loom/renderer/deferred_pipeline.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/image.hpp"
#include "procedural_scene.hpp"

namespace loom::test {

/// What one backend rendered.
struct FlagshipFrame {
    fg::Plan plan;
    fg::ExecutionStats stats;
    /// Every intermediate ("pass.port") and "final", as read back.
    std::map<std::string, rhi::Image> images;
};

/// Renders `frames` frames of the built-in scene at `width` x `height` and reads everything back.
Result<FlagshipFrame> render_flagship(rhi::Device& device, uint32_t width, uint32_t height,
                                      const renderer::PipelineSettings& settings = {}, uint32_t frames = 1);

/// Reads back the latest frame's intermediates and final picture.
Result<std::map<std::string, rhi::Image>> read_back(rhi::Device& device, const renderer::DeferredPipeline& pipeline);

}  // namespace loom::test

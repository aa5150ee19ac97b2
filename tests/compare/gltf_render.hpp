#pragma once
// Renders a loom::scene::Scene through the deferred or the forward pipeline in-process and
// reads every captured texture back.

#include <map>
#include <string>
#include <vector>

#include "loom/framegraph/executor.hpp"
#include "loom/framegraph/plan.hpp"
#include "loom/passes/view.hpp"
#include "loom/renderer/deferred_pipeline.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/image.hpp"
#include "loom/scene/scene.hpp"

namespace loom::test {

struct GltfFrame {
    fg::Plan plan;
    fg::ExecutionStats stats;
    /// Every pass output ("pass.port") and "final".
    std::map<std::string, rhi::Image> images;
    /// The transparent pass's draw order (empty without blended objects).
    std::vector<std::string> blend_order;
    /// The camera, light and shadow settings of the frame.
    passes::SceneView view;
};

/// The settings the tests draw glTF scenes with: deferred or forward, a 512-texel shadow map.
renderer::PipelineSettings gltf_test_settings(bool forward);

/// One frame of `scene` (seen from its first camera, or framed) at width x height.
Result<GltfFrame> render_gltf(rhi::Device& device, scene::Scene scene, bool forward, uint32_t width = 64,
                              uint32_t height = 64);

/// Renders one frame of `pipeline` at width x height and reads everything it captured back.
Result<GltfFrame> render_frame(rhi::Device& device, renderer::DeferredPipeline& pipeline, uint32_t width,
                               uint32_t height);

}  // namespace loom::test

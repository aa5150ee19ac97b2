#pragma once
// The frame graph that both embedding samples (loom-embed-gl, loom-embed-vulkan) run inside
// their "engine": two passes, the second drawing over the engine's own render target.
//
//   pattern  output "color" (RGBA8Unorm, frame-sized): texel (x, y) =
//            (x % 16 / 15, y % 16 / 15, (x / 16 + y / 16) % 2, 1), row 0 on top
//   overlay  input "pattern", optional inout "target" (the engine's texture, imported): copies
//            the pattern into the top-left quadrant of the target and keeps the rest, so the
//            engine's own clear colour shows around it
//
// Every value is exact in 8-bit unorm, so the engine's picture can be checked texel by texel
// (tests/embed does).

#include <memory>

#include "loom/framegraph/framegraph.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

namespace loom::samples {

/// The overlay graph and the pipelines its passes draw with, on one device.
class OverlayGraph {
public:
    /// Compiles the shaders (at run time) and builds the graph; `target_format` is the format
    /// of the engine's texture bound to target_port() (e.g. BGRA8Unorm for a swapchain).
    static Result<std::unique_ptr<OverlayGraph>> create(rhi::Device& device, rhi::Format target_format);
    /// Destroys the pipelines (the device must still exist).
    ~OverlayGraph();
    OverlayGraph(const OverlayGraph&) = delete;
    OverlayGraph& operator=(const OverlayGraph&) = delete;

    /// pattern -> overlay, overlay.target marked as the graph output.
    fg::FrameGraph& graph() { return graph_; }
    /// The port the engine binds its texture to (fg::Executor::import_texture).
    static fg::PortRef target_port() { return fg::port("overlay", "target"); }

private:
    explicit OverlayGraph(rhi::Device& device) : device_(device) {}
    Status build(rhi::Format target_format);

    rhi::Device& device_;
    rhi::ShaderHandle vertex_, pattern_fragment_, overlay_fragment_;
    rhi::PipelineHandle pattern_, overlay_;
    rhi::SamplerHandle sampler_;
    fg::FrameGraph graph_;
};

}  // namespace loom::samples

#pragma once
// loom-engine's frame: an engine-style frame graph drawing an EngineScene (docs/engine.md).
//
//   depth_prepass ─┬─ ssao ─ ssao_blur  (async compute queue) ─────────────────┐
//                  ├─ hzb_0 ─ hzb_1 … hzb_4 ─ light_cull (tiled light list) ─┐ │
//                  │  shadow_cascade_0 … 3 (one array texture) ─────────────┐│ │
//                  └───────────────────────────────────────────────── shade (forward+, sky)
//                       ─ bloom_prefilter ─ bloom_down_1…4 ─ bloom_up_3…0 ─ tonemap
//
// The graph is built once and is independent of the frame size (every texture is a scale of
// the frame or a fixed size, the light list a size per 16x16 tile); the executor plans it for
// each size. With capture on, every pass copies what it wrote into a texture of its own, so
// that each intermediate can be written out although the plan aliases their memory.

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine_scene.hpp"
#include "loom/framegraph/executor.hpp"
#include "loom/framegraph/graph.hpp"
#include "loom/framegraph/pass_context.hpp"
#include "loom/renderer/gpu_scene.hpp"
#include "loom/rhi/device.hpp"
#include "loom/scene/camera.hpp"

namespace loom::engine {

/// Pixels per side of a light-list tile, and uints per tile (a count, then up to 63 light
/// indices). Mirror kTileSize / kTileStride in shaders/engine/frame.glsl.
inline constexpr uint32_t kTileSize = 16;
inline constexpr uint32_t kTileStride = 64;
inline constexpr uint32_t kCascades = 4;
/// Levels of the hierarchical Z (level 4 is one texel per tile) and of the bloom pyramid.
inline constexpr uint32_t kHzbLevels = 5;
inline constexpr uint32_t kBloomLevels = 5;
/// The smallest frame the graph takes: every level of both pyramids at least one texel.
inline constexpr uint32_t kMinFrameSide = 64;

struct FrameSettings {
    /// Allocator of the plan: heap (the default: the frame's transients all differ in
    /// format or size, so only aliasing in bytes saves memory; placed in device heaps where the
    /// device has them, as on Vulkan), interval (shares whole textures of one shape) or
    /// paper (which refuses async passes: use it with async_compute off).
    fg::AllocatorKind allocator = fg::AllocatorKind::Heap;
    /// The pass order the frame is planned in (fg::PlanOptions::order); the picture is the
    /// same in both (default: memory, fg::kDefaultPassOrder).
    fg::PassOrder order = fg::kDefaultPassOrder;
    /// SSAO and its blur on the async compute queue (run in order on devices with one queue).
    bool async_compute = true;
    /// Side of each shadow cascade, texels.
    uint32_t shadow_size = 1024;
    /// Copy every pass output aside for write-out (intermediates()).
    bool capture = true;
    /// Format of the final picture (e.g. the window's back buffer format).
    rhi::Format target_format = rhi::Format::RGBA8Srgb;
};

/// An intermediate kept by capture: all its mip levels and layers as the frame left them.
struct Intermediate {
    std::string name;  ///< "hzb", "shadow_cascades", "occlusion", ...
    rhi::TextureHandle texture;
    rhi::Format format = rhi::Format::Undefined;
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t mips = 1;
    uint32_t layers = 1;
};

class EngineFrame {
public:
    /// Uploads the scene and its lights, creates the pipelines and builds the graph. Errors:
    /// the device's, naming the buffer, texture or shader.
    static Result<std::unique_ptr<EngineFrame>> create(rhi::Device& device, const EngineScene& scene, FrameSettings settings = {});
    ~EngineFrame();
    EngineFrame(const EngineFrame&) = delete;
    EngineFrame& operator=(const EngineFrame&) = delete;

    /// One headless frame of `size` (each side at least kMinFrameSide): begin_frame, the graph,
    /// end_frame. The picture is final_texture().
    Status render(fg::Extent2D size);
    /// Records the graph into a frame the caller began, drawing into `target` (a texture of
    /// `size` in FrameSettings::target_format, e.g. the back buffer), left in `final_state`.
    Status record(rhi::CommandList& commands, rhi::TextureHandle target, fg::Extent2D size,
                  rhi::ResourceState final_state = rhi::ResourceState::Present);
    /// Rebuilds the graph with another allocator and queue choice (the rest of the settings
    /// stay); the next frame plans it. InvalidArgument, with the frame unchanged, for the paper
    /// allocator with async compute on (it refuses async passes).
    Status replan(fg::AllocatorKind allocator, bool async_compute);

    /// The final picture of the latest render() (its capture when capture is on).
    [[nodiscard]] rhi::TextureHandle final_texture();
    /// The captured intermediates of the latest frame, in the order their passes ran.
    [[nodiscard]] const std::vector<Intermediate>& intermediates() const { return captures_; }
    /// The light list of the latest frame (capture only): per tile, a count and light indices.
    [[nodiscard]] rhi::BufferHandle captured_light_list() const { return light_list_capture_; }
    [[nodiscard]] uint64_t captured_light_list_bytes() const { return light_list_capture_bytes_; }
    /// Tiles across and down for a frame of `size`.
    [[nodiscard]] static fg::Extent2D tile_count(fg::Extent2D size);

    [[nodiscard]] fg::FrameGraph& graph() { return graph_; }
    [[nodiscard]] fg::Executor& executor() { return executor_; }
    [[nodiscard]] const FrameSettings& settings() const { return settings_; }
    [[nodiscard]] const EngineScene& scene() const { return scene_; }
    [[nodiscard]] const renderer::GpuScene& gpu_scene() const { return *gpu_; }
    /// The camera's view and projection for a frame of `size` (what every pass reads).
    [[nodiscard]] scene::CameraMatrices camera(fg::Extent2D size) const;
    /// The options the executor plans with (allocator; the frame size is render()'s).
    [[nodiscard]] fg::PlanOptions plan_options(fg::Extent2D size) const;

private:
    struct Programs;
    EngineFrame(rhi::Device& device, const EngineScene& scene, FrameSettings settings);
    Status upload();
    Status create_programs();
    Status build_graph();
    Status prepare_frame(fg::Extent2D size);
    /// Copies what `port` holds (its mip levels and layers) into the capture `name`, then puts
    /// it back in `state` (the state the pass left it in) for the executor.
    Status capture(fg::PassContext& ctx, const std::string& port, const std::string& name, rhi::ResourceState state);
    Status capture_buffer(fg::PassContext& ctx, const std::string& port);
    Status draw_scene(fg::PassContext& ctx, bool shading);

    rhi::Device* device_;
    EngineScene scene_;
    FrameSettings settings_;
    std::shared_ptr<renderer::GpuScene> gpu_;
    std::unique_ptr<Programs> programs_;
    rhi::BufferHandle lights_;
    rhi::BufferHandle draws_;        ///< every draw item's DrawUniforms, at aligned offsets
    uint64_t draw_stride_ = 0;
    std::vector<uint8_t> frame_uniforms_;  ///< this frame's FrameUniforms
    fg::FrameGraph graph_;
    fg::Executor executor_;
    std::vector<Intermediate> captures_;
    rhi::BufferHandle light_list_capture_;
    uint64_t light_list_capture_bytes_ = 0;
};

}  // namespace loom::engine

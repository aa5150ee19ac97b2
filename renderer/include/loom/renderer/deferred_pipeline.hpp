#pragma once
// The paper's Figure 2 pipeline on a loom frame graph (Listing 6, connection for connection):
//
//   shadow ──shadow_map──────────────┐
//   geometry ─position/normal/albedo/emission─┴─► deferred ──color──────────────► composite ──final──► present ──target
//                                          └─high_pass─► blur-h ─► blur-v ──bloom──┘
//
// The deferred pass is composed from the "deferred-render", "shadow-render" and
// "high-pass-render" parts; the blur is separable (two passes). With PipelineSettings::forward,
// one forward pass ("forward-render" + the same two parts) replaces geometry and deferred. Every colour port shares one spec
// (RGBA16Float at the frame size), so the plan shares their textures; the present pass converts
// to the target format (RGBA8Unorm offscreen, the back buffer's format in a window).
//
// Scenes with blended surfaces (PipelineScene::blended) get a transparent pass after the lit
// pass: it blends them, back to front, onto the lit colour and high pass in place, tested
// against the opaque depth (geometry.depth, or forward.depth):
//
//   deferred|forward ──color/high_pass──► transparent ──color──► composite, ──high_pass──► blur-h
//   geometry|forward ──depth────────────┘
//
// Scenes with cut-out surfaces (PipelineScene::masked_shadow_casters) get a masked shadow pass
// that draws them into the shadow map in place, after the standard shadow pass:
//
//   shadow ──shadow_map──► masked-shadow ──shadow_map──► deferred|forward, transparent

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "loom/framegraph/executor.hpp"
#include "loom/framegraph/graph.hpp"
#include "loom/passes/blit_pass.hpp"
#include "loom/passes/blur_pass.hpp"
#include "loom/passes/composite_pass.hpp"
#include "loom/passes/deferred_pass.hpp"
#include "loom/passes/forward_pass.hpp"
#include "loom/passes/geometry_pass.hpp"
#include "loom/passes/mesh_object.hpp"
#include "loom/passes/retained_scene.hpp"
#include "loom/passes/shadow_map_pass.hpp"
#include "loom/rhi/device.hpp"
#include "loom/renderer/masked_shadow_pass.hpp"
#include "loom/renderer/transparent_pass.hpp"

namespace loom::renderer {

struct PipelineSettings {
    fg::AllocatorKind allocator = fg::AllocatorKind::Interval;
    /// The pass order the frame is planned in (fg::PlanOptions::order): declared, or the one
    /// with the lowest peak of live bytes (the default). The pictures are the same in both.
    fg::PassOrder order = fg::kDefaultPassOrder;
    /// Light the objects as they are drawn (the forward pass, composed of the same
    /// "shadow-render" and "high-pass-render" parts) instead of the G-buffer and deferred passes.
    bool forward = false;
    /// The blur passes (blur-h, blur-v) that make the bloom. Off, the graph has neither and the
    /// composite adds no bloom (it reads the unblurred high pass, weighted 0).
    bool bloom = true;
    /// The transparent pass, where the scene has blended objects. Off, they are not drawn.
    bool transparent = true;
    /// Ports ask for CopySrc and every pass copies its outputs for read-back (intermediates()).
    bool capture = true;
    uint32_t shadow_map_size = 2048;
    /// Blur taps on each side; empty: frame height / 24, between 1 and passes::kMaxBlurRadius.
    std::optional<uint32_t> blur_radius;
    float exposure = 1.0f;
    float bloom_strength = 0.8f;
    float threshold = 1.0f;
    /// Format of present.target (RGBA8Unorm offscreen; the back buffer's in a window).
    rhi::Format target_format = rhi::Format::RGBA8Unorm;
    /// Compiles the passes' programs; share one between pipelines (also on different devices:
    /// it holds no GPU objects) so that equal programs compile once. Null: one of its own.
    std::shared_ptr<passes::ShaderLibrary> library;
};

/// An object the transparent pass draws, with the world bounds it is sorted by.
struct BlendedObject {
    std::shared_ptr<const passes::Object> object;
    scene::Bounds bounds;
    /// For objects that move: called at every frame's sort instead of using `bounds`.
    std::function<scene::Bounds()> moving_bounds;
};

/// What the pipeline draws and how it looks at it, whatever kind the objects are: loom::passes'
/// MeshObjects (the flagship sample's procedural scene) or a glTF file's GltfObjects
/// (gltf_scene.hpp).
struct PipelineScene {
    std::string name;
    /// Drawn into the shadow map (their vertex parts only).
    std::vector<std::shared_ptr<const passes::Object>> shadow_casters;
    /// Drawn into the shadow map with their material, which cuts them out (glTF MASK); none:
    /// the pipeline has no masked shadow pass.
    std::vector<std::shared_ptr<const passes::Object>> masked_shadow_casters;
    /// Drawn by the geometry pass (deferred) or the forward pass.
    std::vector<std::shared_ptr<const passes::Object>> opaque;
    /// Drawn by the transparent pass; none: the pipeline has no transparent pass.
    std::vector<BlendedObject> blended;
    /// Shapes of the retained object layer (loom/passes/retained_scene.hpp), drawn besides the
    /// objects above: the pipeline attaches its shadow, masked-shadow, geometry and forward
    /// passes to the scene (sorted queues), and each shape names the passes that draw it
    /// (Shape::passes). Null: none. The scene draws on the pipeline's device only.
    std::shared_ptr<passes::RetainedScene> retained;
    /// Some retained shapes name the masked shadow pass: the pipeline has one even without
    /// masked_shadow_casters.
    bool retained_masked_shadows = false;
    /// The camera of a frame of aspect ratio width / height.
    std::function<scene::CameraMatrices(float aspect)> camera;
    passes::DirectionalLight light;
    passes::Environment environment;
    /// World bounds of everything drawn (the position map is shown relative to them).
    scene::Bounds bounds;
    /// What the shadow map covers.
    scene::Bounds shadow_bounds;
};

/// A texture of the latest captured frame, by "pass.port".
struct Intermediate {
    std::string name;
    rhi::TextureHandle texture;
};

class DeferredPipeline {
public:
    /// Builds the graph and registers every object of `scene` with the passes that draw it
    /// (composing one program per pass and object kind).
    static Result<std::unique_ptr<DeferredPipeline>> create(rhi::Device& device, PipelineScene scene,
                                                            const PipelineSettings& settings = {});
    ~DeferredPipeline();
    DeferredPipeline(const DeferredPipeline&) = delete;
    DeferredPipeline& operator=(const DeferredPipeline&) = delete;

    /// Replaces the graph and its passes by those `settings` describe (e.g. the lit pass
    /// toggled between deferred and forward), as an engine rebuilding its frame graph does. The
    /// scene, the executor and its textures stay: the next frame plans the new graph and the
    /// executor keeps what the new plan can reuse. The shader library stays unless `settings`
    /// names another. After an error the pipeline has no graph until a rebuild succeeds.
    Status rebuild(const PipelineSettings& settings);

    /// Renders one frame of `frame` size offscreen (begin_frame .. end_frame).
    Status render(fg::Extent2D frame);
    /// Records one frame into a frame the caller began, presenting into `target` (imported as
    /// present.target and left in `final_state`).
    Status record(rhi::CommandList& commands, rhi::TextureHandle target, fg::Extent2D frame,
                  rhi::ResourceState final_state = rhi::ResourceState::Present);

    [[nodiscard]] fg::FrameGraph& graph() { return graph_; }
    [[nodiscard]] fg::Executor& executor() { return *executor_; }
    /// The options of the latest frame (frame size, allocator).
    [[nodiscard]] const fg::PlanOptions& options() const { return options_; }
    /// The final picture of the latest offscreen frame (present.target).
    [[nodiscard]] rhi::TextureHandle final_texture() const;
    /// Every output of every pass in the latest frame, copied at the end of its pass (needs
    /// PipelineSettings::capture), in plan order.
    [[nodiscard]] std::vector<Intermediate> intermediates() const;
    /// The passes, in the order they are declared.
    [[nodiscard]] const std::vector<passes::ShaderPass*>& passes() const { return passes_; }
    [[nodiscard]] const passes::ShaderLibrary& library() const { return *library_; }
    /// Blur taps on each side; 0 without bloom (PipelineSettings::bloom off).
    [[nodiscard]] uint32_t blur_radius() const { return blur_h_ ? blur_h_->radius() : 0; }
    /// The camera, light and shadow settings of a frame of size `frame`.
    [[nodiscard]] passes::SceneView view(fg::Extent2D frame) const;
    [[nodiscard]] const PipelineSettings& settings() const { return settings_; }
    /// Sets the composite's bloom strength (for comparisons with and without bloom); stays 0
    /// without the blur passes (PipelineSettings::bloom off).
    void set_bloom_strength(float strength) { composite_->set_bloom_strength(settings_.bloom ? strength : 0.0f); }
    [[nodiscard]] const PipelineScene& scene() const { return scene_; }
    /// The masked shadow pass; null when the scene has no masked shadow casters.
    [[nodiscard]] const renderer::MaskedShadowPass* masked_shadow() const { return masked_shadow_; }
    /// The transparent pass; null when the scene has no blended objects.
    [[nodiscard]] const renderer::TransparentPass* transparent() const { return transparent_; }

private:
    DeferredPipeline(rhi::Device& device, PipelineScene scene, PipelineSettings settings);
    Status build();
    void drop_graph();
    Status prepare(fg::Extent2D frame);

    rhi::Device& device_;
    PipelineScene scene_;
    PipelineSettings settings_;
    std::shared_ptr<passes::ShaderLibrary> library_;
    fg::FrameGraph graph_;
    std::unique_ptr<fg::Executor> executor_;
    fg::PlanOptions options_;

    std::vector<passes::ShaderPass*> passes_;
    passes::ShadowMapPass* shadow_ = nullptr;
    renderer::MaskedShadowPass* masked_shadow_ = nullptr;
    passes::GeometryPass* geometry_ = nullptr;
    passes::DeferredPass* deferred_ = nullptr;
    passes::ForwardPass* forward_ = nullptr;
    renderer::TransparentPass* transparent_ = nullptr;
    passes::BlurPass* blur_h_ = nullptr;
    passes::BlurPass* blur_v_ = nullptr;
    passes::CompositePass* composite_ = nullptr;
    passes::BlitPass* present_ = nullptr;
};

}  // namespace loom::renderer

#include "loom/renderer/deferred_pipeline.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace loom::renderer {
namespace {

template <class P>
Result<P*> add_pass(fg::FrameGraph& graph, std::unique_ptr<P> pass, std::vector<passes::ShaderPass*>& all) {
    P* raw = pass.get();
    auto id = graph.add_pass(std::unique_ptr<fg::Pass>(std::move(pass)));
    if (!id) return id.take_error();
    all.push_back(raw);
    return raw;
}

}  // namespace

DeferredPipeline::DeferredPipeline(rhi::Device& device, PipelineScene scene, PipelineSettings settings)
    : device_(device), scene_(std::move(scene)), settings_(std::move(settings)),
      library_(settings_.library ? settings_.library : std::make_shared<passes::ShaderLibrary>()),
      executor_(std::make_unique<fg::Executor>(device)) {}

DeferredPipeline::~DeferredPipeline() {
    // The executor's textures, then the passes' GPU objects (with the graph), then the scene's
    // objects and their meshes and textures.
    executor_.reset();
}

Result<std::unique_ptr<DeferredPipeline>> DeferredPipeline::create(rhi::Device& device, PipelineScene scene,
                                                                   const PipelineSettings& settings) {
    if (!scene.camera) return make_error(ErrorCode::InvalidArgument, "scene '" + scene.name + "' has no camera");
    std::unique_ptr<DeferredPipeline> pipeline(new DeferredPipeline(device, std::move(scene), settings));
    LOOM_TRY(pipeline->build());
    return pipeline;
}

Status DeferredPipeline::build() {
    passes::PassConfig config;
    config.library = library_;
    config.capturable = settings_.capture;

    auto shadow = add_pass(graph_, std::make_unique<passes::ShadowMapPass>(config, settings_.shadow_map_size), passes_);
    if (!shadow) return shadow.take_error();
    shadow_ = *shadow;
    if (!scene_.masked_shadow_casters.empty() || (scene_.retained && scene_.retained_masked_shadows)) {
        auto masked = add_pass(graph_, std::make_unique<renderer::MaskedShadowPass>(config), passes_);
        if (!masked) return masked.take_error();
        masked_shadow_ = *masked;
    }
    if (settings_.forward) {
        auto forward = add_pass(graph_, std::make_unique<passes::ForwardPass>(config), passes_);
        if (!forward) return forward.take_error();
        forward_ = *forward;
    } else {
        auto geometry = add_pass(graph_, std::make_unique<passes::GeometryPass>(config), passes_);
        if (!geometry) return geometry.take_error();
        geometry_ = *geometry;
        auto deferred = add_pass(graph_, std::make_unique<passes::DeferredPass>(config), passes_);
        if (!deferred) return deferred.take_error();
        deferred_ = *deferred;
    }
    if (!scene_.blended.empty() && settings_.transparent) {
        auto transparent = add_pass(graph_, std::make_unique<renderer::TransparentPass>(config), passes_);
        if (!transparent) return transparent.take_error();
        transparent_ = *transparent;
    }
    if (settings_.bloom) {
        auto blur_h = add_pass(graph_, std::make_unique<passes::BlurPass>(config, passes::BlurAxis::Horizontal, 1, "blur-h"),
                               passes_);
        if (!blur_h) return blur_h.take_error();
        blur_h_ = *blur_h;
        auto blur_v = add_pass(graph_, std::make_unique<passes::BlurPass>(config, passes::BlurAxis::Vertical, 1, "blur-v"),
                               passes_);
        if (!blur_v) return blur_v.take_error();
        blur_v_ = *blur_v;
    }
    auto composite = add_pass(graph_, std::make_unique<passes::CompositePass>(config), passes_);
    if (!composite) return composite.take_error();
    composite_ = *composite;
    fg::TextureSpec target = fg::TextureSpec::of(settings_.target_format).with_scale(1.0f);
    if (settings_.capture) target = target.with_usage(rhi::TextureUsage::CopySrc);
    auto present = add_pass(graph_, std::make_unique<passes::BlitPass>(config, target), passes_);
    if (!present) return present.take_error();
    present_ = *present;

    // Listing 6, connection for connection (and loom's emission map beside the paper's three),
    // then the blur's second half and the present pass.
    using fg::port;
    const std::string lit = settings_.forward ? "forward" : "deferred";
    // The shadow map's last writer: the masked shadow pass adds to the standard one's in place.
    std::string shadows = "shadow";
    if (masked_shadow_) {
        LOOM_TRY(graph_.connect(port("shadow", "shadow_map"), port(masked_shadow_->name(), "shadow_map")));
        shadows = masked_shadow_->name();
    }
    LOOM_TRY(graph_.connect(port(shadows, "shadow_map"), port(lit, "shadow_map")));
    if (!settings_.forward) {
        LOOM_TRY(graph_.connect(port("geometry", "position"), port("deferred", "position")));
        LOOM_TRY(graph_.connect(port("geometry", "normal"), port("deferred", "normal")));
        LOOM_TRY(graph_.connect(port("geometry", "albedo"), port("deferred", "albedo")));
        LOOM_TRY(graph_.connect(port("geometry", "emission"), port("deferred", "emission")));
    }
    // The transparent pass blends onto the lit pass's outputs in place; what follows reads its.
    std::string blended = lit;
    if (transparent_) {
        blended = transparent_->name();
        LOOM_TRY(graph_.connect(port(shadows, "shadow_map"), port(blended, "shadow_map")));
        LOOM_TRY(graph_.connect(port(lit, "color"), port(blended, "color")));
        LOOM_TRY(graph_.connect(port(lit, "high_pass"), port(blended, "high_pass")));
        LOOM_TRY(graph_.connect(port(settings_.forward ? "forward" : "geometry", "depth"), port(blended, "depth")));
    }
    LOOM_TRY(graph_.connect(port(blended, "color"), port("composite", "color")));
    if (settings_.bloom) {
        LOOM_TRY(graph_.connect(port(blended, "high_pass"), port("blur-h", "previous_pass")));
        LOOM_TRY(graph_.connect(port("blur-h", "color"), port("blur-v", "previous_pass")));
        LOOM_TRY(graph_.connect(port("blur-v", "color"), port("composite", "bloom")));
    } else {
        // The composite's program always samples a bloom texture: it gets the high pass, weighted 0.
        LOOM_TRY(graph_.connect(port(blended, "high_pass"), port("composite", "bloom")));
    }
    LOOM_TRY(graph_.connect(port("composite", "final"), port("present", "source")));
    LOOM_TRY(graph_.mark_output(port("present", "target")));

    // An sRGB target encodes by itself.
    composite_->set_encode_srgb(!rhi::format_info(settings_.target_format).features.srgb);
    composite_->set_exposure(settings_.exposure);
    set_bloom_strength(settings_.bloom_strength);
    if (deferred_) deferred_->set_threshold(settings_.threshold);
    if (forward_) forward_->set_threshold(settings_.threshold);
    if (transparent_) transparent_->set_threshold(settings_.threshold);
    for (passes::ShaderPass* pass : passes_) pass->set_capture(settings_.capture);

    // Objects: each registered with every pass that draws it (one program per pass and kind).
    passes::ShaderPass& lit_pass = geometry_ ? static_cast<passes::ShaderPass&>(*geometry_) : *forward_;
    for (const auto& object : scene_.shadow_casters) LOOM_TRY(passes::register_object(*shadow_, object));
    for (const auto& object : scene_.masked_shadow_casters) LOOM_TRY(passes::register_object(*masked_shadow_, object));
    for (const auto& object : scene_.opaque) LOOM_TRY(passes::register_object(lit_pass, object));
    if (scene_.retained) {
        LOOM_TRY(scene_.retained->attach(*shadow_));
        if (masked_shadow_) LOOM_TRY(scene_.retained->attach(*masked_shadow_));
        LOOM_TRY(scene_.retained->attach(lit_pass));
    }
    if (transparent_) {
        for (const BlendedObject& blended_object : scene_.blended) {
            if (blended_object.moving_bounds) {
                LOOM_TRY(transparent_->register_object(blended_object.object, blended_object.moving_bounds));
            } else {
                LOOM_TRY(transparent_->register_object(blended_object.object, blended_object.bounds));
            }
        }
    }
    return {};
}

void DeferredPipeline::drop_graph() {
    // The passes (and their pipelines) go with the graph; the executor's textures are the
    // executor's and outlive it.
    passes_.clear();
    shadow_ = nullptr;
    masked_shadow_ = nullptr;
    geometry_ = nullptr;
    deferred_ = nullptr;
    forward_ = nullptr;
    transparent_ = nullptr;
    blur_h_ = nullptr;
    blur_v_ = nullptr;
    composite_ = nullptr;
    present_ = nullptr;
    graph_ = fg::FrameGraph();
}

Status DeferredPipeline::rebuild(const PipelineSettings& settings) {
    drop_graph();
    settings_ = settings;
    if (settings_.library) {
        library_ = settings_.library;
    } else {
        settings_.library = library_;
    }
    Status built = build();
    if (!built) drop_graph();
    return built;
}

passes::SceneView DeferredPipeline::view(fg::Extent2D frame) const {
    const float aspect = static_cast<float>(frame.width) / static_cast<float>(frame.height);
    passes::SceneView view;
    view.camera = scene_.camera(aspect);
    view.light = scene_.light;
    view.environment = scene_.environment;
    view.shadow.light_view_projection = passes::fit_directional_shadow(scene_.light.direction, scene_.shadow_bounds);
    view.shadow.map_size = settings_.shadow_map_size;
    // About 1.5 shadow texels along the normal: enough against acne at grazing angles.
    const glm::vec3 extent = scene_.shadow_bounds.max - scene_.shadow_bounds.min;
    view.shadow.normal_offset = 1.5f * glm::length(extent) / static_cast<float>(settings_.shadow_map_size);
    view.shadow.depth_bias = 0.0005f;
    view.shadow.pcf_radius = 1;

    return view;
}

Status DeferredPipeline::prepare(fg::Extent2D frame) {
    if (!shadow_) return make_error(ErrorCode::InvalidState, "deferred pipeline: no graph (the last rebuild failed)");
    if (frame.width == 0 || frame.height == 0) {
        return make_error(ErrorCode::InvalidArgument, "deferred pipeline: empty frame size");
    }
    options_.frame = frame;
    options_.allocator = settings_.allocator;
    options_.order = settings_.order;

    const passes::SceneView view = this->view(frame);
    shadow_->set_light_view_projection(view.shadow.light_view_projection);
    if (masked_shadow_) masked_shadow_->set_light_view_projection(view.shadow.light_view_projection);
    if (geometry_) geometry_->set_camera(view.camera);
    if (deferred_) deferred_->set_view(view);
    if (forward_) forward_->set_view(view);
    if (transparent_) transparent_->set_view(view);
    const uint32_t radius = settings_.blur_radius.value_or(
        std::clamp<uint32_t>(static_cast<uint32_t>(std::lround(frame.height / 24.0)), 1u, passes::kMaxBlurRadius));
    if (blur_h_) LOOM_TRY(blur_h_->set_radius(radius));
    if (blur_v_) LOOM_TRY(blur_v_->set_radius(radius));
    return {};
}

Status DeferredPipeline::render(fg::Extent2D frame) {
    LOOM_TRY(prepare(frame));
    executor_->remove_import(fg::port("present", "target"));
    return executor_->run_frame(graph_, options_);
}

Status DeferredPipeline::record(rhi::CommandList& commands, rhi::TextureHandle target, fg::Extent2D frame,
                                rhi::ResourceState final_state) {
    LOOM_TRY(prepare(frame));
    executor_->import_texture(fg::port("present", "target"), target, final_state);
    return executor_->execute(graph_, commands, options_);
}

rhi::TextureHandle DeferredPipeline::final_texture() const { return executor_->texture("present", "target"); }

std::vector<Intermediate> DeferredPipeline::intermediates() const {
    std::vector<Intermediate> out;
    auto plan = executor_->plan();
    if (!plan) return out;
    for (const fg::PlanPass& planned : plan->order) {
        for (const passes::ShaderPass* pass : passes_) {
            if (pass->name() != planned.name) continue;
            for (const passes::CapturedTexture& captured : pass->captured()) {
                out.push_back(Intermediate{pass->name() + "." + captured.port, captured.texture});
            }
        }
    }
    return out;
}

}  // namespace loom::renderer

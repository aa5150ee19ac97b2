#include "loom/passes/forward_pass.hpp"

#include <vector>

#include "loom/passes/parts.hpp"
#include "uniforms.hpp"

namespace loom::passes {

/// The sky behind the objects: a program of its own, drawn full screen inside the forward
/// pass's render pass (never added to a graph).
class ForwardPass::Sky final : public ShaderPass {
public:
    Sky(const PassConfig& config, bool high_pass, const std::string& pass) : ShaderPass(pass + " sky", config.library) {
        add(fullscreen_part());
        add(sky_render_part());
        if (high_pass) add(high_pass_render_part(config));
    }
    Status draw(fg::PassContext& context, const PipelineState& state, const PassBinder& bind) {
        return draw_fullscreen(context, state, bind);
    }
    Status execute(fg::PassContext&) override { return {}; }
};

/// Mirrors SkyUniforms in shaders/include/loom/parts/sky_render.frag.glsl.
struct SkyUniforms {
    glm::vec4 viewport;
};

ForwardPass::ForwardPass(const PassConfig& config, LightingParts parts, std::string name)
    : ShaderPass(std::move(name), config.library), sky_(std::make_unique<Sky>(config, parts.high_pass, this->name())), parts_(parts) {
    add(camera_part());
    add(forward_render_part(config));
    if (parts_.shadows) add(shadow_render_part(config));
    if (parts_.high_pass) add(high_pass_render_part(config));
}

ForwardPass::~ForwardPass() = default;

void ForwardPass::release_gpu() {
    ShaderPass::release_gpu();
    sky_->release_gpu();
}

Status ForwardPass::execute(fg::PassContext& context) {
    std::vector<std::string> colors{"color"};
    if (parts_.high_pass) colors.emplace_back("high_pass");
    auto state = attachment_state(context, colors, "depth");
    if (!state) return state.take_error();
    state->depth = rhi::DepthState{true, true, rhi::CompareOp::Less};
    rhi::SamplerHandle comparison;
    if (parts_.shadows) {
        auto made = sampler(context.device(), shadow_comparison_sampler_desc());
        if (!made) return made.take_error();
        comparison = *made;
    }

    // The sky first, full screen, without depth: the objects cover it where they are drawn.
    std::vector<fg::ColorPort> ports{fg::ColorPort("color", {0.0, 0.0, 0.0, 1.0})};
    if (parts_.high_pass) ports.emplace_back("high_pass", std::array<double, 4>{0.0, 0.0, 0.0, 1.0});
    for (fg::ColorPort& port : ports) port.writes_every_texel = true;
    context.begin_render_pass(ports, fg::DepthPort("depth", 1.0f));
    PipelineState sky_state = *state;
    sky_state.depth = rhi::DepthState{false, false, rhi::CompareOp::Always};
    const fg::Extent2D size = context.extent("color");
    Status drawn = sky_->draw(context, sky_state, [&](Bindings& set) -> Status {
        set.uniforms("LightingUniforms", lighting_uniforms(view_))
            .uniforms("SkyUniforms", SkyUniforms{glm::vec4(static_cast<float>(size.width), static_cast<float>(size.height), 0, 0)});
        if (parts_.high_pass) set.uniforms("HighPassUniforms", HighPassUniforms{glm::vec4(threshold_, 0, 0, 0)});
        return set.status();
    });
    if (drawn) drawn = draw_objects(context, *state, [&](Bindings& set) -> Status {
        set.uniforms("CameraUniforms", camera_uniforms(view_.camera))
            .uniforms("LightingUniforms", lighting_uniforms(view_));
        if (parts_.shadows) {
            LOOM_TRY(detail::bind_shadow_receiver(set, view_.shadow, context.texture("shadow_map"),
                                                  context.extent("shadow_map").width, comparison));
        }
        if (parts_.high_pass) set.uniforms("HighPassUniforms", HighPassUniforms{glm::vec4(threshold_, 0, 0, 0)});
        return set.status();
    });
    context.end_render_pass();
    LOOM_TRY(drawn);
    return record_capture(context);
}

}  // namespace loom::passes

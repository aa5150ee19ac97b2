#include "loom/passes/forward_pass.hpp"

#include <vector>

#include "loom/passes/parts.hpp"
#include "uniforms.hpp"

namespace loom::passes {

ForwardPass::ForwardPass(const PassConfig& config, LightingParts parts, std::string name)
    : ShaderPass(std::move(name), config.library), parts_(parts) {
    add(camera_part());
    add(forward_render_part(config));
    if (parts_.shadows) add(shadow_render_part(config));
    if (parts_.high_pass) add(high_pass_render_part(config));
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

    // Where no object is drawn: the horizon colour, and nothing bright.
    const glm::vec3 background = view_.environment.horizon;
    std::vector<fg::ColorPort> ports{fg::ColorPort("color", {background.r, background.g, background.b, 1.0})};
    if (parts_.high_pass) ports.emplace_back("high_pass", std::array<double, 4>{0.0, 0.0, 0.0, 1.0});
    context.begin_render_pass(ports, fg::DepthPort("depth", 1.0f));
    Status drawn = draw_objects(context, *state, [&](Bindings& set) -> Status {
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

#include "loom/passes/deferred_pass.hpp"

#include <vector>

#include "loom/passes/parts.hpp"
#include "uniforms.hpp"

namespace loom::passes {

DeferredPass::DeferredPass(const PassConfig& config, LightingParts parts, std::string name)
    : ShaderPass(std::move(name), config.library), parts_(parts) {
    add_shader(fullscreen_part().shader);
    add(deferred_render_part(config));
    if (parts_.shadows) add(shadow_render_part(config));
    if (parts_.high_pass) add(high_pass_render_part(config));
}

Status DeferredPass::execute(fg::PassContext& context) {
    std::vector<std::string> colors{"color"};
    if (parts_.high_pass) colors.emplace_back("high_pass");
    auto state = attachment_state(context, colors);
    if (!state) return state.take_error();
    rhi::Device& device = context.device();
    auto nearest = nearest_sampler(device);
    if (!nearest) return nearest.take_error();
    rhi::SamplerHandle comparison;
    if (parts_.shadows) {
        auto made = sampler(device, shadow_comparison_sampler_desc());
        if (!made) return made.take_error();
        comparison = *made;
    }

    std::vector<fg::ColorPort> ports;
    for (const std::string& color : colors) {
        fg::ColorPort port(color);
        port.writes_every_texel = true;  // a full-screen triangle
        ports.push_back(std::move(port));
    }
    context.begin_render_pass(ports);
    Status drawn = draw_fullscreen(context, *state, [&](Bindings& set) -> Status {
        set.uniforms("LightingUniforms", lighting_uniforms(view_))
            .texture("gbuffer_position", context.texture("position"), *nearest)
            .texture("gbuffer_normal", context.texture("normal"), *nearest)
            .texture("gbuffer_albedo", context.texture("albedo"), *nearest)
            .texture("gbuffer_emission", context.texture("emission"), *nearest);
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

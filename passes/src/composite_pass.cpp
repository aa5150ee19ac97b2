#include "loom/passes/composite_pass.hpp"

#include "loom/passes/parts.hpp"
#include "uniforms.hpp"

namespace loom::passes {

CompositePass::CompositePass(const PassConfig& config, std::string name) : ShaderPass(std::move(name), config.library) {
    add_shader(fullscreen_part().shader);
    add(composite_part(config));
}

Status CompositePass::execute(fg::PassContext& context) {
    const std::string colors[] = {"final"};
    auto state = attachment_state(context, colors);
    if (!state) return state.take_error();
    auto nearest = nearest_sampler(context.device());
    if (!nearest) return nearest.take_error();

    fg::ColorPort port("final");
    port.writes_every_texel = true;
    context.begin_render_pass({port});
    Status drawn = draw_fullscreen(context, *state, [&](Bindings& set) {
        set.uniforms("CompositeUniforms",
                     detail::CompositeUniforms{glm::vec4(exposure_, bloom_strength_, encode_srgb_ ? 1.0f : 0.0f, 0.0f)})
            .texture("color", context.texture("color"), *nearest)
            .texture("bloom", context.texture("bloom"), *nearest);
        return set.status();
    });
    context.end_render_pass();
    LOOM_TRY(drawn);
    return record_capture(context);
}

}  // namespace loom::passes

#include "loom/passes/high_pass_pass.hpp"

#include "loom/passes/parts.hpp"
#include "uniforms.hpp"

namespace loom::passes {

HighPassPass::HighPassPass(const PassConfig& config, std::string name) : ShaderPass(std::move(name), config.library) {
    add_shader(fullscreen_part().shader);
    add(color_source_part(config));
    add(high_pass_render_part(config));
    // The high pass is this pass's only output.
    define("LOOM_HIGH_PASS_LOCATION", "0");
}

Status HighPassPass::execute(fg::PassContext& context) {
    const std::string colors[] = {"high_pass"};
    auto state = attachment_state(context, colors);
    if (!state) return state.take_error();
    auto nearest = nearest_sampler(context.device());
    if (!nearest) return nearest.take_error();

    fg::ColorPort port("high_pass");
    port.writes_every_texel = true;
    context.begin_render_pass({port});
    Status drawn = draw_fullscreen(context, *state, [&](Bindings& set) {
        set.texture("source", context.texture("source"), *nearest)
            .uniforms("HighPassUniforms", HighPassUniforms{glm::vec4(threshold_, 0.0f, 0.0f, 0.0f)});
        return set.status();
    });
    context.end_render_pass();
    LOOM_TRY(drawn);
    return record_capture(context);
}

}  // namespace loom::passes

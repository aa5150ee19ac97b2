#include "loom/passes/blit_pass.hpp"

#include "loom/passes/parts.hpp"

namespace loom::passes {

fg::TextureSpec default_blit_target() { return PartOptions{}.blit_target; }

BlitPass::BlitPass(const PassConfig& config, const fg::TextureSpec& target, std::string name)
    : ShaderPass(std::move(name), config.library) {
    add_shader(fullscreen_part().shader);
    add(blit_part(config, target));
}

Status BlitPass::execute(fg::PassContext& context) {
    const std::string colors[] = {"target"};
    auto state = attachment_state(context, colors);
    if (!state) return state.take_error();
    auto nearest = nearest_sampler(context.device());
    if (!nearest) return nearest.take_error();

    fg::ColorPort port("target");
    port.writes_every_texel = true;
    context.begin_render_pass({port});
    Status drawn = draw_fullscreen(context, *state, [&](Bindings& set) {
        set.texture("source", context.texture("source"), *nearest);
        return set.status();
    });
    context.end_render_pass();
    LOOM_TRY(drawn);
    return record_capture(context);
}

}  // namespace loom::passes

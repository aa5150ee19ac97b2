#include "loom/renderer/masked_shadow_pass.hpp"

#include "loom/passes/part_uniforms.hpp"
#include "loom/passes/parts.hpp"

namespace loom::renderer {

MaskedShadowPass::MaskedShadowPass(const passes::PassConfig& config, std::string name)
    : ShaderPass(std::move(name), config.library) {
    // The camera part, given the light's view: it places the vertices and interpolates the
    // surface for the material.
    add(passes::camera_part());
    // The shadow map in/out, of any size: the standard shadow pass decides it.
    add(passes::standard_part("masked-shadow-caster", {.config = config}));
}

Status MaskedShadowPass::execute(fg::PassContext& context) {
    auto state = attachment_state(context, {}, "shadow_map");
    if (!state) return state.take_error();
    state->depth = rhi::DepthState{true, true, rhi::CompareOp::Less};
    context.begin_depth_pass(fg::DepthPort("shadow_map", 1.0f));
    // The light is a direction: no position to shade from (the material needs none).
    const passes::CameraUniforms light{light_view_projection_, glm::vec4(0.0f)};
    Status drawn = draw_objects(context, *state, [&](passes::Bindings& set) {
        set.uniforms("CameraUniforms", light);
        return set.status();
    });
    context.end_render_pass();
    LOOM_TRY(drawn);
    return record_capture(context);
}

}  // namespace loom::renderer

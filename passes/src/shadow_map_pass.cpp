#include "loom/passes/shadow_map_pass.hpp"

#include "loom/passes/parts.hpp"
#include "uniforms.hpp"

namespace loom::passes {

ShadowMapPass::ShadowMapPass(const PassConfig& config, uint32_t map_size, std::string name)
    : ShaderPass(std::move(name), config.library), map_size_(map_size) {
    add(shadow_caster_part(config, map_size));
}

bool ShadowMapPass::uses_object_parts(rhi::ShaderStage stage) const { return stage == rhi::ShaderStage::Vertex; }

Status ShadowMapPass::execute(fg::PassContext& context) {
    auto state = attachment_state(context, {}, "shadow_map");
    if (!state) return state.take_error();
    state->depth = rhi::DepthState{true, true, rhi::CompareOp::Less};
    context.begin_depth_pass(fg::DepthPort("shadow_map", 1.0f));
    // The light's view is a per-pass set: uploaded only in frames where it changed.
    Status drawn = draw_objects(context, *state, [&](Bindings& set) {
        return pass_uniforms(set, "ShadowCasterUniforms", ShadowCasterUniforms{light_view_projection_});
    });
    context.end_render_pass();
    LOOM_TRY(drawn);
    return record_capture(context);
}

}  // namespace loom::passes

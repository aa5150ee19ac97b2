#include "loom/scene_objects/masked_shadow_pass.hpp"

#include "loom/passes/parts.hpp"

namespace loom::scene_objects {
namespace {

/// Mirrors ShadowCasterUniforms (masked_shadow_caster.vert.glsl).
struct ShadowCasterUniforms {
    glm::mat4 light_view_projection;
};
static_assert(sizeof(ShadowCasterUniforms) == 64);

passes::PassPart masked_shadow_caster_part(const passes::PassConfig& config) {
    passes::PassPart part("masked-shadow-caster", 1);
    // Any size: the standard shadow pass decides it.
    part.ports.inout("shadow_map", passes::depth_spec(config));
    part.shader.stage_file(rhi::ShaderStage::Vertex, "loom/parts/masked_shadow_caster.vert.glsl")
        .stage_file(rhi::ShaderStage::Fragment, "loom/parts/masked_shadow_caster.frag.glsl");
    return part;
}

}  // namespace

MaskedShadowPass::MaskedShadowPass(const passes::PassConfig& config, std::string name)
    : ShaderPass(std::move(name), config.library) {
    add(masked_shadow_caster_part(config));
}

Status MaskedShadowPass::execute(fg::PassContext& context) {
    auto state = attachment_state(context, {}, "shadow_map");
    if (!state) return state.take_error();
    state->depth = rhi::DepthState{true, true, rhi::CompareOp::Less};
    context.begin_depth_pass(fg::DepthPort("shadow_map", 1.0f));
    Status drawn = draw_objects(context, *state, [&](passes::Bindings& set) {
        set.uniforms("ShadowCasterUniforms", ShadowCasterUniforms{light_view_projection_});
        return set.status();
    });
    context.end_render_pass();
    LOOM_TRY(drawn);
    return record_capture(context);
}

}  // namespace loom::scene_objects

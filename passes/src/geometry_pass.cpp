#include "loom/passes/geometry_pass.hpp"

#include "loom/passes/parts.hpp"
#include "uniforms.hpp"

namespace loom::passes {

GeometryPass::GeometryPass(const PassConfig& config, std::string name) : ShaderPass(std::move(name), config.library) {
    add(camera_part());
    add(gbuffer_part(config));
}

Status GeometryPass::execute(fg::PassContext& context) {
    const std::string colors[] = {"position", "normal", "albedo", "emission"};
    auto state = attachment_state(context, colors, "depth");
    if (!state) return state.take_error();
    state->depth = rhi::DepthState{true, true, rhi::CompareOp::Less};
    // Zero normals mark texels nothing was drawn on (the deferred pass shows the sky there).
    context.begin_render_pass({{"position", {0.0, 0.0, 0.0, 0.0}},
                               {"normal", {0.0, 0.0, 0.0, 0.0}},
                               {"albedo", {0.0, 0.0, 0.0, 0.0}},
                               {"emission", {0.0, 0.0, 0.0, 0.0}}},
                              fg::DepthPort("depth", 1.0f));
    // The camera is a per-pass set: uploaded only in frames where it moved.
    Status drawn = draw_objects(context, *state, [&](Bindings& set) {
        return pass_uniforms(set, "CameraUniforms", camera_uniforms(camera_));
    });
    context.end_render_pass();
    LOOM_TRY(drawn);
    return record_capture(context);
}

}  // namespace loom::passes

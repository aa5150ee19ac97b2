#pragma once
// The masked shadow pass: adds the shadows of cut-out surfaces (glTF alphaMode MASK) to a
// shadow map the standard shadow-map pass drew. The standard pass uses only its objects' vertex
// parts, so a masked surface would cast the shadow of its whole quad; this pass is composed of
// the "camera" part, looking from the light, and "masked-shadow-caster", whose fragment stage
// runs the object's material, so what the material discards casts nothing. Only masked objects
// go here: opaque ones stay with the cheaper standard pass.
//
//   in/out shadow_map (the standard pass's output, drawn into in place)

#include <string>

#include <glm/glm.hpp>

#include "loom/passes/shader_pass.hpp"

namespace loom::renderer {

class MaskedShadowPass final : public passes::ShaderPass {
public:
    explicit MaskedShadowPass(const passes::PassConfig& config = {}, std::string name = "masked-shadow");

    /// World to the light's clip space: the standard shadow pass's (fit_directional_shadow).
    void set_light_view_projection(const glm::mat4& matrix) { light_view_projection_ = matrix; }

    Status execute(fg::PassContext& context) override;

private:
    glm::mat4 light_view_projection_{1.0f};
};

}  // namespace loom::renderer

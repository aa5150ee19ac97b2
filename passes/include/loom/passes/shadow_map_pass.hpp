#pragma once
// The shadow-map pass: draws its objects' depth as seen from the directional light into an
// absolute-size Depth32F map (port "shadow_map"). It uses only the objects' vertex parts: the
// material does not matter for depth, so the fragment stage is the pass's own.

#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "loom/passes/shader_pass.hpp"

namespace loom::passes {

class ShadowMapPass final : public ShaderPass {
public:
    explicit ShadowMapPass(const PassConfig& config = {}, uint32_t map_size = 2048, std::string name = "shadow");

    /// World to the light's clip space (see fit_directional_shadow).
    void set_light_view_projection(const glm::mat4& matrix) { light_view_projection_ = matrix; }
    [[nodiscard]] uint32_t map_size() const { return map_size_; }

    Status execute(fg::PassContext& context) override;

protected:
    [[nodiscard]] bool uses_object_parts(rhi::ShaderStage stage) const override;

private:
    uint32_t map_size_;
    glm::mat4 light_view_projection_{1.0f};
};

}  // namespace loom::passes

#pragma once
// C++ mirrors of the std140 uniform blocks only the standard passes' own shaders declare (blur,
// composite), and binding helpers. The blocks of the shared parts are public: part_uniforms.hpp.
// Sizes are checked against reflection whenever a block is bound (Bindings::uniforms).

#include <cstdint>

#include <glm/glm.hpp>

#include "loom/passes/part_uniforms.hpp"
#include "loom/passes/shader_pass.hpp"
#include "loom/passes/view.hpp"

namespace loom::passes::detail {

inline constexpr uint32_t kMaxBlurWeights = 64;

struct BlurUniforms {
    int32_t params[4];  // radius, direction x, direction y, unused
    float weights[kMaxBlurWeights];  // as vec4[16]: weight i at [i / 4][i % 4]
};

struct CompositeUniforms {
    glm::vec4 params;  // exposure, bloom strength, encode sRGB
};

static_assert(sizeof(BlurUniforms) == 272 && sizeof(CompositeUniforms) == 16);

/// Binds what the "shadow-render" part declares: ShadowUniforms and the shadow map with a
/// comparison sampler.
Status bind_shadow_receiver(Bindings& set, const ShadowSettings& settings, rhi::TextureHandle shadow_map,
                            uint32_t map_size, rhi::SamplerHandle comparison_sampler);

}  // namespace loom::passes::detail

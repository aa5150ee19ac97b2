// Pass part "high-pass-render" (fragment stage; the paper's Listing 5): splits the colours
// brighter than a threshold off into the high-pass output, for bloom. A colour of luminance l
// keeps the fraction max(l - threshold, 0) / l of itself, so hues survive.
#include "loom/common.glsl"

#ifndef LOOM_HIGH_PASS_LOCATION
#define LOOM_HIGH_PASS_LOCATION 1
#endif

layout(set = LOOM_SET, binding = LOOM_BINDING(0)) uniform HighPassUniforms {
    vec4 params;  // x: luminance threshold
} high_pass_params;

layout(location = LOOM_HIGH_PASS_LOCATION) out vec4 out_high_pass;

vec3 high_pass(vec3 color) {
    float l = luminance(color);
    return color * (max(l - high_pass_params.params.x, 0.0) / max(l, 1e-4));
}

void emit_high_pass(vec3 color) {
    out_high_pass = vec4(high_pass(color), 1.0);
}

// Pass part "composite" (fragment stage): adds the bloom to the colour, applies the exposure,
// maps HDR to [0, 1] with a filmic curve and encodes sRGB (gamma) for display.
#include "loom/passes/tonemap.glsl"

layout(set = LOOM_SET, binding = LOOM_BINDING(0)) uniform CompositeUniforms {
    vec4 params;  // x: exposure, y: bloom strength, z: 1 to encode sRGB, 0 to stay linear
} composite;
layout(set = LOOM_SET, binding = LOOM_BINDING(1)) uniform sampler2D color;
layout(set = LOOM_SET, binding = LOOM_BINDING(2)) uniform sampler2D bloom;

layout(location = 0) out vec4 out_color;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec3 hdr = texelFetch(color, texel, 0).rgb + texelFetch(bloom, texel, 0).rgb * composite.params.y;
    vec3 mapped = tonemap_aces(hdr * composite.params.x);
    out_color = vec4(composite.params.z > 0.5 ? linear_to_srgb(mapped) : mapped, 1.0);
}

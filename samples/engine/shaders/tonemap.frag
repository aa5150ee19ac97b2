#version 450
// Tone mapping: HDR colour plus bloom, exposed and mapped by an ACES filmic fit (Narkowicz
// 2015) into the display range; encoded to sRGB here when the target does not do it itself.
#include "engine/frame.glsl"

layout(set = 0, binding = 1) uniform sampler2D hdr;
layout(set = 0, binding = 2) uniform sampler2D bloom;

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 out_color;

vec3 aces(vec3 x) {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

void main() {
    vec3 color = texelFetch(hdr, ivec2(gl_FragCoord.xy), 0).rgb + texture(bloom, uv).rgb * frame.post.y;
    color = aces(color * frame.post.z);
    if (frame.post.w != 0.0) color = linear_to_srgb(color);
    out_color = vec4(color, 1.0);
}

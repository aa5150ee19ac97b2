#version 450
// Bloom, level 0 (half the frame): the HDR colour averaged over 2x2 pixels by one bilinear tap,
// keeping only what is brighter than the threshold (a soft knee, clamped against fireflies).
#include "engine/frame.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D hdr;
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D bloom;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(bloom);
    if (any(greaterThanEqual(p, size))) return;
    vec3 color = min(texture(hdr, (vec2(p) + 0.5) / vec2(size)).rgb, vec3(64.0));
    float brightness = max(color.r, max(color.g, color.b));
    float knee = frame.post.x * 0.5;
    float soft = clamp(brightness - frame.post.x + knee, 0.0, 2.0 * knee);
    soft = soft * soft / (4.0 * knee + 1e-4);
    float keep = max(soft, brightness - frame.post.x) / max(brightness, 1e-4);
    imageStore(bloom, p, vec4(color * keep, 1.0));
}

#version 450
// The SSAO blur: a 5x5 average weighted down across depth discontinuities, so occlusion does
// not bleed from one surface onto another. Async compute, after ssao.
#include "engine/frame.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D depth;
layout(set = 0, binding = 2) uniform sampler2D raw_occlusion;
layout(set = 0, binding = 3, r8) uniform writeonly image2D occlusion;

float view_depth(ivec2 p) {
    return -view_position(pixel_to_ndc(vec2(p) + 0.5), texelFetch(depth, p, 0).r).z;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(occlusion);
    if (any(greaterThanEqual(p, size))) return;
    float centre = view_depth(p);
    float sum = 0.0;
    float weights = 0.0;
    for (int y = -2; y <= 2; ++y) {
        for (int x = -2; x <= 2; ++x) {
            ivec2 q = clamp(p + ivec2(x, y), ivec2(0), size - 1);
            float w = 1.0 / (1.0 + 64.0 * abs(view_depth(q) - centre) / centre);
            sum += texelFetch(raw_occlusion, q, 0).r * w;
            weights += w;
        }
    }
    imageStore(occlusion, p, vec4(sum / weights));
}

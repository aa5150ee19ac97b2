#version 450
// Hierarchical Z, level 0: the depth buffer as (nearest, farthest) pairs.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D depth;
layout(set = 0, binding = 1, rg32f) uniform writeonly image2D hzb;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(hzb)))) return;
    float d = texelFetch(depth, p, 0).r;
    imageStore(hzb, p, vec4(d, d, 0.0, 0.0));
}

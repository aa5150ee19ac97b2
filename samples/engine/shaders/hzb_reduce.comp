#version 450
// Hierarchical Z, one level from the level above: each texel keeps the nearest and farthest
// depth of the texels it covers. Where the finer level is odd-sized, the last texel of a row or
// column also covers the one left over, so that every level covers the whole frame.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D finer;
layout(set = 0, binding = 1, rg32f) uniform writeonly image2D coarser;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(coarser);
    if (any(greaterThanEqual(p, size))) return;
    ivec2 finer_size = textureSize(finer, 0);
    ivec2 first = 2 * p;
    ivec2 last = 2 * p + 1 + ivec2(equal(p, size - 1)) * (finer_size & 1);
    last = min(last, finer_size - 1);
    vec2 range = vec2(1.0, 0.0);
    for (int y = first.y; y <= last.y; ++y) {
        for (int x = first.x; x <= last.x; ++x) {
            vec2 v = texelFetch(finer, ivec2(x, y), 0).rg;
            range = vec2(min(range.x, v.x), max(range.y, v.y));
        }
    }
    imageStore(coarser, p, vec4(range, 0.0, 0.0));
}

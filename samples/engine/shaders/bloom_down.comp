#version 450
// Bloom, one level down: four bilinear taps, a 4x4 box of the level above.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D finer;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D coarser;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(coarser);
    if (any(greaterThanEqual(p, size))) return;
    vec2 uv = (vec2(p) + 0.5) / vec2(size);
    vec2 texel = 1.0 / vec2(textureSize(finer, 0));
    vec3 sum = texture(finer, uv + vec2(-texel.x, -texel.y)).rgb + texture(finer, uv + vec2(texel.x, -texel.y)).rgb +
               texture(finer, uv + vec2(-texel.x, texel.y)).rgb + texture(finer, uv + vec2(texel.x, texel.y)).rgb;
    imageStore(coarser, p, vec4(sum * 0.25, 1.0));
}

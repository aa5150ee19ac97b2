#version 450
// Bloom, one level up, in place: each level adds the (bilinearly enlarged, 4-tap tent) level
// below it, so level 0 ends up holding the glow of every scale.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D coarser;
layout(set = 0, binding = 1, rgba16f) uniform image2D level;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(level);
    if (any(greaterThanEqual(p, size))) return;
    vec2 uv = (vec2(p) + 0.5) / vec2(size);
    vec2 texel = 0.5 / vec2(textureSize(coarser, 0));
    vec3 sum = texture(coarser, uv + vec2(-texel.x, -texel.y)).rgb + texture(coarser, uv + vec2(texel.x, -texel.y)).rgb +
               texture(coarser, uv + vec2(-texel.x, texel.y)).rgb + texture(coarser, uv + vec2(texel.x, texel.y)).rgb;
    imageStore(level, p, vec4(imageLoad(level, p).rgb + sum * 0.25, 1.0));
}

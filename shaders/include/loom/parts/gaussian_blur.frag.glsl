// Pass part "gaussian-blur" (fragment stage): one direction of a separable Gaussian blur.
// Taps are whole texels (texelFetch, edges clamped), weights come from the CPU
// (loom::passes::gaussian_weights), so the result is reproducible exactly.
layout(set = LOOM_SET, binding = LOOM_BINDING(0)) uniform BlurUniforms {
    ivec4 params;      // x: radius (taps on each side), y, z: direction (1, 0) or (0, 1)
    vec4 weights[16];  // weight of offset i is weights[i / 4][i % 4], i = 0..radius
} blur;
layout(set = LOOM_SET, binding = LOOM_BINDING(1)) uniform sampler2D source;

layout(location = 0) out vec4 out_color;

float blur_weight(int i) {
    return blur.weights[i / 4][i % 4];
}

void main() {
    ivec2 size = textureSize(source, 0);
    ivec2 texel = ivec2(gl_FragCoord.xy);
    ivec2 direction = blur.params.yz;
    vec4 sum = texelFetch(source, texel, 0) * blur_weight(0);
    for (int i = 1; i <= blur.params.x; ++i) {
        vec4 ahead = texelFetch(source, clamp(texel + direction * i, ivec2(0), size - 1), 0);
        vec4 behind = texelFetch(source, clamp(texel - direction * i, ivec2(0), size - 1), 0);
        sum += (ahead + behind) * blur_weight(i);
    }
    out_color = sum;
}

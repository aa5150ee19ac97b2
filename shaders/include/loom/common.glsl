// Helpers shared by loom's shaders: #include "loom/common.glsl".
#ifndef LOOM_COMMON_GLSL
#define LOOM_COMMON_GLSL

// dot(), normalize(), length(), reflect() and cross() of vec3s, with every sum written out in
// one fixed order without fused multiply-adds ("precise"). Mesa lowers the built-ins differently
// for GL (SPIRV-Cross's GLSL) and Vulkan (the SPIR-V): its dot product, for one, fuses its
// multiply-adds on one backend and not on the other, so the built-ins differ in the last bit
// between backends (in about 40 % of a frame's view rays). Through the specular highlight of a
// smooth surface one bit of n.h becomes several 8-bit levels, so lighting uses these.
float dot3(vec3 a, vec3 b) {
    precise float r = a.x * b.x;
    r += a.y * b.y;
    r += a.z * b.z;
    return r;
}

vec3 normalize3(vec3 v) {
    precise vec3 r = v * inversesqrt(dot3(v, v));
    return r;
}

float length3(vec3 v) {
    return sqrt(dot3(v, v));
}

// The reflection of the incident direction `i` about the unit normal `n` (as reflect()).
vec3 reflect3(vec3 i, vec3 n) {
    precise vec3 r = i - n * (2.0 * dot3(n, i));
    return r;
}

vec3 cross3(vec3 a, vec3 b) {
    precise vec3 p = vec3(a.y * b.z, a.z * b.x, a.x * b.y);
    precise vec3 q = vec3(a.z * b.y, a.x * b.z, a.y * b.x);
    precise vec3 r = p - q;
    return r;
}

// Rec. 709 relative luminance of a linear RGB colour.
float luminance(vec3 linear_rgb) {
    return dot3(linear_rgb, vec3(0.2126, 0.7152, 0.0722));
}

// The exact sRGB transfer functions (IEC 61966-2-1), per channel.
vec3 srgb_to_linear(vec3 srgb) {
    vec3 low = srgb / 12.92;
    vec3 high = pow((srgb + 0.055) / 1.055, vec3(2.4));
    return mix(high, low, lessThanEqual(srgb, vec3(0.04045)));
}

vec3 linear_to_srgb(vec3 linear_rgb) {
    vec3 low = linear_rgb * 12.92;
    vec3 high = 1.055 * pow(linear_rgb, vec3(1.0 / 2.4)) - 0.055;
    return mix(high, low, lessThanEqual(linear_rgb, vec3(0.0031308)));
}

// The i-th vertex (0..2) of a triangle that covers the whole viewport, in NDC (y up).
vec2 fullscreen_triangle_position(int vertex_index) {
    return vec2(vertex_index == 1 ? 3.0 : -1.0, vertex_index == 2 ? 3.0 : -1.0);
}

// Texture coordinates of an NDC position: (0,0) at the top-left of the framebuffer
// (NDC y = +1), (1,1) at the bottom-right, so a sampled texture appears unflipped.
vec2 ndc_to_uv(vec2 ndc) {
    return vec2(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5);
}

// m * vec4(p, 1) and m * vec4(v, 0), summed in one fixed order without fused multiply-adds
// ("precise"). GL compiles SPIRV-Cross's GLSL and Vulkan the SPIR-V, and their front ends lower
// a matrix product in different orders; written out like this both round alike, so positions,
// depths and rasterised coverage are the same bits on both backends.
vec4 transform_point(mat4 m, vec3 p) {
    precise vec4 r = m[0] * p.x;
    r += m[1] * p.y;
    r += m[2] * p.z;
    r += m[3];
    return r;
}

vec3 transform_vector(mat3 m, vec3 v) {
    precise vec3 r = m[0] * v.x;
    r += m[1] * v.y;
    r += m[2] * v.z;
    return r;
}

#endif

// Pass part "deferred-render" (fragment stage; the paper's Listing 3): lights the G-buffer.
// With the "shadow-render" part the light is shadowed; with "high-pass-render" the bright part
// of the result also goes to the high-pass output. Where the G-buffer is empty, the sky.
#include "loom/passes/lighting.glsl"
#include "loom/passes/gbuffer.glsl"

layout(set = LOOM_SET, binding = LOOM_BINDING(1)) uniform sampler2D gbuffer_position;
layout(set = LOOM_SET, binding = LOOM_BINDING(2)) uniform sampler2D gbuffer_normal;
layout(set = LOOM_SET, binding = LOOM_BINDING(3)) uniform sampler2D gbuffer_albedo;
layout(set = LOOM_SET, binding = LOOM_BINDING(4)) uniform sampler2D gbuffer_emission;

layout(location = 0) out vec4 out_color;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec4 position = texelFetch(gbuffer_position, texel, 0);
    vec4 normal = texelFetch(gbuffer_normal, texel, 0);
    vec4 albedo = texelFetch(gbuffer_albedo, texel, 0);
    vec4 emission = texelFetch(gbuffer_emission, texel, 0);
    vec3 color;
    if (dot3(normal.xyz, normal.xyz) < 0.25) {
        vec2 uv = gl_FragCoord.xy / vec2(textureSize(gbuffer_position, 0));  // (0,0) top-left
        color = sky_radiance(view_ray(uv));
    } else {
        float visibility = 1.0;
#ifdef LOOM_PART_SHADOW_RENDER
        visibility = shadow_visibility(position.xyz, normal.xyz);
#endif
        color = shade(position.xyz, normalize3(normal.xyz), unpack_material(position, normal, albedo, emission), visibility);
    }
    out_color = vec4(color, 1.0);
#ifdef LOOM_PART_HIGH_PASS_RENDER
    emit_high_pass(color);
#endif
}

// Lighting shared by the deferred and the forward pass: one directional light, hemisphere
// ambient light and a reflected sky, metallic-roughness (GGX) shading. Included from inside a
// pass part: its uniform block is that part's resource LOOM_BINDING(0).
#ifndef LOOM_PASSES_LIGHTING_GLSL
#define LOOM_PASSES_LIGHTING_GLSL

#include "loom/passes/interface.glsl"

layout(set = LOOM_SET, binding = LOOM_BINDING(0)) uniform LightingUniforms {
    mat4 inverse_view_projection;  // clip space back to world space (for the sky behind geometry)
    vec4 camera_position;          // xyz: world position of the eye
    vec4 light_direction;          // xyz: unit vector from a surface towards the light
    vec4 light_radiance;           // rgb: light colour times intensity
    vec4 sky_radiance;             // rgb: sky at the zenith (and ambient light from above)
    vec4 horizon_radiance;         // rgb: sky at the horizon
    vec4 ground_radiance;          // rgb: ambient light from below
    vec4 fog;                      // x: density per world unit (0: none), y: distance where it starts
} lighting;

const float kPi = 3.14159265358979;

// GGX / Trowbridge-Reitz normal distribution; alpha = roughness^2.
float ggx_distribution(float n_dot_h, float roughness) {
    float a = roughness * roughness;
    float a2 = a * a;
    precise float d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    precise float r = a2 / (kPi * d * d);
    return r;
}

// Smith's shadowing-masking with the Schlick-GGX approximation for direct light.
float smith_ggx(float n_dot_v, float n_dot_l, float roughness) {
    float k = (roughness + 1.0) * (roughness + 1.0) / 8.0;
    precise float gv = n_dot_v / (n_dot_v * (1.0 - k) + k);
    precise float gl = n_dot_l / (n_dot_l * (1.0 - k) + k);
    precise float r = gv * gl;
    return r;
}

vec3 fresnel_schlick(float cos_theta, vec3 f0) {
    float m = clamp(1.0 - cos_theta, 0.0, 1.0);
    float m2 = m * m;
    precise vec3 r = f0 + (1.0 - f0) * (m2 * m2 * m);
    return r;
}

// Schlick's Fresnel for ambient light, damped for rough surfaces.
vec3 fresnel_schlick_roughness(float cos_theta, vec3 f0, float roughness) {
    float m = clamp(1.0 - cos_theta, 0.0, 1.0);
    float m2 = m * m;
    precise vec3 r = f0 + (max(vec3(1.0 - roughness), f0) - f0) * (m2 * m2 * m);
    return r;
}

// The sky seen in `direction` (unit length): horizon to zenith above, darker towards the ground.
vec3 sky_radiance(vec3 direction) {
    float y = clamp(direction.y, -1.0, 1.0);
    // 1 - (1 - y)^3: starts at the horizon's colour (where the fog ends) and turns blue quickly.
    float up = 1.0 - y;
    precise vec3 r;
    if (y >= 0.0) {
        r = mix(lighting.horizon_radiance.rgb, lighting.sky_radiance.rgb, 1.0 - up * up * up);
    } else {
        r = mix(lighting.horizon_radiance.rgb, lighting.ground_radiance.rgb, min(-y * 4.0, 1.0));
    }
    return r;
}

// The world-space direction of the view ray through a point of the screen (uv (0,0) top-left).
vec3 view_ray(vec2 uv) {
    vec2 ndc = vec2(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0);
    vec4 far_point = transform_point(lighting.inverse_view_projection, vec3(ndc, 1.0));
    vec4 near_point = transform_point(lighting.inverse_view_projection, vec3(ndc, 0.0));
    return normalize3(far_point.xyz / far_point.w - near_point.xyz / near_point.w);
}

// Outgoing radiance towards the eye of a surface point lit by the directional light (scaled by
// `visibility`, 0 in full shadow), the ambient hemisphere and the reflected sky, plus emission.
vec3 shade(vec3 position, vec3 normal, MaterialSample m, float visibility) {
    vec3 n = normal;
    vec3 v = normalize3(lighting.camera_position.xyz - position);
    vec3 l = lighting.light_direction.xyz;
    vec3 h = normalize3(v + l);
    float n_dot_l = max(dot3(n, l), 0.0);
    float n_dot_v = max(dot3(n, v), 1e-4);
    float n_dot_h = max(dot3(n, h), 0.0);
    float v_dot_h = max(dot3(v, h), 0.0);
    float roughness = clamp(m.roughness, 0.05, 1.0);
    precise vec3 f0 = mix(vec3(0.04), m.albedo, m.metallic);

    vec3 f = fresnel_schlick(v_dot_h, f0);
    precise vec3 specular = ggx_distribution(n_dot_h, roughness) * smith_ggx(n_dot_v, n_dot_l, roughness) * f /
                    (4.0 * n_dot_v * max(n_dot_l, 1e-4));
    precise vec3 diffuse = (1.0 - f) * (1.0 - m.metallic) * m.albedo / kPi;
    precise vec3 direct = (diffuse + specular) * lighting.light_radiance.rgb * (n_dot_l * visibility);

    precise vec3 irradiance = mix(lighting.ground_radiance.rgb, lighting.sky_radiance.rgb, n.y * 0.5 + 0.5);
    precise vec3 reflected = mix(sky_radiance(reflect3(-v, n)), irradiance, roughness);
    vec3 fa = fresnel_schlick_roughness(n_dot_v, f0, roughness);
    // Reflections of the sky are dimmed where the sun is blocked: a cheap stand-in for occlusion.
    precise float occlusion = 0.6 + 0.4 * visibility;
    precise vec3 ambient = (1.0 - fa) * (1.0 - m.metallic) * m.albedo * irradiance + fa * reflected * occlusion;
    precise vec3 color = direct + ambient + m.emissive;

    // Aerial perspective: far surfaces fade into the horizon, so the ground has no visible edge.
    precise float haze = max(length3(lighting.camera_position.xyz - position) - lighting.fog.y, 0.0) * lighting.fog.x;
    precise float fog = 1.0 - exp(-haze * haze);
    precise vec3 result = mix(color, lighting.horizon_radiance.rgb, fog);
    return result;
}

#endif

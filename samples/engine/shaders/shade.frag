#version 450
// Forward+ shading: the glTF metallic-roughness material lit by the sun (through the shadow
// cascades), by the point lights of this pixel's tile in the light list, and by the sky and
// ground, the ambient part darkened by SSAO. Runs with depth test EQUAL on the prepass depth,
// so each pixel is shaded once.
#include "engine/frame.glsl"
#include "engine/draw.glsl"

layout(set = 0, binding = 1) uniform sampler2DArray shadow_cascades;
layout(set = 0, binding = 2) uniform sampler2D ambient_occlusion;
layout(set = 0, binding = 3, std430) readonly buffer Lights { PointLight lights[]; };
layout(set = 0, binding = 4, std430) readonly buffer LightList { uint light_list[]; };

layout(set = 1, binding = 1) uniform sampler2D base_color_map;
layout(set = 1, binding = 2) uniform sampler2D metallic_roughness_map;
layout(set = 1, binding = 3) uniform sampler2D normal_map;
layout(set = 1, binding = 4) uniform sampler2D occlusion_map;
layout(set = 1, binding = 5) uniform sampler2D emissive_map;

layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;
layout(location = 2) in vec4 world_tangent;
layout(location = 3) in vec2 uv0;
layout(location = 4) in vec2 uv1;
layout(location = 5) in vec4 vertex_color;

layout(location = 0) out vec4 out_color;

const float kPi = 3.14159265;

// GGX / Trowbridge-Reitz normal distribution, Smith-Schlick visibility and Schlick's Fresnel.
vec3 brdf(vec3 n, vec3 v, vec3 l, vec3 diffuse_color, vec3 f0, float roughness) {
    vec3 h = normalize(v + l);
    float n_l = max(dot(n, l), 0.0);
    float n_v = max(dot(n, v), 1e-4);
    float n_h = max(dot(n, h), 0.0);
    float v_h = max(dot(v, h), 0.0);
    float a = roughness * roughness;
    float a2 = a * a;
    float d = n_h * n_h * (a2 - 1.0) + 1.0;
    float distribution = a2 / (kPi * d * d);
    float k = (roughness + 1.0) * (roughness + 1.0) / 8.0;
    float visibility = 1.0 / ((n_l * (1.0 - k) + k) * (n_v * (1.0 - k) + k) * 4.0);
    vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - v_h, 5.0);
    return ((1.0 - fresnel) * diffuse_color / kPi + fresnel * distribution * visibility) * n_l;
}

// 1 where the sun reaches `p`, 0 in shadow: 3x3 depth comparisons in the cascade that covers
// the point's view distance (texel fetches, so both APIs compare the same texels).
float sun_visibility(vec3 p, vec3 n) {
    float distance = -transform_point(frame.view, p).z;
    int cascade = kCascades;
    for (int i = kCascades - 1; i >= 0; --i) {
        if (distance < frame.cascade_far[i]) cascade = i;
    }
    if (cascade == kCascades) return 1.0;
    // Normal offset: a texel of this cascade along the normal keeps surfaces out of their own shadow.
    float texel = frame.cascade_texel[cascade];
    vec4 clip = transform_point(frame.cascade_view_projection[cascade], p + n * texel * 1.5);
    vec3 ndc = clip.xyz / clip.w;
    vec2 uv = vec2(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5);
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 1.0;
    ivec2 size = textureSize(shadow_cascades, 0).xy;
    ivec2 centre = ivec2(uv * vec2(size));
    float lit = 0.0;
    for (int y = -1; y <= 1; ++y) {
        for (int x = -1; x <= 1; ++x) {
            ivec2 t = clamp(centre + ivec2(x, y), ivec2(0), size - 1);
            float occluder = texelFetch(shadow_cascades, ivec3(t, cascade), 0).r;
            lit += ndc.z - 0.0005 <= occluder ? 1.0 : 0.0;
        }
    }
    return lit / 9.0;
}

void main() {
    vec4 base = draw.base_color * vertex_color;
    if ((draw.textures.y & kBaseColorTexture) != 0) base *= texture(base_color_map, pick_uv(draw.uv_sets.x, uv0, uv1));
    float metallic = draw.factors.x;
    float roughness = draw.factors.y;
    if ((draw.textures.y & kMetallicRoughnessTexture) != 0) {
        vec4 mr = texture(metallic_roughness_map, pick_uv(draw.uv_sets.y, uv0, uv1));
        roughness *= mr.g;
        metallic *= mr.b;
    }
    roughness = clamp(roughness, 0.04, 1.0);
    metallic = clamp(metallic, 0.0, 1.0);

    vec3 v = normalize(frame.camera_position.xyz - world_position);
    vec3 n = normalize(world_normal);
    if (!gl_FrontFacing) n = -n;
    if ((draw.textures.y & kNormalTexture) != 0) {
        vec3 t = normalize(world_tangent.xyz - n * dot(n, world_tangent.xyz));
        vec3 b = cross(n, t) * world_tangent.w;
        vec3 m = texture(normal_map, pick_uv(draw.uv_sets.z, uv0, uv1)).xyz * 2.0 - 1.0;
        m.xy *= draw.factors.z;
        n = normalize(t * m.x + b * m.y + n * m.z);
    }
    float occlusion = 1.0;
    if ((draw.textures.y & kOcclusionTexture) != 0) {
        occlusion = 1.0 + draw.factors.w * (texture(occlusion_map, pick_uv(draw.uv_sets.w, uv0, uv1)).r - 1.0);
    }
    vec3 emissive = draw.emissive.rgb;
    if ((draw.textures.y & kEmissiveTexture) != 0) emissive *= texture(emissive_map, pick_uv(draw.textures.x, uv0, uv1)).rgb;

    vec3 diffuse_color = base.rgb * (1.0 - metallic);
    vec3 f0 = mix(vec3(0.04), base.rgb, metallic);

    vec3 color = brdf(n, v, frame.sun_direction.xyz, diffuse_color, f0, roughness) * frame.sun_color.rgb *
                 sun_visibility(world_position, normalize(world_normal));

    ivec2 pixel = ivec2(gl_FragCoord.xy);
    ivec2 tile = pixel / kTileSize;
    uint first = (uint(tile.y) * frame.tiles.x + uint(tile.x)) * kTileStride;
    uint count = min(light_list[first], kMaxTileLights);
    for (uint i = 0u; i < count; ++i) {
        PointLight light = lights[light_list[first + 1u + i]];
        vec3 to_light = light.position_radius.xyz - world_position;
        float d2 = dot(to_light, to_light);
        float r = light.position_radius.w;
        float window = clamp(1.0 - (d2 * d2) / (r * r * r * r), 0.0, 1.0);
        float falloff = window * window / (d2 + 0.01);
        color += brdf(n, v, to_light * inversesqrt(d2), diffuse_color, f0, roughness) * light.color.rgb * falloff;
    }

    float ao = texelFetch(ambient_occlusion, pixel, 0).r;
    // Ambient: the hemisphere around the normal lights the diffuse part, the sky in the mirror
    // direction (blurred towards the horizon colour by roughness) the specular part.
    vec3 hemisphere = mix(frame.ground_color.rgb, frame.sky_horizon.rgb, clamp(n.y * 0.5 + 0.5, 0.0, 1.0));
    vec3 r = reflect(-v, n);
    vec3 mirrored = r.y >= 0.0 ? mix(frame.sky_horizon.rgb, frame.sky_zenith.rgb, sqrt(r.y)) : frame.ground_color.rgb;
    mirrored = mix(mirrored, hemisphere, roughness);
    vec3 fresnel = f0 + (max(vec3(1.0 - roughness), f0) - f0) * pow(1.0 - max(dot(n, v), 0.0), 5.0);
    color += (hemisphere * diffuse_color + mirrored * fresnel) * frame.lighting.x * ao * occlusion;
    color += emissive;
    out_color = vec4(color, 1.0);
}

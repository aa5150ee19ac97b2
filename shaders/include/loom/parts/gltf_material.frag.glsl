// Object part "gltf-material" (fragment stage): the glTF 2.0 metallic-roughness material —
// base colour (factor × sRGB texture × vertex colour), metallic-roughness (B, G), tangent-space
// normal map (with its scale), occlusion (R, with its strength), emissive (factor × sRGB
// texture), each texture on its own UV set and sampler — and the alpha modes: MASK discards
// below the cutoff, BLEND hands its alpha to the pass through object_alpha().
//
// The standard passes' contract (loom/passes/interface.glsl) has no place for what glTF needs
// besides a MaterialSample: a shading normal other than the interpolated one, an alpha, an
// occlusion term. So that glTF objects still compose with the standard geometry, forward and
// shadow passes as they are:
// - the normal: the material function takes the surface `inout` and replaces its normal (normal
//   map, back faces of double-sided surfaces turned towards the viewer); the macro at the end
//   makes the passes' `object_material(s)` call it. Every standard pass shades with `s` after
//   that call, so the G-buffer and the forward pass both see the new normal.
// - the alpha: object_alpha() after object_material() (the transparent pass reads it).
// - occlusion darkens the albedo: the G-buffer has no channel for it, so the ambient term and
//   the sun alike are dimmed where the map says (glTF asks for the ambient term only).
layout(set = LOOM_SET, binding = LOOM_BINDING(0)) uniform sampler2D gltf_base_color;
layout(set = LOOM_SET, binding = LOOM_BINDING(1)) uniform sampler2D gltf_metallic_roughness;
layout(set = LOOM_SET, binding = LOOM_BINDING(2)) uniform sampler2D gltf_normal;
layout(set = LOOM_SET, binding = LOOM_BINDING(3)) uniform sampler2D gltf_occlusion;
layout(set = LOOM_SET, binding = LOOM_BINDING(4)) uniform sampler2D gltf_emissive;

#ifdef LOOM_PART_CAMERA
layout(location = 6) in vec4 v_gltf_tangent;
layout(location = 7) in vec2 v_gltf_uv1;
#endif

float gltf_alpha = 1.0;

vec2 gltf_uv(SurfaceInput surface, int uv_set) {
#ifdef LOOM_PART_CAMERA
    if (uv_set == 1) return v_gltf_uv1;
#endif
    return surface.uv;
}

// The coordinates texture `index` (kGltf*Index) samples: its UV set, moved by its transform.
vec2 gltf_texture_uv(SurfaceInput surface, int index, int uv_set) {
    vec3 uv = vec3(gltf_uv(surface, uv_set), 1.0);
    return vec2(dot3(gltf.uv_transform[2 * index].xyz, uv), dot3(gltf.uv_transform[2 * index + 1].xyz, uv));
}

bool gltf_has(int texture_bit) {
    return (gltf.textures.y & texture_bit) != 0;
}

// The normal map's normal in world space, from the interpolated normal and tangent frame.
vec3 gltf_mapped_normal(vec3 n, vec3 map_value) {
#ifdef LOOM_PART_CAMERA
    vec3 t = v_gltf_tangent.xyz - n * dot3(n, v_gltf_tangent.xyz);
    if (dot3(t, t) < 1e-12) return n;  // no usable tangent: keep the surface normal
    t = normalize3(t);
    vec3 b = cross3(n, t) * (v_gltf_tangent.w < 0.0 ? -1.0 : 1.0);
    vec3 tangent_space = map_value * 2.0 - 1.0;
    tangent_space.xy *= gltf.factors.z;
    vec3 mapped = t * tangent_space.x + b * tangent_space.y + n * tangent_space.z;
    return dot3(mapped, mapped) > 1e-12 ? normalize3(mapped) : n;
#else
    return n;
#endif
}

MaterialSample gltf_object_material(inout SurfaceInput surface) {
    // Every texture is sampled before the mask's discard, in uniform control flow (the bits are
    // uniforms), so that implicit derivatives stay defined.
    vec4 base = gltf.base_color_factor * surface.color;
    if (gltf_has(kGltfBaseColor)) base *= texture(gltf_base_color, gltf_texture_uv(surface, kGltfBaseColorIndex, gltf.uv_sets.x));
    float metallic = gltf.factors.x;
    float roughness = gltf.factors.y;
    if (gltf_has(kGltfMetallicRoughness)) {
        vec4 mr = texture(gltf_metallic_roughness, gltf_texture_uv(surface, kGltfMetallicRoughnessIndex, gltf.uv_sets.y));
        roughness *= mr.g;
        metallic *= mr.b;
    }
    vec3 n = surface.world_normal;
    if (gltf_has(kGltfNormal)) n = gltf_mapped_normal(n, texture(gltf_normal, gltf_texture_uv(surface, kGltfNormalIndex, gltf.uv_sets.z)).xyz);
    float occlusion = 1.0;
    if (gltf_has(kGltfOcclusion)) {
        occlusion = 1.0 + gltf.factors.w * (texture(gltf_occlusion, gltf_texture_uv(surface, kGltfOcclusionIndex, gltf.uv_sets.w)).r - 1.0);
    }
    vec3 emissive = gltf.emissive_factor.rgb;
    if (gltf_has(kGltfEmissive)) emissive *= texture(gltf_emissive, gltf_texture_uv(surface, kGltfEmissiveIndex, gltf.textures.x)).rgb;

    gltf_alpha = 1.0;
    if (gltf.alpha.x == kGltfAlphaMask) {
        if (base.a < gltf.alpha.y) discard;
    } else if (gltf.alpha.x == kGltfAlphaBlend) {
        gltf_alpha = clamp(base.a, 0.0, 1.0);
    }

    // Back faces (drawn only for double-sided materials) are lit from the side they show.
    surface.world_normal = gl_FrontFacing ? n : -n;
    MaterialSample m;
    m.albedo = base.rgb * occlusion;
    m.metallic = clamp(metallic, 0.0, 1.0);
    m.roughness = clamp(roughness, 0.0, 1.0);
    m.emissive = emissive;
    return m;
}

// The alpha of the surface the latest object_material() call evaluated (1 unless BLEND).
float object_alpha() {
    return gltf_alpha;
}

#define object_material gltf_object_material

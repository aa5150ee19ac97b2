// Pass part "shadow-render" (fragment stage; the paper's Listing 4): how much of the
// directional light reaches a point, from a depth map rendered from the light. Percentage-closer
// filtering over (2r+1)^2 comparison taps, each bilinear in hardware.
layout(set = LOOM_SET, binding = LOOM_BINDING(0)) uniform ShadowUniforms {
    mat4 light_view_projection;  // world to the light's clip space (as the shadow map was drawn)
    vec4 params;                 // x: 1 / shadow map size, y: normal offset (world units),
                                 // z: depth bias, w: PCF radius r in texels
} shadow;
layout(set = LOOM_SET, binding = LOOM_BINDING(1)) uniform sampler2DShadow shadow_map;

float shadow_visibility(vec3 world_position, vec3 world_normal) {
    vec3 p = world_position + world_normal * shadow.params.y;
    vec4 clip = transform_point(shadow.light_view_projection, p);
    vec3 ndc = clip.xyz / clip.w;
    vec2 uv = ndc_to_uv(ndc.xy);
    float depth = ndc.z - shadow.params.z;
    if (uv.x < 0.0 || uv.y < 0.0 || uv.x > 1.0 || uv.y > 1.0 || depth >= 1.0) return 1.0;
    int r = int(shadow.params.w);
    float lit = 0.0;
    for (int y = -r; y <= r; ++y) {
        for (int x = -r; x <= r; ++x) {
            lit += texture(shadow_map, vec3(uv + vec2(x, y) * shadow.params.x, depth));
        }
    }
    return lit / float((2 * r + 1) * (2 * r + 1));
}

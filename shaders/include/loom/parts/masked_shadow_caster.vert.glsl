// Pass part "masked-shadow-caster" (vertex stage): the object's vertex seen from the light, as
// "shadow-caster" places it, and the surface attributes the object's material needs to decide
// its coverage (the varyings of the "camera" part, at the same locations).
layout(set = LOOM_SET, binding = LOOM_BINDING(0)) uniform ShadowCasterUniforms {
    mat4 light_view_projection;  // world to the light's clip space
} caster;

layout(location = 0) out vec3 v_world_position;
layout(location = 1) out vec3 v_world_normal;
layout(location = 2) out vec2 v_uv;
layout(location = 3) out vec4 v_color;

void main() {
    ObjectVertex v = object_vertex();
    v_world_position = v.world_position;
    v_world_normal = v.world_normal;
    v_uv = v.uv;
    v_color = v.color;
    gl_Position = transform_point(caster.light_view_projection, v.world_position);
}

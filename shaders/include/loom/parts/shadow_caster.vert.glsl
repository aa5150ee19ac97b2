// Pass part "shadow-caster" (vertex stage): the object's vertex seen from the light.
layout(set = LOOM_SET, binding = LOOM_BINDING(0)) uniform ShadowCasterUniforms {
    mat4 light_view_projection;  // world to the light's clip space
} caster;

void main() {
    ObjectVertex v = object_vertex();
    gl_Position = transform_point(caster.light_view_projection, v.world_position);
}

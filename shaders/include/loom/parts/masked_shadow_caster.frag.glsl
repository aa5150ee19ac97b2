// Pass part "masked-shadow-caster" (fragment stage): depth only, but the object's material runs
// first, so that what its alpha mode discards (glTF MASK below the cutoff) casts no shadow.
layout(location = 0) in vec3 v_world_position;
layout(location = 1) in vec3 v_world_normal;
layout(location = 2) in vec2 v_uv;
layout(location = 3) in vec4 v_color;

void main() {
    SurfaceInput s;
    s.world_position = v_world_position;
    s.world_normal = normalize(v_world_normal);
    s.uv = v_uv;
    s.color = v_color;
    object_material(s);
}

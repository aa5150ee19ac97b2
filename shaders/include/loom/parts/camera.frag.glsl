// Pass part "camera" (fragment stage): the interpolated surface attributes.
layout(location = 0) in vec3 v_world_position;
layout(location = 1) in vec3 v_world_normal;
layout(location = 2) in vec2 v_uv;
layout(location = 3) in vec4 v_color;

// The surface point of this fragment. Objects are drawn with back faces culled, so the
// interpolated normal faces the viewer.
SurfaceInput surface_input() {
    SurfaceInput s;
    s.world_position = v_world_position;
    s.world_normal = normalize3(v_world_normal);
    s.uv = v_uv;
    s.color = v_color;
    return s;
}

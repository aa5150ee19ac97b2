// Pass part "camera" (vertex stage): places the object's world-space vertex in front of the
// camera and hands the surface attributes to the fragment stage.
layout(set = LOOM_SET, binding = LOOM_BINDING(0)) uniform CameraUniforms {
    mat4 view_projection;  // world to clip space
    vec4 camera_position;  // xyz: world position of the eye
} camera;

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
    gl_Position = transform_point(camera.view_projection, v.world_position);
}

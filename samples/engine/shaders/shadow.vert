#version 450
// One shadow cascade: the scene from the sun, into one layer of the cascade array.
#include "engine/frame.glsl"

layout(location = 0) in vec3 in_position;

layout(push_constant) uniform Caster {
    mat4 model;
    ivec4 cascade;  // x: which cascade
} caster;

void main() {
    gl_Position = transform_point(frame.cascade_view_projection[caster.cascade.x], transform_point(caster.model, in_position).xyz);
}

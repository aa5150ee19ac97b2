// Included by uses_include.frag (through an include directory); it includes a sibling.
#include "scale.glsl"

vec3 tint(vec3 c) {
    return c * vec3(1.0, 0.5, 0.25) * kScale;
}

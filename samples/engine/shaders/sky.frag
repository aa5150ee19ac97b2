#version 450
// The sky behind the scene: a gradient from the horizon to the zenith, the ground colour
// below, and the sun's disc (bright enough to bloom).
#include "engine/frame.glsl"

layout(location = 0) in vec2 ndc;
layout(location = 0) out vec4 out_color;

void main() {
    vec4 far_point = transform_point(frame.inverse_view_projection, vec3(ndc, 1.0));
    vec3 direction = normalize(far_point.xyz / far_point.w - frame.camera_position.xyz);
    float up = direction.y;
    vec3 color = up >= 0.0 ? mix(frame.sky_horizon.rgb, frame.sky_zenith.rgb, sqrt(up))
                           : mix(frame.sky_horizon.rgb, frame.ground_color.rgb, min(-up * 4.0, 1.0));
    float sun = dot(direction, frame.sun_direction.xyz);
    if (sun > 0.9995) color += frame.sun_color.rgb * 4.0;
    out_color = vec4(color, 1.0);
}

// What every pass of loom-engine's frame reads: the camera, the sun and its shadow cascades,
// the sky, the tile grid of the light list and the frame's tuning values. Mirrors
// FrameUniforms in samples/engine/engine_frame.cpp (std140).
#ifndef ENGINE_FRAME_GLSL
#define ENGINE_FRAME_GLSL

#include "loom/common.glsl"

// Pixels per side of a light-list tile, and uints per tile in the light list (a count, then
// up to kMaxTileLights light indices). Mirrored by kTileSize / kTileStride in engine_frame.hpp.
const int kTileSize = 16;
const uint kTileStride = 64u;
const uint kMaxTileLights = kTileStride - 1u;
const int kCascades = 4;

layout(set = 0, binding = 0, std140) uniform Frame {
    mat4 view;
    mat4 projection;
    mat4 view_projection;
    mat4 inverse_projection;
    mat4 inverse_view_projection;
    mat4 cascade_view_projection[kCascades];
    vec4 cascade_far;       // view-space distance where cascade i ends
    vec4 cascade_texel;     // world size of one texel of cascade i
    vec4 camera_position;   // xyz
    vec4 sun_direction;     // xyz: unit vector towards the sun
    vec4 sun_color;         // linear rgb radiance
    vec4 sky_zenith;        // rgb
    vec4 sky_horizon;       // rgb
    vec4 ground_color;      // rgb: what the lower hemisphere reflects
    vec4 screen;            // width, height, 1 / width, 1 / height
    uvec4 tiles;            // tiles across, tiles down, light count, 0
    vec4 lighting;          // ambient strength, SSAO radius (world units), SSAO strength, 0
    vec4 post;              // bloom threshold, bloom strength, exposure, 1 when the target does not encode sRGB itself
} frame;

// One point light as the light buffer stores it (std430).
struct PointLight {
    vec4 position_radius;   // world position, radius of influence
    vec4 color;             // linear rgb (intensity included), 0
};

// NDC (y up) of the centre of pixel p (row 0 at the top).
vec2 pixel_to_ndc(vec2 p) {
    return vec2(p.x * frame.screen.z * 2.0 - 1.0, 1.0 - p.y * frame.screen.w * 2.0);
}

// View-space position of depth-buffer value `depth` at NDC `ndc`.
vec3 view_position(vec2 ndc, float depth) {
    vec4 v = transform_point(frame.inverse_projection, vec3(ndc, depth));
    return v.xyz / v.w;
}

#endif

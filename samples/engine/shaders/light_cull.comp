#version 450
// The light list: for each 16x16-pixel tile, the point lights whose sphere of influence meets
// the tile's view-space box between its nearest and farthest depth (read from the hierarchical
// Z level of the tile size). One invocation per tile walks the lights in order, so the list,
// and the sum the shading pass makes of it, is the same on every run and API.
#include "engine/frame.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D hzb_tiles;
layout(set = 0, binding = 2, std430) readonly buffer Lights { PointLight lights[]; };
layout(set = 0, binding = 3, std430) writeonly buffer LightList { uint light_list[]; };

void main() {
    uvec2 tile = gl_GlobalInvocationID.xy;
    if (tile.x >= frame.tiles.x || tile.y >= frame.tiles.y) return;
    uint first = (tile.y * frame.tiles.x + tile.x) * kTileStride;
    ivec2 hzb_size = textureSize(hzb_tiles, 0);
    vec2 depth_range = texelFetch(hzb_tiles, min(ivec2(tile), hzb_size - 1), 0).rg;
    uint count = 0u;
    if (depth_range.x < 1.0) {
        vec2 corner0 = pixel_to_ndc(vec2(tile) * float(kTileSize));
        vec2 corner1 = pixel_to_ndc(min(vec2(tile + 1u) * float(kTileSize), frame.screen.xy));
        vec3 lo = vec3(1e30);
        vec3 hi = vec3(-1e30);
        for (int i = 0; i < 8; ++i) {
            vec2 ndc = vec2((i & 1) == 0 ? corner0.x : corner1.x, (i & 2) == 0 ? corner0.y : corner1.y);
            vec3 v = view_position(ndc, (i & 4) == 0 ? depth_range.x : depth_range.y);
            lo = min(lo, v);
            hi = max(hi, v);
        }
        for (uint i = 0u; i < frame.tiles.z && count < kMaxTileLights; ++i) {
            vec4 light = lights[i].position_radius;
            vec3 centre = transform_point(frame.view, light.xyz).xyz;
            vec3 d = centre - clamp(centre, lo, hi);
            if (dot(d, d) <= light.w * light.w) {
                light_list[first + 1u + count] = i;
                ++count;
            }
        }
    }
    light_list[first] = count;
}

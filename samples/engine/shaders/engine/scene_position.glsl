// The clip position of a scene vertex, computed the same way by the depth prepass and by the
// shading pass, with transform_point (loom/common.glsl: one summation order, no fused
// multiply-adds), so that both programs and both APIs get the same bits and shading's EQUAL
// depth test meets the prepass depth exactly.
#ifndef ENGINE_SCENE_POSITION_GLSL
#define ENGINE_SCENE_POSITION_GLSL

#include "engine/frame.glsl"
#include "engine/draw.glsl"

vec4 scene_clip_position(vec3 position, out vec3 world_position) {
    world_position = transform_point(draw.model, position).xyz;
    return transform_point(frame.view_projection, world_position);
}

#endif

#version 450
// Screen-space ambient occlusion from the depth buffer alone: view-space positions and normals
// reconstructed from depth, 8 directions x 2 steps around each pixel, occlusion by the
// neighbours above the surface within a world-space radius. Runs on the async compute queue,
// beside the shadow cascades. A 4-pixel pattern varies the step lengths; the blur evens it out.
#include "engine/frame.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D depth;
layout(set = 0, binding = 2, r8) uniform writeonly image2D occlusion;

const vec2 kDirections[8] = vec2[](vec2(1.0, 0.0), vec2(0.7071, 0.7071), vec2(0.0, 1.0), vec2(-0.7071, 0.7071),
                                   vec2(-1.0, 0.0), vec2(-0.7071, -0.7071), vec2(0.0, -1.0), vec2(0.7071, -0.7071));

vec3 position_at(ivec2 p) {
    ivec2 size = textureSize(depth, 0);
    p = clamp(p, ivec2(0), size - 1);
    return view_position(pixel_to_ndc(vec2(p) + 0.5), texelFetch(depth, p, 0).r);
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(occlusion)))) return;
    float d = texelFetch(depth, p, 0).r;
    if (d >= 1.0) {
        imageStore(occlusion, p, vec4(1.0));
        return;
    }
    vec3 centre = position_at(p);
    // The neighbour differences with the smaller depth step make the normal (no smearing across edges).
    vec3 right = position_at(p + ivec2(1, 0)) - centre;
    vec3 left = centre - position_at(p - ivec2(1, 0));
    vec3 down = position_at(p + ivec2(0, 1)) - centre;
    vec3 up = centre - position_at(p - ivec2(0, 1));
    vec3 dx = abs(right.z) < abs(left.z) ? right : left;
    vec3 dy = abs(down.z) < abs(up.z) ? down : up;
    vec3 n = normalize(cross(dy, dx));
    if (dot(n, -centre) < 0.0) n = -n;

    float radius = frame.lighting.y;
    float radius_pixels = clamp(radius * frame.projection[1][1] * 0.5 * frame.screen.y / -centre.z, 2.0, 48.0);
    float jitter = 0.625 + 0.25 * float((p.x & 1) + 2 * (p.y & 1)) / 3.0;
    float occluded = 0.0;
    for (int i = 0; i < 8; ++i) {
        for (int s = 1; s <= 2; ++s) {
            vec2 offset = kDirections[i] * radius_pixels * jitter * (float(s) * 0.5);
            vec3 to_sample = position_at(p + ivec2(round(offset))) - centre;
            float distance2 = dot(to_sample, to_sample);
            if (distance2 < 1e-8) continue;
            float cosine = dot(n, to_sample) * inversesqrt(distance2);
            occluded += max(cosine - 0.1, 0.0) * max(1.0 - distance2 / (radius * radius), 0.0);
        }
    }
    float ao = clamp(1.0 - frame.lighting.z * occluded / 16.0, 0.0, 1.0);
    imageStore(occlusion, p, vec4(ao));
}

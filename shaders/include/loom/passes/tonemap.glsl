// HDR to display: exposure, a filmic curve and the sRGB encoding (composite pass; the CPU
// reference in tests/passes repeats these formulas).
#ifndef LOOM_PASSES_TONEMAP_GLSL
#define LOOM_PASSES_TONEMAP_GLSL

#include "loom/common.glsl"

// Narkowicz's fit of the ACES filmic curve (2015), clamped to [0, 1].
vec3 tonemap_aces(vec3 x) {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

#endif

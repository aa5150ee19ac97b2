// Pass part "blit" (fragment stage): copies its source texel for texel (the present pass,
// which converts the frame to the target's format).
layout(set = LOOM_SET, binding = LOOM_BINDING(0)) uniform sampler2D source;

layout(location = 0) out vec4 out_color;

void main() {
    out_color = texelFetch(source, ivec2(gl_FragCoord.xy), 0);
}

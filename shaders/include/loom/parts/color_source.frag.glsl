// Pass part "color-source" (fragment stage): a post-process main that reads its source texel
// by texel and hands each colour to the high-pass part (the stand-alone high-pass pass).
layout(set = LOOM_SET, binding = LOOM_BINDING(0)) uniform sampler2D source;

void main() {
    vec3 color = texelFetch(source, ivec2(gl_FragCoord.xy), 0).rgb;
#ifdef LOOM_PART_HIGH_PASS_RENDER
    emit_high_pass(color);
#endif
}

// Included relative to tint.glsl.
const float kScale = 2.0;

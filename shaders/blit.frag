#version 450
// Copies a texture: pair with fullscreen.vert.

layout(set = 0, binding = 0) uniform sampler2D source;

layout(location = 0) in vec2 uv;

layout(location = 0) out vec4 frag_color;

void main() {
    frag_color = texture(source, uv);
}

#version 450
// A shader that must not compile: used by shaderc_tool_test.

layout(location = 0) out vec4 frag_color;

void main() {
    frag_color = vec4(undeclared_name);
}

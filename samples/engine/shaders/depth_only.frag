#version 450
// Depth-only passes (shadow cascades): no colour output.
void main() {}

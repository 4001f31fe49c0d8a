#version 450 core
// Depth-only pass of the bark (shadow maps, depth pre-pass): nothing to write but depth.
void main() {}

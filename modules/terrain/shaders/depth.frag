#version 450 core
// terrain/depth.frag: shadow-map and depth-only passes (depth comes from chunk.vert, which also
// clips the padding beyond the field).
void main() {}

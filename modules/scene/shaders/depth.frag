#version 450 core
// Depth-only pass (shadow casters): no colour attachment, the rasteriser writes depth.
void main() {}

#version 450 core
// grass/blade_depth.frag: the blades' shadow pass writes depth only (the shadow FBO has no
// colour attachment); the geometry comes from the same blade.vert/.tesc/.tese as the colour
// pass, so the shadow has the simulated, tessellated shape the camera sees.
void main() {}

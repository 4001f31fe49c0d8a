#version 450 core
// Depth-only pass (shadow casters): an empty shader with early depth tests for opaque geometry,
// an alpha test for cut-out geometry (seed 004 §3.7.1: 23.58 vs 31.52 ms when split this way).
#include "voxel/common.glsl"

#ifdef ALPHA_CUT
in vec2 v_uv;
flat in uint v_layer;
void main() {
  if (texture(u_diffuse, vec3(v_uv, float(v_layer))).a < u_alpha_cutoff) discard;
}
#else
layout(early_fragment_tests) in;
void main() {}
#endif

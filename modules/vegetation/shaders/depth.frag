#version 450 core
// Depth-only pass of the bark (shadow maps, depth pre-pass): only the LOD transition's dithered
// fade (the seed's dithered shadow transitions, §4.7) decides which fragments write depth.
#include "vegetation/lib/leaf_alpha.glsl"

flat in float v_fade;
in vec3 v_hash_position;

void main() {
  if (v_fade < sylva_hashed_threshold(v_hash_position * 1.37 + 11.0)) discard;
}

#version 450 core
// Depth-only pass of the leaves: the same season discard and the same alpha test as the colour
// pass of a single-sampled target (no multisampling in shadow maps, so alpha-to-coverage becomes
// the hashed test).
#include "vegetation/lib/leaf_alpha.glsl"

in vec2 v_uv;
flat in float v_season_offset;
in vec3 v_hash_position;
flat in float v_fade;  // LOD transition fade: dithered in shadow maps (seed §4.7)

layout(binding = 0) uniform sampler2DArray u_leaf_color;
layout(binding = 3) uniform sampler2D u_season;
layout(binding = 6) uniform sampler2DArray u_leaf_coverage;
uniform float u_season_time;
uniform int u_alpha_mode;  // 0 alpha test, 1 hashed (2 is treated as 1)

void main() {
  // Derivatives (inside sylva_leaf_alpha) before any discard, as in leaf.frag.
  float layer = gl_FrontFacing ? 0.0 : 1.0;
  float a = texture(u_leaf_color, vec3(v_uv, layer)).a;
  float alpha = sylva_leaf_alpha(min(u_alpha_mode, 1), a, u_leaf_coverage, v_uv, layer, v_hash_position);
  float fade_threshold = sylva_hashed_threshold(v_hash_position * 1.37 + 11.0);
  if (v_fade < fade_threshold) discard;
  if (texture(u_season, vec2(0.5, u_season_time + v_season_offset)).a < 0.5 || alpha <= 0.0) discard;
}

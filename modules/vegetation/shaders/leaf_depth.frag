#version 450 core
// Depth-only pass of the leaves: the same season discard and alpha test as the colour pass (no
// multisampling in shadow maps, so no alpha-to-coverage here).
in vec2 v_uv;
flat in float v_season_offset;

layout(binding = 0) uniform sampler2DArray u_leaf_color;
layout(binding = 3) uniform sampler2D u_season;
uniform float u_season_time;

void main() {
  if (texture(u_season, vec2(0.5, u_season_time + v_season_offset)).a < 0.5) discard;
  if (texture(u_leaf_color, vec3(v_uv, 0.0)).a < 0.5) discard;
}

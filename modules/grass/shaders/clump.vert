#version 450 core
// grass/clump.vert: two crossed vertical quads per clump (seed 003 §2.4: fixed random
// rotation, not camera-facing), tops swaying with the shared wind like the blades' equilibrium
// bend (wind_response * wind / stiffness). The same program draws seed 003's wide billboards
// (§2.4.3, far_field.hpp): u_wide.z = 2, as wide as a tile group, strand texture repeated along
// the width, strands kept below fade * wide_keep (in size.z).
#include "grass/far.glsl"
#include "render/lib/wind.glsl"

layout(std430, binding = GRASS_CLUMPS_BINDING) readonly buffer Clumps { Clump clumps[]; };
layout(std140, binding = GRASS_WIND_UBO_BINDING) uniform GrassWind { SylvaWind u_wind; };

uniform mat4 u_view_proj;
uniform vec3 u_origin_rel;
uniform vec3 u_camera;
uniform vec4 u_fades;
uniform float u_sway;
uniform int u_first;
uniform vec4 u_wide;        // x wide_distance, y wide_fade [m], z level (0 clumps, 1 clumps giving way, 2 wide),
                            // w 1: small clumps keep strands below fade * size.z (overcrowding guard, dense_keep)
uniform float u_cell_width; // clump_width [m]: one atlas cell across

out vec3 c_rel_pos;
out vec2 c_uv;
out float c_v;
flat out vec3 c_color;
flat out float c_fade;
flat out vec3 c_normal;
flat out float c_repeat;  // wide billboards: atlas cells across (c_uv = (u in cells, v)); 0: c_uv is the atlas uv
flat out vec2 c_cell;
flat out float c_phase;   // per-clump phase of the colour motion (the sway phase)

const vec2 kCorners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));

void main() {
  Clump c = clumps[u_first + gl_InstanceID];
  int quad = gl_VertexID / 6;
  vec2 corner = kCorners[gl_VertexID % 6];
  float d = length(c.root.xyz - u_camera);
  c_fade = grass_clump_fade(d, u_fades);
  float wide = grass_ramp(d, u_wide.x - u_wide.y, u_wide.x);
  if (u_wide.z == 2.0) c_fade *= wide * c.size.z;  // size.z: the group's strand keep
  else if (u_wide.z == 1.0) c_fade *= 1.0 - wide;
  if (u_wide.z != 2.0 && u_wide.w == 1.0) c_fade *= c.size.z;  // seed 003 §2.4.2 shifted threshold
  c_repeat = 0.0;
  c_phase = c.color.w;
  c_cell = vec2(0.0);
  if (c_fade <= 0.0) {
    gl_Position = vec4(0.0, 0.0, -2.0, 1.0);  // outside the clip volume: the clump is not drawn
    c_rel_pos = vec3(0.0);
    c_uv = vec2(0.0);
    c_v = 0.0;
    c_color = vec3(0.0);
    c_normal = vec3(0.0, 1.0, 0.0);
    return;
  }
  float angle = c.root.w + float(quad) * 1.5707963;
  vec3 across = vec3(cos(angle), 0.0, sin(angle));
  vec3 pos = c.root.xyz + (corner.x - 0.5) * c.size.x * across + vec3(0.0, corner.y * c.size.y, 0.0);
  vec3 wind = sylva_wind(u_wind, c.root.xyz);
  vec3 bend = vec3(wind.x, 0.0, wind.z) * u_sway;
  float bl = length(bend);
  float max_bend = 0.6 * c.size.y;
  if (bl > max_bend) bend *= max_bend / bl;
  pos += bend * corner.y * corner.y;
  pos.y -= (bl > 0.0 ? min(bl, max_bend) : 0.0) * 0.3 * corner.y * corner.y;  // keep the length roughly
  c_rel_pos = pos + u_origin_rel;
  float cell = c.size.w;
  c_uv = (vec2(mod(cell, 2.0), floor(cell / 2.0)) + corner) * 0.5;
  if (u_wide.z == 2.0) {
    c_repeat = max(1.0, floor(c.size.x / max(u_cell_width, 1e-3) + 0.5));
    c_cell = vec2(mod(cell, 2.0), floor(cell / 2.0));
    c_uv = vec2(corner.x * c_repeat, corner.y);
  }
  c_v = corner.y;
  c_color = c.color.rgb;
  c_normal = normalize(cross(across, vec3(0.0, 1.0, 0.0)) * 0.5 + vec3(0.0, 1.0, 0.0));
  gl_Position = u_view_proj * vec4(c_rel_pos, 1.0);
}

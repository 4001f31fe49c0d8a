#version 450 core
// grass/ground.frag: the ground layer. Seed 003 §2.5 far grass: a top-view grass texture whose
// (equalised noise) alpha is thresholded by density * fade * coverage per pixel, so neighbouring
// areas of different density join without seams and the layer appears texel by texel as it
// fades in. With the under-layer on (far_field.hpp), texels below that threshold are not
// discarded but drawn as the grass's undergrowth wherever the density map has grass (alpha <
// density): the same colour family and light as the blades, a little darker, so gaps between
// blades near the camera and between clumps further out show grass, not a different ground.
#include "grass/far.glsl"
#include "grass/color.glsl"
#include "render/lib/fog.glsl"
#include "render/lib/shadows.glsl"

layout(binding = 0) uniform sampler2D u_ground;
layout(binding = 1) uniform sampler2D u_density;
layout(binding = 2) uniform sampler2D u_tint;  // the maps' tint (maps.hpp), read when u_tinted is 1
uniform int u_tinted;

uniform vec4 u_fades;        // mid, mid_fade, far, far_fade
uniform float u_texture_scale;
uniform vec2 u_origin_xz;    // blade-set origin modulo the texture repeat
uniform vec2 u_map_min;      // density map rectangle, blade-set local x/z
uniform vec2 u_map_size;
uniform vec4 u_layer_rect;   // the layer's rectangle (map rectangle grown by the margin), local x/z: min, max
uniform vec3 u_base_color;
uniform vec3 u_tip_color;
uniform int u_receive_shadows;  // sun term times the render core's cascaded shadows
uniform vec3 u_coverage;     // x tau_side, y tau_top, z gain (far_field.hpp coverage model)
uniform vec4 u_shading;      // x brightness (calibration), y ambient, z under-layer on (0/1), w under-layer shade
uniform float u_translucency;  // the blades' shading.translucency
uniform float u_max_slope_deg; // far_field.hpp slope_keep()
uniform vec2 u_color_motion;   // seed 003 §3.4.3: the far layer pulses in sync (phase 0)
// Seed 003 §2.5 noise sub-regions (far_field.hpp): on/off, far tile side [m], the origin's far
// tile and its offset inside that tile (local x/z), the tiles' hash seed.
uniform int u_noise_sub;
uniform float u_noise_tile;
uniform ivec2 u_noise_base;
uniform vec2 u_noise_frac;
uniform uint u_noise_seed;

in vec3 g_local;
in vec3 g_rel_pos;
in vec3 g_normal;
in vec3 g_color;

out vec4 o_color;

void main() {
  if (any(lessThan(g_local.xz, u_layer_rect.xy)) || any(greaterThan(g_local.xz, u_layer_rect.zw))) discard;
  // Outside the map rectangle (the layer's margin) the density continues the map's edge.
  vec2 m = clamp((g_local.xz - u_map_min) / u_map_size, vec2(0.0), vec2(1.0));
  // Image rows run along +z and uploads flip rows: v = 1 at the rectangle's min z.
  float density = texture(u_density, vec2(m.x, 1.0 - m.y)).r;
  // slope_keep() of far_field.cpp: no far grass on cliffs.
  if (u_max_slope_deg < 90.0) {
    float slope = degrees(acos(clamp(normalize(g_normal).y, -1.0, 1.0)));
    density *= 1.0 - grass_ramp(slope, u_max_slope_deg - 8.0, u_max_slope_deg);
  }
  float distance = length(g_rel_pos);
  float fade = grass_ground_fade(distance, u_fades);
  vec4 t;
  if (u_noise_sub != 0) {
    // Each far tile samples its own sub-region (random offset, quarter turn) of the texture; the
    // gradients are those of the continuous mapping, so tile borders do not pick coarse mips.
    vec2 p = g_local.xz + u_noise_frac;
    vec2 cell = floor(p / u_noise_tile);
    vec3 r = grass_noise_subregion(u_noise_base + ivec2(cell), u_noise_seed);
    int turns = int(r.z);
    mat2 rot = mat2(1.0, 0.0, 0.0, 1.0);
    for (int q = 0; q < turns; ++q) rot = mat2(0.0, 1.0, -1.0, 0.0) * rot;
    vec2 uv = (p - cell * u_noise_tile) / u_texture_scale;
    t = textureGrad(u_ground, rot * uv + r.xy, rot * (dFdx(g_local.xz) / u_texture_scale), rot * (dFdy(g_local.xz) / u_texture_scale));
  } else {
    t = texture(u_ground, (g_local.xz + u_origin_xz) / u_texture_scale);
  }
  vec3 n = normalize(g_normal);
  float s = clamp(abs(dot(g_rel_pos / max(distance, 1e-6), n)), 0.05, 1.0);
  float cot_elevation = sqrt(max(1.0 - s * s, 0.0)) / s;
  float cover = 1.0 - exp(-u_coverage.z * (u_coverage.y + u_coverage.x * cot_elevation));
  bool top = t.a < density * fade * cover;
  // 1.004: the largest 8-bit alpha is 1.0, which "< 1" would leave as a hole at full density.
  bool under = u_shading.z > 0.5 && t.a < 1.004 * density * (1.0 - grass_ramp(distance, u_fades.z - u_fades.w, u_fades.z));
  if (!top && !under) discard;
  vec3 albedo = grass_mean_albedo(u_base_color, u_tip_color) * g_color * (t.rgb * 1.4);
  if (!top) albedo *= u_shading.w;
  // The tint map colours the layer as it colours the blades and clumps (seed 001 §3.3 texture
  // maps; Sylva's tint), so the far field matches the near one.
  if (u_tinted != 0) albedo *= texture(u_tint, vec2(m.x, 1.0 - m.y)).rgb;
  albedo *= grass_color_pulse(u_color_motion, 0.0);
  float lit = u_receive_shadows != 0 ? sylva_shadow(g_rel_pos, n) : 1.0;
  vec3 color = albedo * grass_canopy_light(g_rel_pos / max(distance, 1e-6), u_translucency, lit, u_shading.y) * u_shading.x;
  o_color = vec4(apply_fog(color, g_rel_pos), 1.0);
}

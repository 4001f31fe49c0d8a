#version 450 core
// terrain/terrain.frag: height/slope materials (sand, grass, rock, snow) with procedural detail,
// normals from the full-resolution height texture, sun + hemisphere ambient, fog, optional
// cascaded shadows, and the debug views. Output: linear HDR colour.
#include "render/lib/lighting.glsl"
#include "render/lib/fog.glsl"
#include "render/lib/noise.glsl"
#if SYLVA_TERRAIN_SHADOWS
#include "render/lib/shadows.glsl"
#endif

layout(binding = 0) uniform sampler2D u_heights;  // R32F, texel (i, j) = field sample (i, j)

uniform int u_has_heights;     // 0: normals from screen-space derivatives (no height texture)
uniform ivec2 u_field_size;    // field samples (columns, rows)
uniform float u_spacing;
uniform vec2 u_height_range;   // field min / max [m]
uniform int u_debug_view;      // 0 shaded, 1 LOD colours, 2 morph weight, 3 flat colour
uniform int u_level;           // LOD level of the chunk (debug)
uniform vec4 u_flat_color;     // debug view 3, wireframe and bounds
// Materials: x sand height share, y snow height share, z rock slope (1 - n.y), w detail [1/m]
uniform vec4 u_material;
uniform float u_detail_strength;
uniform vec3 u_sand_color;
uniform vec3 u_grass_color;
uniform vec3 u_rock_color;
uniform vec3 u_snow_color;

in vec3 v_rel;
in vec2 v_grid;
in float v_morph;

out vec4 o_color;

float field_height(vec2 grid) {
  return texture(u_heights, (grid + 0.5) / vec2(u_field_size)).r;
}

vec3 lod_color(int level) {
  const vec3 palette[8] = vec3[8](vec3(0.9, 0.2, 0.2), vec3(0.95, 0.6, 0.1), vec3(0.9, 0.9, 0.2), vec3(0.3, 0.85, 0.3),
                                  vec3(0.2, 0.8, 0.85), vec3(0.25, 0.4, 0.95), vec3(0.65, 0.35, 0.9), vec3(0.9, 0.9, 0.9));
  return palette[level % 8];
}

void main() {
  // Padding beyond the field (non-square / non-power-of-two fields) is not terrain.
  if (v_grid.x > float(u_field_size.x - 1) + 1e-3 || v_grid.y > float(u_field_size.y - 1) + 1e-3) discard;
  if (u_debug_view == 3) {
    o_color = u_flat_color;
    return;
  }
  vec3 n;
  float h;
  if (u_has_heights != 0) {
    float hl = field_height(v_grid - vec2(1.0, 0.0)), hr = field_height(v_grid + vec2(1.0, 0.0));
    float hd = field_height(v_grid - vec2(0.0, 1.0)), hu = field_height(v_grid + vec2(0.0, 1.0));
    n = normalize(vec3(-(hr - hl) / (2.0 * u_spacing), 1.0, -(hu - hd) / (2.0 * u_spacing)));
    h = field_height(v_grid);
  } else {
    n = normalize(cross(dFdy(v_rel), dFdx(v_rel)));
    if (n.y < 0.0) n = -n;
    h = v_rel.y + sylva_params.y;
  }
  if (u_debug_view == 1 || u_debug_view == 2) {
    vec3 c = u_debug_view == 1 ? lod_color(u_level) : mix(vec3(0.1, 0.3, 0.9), vec3(0.95, 0.3, 0.1), v_morph);
    o_color = vec4(c * (0.35 + 0.65 * max(dot(n, sun_direction()), 0.0)), 1.0);
    return;
  }
  float range = max(u_height_range.y - u_height_range.x, 1e-3);
  float t = (h - u_height_range.x) / range;
  float slope = 1.0 - n.y;
  vec2 world = v_grid * u_spacing;
  float detail = sylva_fbm2(world, 4, 0.5, 2.0, u_material.w, 7u);          // [-1, 1]
  float breakup = 0.06 * sylva_fbm2(world, 3, 0.5, 2.0, u_material.w * 0.25, 11u);
  float sand = 1.0 - smoothstep(u_material.x - 0.02, u_material.x + 0.02, t + breakup);
  float snow = smoothstep(u_material.y - 0.04, u_material.y + 0.04, t + breakup) * (1.0 - smoothstep(0.35, 0.6, slope));
  float rock = smoothstep(u_material.z - 0.12, u_material.z + 0.12, slope + 0.5 * breakup);
  vec3 albedo = u_grass_color;
  albedo = mix(albedo, u_sand_color, sand);
  albedo = mix(albedo, u_rock_color, rock);
  albedo = mix(albedo, u_snow_color, snow);
  albedo *= 1.0 + u_detail_strength * detail;
  float shadow = 1.0;
#if SYLVA_TERRAIN_SHADOWS
  shadow = sylva_shadow(v_rel, n);
#endif
  vec3 color = shade_diffuse(albedo, n, shadow);
  o_color = vec4(apply_fog(color, v_rel), 1.0);
}

#version 450 core
// Two-sided leaves (seed 000 §3.2, §4.6): per-side colour deviation, venation normal map and
// Half-Life-2 translucency; diffuse + Cook-Torrance specular + ambient + translucency; the season
// colour c_s from the season texture at seasonCoord, budding and leaf fall by discard; edges by
// alpha-to-coverage or the (hashed) alpha test, see lib/leaf_alpha.glsl.
#include "render/lib/fog.glsl"
#include "render/lib/shadows.glsl"
#include "vegetation/lib/leaf_alpha.glsl"
#include "vegetation/lib/leaf_shading.glsl"

in vec2 v_uv;
flat in float v_season_offset;
in vec3 v_hash_position;
in vec3 v_rel;
in vec3 v_normal;
in vec3 v_tangent;
flat in vec3 v_variation;
flat in float v_fade;  // LOD transition fade (1 opaque)

layout(binding = 0) uniform sampler2DArray u_leaf_color;         // layer 0 front, 1 back
layout(binding = 1) uniform sampler2DArray u_leaf_normal;
layout(binding = 2) uniform sampler2DArray u_leaf_translucency;
layout(binding = 3) uniform sampler2D u_season;
layout(binding = 6) uniform sampler2DArray u_leaf_coverage;  // box-filtered alpha

uniform float u_season_time;      // the season parameter (0 = 1 January)
uniform int u_alpha_mode;  // 0 alpha test, 1 hashed alpha test, 2 alpha-to-coverage (AlphaMode)
uniform int u_samples;     // samples per pixel of the target
uniform float u_roughness;
uniform float u_ior;
uniform vec3 u_specular_color;
uniform vec3 u_translucent_color;
uniform float u_diffuse;
uniform float u_ambient;

out vec4 o_color;

void main() {
  // Everything that takes derivatives comes before the first discard (uniform control flow).
  float layer = gl_FrontFacing ? 0.0 : 1.0;
  vec4 col = texture(u_leaf_color, vec3(v_uv, layer));
  float alpha = sylva_leaf_alpha(u_alpha_mode, col.a, u_leaf_coverage, v_uv, layer, v_hash_position);
  // LOD transitions: the fade scales the coverage (alpha-to-coverage) or dithers the alpha test.
  float fade_threshold = sylva_hashed_threshold(v_hash_position * 1.37 + 11.0);
  if (u_alpha_mode == 2) {
    alpha *= v_fade;
  } else if (v_fade < fade_threshold) {
    alpha = 0.0;
  }
  // Season (seed §4.6): seasonCoord = season + 0.2 leafSpecificNumber + instance offset; budding
  // and leaf fall where the season texture is transparent.
  vec4 season = texture(u_season, vec2(0.5, u_season_time + v_season_offset));
  vec3 nts = texture(u_leaf_normal, vec3(v_uv, layer)).xyz * 2.0 - 1.0;
  vec4 tr = texture(u_leaf_translucency, vec3(v_uv, layer));
  int mask = u_alpha_mode == 2 ? sylva_coverage_mask(alpha, u_samples, v_hash_position) : 1;
  if (season.a < 0.5 || alpha <= 0.0 || mask == 0) discard;
  if (u_alpha_mode == 2) gl_SampleMask[0] = mask;

  // Tangent frame of the visible side: front (b, t, n); back (-b, t, -n).
  vec3 n = normalize(v_normal);
  vec3 t = normalize(v_tangent - dot(v_tangent, n) * n);
  vec3 b = cross(t, n);
  if (!gl_FrontFacing) {
    n = -n;
    b = -b;
  }
  vec3 N = normalize(b * nts.x + t * nts.y + n * nts.z);
  vec3 V = normalize(-v_rel);
  vec3 L = sun_direction();

  vec3 cv = col.rgb - 0.5;                 // colour deviation c_v
  vec3 cs = season.rgb + v_variation;      // seasonal colour c_s with per-instance variation
  vec3 base = max(cv + cs, vec3(0.0));
  float diffuse = max(dot(N, L), 0.0);
  float specular = sylva_cook_torrance(N, L, V, u_roughness, u_ior);
  float translucency = 0.0;
  if (dot(n, L) < 0.0) {
    // Light enters through the other side: express L in that side's tangent space (-b, t, -n).
    vec3 l_ts = vec3(dot(L, -b), dot(L, t), dot(L, -n));
    translucency = sylva_hl2_translucency(tr.rgb * 2.0 - 1.0, tr.a, l_ts);
  }
  // The sun reaches the side facing it: shadow lookups use that side's normal (the visible side
  // for reflection, the far side for light passing through). 1 when no shadow maps are bound.
  float shadow = sylva_shadow(v_rel, dot(n, L) >= 0.0 ? n : -n);
  vec3 color = shadow * sun_radiance() * (diffuse * u_diffuse * base + specular * u_specular_color +
                                          translucency * base * u_translucent_color) +
               hemisphere_ambient(N) * u_ambient * base;
  o_color = vec4(apply_fog(color, v_rel), 1.0);
}

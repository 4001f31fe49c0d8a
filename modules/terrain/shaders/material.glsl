// terrain/material.glsl: the terrain's layered material (issue 19; C++ side and the altitude
// model in include/sylva/terrain/material.hpp). Layers: lowland grass, alpine meadow, dirt,
// scree, rock, snow, sand, blended by altitude in metres (u_lines), slope and curvature, with
// detail from ONE small tiling noise texture (u_detail, mipmapped) read at four scales. Mip
// filtering by the pixel footprint averages albedo variation and relief gradients toward their
// mean as the ground recedes, so nothing shimmers; scales whose texels fall below ~1/8 pixel are
// faded out and not fetched (the far ground costs fewer lookups). Steep ground is projected
// triplanar (three planes blended by the normal), so cliffs are not stretched.
#ifndef SYLVA_TERRAIN_MATERIAL_GLSL
#define SYLVA_TERRAIN_MATERIAL_GLSL

layout(binding = 1) uniform sampler2D u_detail;  // r, g: fBm (sd 0.4); b, a: relief gradient (unit RMS)

uniform vec4 u_lines;   // world heights [m]: x snow line, y rock line, z tree line, w water level
uniform vec4 u_layer;   // x beach height [m], y rock slope (1 - n.y), z 1 / finest tile [1/m], w detail strength
uniform vec2 u_pole;    // x/z unit vector toward the nearer pole ((0, -1) north of the equator)
uniform vec3 u_grass_color;
uniform vec3 u_meadow_color;
uniform vec3 u_dirt_color;
uniform vec3 u_scree_color;
uniform vec3 u_rock_color;
uniform vec3 u_snow_color;
uniform vec3 u_sand_color;

// Tile ratios between the scales: not integers, so the repeats of one never line up with another's.
const float kScale1 = 5.3, kScale2 = 28.0, kScale3 = 204.0;

struct TerrainSurface {
  vec3 albedo;     // linear
  vec3 normal;     // with the detail relief
  float occlusion; // sky visibility from the curvature, [0.6, 1]
  vec4 layers;     // debug view: x snow, y rock + scree, z dirt, w sand
};

// One scale: albedo channels (r, g) and the world-space relief gradient, triplanar with the
// weights w (x: plane zy, y: plane xz, z: plane xy). Explicit gradients: the branches are not
// uniform control flow, where implicit derivatives are undefined.
vec2 detail_scale(vec3 p, vec3 dpdx, vec3 dpdy, float inv_tile, vec3 w, out vec3 grad) {
  vec2 v = vec2(0.0);
  grad = vec3(0.0);
  if (w.y > 0.0) {
    vec4 s = textureGrad(u_detail, p.xz * inv_tile, dpdx.xz * inv_tile, dpdy.xz * inv_tile);
    v += w.y * s.rg;
    grad += w.y * vec3(s.b, 0.0, s.a);
  }
  if (w.x > 0.0) {  // offsets decorrelate the planes where they overlap
    vec4 s = textureGrad(u_detail, p.zy * inv_tile + 0.37, dpdx.zy * inv_tile, dpdy.zy * inv_tile);
    v += w.x * s.rg;
    grad += w.x * vec3(0.0, s.a, s.b);
  }
  if (w.z > 0.0) {
    vec4 s = textureGrad(u_detail, p.xy * inv_tile + 0.71, dpdx.xy * inv_tile, dpdy.xy * inv_tile);
    v += w.z * s.rg;
    grad += w.z * vec3(s.b, s.a, 0.0);
  }
  return v;
}

// 1 while a scale's texel (tile / 256) covers more than ~1/2 pixel, 0 below ~1/8: the scale's
// detail is then averaged away by the mips anyway, and its low frequencies would show the tile's
// repeats across the distance.
float detail_fade(float footprint, float inv_tile) {
  return 1.0 - smoothstep(1.0 / 128.0, 1.0 / 32.0, footprint * inv_tile);
}

// p: position [m] (x/z from the field's origin, y the world height); n: the field's normal;
// curvature: (mean height around - height) / radius (> 0 in hollows); h: world height [m].
TerrainSurface terrain_surface(vec3 p, vec3 n, float curvature, float h) {
  vec3 dpdx = dFdx(p), dpdy = dFdy(p);
  float footprint = max(length(dpdx), length(dpdy));
  float inv_tile0 = u_layer.z;
  float strength = u_layer.w;

  // Triplanar weights: the xz plane alone up to ~35 degrees, blended planes on steeper ground.
  vec3 w = pow(abs(n), vec3(8.0));
  w /= (w.x + w.y + w.z);
  w = clamp((w - 0.05) / 0.95, 0.0, 1.0);
  w /= max(w.x + w.y + w.z, 1e-4);

  float f0 = detail_fade(footprint, inv_tile0);
  float f1 = detail_fade(footprint, inv_tile0 / kScale1);
  float f2 = detail_fade(footprint, inv_tile0 / kScale2);
  vec3 g0 = vec3(0.0), g1 = vec3(0.0), g2 = vec3(0.0), g3;
  vec2 d0 = vec2(0.0), d1 = vec2(0.0), d2 = vec2(0.0);
  if (f0 > 0.0) d0 = f0 * detail_scale(p, dpdx, dpdy, inv_tile0, w, g0);
  if (f1 > 0.0) d1 = f1 * detail_scale(p, dpdx, dpdy, inv_tile0 / kScale1, w, g1);
  if (f2 > 0.0) d2 = f2 * detail_scale(p, dpdx, dpdy, inv_tile0 / kScale2, w, g2);
  // The macro scale (~500 m) is planar: its features are larger than any cliff.
  vec2 d3 = detail_scale(p, dpdx, dpdy, inv_tile0 / kScale3, vec3(0.0, 1.0, 0.0), g3);

  // Breakup of the layer borders in metres of altitude and in slope, from the coarse scales.
  float breakup = d2.g + 0.6 * d3.g + 0.35 * d1.g;  // sd ~0.5
  float fine = d0.r;                                // small patches (tufts, stones)
  float slope = 1.0 - n.y;

  // Aspect: pole-facing slopes hold snow ~100 m lower, sun-facing ones shed it (northern
  // hemisphere: north = -z; u_lines.x already carries the season and latitude).
  float pole = 2.0 * dot(n.xz, u_pole);

  // Lowland grass -> alpine meadow above the tree line (a 300 m band).
  float meadow = smoothstep(u_lines.z - 150.0, u_lines.z + 150.0, h + 120.0 * breakup);
  // Dirt: hollows, gullies and moderately steep banks, plus small bare patches in the grass.
  float dirt = smoothstep(0.02, 0.08, curvature + 0.03 * breakup) * smoothstep(0.06, 0.2, slope + 0.05 * fine);
  dirt = max(dirt, smoothstep(0.18, 0.3, slope + 0.08 * breakup));
  dirt = max(dirt, smoothstep(0.55, 0.85, fine * 0.6 + d1.r * 0.9));
  // Scree above the rock line on gentler ground and in the hollows below cliffs.
  float alpine = smoothstep(u_lines.y - 120.0, u_lines.y + 120.0, h + 150.0 * breakup);
  float scree = alpine * (1.0 - smoothstep(0.5, 0.9, fine + 1.2 * d1.g - 2.0 * curvature));
  scree = max(scree, smoothstep(0.05, 0.12, curvature) * smoothstep(0.15, 0.3, slope) * alpine);
  // Rock: steep ground anywhere, exposed ridges above the rock line.
  float rock = smoothstep(u_layer.y - 0.06, u_layer.y + 0.06, slope + 0.1 * breakup + 0.04 * fine);
  rock = max(rock, alpine * smoothstep(0.02, 0.1, -curvature + 0.05 * breakup) * smoothstep(0.1, 0.25, slope));
  // Snow above the line, more in hollows and on pole-facing slopes, none on walls.
  float snow_h = h + 90.0 * breakup + clamp(600.0 * curvature, -80.0, 120.0) + 100.0 * pole + 10.0 * fine;
  float snow = smoothstep(u_lines.x - 40.0, u_lines.x + 40.0, snow_h) * (1.0 - smoothstep(0.3, 0.45, slope + 0.08 * fine));
  // Sand: the beach band above the water level, on gentle ground.
  float sand = (1.0 - smoothstep(u_layer.x * 0.7, u_layer.x, h - u_lines.w + 0.3 * u_layer.x * breakup)) *
               step(1e-3, u_layer.x) * (1.0 - smoothstep(0.15, 0.3, slope));

  float v = (0.55 * d0.r + 0.45 * d1.r + 0.35 * d2.r) * strength;  // albedo variation, sd ~0.3 near
  float macro = d3.r * strength;
  vec3 grass = u_grass_color * (1.0 + 0.45 * v + 0.25 * macro);
  grass = mix(grass, grass * vec3(1.45, 1.25, 0.7), smoothstep(-0.3, 0.6, d1.g + 0.5 * macro));  // drier tufts
  vec3 albedo = mix(grass, u_meadow_color * (1.0 + 0.4 * v), meadow);
  albedo = mix(albedo, u_dirt_color * (1.0 + 0.5 * v), dirt);
  albedo = mix(albedo, u_scree_color * (1.0 + (0.6 * d0.r + 0.3 * d1.r) * strength), scree);
  vec3 rock_albedo = u_rock_color * (1.0 + 0.5 * v + 0.2 * macro);
  albedo = mix(albedo, rock_albedo, rock);
  albedo = mix(albedo, u_sand_color * (1.0 + 0.25 * v), sand);
  albedo = mix(albedo, u_snow_color * (1.0 + 0.05 * v), snow);

  // Relief: strongest on rock and scree, gentle under snow; projected onto the tangent plane.
  float rough = mix(1.0, 1.6, max(rock, scree)) * mix(1.0, 0.35, snow);
  vec3 g = (0.22 * g0 + 0.16 * g1 + 0.1 * g2) * rough * strength;
  vec3 nd = normalize(n - (g - dot(g, n) * n));

  TerrainSurface s;
  s.albedo = max(albedo, vec3(0.0));
  s.normal = nd;
  s.occlusion = clamp(1.0 - 2.5 * max(curvature, 0.0), 0.6, 1.0);
  s.layers = vec4(snow, max(rock, scree), dirt, sand);
  return s;
}

#endif

// terrain/material.glsl: the terrain's layered material (issue 19; C++ side and the altitude
// model in include/sylva/terrain/material.hpp). Layers: lowland grass, alpine meadow, dirt,
// scree, rock, snow, sand, blended by altitude in metres (u_lines), slope and curvature, with
// detail from ONE small tiling noise texture (u_detail, mipmapped) read at three scales plus a
// ~400 m variation stored with the field's shape. Mip
// filtering by the pixel footprint averages albedo variation and relief gradients toward their
// mean as the ground recedes, so nothing shimmers; scales whose texels fall below ~1/8 pixel are
// faded out (and not fetched where branches are real). Steep ground is projected on a side plane
// (biplanar, see detail_scale), so cliffs are not stretched.
#ifndef SYLVA_TERRAIN_MATERIAL_GLSL
#define SYLVA_TERRAIN_MATERIAL_GLSL

// RGBA8, encoded by make_detail_texture: r, g fBm (sd 0.4) as v / 2 + 1/2; b, a the relief
// gradient (unit RMS) as g / 8 + 1/2.
layout(binding = 1) uniform sampler2D u_detail;

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

// The finest detail scale the program fetches (0-3; 3: none), chosen per chunk by the renderer
// (first_detail_scale in material_gpu.hpp) where every pixel of the chunk lies beyond the
// distance at which the finer scales' fades reach 0: the same picture, bit for bit, without
// their fetches, which llvmpipe would run under an all-off mask (it does not skip branches).
#ifndef SYLVA_TERRAIN_FIRST_SCALE
#define SYLVA_TERRAIN_FIRST_SCALE 0
#endif

// Tile ratios between the scales: not integers, so the repeats of one never line up with another's.
const float kScale1 = 5.3, kScale2 = 28.0;

// One texel of the shape texture (RGBA16_SNORM, material.hpp) decoded: the field's unit normal,
// curvature ((mean height around - height) / radius) and the ~400 m macro variation.
struct ShapeSample {
  vec3 normal;
  float curvature;
  float macro;
};
ShapeSample decode_shape(vec4 shape) {
  ShapeSample s;
  s.normal = vec3(shape.x, sqrt(max(1.0 - dot(shape.xy, shape.xy), 0.0)), shape.y);
  s.curvature = shape.z;
  s.macro = 1.6 * shape.w;
  return s;
}

struct TerrainSurface {
  vec3 albedo;     // linear
  vec3 normal;     // with the detail relief
  float occlusion; // sky visibility from the curvature, [0.6, 1]
  vec4 layers;     // debug view: x snow, y rock + scree, z dirt, w sand
};

// One scale: albedo channels (r, g) and the world-space relief gradient, "biplanar": the xz plane
// with weight wy and ONE side plane (zy where |n.x| > |n.z|, else xy) with weight 1 - wy. Two
// fetches, not three: llvmpipe runs both sides of every branch (execution masks), so only
// fetches that are not written cost nothing; the side planes of a face meet in a seam where its
// normal points 45 degrees between x and z, on rock. Implicit derivatives inside the branches:
// where a quad is split by one, the branch's weight (fade or plane weight) is about 0.
vec2 detail_scale(vec2 pxz, vec2 pside, bool xside, float inv_tile, float wy, out vec3 grad) {
  vec2 v = vec2(0.0);
  grad = vec3(0.0);
  if (wy > 0.0) {
    vec4 s = texture(u_detail, pxz * inv_tile) * vec4(2.0, 2.0, 8.0, 8.0) - vec4(1.0, 1.0, 4.0, 4.0);
    v += wy * s.rg;
    grad += wy * vec3(s.b, 0.0, s.a);
  }
  if (wy < 1.0) {  // the offset decorrelates the side plane from the xz plane where they overlap
    vec4 s = texture(u_detail, pside * inv_tile + 0.37) * vec4(2.0, 2.0, 8.0, 8.0) - vec4(1.0, 1.0, 4.0, 4.0);
    v += (1.0 - wy) * s.rg;
    grad += (1.0 - wy) * (xside ? vec3(0.0, s.a, s.b) : vec3(s.b, s.a, 0.0));
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
// curvature: (mean height around - height) / radius (> 0 in hollows); h: world height [m];
// macro: the ~400 m variation from the shape texture, in about [-1, 1].
TerrainSurface terrain_surface(vec3 p, vec3 n, float curvature, float h, float macro) {
  float footprint = max(length(dFdx(p)), length(dFdy(p)));
  float inv_tile0 = u_layer.z;
  float strength = u_layer.w;

  // Plane weights: the xz plane alone up to 49 degrees (it stretches the texture by 1 / n.y, at
  // most 1.5x there), blended with the side plane up to 60 degrees, the side plane alone beyond.
  float wy = clamp((smoothstep(0.5, 0.65, n.y) - 0.05) / 0.9, 0.0, 1.0);
  bool xside = abs(n.x) > abs(n.z);
  vec2 pside = xside ? p.zy : p.xy;

  float f0 = detail_fade(footprint, inv_tile0);
  float f1 = detail_fade(footprint, inv_tile0 / kScale1);
  float f2 = detail_fade(footprint, inv_tile0 / kScale2);
  vec3 g0 = vec3(0.0), g1 = vec3(0.0), g2 = vec3(0.0);
  vec2 d0 = vec2(0.0), d1 = vec2(0.0), d2 = vec2(0.0);
#if SYLVA_TERRAIN_FIRST_SCALE <= 0
  if (f0 > 0.0) d0 = f0 * detail_scale(p.xz, pside, xside, inv_tile0, wy, g0);
#endif
#if SYLVA_TERRAIN_FIRST_SCALE <= 1
  if (f1 > 0.0) d1 = f1 * detail_scale(p.xz, pside, xside, inv_tile0 / kScale1, wy, g1);
#endif
#if SYLVA_TERRAIN_FIRST_SCALE <= 2
  if (f2 > 0.0) d2 = f2 * detail_scale(p.xz, pside, xside, inv_tile0 / kScale2, wy, g2);
#endif

  // Breakup of the layer borders in metres of altitude and in slope, from the coarse scales.
  float breakup = d2.g + 1.0 * macro + 0.35 * d1.g;  // sd ~0.5
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
  macro *= strength;
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

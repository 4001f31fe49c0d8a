#version 450 core
// terrain/terrain.frag: the layered material of terrain/material.glsl (altitude bands in metres,
// slope, curvature, detail at three scales, triplanar cliffs), the field's normal and curvature
// from the shape texture (one fetch), sun + hemisphere ambient darkened in hollows, fog,
// optional cascaded shadows, and the debug views. Output: linear HDR colour.
#include "render/lib/lighting.glsl"
#include "render/lib/fog.glsl"
#include "terrain/material.glsl"
#if SYLVA_TERRAIN_SHADOWS
#include "render/lib/shadows.glsl"
#endif

// RGBA16_SNORM, texel (i, j) = field sample (i, j): x/z of the unit normal, curvature, macro
// variation (material.hpp).
layout(binding = 2) uniform sampler2D u_shape;

// The view is compiled in, one program per view (renderer.cpp): llvmpipe runs every side of a
// branch under execution masks, so a run-time switch made the shaded view pay for all the debug
// views and the flat view for the whole material. 0 shaded, 1 LOD colours, 2 morph weight,
// 3 flat colour, 4 material layers (DebugView).
#ifndef SYLVA_TERRAIN_VIEW
#define SYLVA_TERRAIN_VIEW 0
#endif

// 1: the albedo and occlusion come from the baked far material (SRGB8_ALPHA8, texel (i, j) =
// field sample (i, j), mipmapped; far_material.hpp) instead of terrain_surface; only compiled
// with SYLVA_TERRAIN_FIRST_SCALE 3 and the shaded view.
#ifndef SYLVA_TERRAIN_BAKED
#define SYLVA_TERRAIN_BAKED 0
#endif
#if SYLVA_TERRAIN_BAKED
layout(binding = 3) uniform sampler2D u_far_material;
#endif

uniform int u_has_shape;       // 0: normals from screen-space derivatives, no curvature
uniform ivec2 u_field_size;    // field samples (columns, rows)
uniform float u_spacing;
uniform int u_level;           // LOD level of the chunk (debug)
uniform vec4 u_flat_color;     // debug view 3, wireframe and bounds

// Aerial perspective: 0 per pixel (apply_fog), 1 per vertex (chunk.vert), 2 off, 3 per vertex
// with the sky radiance per vertex too (chunks below the camera)
// (TerrainRenderSettings::aerial_perspective).
#ifndef SYLVA_TERRAIN_AIR
#define SYLVA_TERRAIN_AIR 0
#endif
#if SYLVA_TERRAIN_AIR == 1 || SYLVA_TERRAIN_AIR == 3
in vec3 v_air_extinction;
#endif
#if SYLVA_TERRAIN_AIR == 3
in vec3 v_air_sky;
#endif

in vec3 v_rel;
in vec2 v_grid;
in float v_morph;

out vec4 o_color;

vec3 lod_color(int level) {
  const vec3 palette[8] = vec3[8](vec3(0.9, 0.2, 0.2), vec3(0.95, 0.6, 0.1), vec3(0.9, 0.9, 0.2), vec3(0.3, 0.85, 0.3),
                                  vec3(0.2, 0.8, 0.85), vec3(0.25, 0.4, 0.95), vec3(0.65, 0.35, 0.9), vec3(0.9, 0.9, 0.9));
  return palette[level % 8];
}

void main() {
  // No discard here (padding is clipped in chunk.vert): it would turn off the early depth test.
#if SYLVA_TERRAIN_VIEW == 3
  o_color = u_flat_color;
#else
  // The drawn surface's height (within tau pixels of the field's) places the altitude bands.
  float h = v_rel.y + sylva_params.y;
  vec3 n;
  float curvature = 0.0, macro = 0.0;
  if (u_has_shape != 0) {
    ShapeSample shape = decode_shape(texture(u_shape, (v_grid + 0.5) / vec2(u_field_size)));
    n = shape.normal;
    curvature = shape.curvature;
    macro = shape.macro;
  } else {
    n = normalize(cross(dFdy(v_rel), dFdx(v_rel)));
    if (n.y < 0.0) n = -n;
  }
#if SYLVA_TERRAIN_VIEW == 1 || SYLVA_TERRAIN_VIEW == 2
#if SYLVA_TERRAIN_VIEW == 1
  vec3 c = lod_color(u_level);
#else
  vec3 c = mix(vec3(0.1, 0.3, 0.9), vec3(0.95, 0.3, 0.1), v_morph);
#endif
  o_color = vec4(c * (0.35 + 0.65 * max(dot(n, sun_direction()), 0.0)), 1.0);
#else
#if SYLVA_TERRAIN_BAKED
  // Far chunks (renderer.cpp, far_material.hpp): the material without detail scales, evaluated
  // once per field sample by far_material_bake.frag and filtered like the shape texture; the
  // normal (no detail relief at first scale 3) stays the shape texture's.
  vec4 baked = texture(u_far_material, (v_grid + 0.5) / vec2(u_field_size));
  TerrainSurface surface;
  surface.albedo = baked.rgb;
  surface.normal = n;
  surface.occlusion = baked.a;
#else
  TerrainSurface surface = terrain_surface(vec3(v_grid.x * u_spacing, h, v_grid.y * u_spacing), n, curvature, h, macro);
#endif
#if SYLVA_TERRAIN_VIEW == 4
  // Unlit layer colours: snow white, rock/scree grey, dirt brown, sand yellow, vegetation green.
  vec3 c = vec3(0.15, 0.55, 0.1);
  c = mix(c, vec3(0.45, 0.28, 0.1), surface.layers.z);
  c = mix(c, vec3(0.4), surface.layers.y);
  c = mix(c, vec3(0.95, 0.8, 0.3), surface.layers.w);
  c = mix(c, vec3(1.0), surface.layers.x);
  o_color = vec4(c, 1.0);
#else
  float shadow = 1.0;
#if SYLVA_TERRAIN_SHADOWS
  shadow = sylva_shadow(v_rel, n);
#endif
  vec3 nd = surface.normal;
  // The detail relief can turn a normal away from the sun where the field faces it (and the
  // shadow map lights it): the sun term follows the detail only as far as the field allows.
  float sun = lambert(nd, sun_direction()) * smoothstep(0.0, 0.15, dot(n, sun_direction()));
  vec3 color = surface.albedo * (sun_radiance() * sun * shadow + hemisphere_ambient(nd) * surface.occlusion);
#if SYLVA_TERRAIN_AIR == 0
  o_color = vec4(apply_fog(color, v_rel), 1.0);
#elif SYLVA_TERRAIN_AIR == 1
  o_color = vec4(air_from_vertex(color, v_rel, v_air_extinction), 1.0);
#elif SYLVA_TERRAIN_AIR == 3
  vec3 t = exp(-v_air_extinction * length(v_rel));
  o_color = vec4(color * t + (min(t.r, min(t.g, t.b)) > 0.998 ? vec3(0.0) : v_air_sky * (1.0 - t)), 1.0);
#else
  o_color = vec4(color, 1.0);
#endif
#endif
#endif
#endif
}

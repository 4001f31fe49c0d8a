#version 450 core
// terrain/model.frag: the general model (seed 002 §4) in the height-field terrain's layered
// material (terrain/material.glsl: altitude bands in metres, slope from the mesh normal, so an
// overhang's underside is rock), sun, hemisphere ambient, fog, optional cascaded shadows, and
// the debug views. Output: linear HDR colour.
#include "render/lib/lighting.glsl"
#include "render/lib/fog.glsl"
#include "terrain/material.glsl"
#if SYLVA_TERRAIN_SHADOWS
#include "render/lib/shadows.glsl"
#endif

uniform int u_debug_view;   // 0 shaded, 1 LOD colours (u_flat_color = the level's), 2 flat colour
uniform vec4 u_flat_color;

in vec3 v_rel;
in vec3 v_world;
in vec3 v_normal;

out vec4 o_color;

void main() {
  if (u_debug_view == 2) {
    o_color = u_flat_color;
    return;
  }
  vec3 n = normalize(v_normal);
  if (dot(n, v_rel) > 0.0) n = -n;  // the back of the sheet (seen from below) is lit as its front
  if (u_debug_view == 1) {
    o_color = vec4(u_flat_color.rgb * (0.35 + 0.65 * max(dot(n, sun_direction()), 0.0)), 1.0);
    return;
  }
  TerrainSurface surface = terrain_surface(v_world, n, 0.0, v_world.y, 0.0);
  float shadow = 1.0;
#if SYLVA_TERRAIN_SHADOWS
  shadow = sylva_shadow(v_rel, n);
#endif
  vec3 nd = surface.normal;
  // As terrain.frag: the detail relief follows the sun only as far as the surface normal allows.
  float sun = lambert(nd, sun_direction()) * smoothstep(0.0, 0.15, dot(n, sun_direction()));
  vec3 color = surface.albedo * (sun_radiance() * sun * shadow + hemisphere_ambient(nd) * surface.occlusion);
  o_color = vec4(apply_fog(color, v_rel), 1.0);
}

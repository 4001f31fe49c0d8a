#version 450 core
// grass/blade.tesc: tessellation level from the blade's projected size (seed 001 eq. 2.3, but
// in pixels: segments = clamp(ceil(px / pixels_per_segment), 1, max_level); or eq. 2.3's own
// distance law with cull.distance_tess_law; no ceil with a fractional cull.tess_spacing;
// blade.glsl grass_tess_level), and the blade's
// Bezier control points for the evaluation shader. The quad domain is 1 column across the
// blade (u) and `segments` rows along it (v), as seed 001 §3.7 suggests.
#include "grass/blade.glsl"

layout(vertices = 1) out;

layout(std430, binding = GRASS_BLADES_BINDING) readonly buffer Blades { Blade blades[]; };

flat in uint v_blade[];

patch out vec3 tc_p0;
patch out vec3 tc_p1;
patch out vec3 tc_p2;
patch out vec3 tc_width_dir;   // unit, across the blade
patch out vec4 tc_params;      // x drawn width [m], y shade random, z shape random, w packed colour

uniform vec3 u_camera;         // blade-set local
uniform float u_ppr;           // pixels per radian
uniform vec4 u_tess;           // x max level, y pixels per segment, z distance law, w spacing (blade.glsl grass_tess_level)
uniform vec4 u_thinning;       // start, near_distance, min_keep, enabled
uniform vec4 u_cull;           // x density_scale, y width_compensation

void main() {
  Blade b = blades[v_blade[0]];
  tc_p0 = b.v0.xyz;
  tc_p1 = grass_drawn_control(b);  // seed 001 eq. 2.4 jitter when the blade has it
  tc_p2 = b.v2.xyz;
  tc_width_dir = grass_width_dir(b.up.xyz, b.v0.w);
  float d = length(b.v0.xyz - u_camera);
  float keep = grass_distance_keep(d, u_thinning) * u_cull.x;
  // A blade about to be thinned out narrows over the last kFadeBand of keep instead of popping.
  const float kFadeBand = 0.1;
  float narrowing = clamp((keep - b.attr.x) / kFadeBand, 0.0, 1.0);
  tc_params = vec4(b.v2.w * grass_width_scale(keep, u_cull.y) * narrowing, b.attr.y, b.attr.w, b.attr.z);

  float n = grass_tess_level(b.v0.xyz, tc_p1, b.v2.xyz, b.v1.w, u_camera, u_ppr, u_tess, u_thinning.y);
  gl_TessLevelOuter[0] = n;    // left edge (u = 0), along the blade
  gl_TessLevelOuter[1] = 1.0;  // bottom edge
  gl_TessLevelOuter[2] = n;    // right edge
  gl_TessLevelOuter[3] = 1.0;  // top edge
  gl_TessLevelInner[0] = 1.0;  // across
  gl_TessLevelInner[1] = n;    // along
}

#version 450 core
// grass/blade.tese: places the tessellated quad on the blade (seed 001 eq. 2.5/2.6): the centre
// curve c(v) by De Casteljau, the edges c(v) -/+ w/2 * taper(v) * width_dir (the two parallel
// splines of the seed, tapered by Jahrmann & Wimmer's shape functions), tangent from the curve,
// normal = width_dir x tangent, bent across the blade for a rounded look.
#include "grass/blade.glsl"

// cull.tess_spacing picks the spacing (GRASS_TESS_SPACING 1 fractional_even, 2 fractional_odd,
// set by grass_field.cpp; unset = equal, seed 001's code): fractional levels morph new segments
// in instead of popping them (seed 001 pitfall "LOD popping").
#if defined(GRASS_TESS_SPACING) && GRASS_TESS_SPACING == 1
layout(quads, fractional_even_spacing, ccw) in;
#elif defined(GRASS_TESS_SPACING) && GRASS_TESS_SPACING == 2
layout(quads, fractional_odd_spacing, ccw) in;
#else
layout(quads, equal_spacing, ccw) in;
#endif

patch in vec3 tc_p0;
patch in vec3 tc_p1;
patch in vec3 tc_p2;
patch in vec3 tc_width_dir;
patch in vec4 tc_params;

uniform mat4 u_view_proj;     // camera-relative view-projection (rotation only)
uniform vec3 u_origin_rel;    // blade-set origin minus camera position [m]
uniform int u_shape;          // 0 quad, 1 triangle, 2 quadratic, 3 triangle-tip

out vec3 te_rel_pos;          // camera-relative position [m]
out vec3 te_normal;
out vec2 te_uv;               // u across, v along the blade
flat out vec3 te_color_mult;
flat out float te_shade;

float taper(float v) {
  if (u_shape == 1) return 1.0 - v;
  if (u_shape == 2) return 1.0 - v * v;
  if (u_shape == 3) return v < 0.5 ? 1.0 : 2.0 * (1.0 - v);
  return 1.0;
}

void main() {
  float u = gl_TessCoord.x;
  float v = gl_TessCoord.y;
  vec3 c = grass_bezier(tc_p0, tc_p1, tc_p2, v);
  vec3 t = grass_bezier_tangent(tc_p0, tc_p1, tc_p2, v);
  float tl = length(t);
  vec3 tangent = tl > 1e-8 ? t / tl : normalize(tc_p2 - tc_p0 + vec3(0.0, 1e-6, 0.0));
  vec3 w = tc_width_dir;
  vec3 pos = c + (u - 0.5) * tc_params.x * taper(v) * w;
  vec3 n = cross(w, tangent);
  float nl = length(n);
  n = nl > 1e-8 ? n / nl : vec3(0.0, 1.0, 0.0);
  // Rounded cross-section: tilt the normal towards the edges.
  n = normalize(n + (u - 0.5) * 0.8 * w);
  te_rel_pos = pos + u_origin_rel;
  te_normal = n;
  te_uv = vec2(u, v);
  te_color_mult = grass_unpack_color(tc_params.w) * 2.0;
  te_shade = tc_params.y;
  gl_Position = u_view_proj * vec4(te_rel_pos, 1.0);
}

#version 450 core
// Slice bake, leaves (slice_bake.hpp): the leaf colour texture without the season (added when the
// slices are drawn, seed §3.3), slice-space normal of the visible side with leafSpecificNumber in
// alpha (§2.12), the level-1 branch and x coordinates. Hashed alpha test (leaf_alpha.glsl) on the
// box-filtered coverage where the leaf texture is minified, the 0.5 test where it is not: a slice
// texel is often larger than a needle spray's or a leaf cluster's gaps, and a fixed threshold kept
// only a cluster's solid parts (conifer slices covered 0.66 of LOD0's crown; with the hashed
// test each texel is kept with the probability of its covered share, crown_gl_test).
#include "vegetation/lib/leaf_alpha.glsl"

in vec2 v_uv;
in vec3 v_hash_position;
in vec3 v_normal;
in vec3 v_tangent;
flat in int v_level1;
flat in int v_root;
in vec2 v_x;
flat in float v_leaf_number;

layout(binding = 0) uniform sampler2DArray u_leaf_color;
layout(binding = 1) uniform sampler2DArray u_leaf_normal;
layout(binding = 6) uniform sampler2DArray u_leaf_coverage;  // box-filtered alpha
uniform vec3 u_slice_axis;
uniform vec3 u_slice_normal;

layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_branch;

void main() {
  float layer = gl_FrontFacing ? 0.0 : 1.0;
  vec4 col = texture(u_leaf_color, vec3(v_uv, layer));
  vec3 nts = texture(u_leaf_normal, vec3(v_uv, layer)).xyz * 2.0 - 1.0;
  if (sylva_leaf_alpha(1, col.a, u_leaf_coverage, v_uv, layer, v_hash_position) < 0.5) discard;
  vec3 n = normalize(v_normal);
  vec3 t = normalize(v_tangent - dot(v_tangent, n) * n);
  vec3 b = cross(t, n);
  if (!gl_FrontFacing) {
    n = -n;
    b = -b;
  }
  vec3 N = normalize(b * nts.x + t * nts.y + n * nts.z);
  vec3 ns = vec3(dot(N, u_slice_axis), N.y, dot(N, u_slice_normal));
  o_color = vec4(col.rgb, 1.0);
  o_normal = vec4(ns * 0.5 + 0.5, 0.25 + 0.75 * clamp(v_leaf_number, 0.0, 1.0));
  o_branch = vec4(float(v_level1), v_x.x, v_x.y, float(v_root + 1));
}

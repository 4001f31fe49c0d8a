// Image-based levels (LOD1/LOD2, seed 000 §2.6-2.10): slice geometry, the backward transform of
// §2.7 and the slice lookups shared by the colour and depth passes. See slice_bake.hpp for the
// baked maps and slice_renderer.hpp for the bindings.
#ifndef SYLVA_VEGETATION_SLICES_GLSL
#define SYLVA_VEGETATION_SLICES_GLSL

#include "vegetation/lib/tree_animation.glsl"

const float SYLVA_PI = 3.14159265358979;

layout(std140, binding = 5) uniform SylvaSliceSet {  // SliceSetGpu, slice_renderer.cpp
  vec4 center_radius;  // xyz centre of the rest bounds (object), w horizontal radius R [m]
  vec4 extent;         // x half height [m], y quad margin [m], z directions, w layers
  vec4 fade_range;     // xy |cos| range over which a slice fades in (view-parallel slices hidden)
                       // z texels per side, w leaf displacement [m per m/s]
  vec4 leaf_scroll;    // xy, zw offsets of the two scrolling lookups (eq. 3.40)
  vec4 misc;           // x 1 / leaf displacement scale [1/m], y colour noise [rad per m/s], z depth offset in
                       // shadows (0 / 1), w largest leaf displacement [m]
} sylva_slices;

layout(binding = 8) uniform sampler2DArray u_slice_color;   // RGBA8 colour, alpha coverage
layout(binding = 9) uniform sampler2DArray u_slice_normal;  // RGBA8 normal (a, y, n), leaf code
layout(binding = 10) uniform sampler2DArray u_slice_depth;  // R32F offset along n [m]
layout(binding = 11) uniform sampler2DArray u_slice_branch; // RGBA32F level-1 branch, x1, x0, +-(root + 1)
layout(binding = 12) uniform sampler2D u_leaf_displacement; // RG8 smooth tileable field

vec3 sylva_slice_axis(int j) {
  float a = float(j) * SYLVA_PI / sylva_slices.extent.z;
  return vec3(cos(a), 0.0, -sin(a));
}
vec3 sylva_slice_normal(int j) {
  float a = float(j) * SYLVA_PI / sylva_slices.extent.z;
  return vec3(sin(a), 0.0, cos(a));
}
// Rest rectangle of every slice in slice coordinates (x along a_j from the centre, y = object y).
vec2 sylva_slice_rect_min() {
  return vec2(-sylva_slices.center_radius.w, sylva_slices.center_radius.y - sylva_slices.extent.x);
}
vec2 sylva_slice_rect_size() { return vec2(2.0 * sylva_slices.center_radius.w, 2.0 * sylva_slices.extent.x); }

// Displacement of the axis point at x of a branch, bent in its rest frame: the LOD0 bend step
// (tree_animation.glsl) with the same control signal, saturation and profile, so slices sway with
// the geometry. Object space [m].
vec3 sylva_branch_displacement(int index, int level, float x, SylvaTreeInstance inst) {
  SylvaTreeBranch b = sylva_branches[index];
  vec3 r = b.r_object.xyz;
  vec3 s = b.s_object.xyz;
  vec2 amp = sylva_branch_control(b, inst, level, r, s);
  float a = sqrt(amp.x * amp.x + amp.y * amp.y);
  if (a == 0.0) return vec3(0.0);
  vec3 e = (amp.x * r + amp.y * s) / a;
  float sat = sylva_saturate_amplitude(a, b.attach_object.w);
  vec4 p = sylva_bend_profile(x, sat, b.s_parent.w, b.t_parent.w, sylva_anim.misc.x);
  return b.r_parent.w * ((p.x - x) * b.t_object.xyz + p.y * e);
}

// Backward transform (seed §2.7, eq. 3.39): the rest point that moves to slice point q. The
// branch map at q names the level-1 branch and the x values of the rest texel there; the forward
// displacement (level-1 branch on the unbent trunk, then the trunk, as in the seed's two-level
// version) is subtracted. Then the scrolling leaf displacement (eq. 3.40, two lookups of a smooth
// field scrolling in two directions, added to the coordinate). Zero wind returns q unchanged.
vec2 sylva_backward_transform(vec2 q, int slice, int direction, SylvaTreeInstance inst) {
  float speed = inst.wind.w;
  if (speed == 0.0 || SYLVA_TREE_ANIMATION == 0) return q;
  float res = sylva_slices.fade_range.z;
  vec2 uv = (q - sylva_slice_rect_min()) / sylva_slice_rect_size();
  ivec2 texel = clamp(ivec2(floor(uv * res)), ivec2(0), ivec2(int(res) - 1));
  vec4 bd = texelFetch(u_slice_branch, ivec3(texel, slice), 0);
  vec3 d = vec3(0.0);
  int b1 = int(round(bd.x));
  if (b1 >= 0 && SYLVA_TREE_ANIMATION >= 2) d += sylva_branch_displacement(b1, 1, clamp(bd.y, 0.0, 1.0), inst);
  d += sylva_branch_displacement(int(round(abs(bd.w))) - 1, 0, clamp(bd.z, 0.0, 1.0), inst);
  vec2 p = q - vec2(dot(d, sylva_slice_axis(direction)), d.y);
#if SYLVA_TREE_ANIMATION >= 3
  if (sylva_anim.leaf2.z != 0.0) {
    vec2 o = q * sylva_slices.misc.x;
    vec2 f = textureLod(u_leaf_displacement, o + sylva_slices.leaf_scroll.xy, 0.0).rg +
             textureLod(u_leaf_displacement, o * 1.7 + sylva_slices.leaf_scroll.zw, 0.0).rg - 1.0;
    p += f * min(sylva_slices.fade_range.w * speed, sylva_slices.misc.w);
  }
#endif
  return p;
}

// Parallax correction with the baked depth map (beyond the seed, which draws slice content on the
// plane): the viewing ray through slice point q meets the layer at depth d (offset along n) at
// q + d * V.xy / V.n, with V the view direction in slice coordinates (a, y, n); three fixed-point
// steps with the depth found there. Content then sits where its depth puts it, so slices seen off
// their normal keep the crown's shape instead of smearing it over the slab. `view` is any vector
// along the viewing ray in object space (its sign does not matter). |V.n| is clamped at 0.35 (70
// degrees off the normal) so grazing views stay bounded.
vec2 sylva_slice_parallax(vec2 q, int slice, int direction, vec3 view) {
  vec3 a = sylva_slice_axis(direction);
  vec3 n = sylva_slice_normal(direction);
  vec3 v = normalize(view);
  float vn = dot(v, n);
  vn = vn < 0.0 ? min(vn, -0.35) : max(vn, 0.35);
  vec2 k = vec2(dot(v, a), v.y) / vn;
  vec2 size = sylva_slice_rect_size();
  vec2 lo = sylva_slice_rect_min();
  float d = textureLod(u_slice_depth, vec3((q - lo) / size, float(slice)), 0.0).r;
  vec2 p = q + k * d;
  d = textureLod(u_slice_depth, vec3((p - lo) / size, float(slice)), 0.0).r;
  p = q + k * d;
  d = textureLod(u_slice_depth, vec3((p - lo) / size, float(slice)), 0.0).r;
  return q + k * d;
}

// Distance along the unit viewing ray from the slice plane to the layer at depth d (same clamp).
float sylva_slice_ray_distance(float d, int direction, vec3 view) {
  float vn = dot(normalize(view), sylva_slice_normal(direction));
  vn = vn < 0.0 ? min(vn, -0.35) : max(vn, 0.35);
  return d / vn;
}

// Direction-selection interval [lo, hi) of direction j for a horizontal object-space view
// direction (seed §2.10 hides view-parallel slices): weight w_k rises with |cos| between the view
// and direction k's normal, weights normalised, so each pixel shows exactly one direction.
// slice.vert evaluates it with the direction to the tree's centre (right for a distant camera);
// the fragment shaders evaluate it again with the direction to the fragment: next to or inside
// the cluster the two differ by up to 90 degrees, and a slice picked by the centre's weights is
// then seen edge-on and smears its texels into streaks (editor report, lod_close_gl_test).
vec2 sylva_slice_pick_range(int j, vec3 view) {
  vec2 h = view.xz;
  float hl = length(h);
  h = hl > 1.0e-6 ? h / hl : vec2(0.0, 1.0);
  int dirs = int(sylva_slices.extent.z);
  float total = 0.0;
  float before = 0.0;
  float own = 0.0;
  for (int k = 0; k < dirs; ++k) {
    float w = smoothstep(sylva_slices.fade_range.x, sylva_slices.fade_range.y, abs(dot(h, sylva_slice_normal(k).xz)));
    if (k < j) before += w;
    if (k == j) own = w;
    total += w;
  }
  total = max(total, 1.0e-6);
  return vec2(before, before + own) / total;
}

// Pixel footprint on the slice [m] for the hashed cells and the minification blend: the geometric
// mean of the two screen-axis derivatives, so a slice seen at a grazing angle (one long axis) is
// not treated as minified (that drew solid blocks of coarse-mip coverage near the camera).
// Arguments: dFdx and dFdy of the slice coordinate (the library is shared with slice.vert).
float sylva_slice_footprint(vec2 dqdx, vec2 dqdy) { return sqrt(length(dqdx) * length(dqdy)); }

// Object-space direction of a world (camera-relative) vector for an instance (inverse yaw).
vec3 sylva_instance_inverse_vector(SylvaTreeInstance inst, vec3 v) {
  float c = inst.rotation.x;
  float s = inst.rotation.y;
  return vec3(c * v.x - s * v.z, v.y, s * v.x + c * v.z);
}

// Stable dither threshold in (0, 1): hash of the rest slice point in power-of-two cells of the
// pixel footprint (metres), per slice and instance, so the pattern sticks to the swaying content.
float sylva_slice_threshold(vec2 q_rest, float footprint, int slice, float salt) {
  float cell = exp2(ceil(log2(max(footprint, 1.0e-6))));
  uint h = sylva_hash(ivec3(ivec2(floor(q_rest / cell)), slice), floatBitsToUint(salt));
  return (float(h >> 8u) + 0.5) * (1.0 / 16777216.0);
}

#endif

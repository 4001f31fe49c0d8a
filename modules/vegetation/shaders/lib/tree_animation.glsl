// LOD0 wind animation (seed 000 §3.1, §4.4): the GLSL twin of src/animation.cpp and of
// bend_profile / saturate_amplitude in <sylva/vegetation/bending.hpp>. Same operations in the same
// order on the same packed data; tree_animation_gl_test compares the two.
//
// SYLVA_TREE_ANIMATION selects how much is animated (seed table 5.5 levels):
//   0 static (rest positions), 1 trunk only, 2 every branch level, 3 branches and leaves (default).
#ifndef SYLVA_VEGETATION_TREE_ANIMATION_GLSL
#define SYLVA_VEGETATION_TREE_ANIMATION_GLSL

#include "render/lib/noise.glsl"
#include "vegetation/lib/tree_data.glsl"

#ifndef SYLVA_TREE_ANIMATION
#define SYLVA_TREE_ANIMATION 3
#endif

#if SYLVA_TREE_ANIMATION == 1
const int SYLVA_ANIMATED_LEVELS = 1;
#else
const int SYLVA_ANIMATED_LEVELS = 4;
#endif

struct SylvaChain {
  vec3 origin;
  vec3 t;
  vec3 r;
  vec3 s;
};

vec3 sylva_instance_vector(SylvaTreeInstance inst, vec3 v) {
  float c = inst.rotation.x;
  float s = inst.rotation.y;
  return vec3(c * v.x + s * v.z, v.y, -s * v.x + c * v.z);
}

vec3 sylva_instance_point(SylvaTreeInstance inst, vec3 p) {
  return inst.translation_scale.xyz + sylva_instance_vector(inst, inst.translation_scale.w * p);
}

// sign(a) max(|a|, eps) with sign(0) = +1 (GLSL's sign(0) = 0 would divide by zero).
float sylva_guard_derivative(float a, float eps) {
  float m = max(abs(a), eps);
  return a < 0.0 ? -m : m;
}

float sylva_saturate_amplitude(float a, float limit) {
  if (isnan(a)) return limit;
  float q = a / limit;
  if (abs(q) <= 1.0) return a / sqrt(1.0 + q * q);
  float iq = 1.0 / q;
  return (q < 0.0 ? -limit : limit) / sqrt(1.0 + iq * iq);
}

// Eq. 3.8 + 3.9: (along, across, cos theta, sin theta) in units of the branch length.
vec4 sylva_bend_profile(float x, float a, float c2, float c4, float eps) {
  float x2 = x * x;
  float u = a * (c2 * x2 + c4 * (x2 * x2));
  float du = a * (2.0 * c2 * x + 4.0 * c4 * (x2 * x));
  float g = sylva_guard_derivative(du, eps);
  float s = sqrt(1.0 + du * du);
  float d = u / g * (s - 1.0);
  float inv_s = 1.0 / s;
  return vec4(x - d * inv_s, u * inv_s, inv_s, du * inv_s);
}

vec2 sylva_branch_control(SylvaTreeBranch b, SylvaTreeInstance inst, int level, vec3 r, vec3 s) {
  vec4 lp = sylva_anim.level[level];
  if (lp.w == 0.0 || level >= SYLVA_ANIMATED_LEVELS) return vec2(0.0);
  vec3 w = inst.wind.xyz;
  float offset = sylva_anim.clock_offset[level] + b.r_object.w + inst.rotation.z * lp.z;
  float nr = sylva_noise1(sylva_anim.clock_cell[level], offset, b.seeds.x);
  float ns = sylva_noise1(sylva_anim.clock_cell[level], offset, b.seeds.y);
  float turb = lp.y * inst.wind.w;
  return vec2(lp.x * dot(w, r) + turb * nr, lp.x * dot(w, s) + turb * ns);
}

void sylva_bend_step(inout SylvaChain c, SylvaTreeBranch b, float x, vec2 amp, float eps) {
  float len = b.r_parent.w;
  float a = sqrt(amp.x * amp.x + amp.y * amp.y);
  if (a == 0.0) {
    c.origin = c.origin + (x * len) * c.t;
    return;
  }
  float inv_a = 1.0 / a;
  float er = amp.x * inv_a;
  float es = amp.y * inv_a;
  vec3 e = er * c.r + es * c.s;
  float sat = sylva_saturate_amplitude(a, b.attach_object.w);
  vec4 p = sylva_bend_profile(x, sat, b.s_parent.w, b.t_parent.w, eps);
  c.origin = c.origin + len * (p.x * c.t + p.y * e);
  vec3 delta = -p.w * c.t + (p.z - 1.0) * e;
  vec3 t_new = p.z * c.t + p.w * e;
  c.r = c.r + er * delta;
  c.s = c.s + es * delta;
  c.t = t_new;
}

SylvaChain sylva_evaluate_chain(uint branch, vec4 xvec, SylvaTreeInstance inst) {
  SylvaTreeBranch own = sylva_branches[branch];
  int level = int(own.s_object.w);
  bool transport = sylva_anim.misc.y != 0.0;
  float eps = sylva_anim.misc.x;
  SylvaChain c;
  c.origin = vec3(0.0);
  c.t = vec3(0.0, 1.0, 0.0);
  c.r = vec3(1.0, 0.0, 0.0);
  c.s = vec3(0.0, 0.0, -1.0);
  for (int k = 0; k <= level; ++k) {
    SylvaTreeBranch b = sylva_branches[own.chain[k]];
    if (k == 0) {
      c.origin = b.attach_object.xyz;
      c.t = b.t_object.xyz;
      c.r = b.r_object.xyz;
      c.s = b.s_object.xyz;
    } else if (transport) {
      vec3 ap = b.attach_parent.xyz;
      c.origin = c.origin + (ap.x * c.r + ap.y * c.s + ap.z * c.t);
      vec3 r = b.r_parent.x * c.r + b.r_parent.y * c.s + b.r_parent.z * c.t;
      vec3 s = b.s_parent.x * c.r + b.s_parent.y * c.s + b.s_parent.z * c.t;
      vec3 t = b.t_parent.x * c.r + b.t_parent.y * c.s + b.t_parent.z * c.t;
      c.r = r;
      c.s = s;
      c.t = t;
    } else {
      c.origin = c.origin + b.attach_object.xyz;
      c.t = b.t_object.xyz;
      c.r = b.r_object.xyz;
      c.s = b.s_object.xyz;
    }
    vec2 amp = sylva_branch_control(b, inst, k, c.r, c.s);
    sylva_bend_step(c, b, xvec[k], amp, eps);
  }
  return c;
}

// Trunk-only animation (level 1 of the seed's table 5.5): the root branch bends and everything
// above the attachment point x0 = xvec[0] moves rigidly with the root's bent frame there. Equal to
// the full chain with every higher level and the leaves disabled (frame transport on), but one bend
// step per vertex instead of one per level. Returns the object-space position and the rest
// normal and tangent turned with it.
void sylva_trunk_rigid(uint branch, vec4 xvec, SylvaTreeInstance inst, vec3 rest_position, vec3 rest_normal,
                       vec3 rest_tangent, out vec3 position, out vec3 normal, out vec3 tangent) {
  SylvaTreeBranch own = sylva_branches[branch];
  SylvaTreeBranch root = sylva_branches[own.chain[0]];
  SylvaChain c;
  c.origin = root.attach_object.xyz;
  c.t = root.t_object.xyz;
  c.r = root.r_object.xyz;
  c.s = root.s_object.xyz;
  vec2 amp = sylva_branch_control(root, inst, 0, c.r, c.s);
  sylva_bend_step(c, root, xvec[0], amp, sylva_anim.misc.x);
  vec3 rest_axis = root.attach_object.xyz + (xvec[0] * root.r_parent.w) * root.t_object.xyz;
  vec3 d = rest_position - rest_axis;
  position = c.origin + dot(d, root.r_object.xyz) * c.r + dot(d, root.s_object.xyz) * c.s + dot(d, root.t_object.xyz) * c.t;
  normal = dot(rest_normal, root.r_object.xyz) * c.r + dot(rest_normal, root.s_object.xyz) * c.s +
           dot(rest_normal, root.t_object.xyz) * c.t;
  tangent = dot(rest_tangent, root.r_object.xyz) * c.r + dot(rest_tangent, root.s_object.xyz) * c.s +
            dot(rest_tangent, root.t_object.xyz) * c.t;
}

uint sylva_leaf_field_seed(uint component) { return sylva_tree_wind.seeds.y + 0x9e3779b9u * (component + 1u); }

vec2 sylva_leaf_control(SylvaTreeLeaf leaf, SylvaTreeInstance inst) {
  if (sylva_anim.leaf2.z == 0.0 || SYLVA_TREE_ANIMATION < 3) return vec2(0.0);
  float speed = inst.wind.w;
  uint octave = uint(sylva_anim.leaf_clock.y);
  ivec3 cell = ivec3(uvec3(sylva_tree_wind.cells.xyz) << octave);
  vec3 rel = sylva_instance_point(inst, leaf.origin.xyz);
  vec3 off = (sylva_tree_wind.turbulence_offset.xyz + rel * sylva_tree_wind.turbulence.z) * sylva_anim.leaf2.y;
  float fx = sylva_noise3(cell, off, sylva_leaf_field_seed(0u));
  float fy = sylva_noise3(cell, off, sylva_leaf_field_seed(1u));
  uint seed = floatBitsToUint(leaf.origin.w);
  float foff = sylva_anim.leaf_clock_offset.x + leaf.n_parent.w + inst.rotation.z * sylva_anim.leaf2.x;
  float nx = sylva_noise1(sylva_anim.leaf_clock.x, foff, seed);
  float ny = sylva_noise1(sylva_anim.leaf_clock.x, foff, seed + 1u);
  float mixv = sylva_anim.leaf.z;
  float ax = sylva_anim.leaf.x * speed * ((1.0 - mixv) * fx + mixv * nx);
  float ay = sylva_anim.leaf.x * sylva_anim.leaf.y * speed * ((1.0 - mixv) * fy + mixv * ny);
  float qx = ax / sylva_anim.leaf.w;
  float qy = ay / sylva_anim.leaf.w;
  return vec2(ax / sqrt(1.0 + qx * qx), ay / sqrt(1.0 + qy * qy));
}

// Deformed leaf vertex in object space: position, normal n2 and blade axis t1 (eq. 3.16).
void sylva_deform_leaf(uint branch, uint leaf_index, vec4 xvec, vec2 corner, SylvaTreeInstance inst,
                       out vec3 position, out vec3 normal, out vec3 tangent) {
  SylvaChain c = sylva_evaluate_chain(branch, xvec, inst);
  SylvaTreeLeaf leaf = sylva_leaves[leaf_index];
  vec3 t0;
  vec3 n0;
  if (sylva_anim.misc.y != 0.0) {
    t0 = leaf.t_parent.x * c.r + leaf.t_parent.y * c.s + leaf.t_parent.z * c.t;
    n0 = leaf.n_parent.x * c.r + leaf.n_parent.y * c.s + leaf.n_parent.z * c.t;
  } else {
    t0 = leaf.t_object.xyz;
    n0 = leaf.n_object.xyz;
  }
  vec2 a = sylva_leaf_control(leaf, inst);
  vec3 t1 = t0;
  vec3 n2 = n0;
  vec3 b2 = cross(t0, n0);
  if (a.x != 0.0 || a.y != 0.0) {
    vec3 b0 = b2;
    t1 = normalize(t0 + n0 * a.x);
    vec3 n1 = cross(b0, t1);
    n2 = normalize(n1 + b0 * a.y);
    b2 = cross(t1, n2);
  }
  position = c.origin + (corner.x * b2 + corner.y * t1);
  normal = n2;
  tangent = t1;
}

#endif

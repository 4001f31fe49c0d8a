#version 450 core
// Leaves of LOD0 trees: the branch chain of their parent, then the leaf's own tilt and twist
// (eq. 3.16), then the instance transform. Compiled with SYLVA_DEPTH_ONLY for the depth pass (the
// varyings the alpha test needs are kept), so every pass deforms identically.
#include "vegetation/lib/tree_animation.glsl"

layout(location = 0) in vec3 a_position;  // rest position (object)
layout(location = 1) in vec3 a_normal;    // rest normal (object)
layout(location = 2) in vec2 a_corner;    // (P_x, P_y) in the leaf frame (b, t)
layout(location = 3) in vec2 a_uv;
layout(location = 4) in vec4 a_xvec;
layout(location = 5) in uint a_branch;
layout(location = 6) in uint a_leaf;

uniform mat4 u_view_proj;
uniform int u_instance_base;

out vec2 v_uv;
flat out float v_season_offset;
out vec3 v_hash_position;  // rest object-space position: the hashed alpha test's stable key  // leaf spread * leafSpecificNumber + instance offset, before the season
#ifndef SYLVA_DEPTH_ONLY
out vec3 v_rel;
out vec3 v_normal;   // front side normal n2 (world)
out vec3 v_tangent;  // blade axis t1 (world)
flat out vec3 v_variation;
#endif

uniform float u_leaf_spread;
flat out float v_fade;  // LOD transition fade of the instance (lod_selection.hpp)

#ifdef SYLVA_TREE_BAKE
flat out int v_root;    // root (trunk) branch
flat out int v_level1;        // level-1 ancestor of the parent branch (-1: the trunk), slice_bake.hpp
out vec2 v_x;                 // x on the level-1 branch, x on the trunk
flat out float v_leaf_number; // leafSpecificNumber
#endif

#ifdef SYLVA_TREE_CAPTURE
layout(std430, binding = 7) writeonly buffer SylvaTreeCapture { vec4 sylva_capture[]; };
#endif

void main() {
  SylvaTreeInstance inst = sylva_instances[u_instance_base + gl_InstanceID];
  vec3 p;
  vec3 n;
  vec3 t;
#if SYLVA_TREE_ANIMATION == 0
  SylvaTreeLeaf leaf0 = sylva_leaves[a_leaf];
  p = a_position;
  n = a_normal;
  t = leaf0.t_object.xyz;
#elif SYLVA_TREE_ANIMATION == 1
  SylvaTreeLeaf leaf0 = sylva_leaves[a_leaf];
  sylva_trunk_rigid(a_branch, a_xvec, inst, a_position, a_normal, leaf0.t_object.xyz, p, n, t);
#else
  sylva_deform_leaf(a_branch, a_leaf, a_xvec, a_corner, inst, p, n, t);
#endif
#ifdef SYLVA_TREE_CAPTURE
  if (gl_InstanceID == 0) {
    sylva_capture[gl_VertexID * 2] = vec4(p, 1.0);
    sylva_capture[gl_VertexID * 2 + 1] = vec4(n, 0.0);
  }
#endif
  vec3 rel = sylva_instance_point(inst, p);
  gl_Position = u_view_proj * vec4(rel, 1.0);
  v_uv = a_uv;
  v_hash_position = a_position;
  v_season_offset = u_leaf_spread * sylva_leaves[a_leaf].t_parent.w + inst.rotation.w;
  v_fade = inst.lod.x;
#ifdef SYLVA_TREE_BAKE
  v_level1 = sylva_branches[a_branch].chain[1];
  v_root = sylva_branches[a_branch].chain[0];
  v_x = vec2(a_xvec.y, a_xvec.x);
  v_leaf_number = sylva_leaves[a_leaf].t_parent.w;
#endif
#ifndef SYLVA_DEPTH_ONLY
  v_rel = rel;
  v_normal = sylva_instance_vector(inst, n);
  v_tangent = sylva_instance_vector(inst, t);
  v_variation = inst.variation.rgb;
#endif
}

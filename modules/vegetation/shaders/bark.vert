#version 450 core
// Bark (branch tubes) of LOD0 trees: the hierarchical bend of lib/tree_animation.glsl, then the
// instance transform. The depth/shadow pass compiles this same file with SYLVA_DEPTH_ONLY, so the
// deformation is identical in every pass.
#include "vegetation/lib/tree_animation.glsl"

layout(location = 0) in vec3 a_position;  // rest position (object)
layout(location = 1) in vec3 a_local;     // offset in the branch frame
layout(location = 2) in vec3 a_normal;    // normal in the branch frame
layout(location = 3) in vec2 a_uv;
layout(location = 4) in vec4 a_xvec;
layout(location = 5) in uint a_branch;

uniform mat4 u_view_proj;  // camera-relative
uniform int u_instance_base;

#ifndef SYLVA_DEPTH_ONLY
out vec3 v_rel;      // camera-relative world position
out vec3 v_normal;   // world
out vec3 v_axis;     // world branch axis
out vec2 v_uv;
#endif

// LOD transitions (lod_selection.hpp): the instance's fade, dithered on the rest position.
flat out float v_fade;
out vec3 v_hash_position;

#ifdef SYLVA_TREE_BAKE
flat out int v_root;    // root (trunk) branch
flat out int v_level1;  // level-1 ancestor branch (-1: the trunk), slice_bake.hpp
out vec2 v_x;           // x on the level-1 branch, x on the trunk
#endif

#ifdef SYLVA_TREE_CAPTURE
layout(std430, binding = 7) writeonly buffer SylvaTreeCapture { vec4 sylva_capture[]; };
#endif

void main() {
  SylvaTreeInstance inst = sylva_instances[u_instance_base + gl_InstanceID];
  vec3 p;
  vec3 n;
  vec3 axis;
#if SYLVA_TREE_ANIMATION == 0
  SylvaTreeBranch b = sylva_branches[a_branch];
  p = a_position;
  n = a_normal.x * b.r_object.xyz + a_normal.y * b.s_object.xyz + a_normal.z * b.t_object.xyz;
  axis = b.t_object.xyz;
#elif SYLVA_TREE_ANIMATION == 1
  SylvaTreeBranch b = sylva_branches[a_branch];
  vec3 rest_n = a_normal.x * b.r_object.xyz + a_normal.y * b.s_object.xyz + a_normal.z * b.t_object.xyz;
  sylva_trunk_rigid(a_branch, a_xvec, inst, a_position, rest_n, b.t_object.xyz, p, n, axis);
#else
  SylvaChain c = sylva_evaluate_chain(a_branch, a_xvec, inst);
  p = c.origin + (a_local.x * c.r + a_local.y * c.s + a_local.z * c.t);
  n = a_normal.x * c.r + a_normal.y * c.s + a_normal.z * c.t;
  axis = c.t;
#endif
#ifdef SYLVA_TREE_CAPTURE
  if (gl_InstanceID == 0) {
    sylva_capture[gl_VertexID * 2] = vec4(p, 1.0);
    sylva_capture[gl_VertexID * 2 + 1] = vec4(n, 0.0);
  }
#endif
  vec3 rel = sylva_instance_point(inst, p);
  gl_Position = u_view_proj * vec4(rel, 1.0);
  v_fade = inst.lod.x;
  v_hash_position = a_position;
#ifdef SYLVA_TREE_BAKE
  v_level1 = sylva_branches[a_branch].chain[1];
  v_root = sylva_branches[a_branch].chain[0];
  v_x = vec2(a_xvec.y, a_xvec.x);
#endif
#ifndef SYLVA_DEPTH_ONLY
  v_rel = rel;
  v_normal = sylva_instance_vector(inst, n);
  v_axis = sylva_instance_vector(inst, axis);
  v_uv = a_uv;
#endif
}

// The packed tree data of <sylva/vegetation/tree_mesh.hpp> and <sylva/vegetation/animation.hpp>
// as GLSL blocks. Binding points are the constants of <sylva/vegetation/tree_renderer.hpp>.
#ifndef SYLVA_VEGETATION_TREE_DATA_GLSL
#define SYLVA_VEGETATION_TREE_DATA_GLSL

#include "render/lib/wind.glsl"

struct SylvaTreeBranch {     // BranchGpu, 160 bytes
  vec4 r_parent;             // xyz rest r in the parent's frame, w length
  vec4 s_parent;             // w c2
  vec4 t_parent;             // w c4
  vec4 attach_parent;        // xyz offset from the parent's axis point, parent frame; w parent x
  vec4 attach_object;        // xyz the same offset in object space (root: start); w amplitude limit
  vec4 r_object;             // w noise phase
  vec4 s_object;             // w level
  vec4 t_object;             // w base radius
  uvec4 seeds;               // x, y noise seeds of the r and s signals
  ivec4 chain;               // ancestor indices by level
};

struct SylvaTreeLeaf {       // LeafGpu, 80 bytes
  vec4 t_parent;             // xyz blade axis in the parent's frame, w leafSpecificNumber
  vec4 n_parent;             // xyz normal in the parent's frame, w flutter phase
  vec4 t_object;             // w width
  vec4 n_object;             // w length
  vec4 origin;               // xyz rest attachment point, w flutter seed bits
};

struct SylvaTreeInstance {   // InstanceGpu, 80 bytes
  vec4 translation_scale;    // xyz camera-relative position, w scale
  vec4 rotation;             // x cos(yaw), y sin(yaw), z time offset, w season offset
  vec4 wind;                 // xyz object-space wind [m/s], w its length
  vec4 variation;            // rgb colour variation, w instance number
  vec4 lod;                  // x transition fade (1 opaque), y LOD coordinate
};

layout(std430, binding = 3) readonly buffer SylvaTreeBranches { SylvaTreeBranch sylva_branches[]; };
layout(std430, binding = 4) readonly buffer SylvaTreeLeaves { SylvaTreeLeaf sylva_leaves[]; };
layout(std430, binding = 5) readonly buffer SylvaTreeInstances { SylvaTreeInstance sylva_instances[]; };

layout(std140, binding = 4) uniform SylvaTreeAnimation {  // AnimationGpu, 176 bytes
  vec4 level[4];             // x response, y turbulence, z frequency, w enabled
  ivec4 clock_cell;
  vec4 clock_offset;
  vec4 leaf;                 // x amplitude, y twist, z flutter share, w saturation
  vec4 leaf2;                // x flutter frequency, y 2^octave, z enabled, w octave
  ivec4 leaf_clock;          // x cell, y octave
  vec4 leaf_clock_offset;    // x offset
  vec4 misc;                 // x epsilon, y frame transport, z wind scale
} sylva_anim;

layout(std140, binding = 1) uniform SylvaTreeWindBlock { SylvaWind sylva_tree_wind; };

#endif

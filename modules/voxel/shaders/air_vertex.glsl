// The vertex shaders' half of the per-vertex aerial perspective (SYLVA_VOXEL_AIR 1, common.glsl;
// the terrain's chunk.vert does the same): the extinction of air and haze per metre along the
// vertex's view ray, which varies smoothly across a face, so it is interpolated; shade.frag
// multiplies it by the pixel's own distance (air_from_vertex in render/lib/fog.glsl).
#ifndef SYLVA_VOXEL_AIR_VERTEX_GLSL
#define SYLVA_VOXEL_AIR_VERTEX_GLSL
#include "voxel/common.glsl"

#if SYLVA_VOXEL_AIR == 1
#include "render/lib/fog.glsl"
out vec3 v_air_extinction;  // [1/block], per channel
#endif

// rel_pos: the vertex's camera-relative position [blocks]. Does nothing for the other variants.
void voxel_air_vertex(vec3 rel_pos) {
#if SYLVA_VOXEL_AIR == 1
  v_air_extinction = air_extinction(rel_pos);
#endif
}

#endif

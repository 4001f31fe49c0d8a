#version 450 core
// Baked plant meshes (plant_mesh.hpp, issue #18): a chunk's plant faces pre-transformed on the
// CPU, drawn indexed; vertex pulling by the index (gl_VertexID). The same varyings as plant.vert's
// cubes, so shade.frag shades both alike.
#include "voxel/common.glsl"
#include "voxel/air_vertex.glsl"

struct PlantMeshVertex {
  float px, py, pz;  // chunk-relative position, blocks
  float u, v;        // voxel_uv of the cube's local corner
  uint normal;       // snorm8 x, y, z
  uint block_face;   // block | (2 * axis + negative) << 16, in the cube's frame
};
layout(std430, binding = 2) readonly buffer VoxelPlantMesh { PlantMeshVertex voxel_mesh[]; };

out vec3 v_rel_pos;
out vec3 v_normal;
out vec2 v_uv;
out float v_ao;
flat out uint v_layer;
flat out uint v_block;

void main() {
  PlantMeshVertex m = voxel_mesh[gl_VertexID];
  uint block = m.block_face & 0xFFFFu;
  uint face = m.block_face >> 16;
  v_rel_pos = u_chunk_offset + vec3(m.px, m.py, m.pz);
  v_normal = unpackSnorm4x8(m.normal).xyz;
  v_uv = vec2(m.u, m.v);
  v_ao = 1.0;
  v_layer = voxel_layer(block, int(face >> 1), (face & 1u) != 0u ? -1 : 1);
  v_block = block;
  voxel_air_vertex(v_rel_pos);
  gl_Position = u_view_projection * vec4(v_rel_pos, 1.0);
}

#version 450 core
// Instanced cubes for L-system plant parts: one instance per turtle-placed block (the seed's
// flyweight, §1.4): chunk-relative centre, edge length, rotation and block.
#include "voxel/common.glsl"

struct PlantPartGpu {
  vec4 center_size;  // xyz centre relative to the chunk origin, w edge length
  uvec4 data;        // x, y: rotation quaternion as snorm16 pairs (xy, zw); z: block id
};
layout(std430, binding = 2) readonly buffer VoxelPlantParts { PlantPartGpu voxel_parts[]; };
uniform uint u_instance_base;

out vec3 v_rel_pos;
out vec3 v_normal;
out vec2 v_uv;
out float v_ao;
flat out uint v_layer;
flat out uint v_block;

vec3 quat_rotate(vec4 q, vec3 v) { return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v); }

void main() {
  PlantPartGpu part = voxel_parts[u_instance_base + uint(gl_InstanceID)];
  vec4 rot = vec4(unpackSnorm2x16(part.data.x), unpackSnorm2x16(part.data.y));
  rot /= max(length(rot), 1e-6);
  uint block = part.data.z;
  int face = gl_VertexID / 6;
  int k = gl_VertexID % 6;
  int axis = face >> 1;
  int sign = (face & 1) != 0 ? -1 : 1;
  ivec2 corner = kVoxelCorners[voxel_corner(k, sign, false)];
  int u = (axis + 1) % 3;
  int v = (axis + 2) % 3;
  vec3 local = vec3(0.0);
  if (sign > 0) local[axis] = 1.0;
  local[u] = float(corner.x);
  local[v] = float(corner.y);
  vec3 normal = vec3(0.0);
  normal[axis] = float(sign);
  float size = part.center_size.w;
  vec3 p = quat_rotate(rot, (local - 0.5) * size) + part.center_size.xyz;
  v_rel_pos = u_chunk_offset + p;
  v_normal = quat_rotate(rot, normal);
  v_uv = voxel_uv(local, axis);
  v_ao = 1.0;
  v_layer = voxel_layer(block, axis, sign);
  v_block = block;
  gl_Position = u_view_projection * vec4(v_rel_pos, 1.0);
}

#version 450 core
// Chunk quads by vertex pulling: 6 vertices per PackedQuad (see mesher.hpp for the bit layout).
#include "voxel/common.glsl"
#include "voxel/air_vertex.glsl"

layout(std430, binding = 1) readonly buffer VoxelQuads { uvec2 voxel_quads[]; };
uniform uint u_quad_base;  // first quad of this draw (alpha-cut quads follow the opaque ones)

out vec3 v_rel_pos;
out vec3 v_normal;
out vec2 v_uv;
out float v_ao;
flat out uint v_layer;
flat out uint v_block;

void main() {
  uvec2 q = voxel_quads[u_quad_base + uint(gl_VertexID) / 6u];
  int k = gl_VertexID % 6;
  ivec3 origin = ivec3(q.x & 63u, (q.x >> 6) & 63u, (q.x >> 12) & 63u);
  int du = int((q.x >> 18) & 63u) + 1;
  int dv = int((q.x >> 24) & 63u) + 1;
  uint block = q.y & 0xffffu;
  int face = int((q.y >> 16) & 7u);
  int axis = face >> 1;
  int sign = (face & 1) != 0 ? -1 : 1;
  uvec4 ao = uvec4((q.y >> 19) & 3u, (q.y >> 21) & 3u, (q.y >> 23) & 3u, (q.y >> 25) & 3u);
  // Split along the diagonal that keeps AO interpolation isotropic (Lysenko 2012).
  bool diagonal13 = ao.x + ao.z > ao.y + ao.w;
  int c = voxel_corner(k, sign, diagonal13);
  ivec2 corner = kVoxelCorners[c];
  int u = (axis + 1) % 3;
  int v = (axis + 2) % 3;
  vec3 p = vec3(origin);
  if (sign > 0) p[axis] += 1.0;
  p[u] += float(corner.x * du);
  p[v] += float(corner.y * dv);
  vec3 normal = vec3(0.0);
  normal[axis] = float(sign);
  v_rel_pos = u_chunk_offset + p;
  v_normal = normal;
  v_uv = voxel_uv(p, axis);
  v_ao = float(ao[c]) / 3.0;
  v_layer = voxel_layer(block, axis, sign);
  v_block = block;
  voxel_air_vertex(v_rel_pos);
  gl_Position = u_view_projection * vec4(v_rel_pos, 1.0);
}

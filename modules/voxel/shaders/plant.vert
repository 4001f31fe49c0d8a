#version 450 core
// Instanced cubes for L-system plant parts: one instance per turtle-placed block (the seed's
// flyweight, §1.4): chunk-relative centre, edge length, rotation and block.
// CROSS_QUADS builds the tuft variant (tufts.hpp): two crossed cut-out quads per instance, the
// foot at center_size.xyz, height center_size.w, a turn about y, data.w = tint rgb + width (unorm8).
#include "voxel/common.glsl"
#include "voxel/air_vertex.glsl"

struct PlantPartGpu {
  vec4 center_size;  // xyz centre relative to the chunk origin, w edge length
  uvec4 data;        // x, y: rotation quaternion as snorm16 pairs (xy, zw); z: block id
};
layout(std430, binding = 2) readonly buffer VoxelPlantParts { PlantPartGpu voxel_parts[]; };
uniform uint u_instance_base;
uniform int u_front_faces_only;  // 1: 18 vertices per instance, the three faces turned to the eye

out vec3 v_rel_pos;
out vec3 v_normal;
out vec2 v_uv;
out float v_ao;
#ifdef CROSS_QUADS
out vec3 v_tint;
#endif
flat out uint v_layer;
flat out uint v_block;

vec3 quat_rotate(vec4 q, vec3 v) { return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v); }

void main() {
  PlantPartGpu part = voxel_parts[u_instance_base + uint(gl_InstanceID)];
  vec4 rot = vec4(unpackSnorm2x16(part.data.x), unpackSnorm2x16(part.data.y));
  rot /= max(length(rot), 1e-6);
  uint block = part.data.z;
#ifdef CROSS_QUADS
  // Quad 0 spans x, quad 1 spans z (before the turn); corner.y runs up the tuft.
  int quad = gl_VertexID / 6;
  ivec2 corner = kVoxelCorners[kVoxelTriA[gl_VertexID % 6]];
  vec4 tint_width = unpackUnorm4x8(part.data.w);
  float across = (float(corner.x) - 0.5) * tint_width.w * 2.0;
  vec3 local = quad == 0 ? vec3(across, 0.0, 0.0) : vec3(0.0, 0.0, across);
  local.y = float(corner.y) * part.center_size.w;
  vec3 p = quat_rotate(rot, local) + part.center_size.xyz;
  v_rel_pos = u_chunk_offset + p;
  // Lit like a leafy tuft rather than a flat card: the quad normal turned toward the viewer and
  // tilted up, so neither side of a tuft turns black (shade.frag does not flip it again).
  vec3 qn = quat_rotate(rot, quad == 0 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0));
  if (dot(qn, -v_rel_pos) < 0.0) qn = -qn;
  v_normal = normalize(qn * 0.5 + vec3(0.0, 1.0, 0.0));
  v_uv = vec2(float(corner.x), -float(corner.y));
  // Darker at the foot, where the blades crowd together (a cheap contact occlusion).
  v_ao = mix(0.7, 1.0, float(corner.y));
  v_tint = tint_width.rgb * 2.0;
  v_layer = voxel_layer(block, 0, 1);
#else
  int face = gl_VertexID / 6;
  int k = gl_VertexID % 6;
  int axis = face >> 1;
  int sign = (face & 1) != 0 ? -1 : 1;
  if (u_front_faces_only != 0) {
    // 18 vertices: per axis the one face whose side of the cube the eye is on (the eye in the
    // part's frame: rotate (eye - centre) back). For a convex cube these are all that can show.
    vec3 eye_local = quat_rotate(vec4(-rot.xyz, rot.w), -u_chunk_offset - part.center_size.xyz);
    axis = face;
    sign = eye_local[axis] >= 0.0 ? 1 : -1;
  }
  // data.w: the part's hidden faces (plant_faces.hpp, bit 2 axis + (sign < 0)); a hidden face
  // collapses to a point outside the clip volume, so it is never rasterised.
  if (((part.data.w >> uint(2 * axis + (sign < 0 ? 1 : 0))) & 1u) != 0u) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
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
#endif
  v_block = block;
  voxel_air_vertex(v_rel_pos);
  gl_Position = u_view_projection * vec4(v_rel_pos, 1.0);
}

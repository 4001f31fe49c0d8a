// Shared declarations of the voxel shaders: the block table, the texture arrays and the
// varyings both the chunk (vertex pulling) and plant (instanced cube) vertex shaders produce.
#ifndef SYLVA_VOXEL_COMMON_GLSL
#define SYLVA_VOXEL_COMMON_GLSL

// One entry per BlockId (C++: VoxelRenderer block table).
struct VoxelBlock {
  uvec4 layers;    // x top, y side, z bottom texture layer; w flags (1 alpha-cut, 2 emissive)
  vec4 emission;   // rgb linear emitted light
  vec4 material;   // x specular intensity, y Phong shininess
};
// The air between the camera and a face (VoxelRenderSettings::aerial_perspective): 0 per pixel
// (apply_fog in shade.frag), 1 per vertex (VOXEL_AIR_VERTEX in the vertex shaders: the
// extinction per metre, interpolated; air_from_vertex per pixel), 2 off.
#ifndef SYLVA_VOXEL_AIR
#define SYLVA_VOXEL_AIR 0
#endif

layout(std430, binding = 3) readonly buffer VoxelBlocks { VoxelBlock voxel_blocks[]; };

layout(binding = 0) uniform sampler2DArray u_diffuse;   // sRGB albedo + cut-out alpha
layout(binding = 1) uniform sampler2DArray u_specular;  // specular intensity map (seed §2.3.2)

uniform mat4 u_view_projection;  // camera-relative
uniform vec3 u_chunk_offset;     // chunk origin - camera position, computed in double on the CPU
uniform float u_alpha_cutoff;

// Texture layer of a block's face; axis 0 x, 1 y, 2 z; sign +1 / -1.
uint voxel_layer(uint block, int axis, int sign) {
  uvec4 l = voxel_blocks[block].layers;
  return axis == 1 ? (sign > 0 ? l.x : l.z) : l.y;
}

// Texture coordinates of a point on a face, in blocks: the two axes across the face, with t
// running down world y on side faces so textures stand upright.
vec2 voxel_uv(vec3 p, int axis) {
  if (axis == 1) return p.xz;
  if (axis == 0) return vec2(p.z, -p.y);
  return vec2(p.x, -p.y);
}

const ivec2 kVoxelCorners[4] = ivec2[](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 1));
// Corner indices of the two triangles of a quad for diagonal 0-2 / 1-3, counter-clockwise
// seen from the +normal side; reversed for faces pointing along -axis.
const int kVoxelTriA[6] = int[](0, 1, 2, 0, 2, 3);
const int kVoxelTriB[6] = int[](0, 1, 3, 1, 2, 3);
const int kVoxelTriARev[6] = int[](0, 2, 1, 0, 3, 2);
const int kVoxelTriBRev[6] = int[](0, 3, 1, 1, 3, 2);

int voxel_corner(int k, int sign, bool diagonal13) {
  if (sign > 0) return diagonal13 ? kVoxelTriB[k] : kVoxelTriA[k];
  return diagonal13 ? kVoxelTriBRev[k] : kVoxelTriARev[k];
}

#endif

#pragma once
// A chunk's plant parts baked into one static indexed mesh (issue #18, "Voxel world"; the next
// step after the instanced cubes of plant_batch: on llvmpipe plant cost follows vertices through
// the vertex shader, and an instanced cube runs 18-36 of them per part every frame). Plants do not
// sway (plant.vert has no wind), so the parts can be transformed once, on the CPU, when a chunk's
// plants change: each visible face becomes 4 shared vertices and 6 indices, and faces are grouped
// by the direction they point so a whole group that no eye position can see is skipped by one
// comparison per group (PlantMesh::visible_groups) instead of per vertex.
//
// Used by the renderer for far plant shells (VoxelRenderSettings::plant_far_mesh) and for the
// near plants' exact parts (plant_near_mesh), both on by default; shadow passes keep the
// instanced cubes (plant.vert).

#include <sylva/voxel/block.hpp>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace sylva::voxel {

// One cube to bake: chunk-relative centre (blocks), edge length (> 0), rotation, block and the
// hidden-face mask of plant_faces.hpp (bit 2 * axis + (negative ? 1 : 0), in the cube's own frame).
struct PlantMeshPart {
  glm::vec3 center{0.0f};
  float size = 1.0f;
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};
  BlockId block = kAir;
  std::uint8_t hidden = 0;
};

// 28 bytes, what plant.vert computes per vertex: chunk-relative position, texture coordinates in
// blocks (voxel_uv of the cube's local corner), the normal as snorm8 x, y, z, and the block with
// the face in the cube's frame (block | (2 * axis + negative) << 16) for the texture layer.
struct PlantMeshVertex {
  float position[3];
  float uv[2];
  std::uint32_t normal;
  std::uint32_t block_face;
};
static_assert(sizeof(PlantMeshVertex) == 28);

// Groups 0-5: faces whose chunk-space normal is exactly +x, -x, +y, -y, +z, -z (cubes turned only
// by quarter turns about y, e.g. every far shell); group 6: every other face (turned parts), always
// drawn. Indices are stored group after group.
inline constexpr int kPlantMeshGroups = 7;

struct PlantMesh {
  std::vector<PlantMeshVertex> vertices;  // 4 per face, shared by its two triangles
  std::vector<std::uint32_t> indices;     // 6 per face, counter-clockwise seen from outside
  struct Group {
    std::uint32_t first = 0;  // first index
    std::uint32_t count = 0;  // indices
    // Groups 0-5: the outermost face plane against the normal (for +x the least x of its faces,
    // for -x the greatest): an eye on the far side of it sees no face of the group.
    float plane = 0.0f;
  };
  std::array<Group, kPlantMeshGroups> groups{};
  // Per plant (bake_plant_mesh's `plant_starts`; one cluster for all parts without them): its
  // indices in each group. Inside a group the plants follow each other in order, so plants
  // i..j-1 are the one range [clusters[i].first[g], clusters[j - 1].first[g] + count[g]).
  struct Cluster {
    std::array<std::uint32_t, kPlantMeshGroups> first{};
    std::array<std::uint32_t, kPlantMeshGroups> count{};
  };
  std::vector<Cluster> clusters;
  std::uint64_t triangles() const { return indices.size() / 3; }

  // Bit g set: group g may face an eye at `eye` (chunk-relative, blocks). Empty groups are clear.
  // A face is turned away when the eye lies on or behind its plane; back-face culling then drops
  // it anyway, so leaving such a group out changes no pixel.
  std::uint32_t visible_groups(const glm::vec3& eye) const;
};

// Bakes `parts` (faces in `hidden` left out, parts with all six hidden add nothing). Not fallible:
// parts with a non-finite or non-positive size are skipped. `plant_starts` (optional, ascending,
// each <= parts.size()): the index of each plant's first part, one cluster per entry (the first
// entry should be 0; parts before it belong to no cluster but are baked).
PlantMesh bake_plant_mesh(std::span<const PlantMeshPart> parts, std::span<const std::uint32_t> plant_starts = {});

}  // namespace sylva::voxel

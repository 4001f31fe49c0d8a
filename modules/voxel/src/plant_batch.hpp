#pragma once
// A chunk's plant parts as the instance list plant.vert reads (internal to the renderer): one
// instance per turtle-placed block (the seed's flyweight, §1.4) minus the parts hidden inside
// others, with per-part hidden-face masks (plant_faces.hpp) so the vertex shader collapses faces
// no camera can see. Issue #18: L-system plants at world scale.

#include <sylva/render/frustum.hpp>
#include <sylva/voxel/plant_faces.hpp>
#include <sylva/voxel/world.hpp>
#include <sylva/voxel/worldgen.hpp>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace sylva::voxel {

// std430 layout of plant.vert's PlantPartGpu: chunk-relative centre (tufts: foot) and size,
// rotation as two snorm16 pairs, block, extra (plants: hidden-face masks, see PlantBatch; tufts:
// tint and width as unorm8).
struct PlantPartGpu {
  float center_size[4];
  std::uint32_t data[4];
};
static_assert(sizeof(PlantPartGpu) == 32);

PlantPartGpu make_part(const glm::vec3& center, float size, const glm::quat& q, BlockId block, std::uint32_t extra);

// Far plants (issue #18): a plant's parts snapped to a grid of its start block size, one cube per
// occupied cell (the class with more parts in it wins: opaque on a tie), so neighbours touch face
// to face and the faces between them, and the crown's inner cubes, are hidden: the far model is
// the plant's outer shell. Near plants keep their exact parts (hidden faces by opaque parts only:
// leaves are seen through their holes).
struct PlantBatch {
  // Layout: [near opaque][near cut-out][far opaque][far cut-out]; parts with every face hidden
  // are left out. PlantPartGpu::data[3] holds the part's hidden-face mask (plant_faces.hpp bits).
  std::vector<PlantPartGpu> parts;
  std::uint32_t count[2][2] = {{0, 0}, {0, 0}};  // [near 0 / far 1][opaque 0 / cut-out 1]
  std::uint32_t first[2][2] = {{0, 0}, {0, 0}};  // index of the first part of each range
  std::size_t parts_hidden = 0;                  // near parts left out (every face hidden)
  // Triangles of the faces not hidden per range: all faces (near leaves, shadows) and at most
  // three per part (the faces turned to the eye; view-dependent, so an upper bound).
  std::uint64_t triangles_all[2][2] = {{0, 0}, {0, 0}};
  std::uint64_t triangles_front[2][2] = {{0, 0}, {0, 0}};
  render::Aabb box{glm::dvec3(1e300), glm::dvec3(-1e300)};  // world; empty when min > max
  // Per plant, in order (per-plant culling draws runs of neighbouring visible plants): its
  // bounds and where its parts start in each range, with the triangles before it in that range.
  struct Plant {
    render::Aabb box;  // world
    std::uint32_t first[2][2];
    std::uint64_t triangles_all[2][2];
    std::uint64_t triangles_front[2][2];
  };
  std::vector<Plant> plants;
};

// Hidden-face masks per cached plant model (seed §4.7: computed once per variant, reused by every
// plant of it). Not thread-safe.
class PlantFaceCache {
 public:
  // `far_cell`: the far grid's edge in start block sizes (VoxelRenderSettings::plant_far_cell).
  explicit PlantFaceCache(float far_cell = 1.0f) : far_cell_(far_cell) {}
  float far_cell() const { return far_cell_; }
  struct FarPart {
    PlantPart part;
    int output = 0;
    std::uint8_t hidden = 0;
  };
  struct Model {
    std::vector<std::uint8_t> near;  // hidden faces of the model's parts, outputs in order, then parts
    std::vector<FarPart> far;        // the far shell, hidden parts left out
  };
  const Model& model(const PlantModel& model, const WorldGenerator& generator, SpeciesIndex species);
  void clear() { cache_.clear(); }

 private:
  float far_cell_ = 1.0f;
  std::unordered_map<const PlantModel*, Model> cache_;
};

// The plants of chunk `c`. `hide_faces` false keeps every part and face (the instanced picture
// before issue #18, for comparisons).
PlantBatch build_plant_batch(const World& world, const WorldGenerator& generator, const ChunkCoord& c,
                             bool hide_faces, PlantFaceCache& cache);

}  // namespace sylva::voxel

#include "plant_batch.hpp"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <bit>
#include <cmath>

namespace sylva::voxel {

PlantPartGpu make_part(const glm::vec3& center, float size, const glm::quat& q, BlockId block, std::uint32_t extra) {
  PlantPartGpu g;
  g.center_size[0] = center.x;
  g.center_size[1] = center.y;
  g.center_size[2] = center.z;
  g.center_size[3] = size;
  g.data[0] = glm::packSnorm2x16(glm::vec2(q.x, q.y));
  g.data[1] = glm::packSnorm2x16(glm::vec2(q.z, q.w));
  g.data[2] = block;
  g.data[3] = extra;
  return g;
}

const PlantFaceCache::Model& PlantFaceCache::model(const PlantModel& model, const WorldGenerator& generator,
                                                   SpeciesIndex species) {
  auto it = cache_.find(&model);
  if (it != cache_.end()) return it->second;
  const BlockPalette& palette = generator.palette();
  std::vector<FacePart> parts;
  for (int o = 0; o < kPlantOutputs; ++o) {
    const BlockId block = generator.part_block(species, o);
    if (block == kAir) continue;
    const bool opaque = palette.render(block) != RenderClass::kAlphaCut;
    for (const PlantPart& part : model.outputs[static_cast<std::size_t>(o)]) parts.push_back({part, opaque, o});
  }
  Model m;
  m.near = hidden_faces(parts, false);
  // The grid of the start block size (far_cell 1): trunks keep their thickness, leaves their block size.
  const std::vector<FacePart> shell = snap_to_grid(parts, model.start_size * far_cell_);
  const std::vector<std::uint8_t> hidden = hidden_faces(shell, true);
  for (std::size_t i = 0; i < shell.size(); ++i) {
    if (hidden[i] != kAllFaces) m.far.push_back({shell[i].part, shell[i].tag, hidden[i]});
  }
  return cache_.emplace(&model, std::move(m)).first->second;
}

namespace {

std::uint64_t triangles_all(std::uint8_t hidden) { return 2u * static_cast<unsigned>(6 - std::popcount(hidden)); }
// The three faces turned to the eye are one per axis: a face shows unless it is hidden, so per
// axis at most one, and none when both faces of the axis are hidden.
std::uint64_t triangles_front(std::uint8_t hidden) {
  std::uint64_t n = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const std::uint8_t both = face_bit(axis, false) | face_bit(axis, true);
    if ((hidden & both) != both) n += 2;
  }
  return n;
}

}  // namespace

PlantBatch build_plant_batch(const World& world, const WorldGenerator& generator, const ChunkCoord& c,
                             bool hide_faces, PlantFaceCache& cache) {
  PlantBatch batch;
  const auto* plants = world.plants(c);
  if (!plants || plants->empty()) return batch;
  const BlockPalette& palette = world.palette();
  const BlockPos origin = chunk_origin(c);
  const glm::dvec3 chunk_base(static_cast<double>(origin.x), static_cast<double>(origin.y), static_cast<double>(origin.z));
  std::vector<PlantPartGpu> lists[2][2];  // [near / far][opaque / cut-out]
  auto add = [&](int lod, BlockId block, const glm::vec3& center, float size, const glm::quat& q, std::uint8_t hidden) {
    const int cut = palette.render(block) == RenderClass::kAlphaCut ? 1 : 0;
    lists[lod][cut].push_back(make_part(center, size, q, block, hidden));
    batch.triangles_all[lod][cut] += triangles_all(hidden);
    batch.triangles_front[lod][cut] += triangles_front(hidden);
  };
  for (const PlantInstance& p : *plants) {
    PlantBatch::Plant range;
    for (int lod = 0; lod < 2; ++lod)
      for (int cut = 0; cut < 2; ++cut) {
        range.first[lod][cut] = static_cast<std::uint32_t>(lists[lod][cut].size());
        range.triangles_all[lod][cut] = batch.triangles_all[lod][cut];
        range.triangles_front[lod][cut] = batch.triangles_front[lod][cut];
      }
    const PlantVariants& variants = generator.variants(p.species);
    const PlantModel& model = variants.at(p.variant % variants.size());
    const PlantFaceCache::Model& faces = cache.model(model, generator, p.species);
    const glm::quat yaw = glm::angleAxis(static_cast<float>(p.yaw_quarters) * 1.5707963f, glm::vec3(0, 1, 0));
    // Ground block centre relative to the chunk origin.
    const glm::vec3 base(static_cast<float>(p.ground.x - origin.x) + 0.5f, static_cast<float>(p.ground.y - origin.y) + 0.5f,
                         static_cast<float>(p.ground.z - origin.z) + 0.5f);
    std::size_t index = 0;
    for (int o = 0; o < kPlantOutputs; ++o) {
      const BlockId block = generator.part_block(p.species, o);
      if (block == kAir) continue;
      for (const PlantPart& part : model.outputs[static_cast<std::size_t>(o)]) {
        const std::uint8_t hidden = hide_faces ? turn_faces(faces.near[index], p.yaw_quarters) : 0;
        ++index;
        if (hidden == kAllFaces) {
          ++batch.parts_hidden;
          continue;
        }
        add(0, block, base + yaw * part.position, part.size, yaw * part.orientation, hidden);
      }
    }
    for (const PlantFaceCache::FarPart& f : faces.far) {
      add(1, generator.part_block(p.species, f.output), base + yaw * f.part.position, f.part.size, glm::quat(1, 0, 0, 0),
          turn_faces(f.hidden, p.yaw_quarters));
    }
    // Bounds: any turn about y keeps the model inside the circle through its farthest box corner.
    // (The far shell's cubes stay within half a cell of the parts' centres: inside these bounds
    // grown by half a far cell.)
    const float half_cell = 0.5f * model.start_size * std::max(cache.far_cell(), 1.0f);
    const glm::vec3 lo = model.bounds_min - half_cell, hi = model.bounds_max + half_cell;
    const double r = std::sqrt(std::max(lo.x * lo.x, hi.x * hi.x) + std::max(lo.z * lo.z, hi.z * hi.z));
    const glm::dvec3 world_base = chunk_base + glm::dvec3(base);
    range.box = {world_base + glm::dvec3(-r, lo.y, -r), world_base + glm::dvec3(r, hi.y, r)};
    batch.box.min = glm::min(batch.box.min, range.box.min);
    batch.box.max = glm::max(batch.box.max, range.box.max);
    batch.plants.push_back(range);
  }
  for (int lod = 0; lod < 2; ++lod)
    for (int cut = 0; cut < 2; ++cut) {
      batch.first[lod][cut] = static_cast<std::uint32_t>(batch.parts.size());
      batch.count[lod][cut] = static_cast<std::uint32_t>(lists[lod][cut].size());
      batch.parts.insert(batch.parts.end(), lists[lod][cut].begin(), lists[lod][cut].end());
      for (PlantBatch::Plant& plant : batch.plants) plant.first[lod][cut] += batch.first[lod][cut];
    }
  return batch;
}

}  // namespace sylva::voxel

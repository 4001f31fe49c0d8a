#include <sylva/voxel/world.hpp>

#include <sylva/core/assert.hpp>

#include <algorithm>

namespace sylva::voxel {

World::World(const BlockPalette& palette) : palette_(&palette) {}

BlockId World::get(const BlockPos& p) const {
  const Chunk* c = find(chunk_of(p));
  return c ? c->get(local_of(p.x), local_of(p.y), local_of(p.z)) : kAir;
}

bool World::set(const BlockPos& p, BlockId id) {
  SYLVA_ASSERT(id < palette_->size(), "block id {} outside palette of {}", id, palette_->size());
  const ChunkCoord cc = chunk_of(p);
  auto it = slots_.find(cc);
  if (it == slots_.end()) {
    if (id == kAir) return false;
    // A new all-air chunk looks to its neighbours exactly like the missing one it replaces, so
    // only the edited block below marks meshes.
    it = slots_.emplace(cc, Slot{}).first;
  }
  const int lx = local_of(p.x), ly = local_of(p.y), lz = local_of(p.z);
  if (!it->second.chunk.set(lx, ly, lz, id)) return false;
  // A plant stands on its ground block: changing that block removes the plant (the same rule
  // populate() applies when a saved chunk is loaded, so edits and reloads agree).
  auto& plants = it->second.plants;
  const auto before = plants.size();
  std::erase_if(plants, [&p](const PlantInstance& plant) { return plant.ground == p; });
  if (plants.size() != before) ++plant_epoch_;
  // The edited block lies in the padded ring of every neighbour it borders (AO reads diagonals).
  auto range = [](int l, int& lo, int& hi) {
    lo = l == 0 ? -1 : 0;
    hi = l == kChunkSize - 1 ? 1 : 0;
  };
  int x0, x1, y0, y1, z0, z1;
  range(lx, x0, x1);
  range(ly, y0, y1);
  range(lz, z0, z1);
  for (int dy = y0; dy <= y1; ++dy) {
    for (int dz = z0; dz <= z1; ++dz) {
      for (int dx = x0; dx <= x1; ++dx) mark_dirty(cc.offset(dx, dy, dz));
    }
  }
  return true;
}

Chunk* World::find(const ChunkCoord& c) {
  auto it = slots_.find(c);
  return it == slots_.end() ? nullptr : &it->second.chunk;
}

const Chunk* World::find(const ChunkCoord& c) const {
  auto it = slots_.find(c);
  return it == slots_.end() ? nullptr : &it->second.chunk;
}

Chunk& World::insert(const ChunkCoord& c, Chunk chunk) {
  Slot& slot = slots_[c];
  slot.chunk = std::move(chunk);
  mark_ring(c);
  return slot.chunk;
}

bool World::erase(const ChunkCoord& c) {
  auto it = slots_.find(c);
  if (it == slots_.end()) return false;
  if (!it->second.plants.empty()) ++plant_epoch_;
  slots_.erase(it);
  mark_ring(c);
  ++mesh_epoch_;
  return true;
}

void World::set_plants(const ChunkCoord& c, std::vector<PlantInstance> plants) {
  auto it = slots_.find(c);
  if (it == slots_.end()) return;
  it->second.plants = std::move(plants);
  ++plant_epoch_;
}

const std::vector<PlantInstance>* World::plants(const ChunkCoord& c) const {
  auto it = slots_.find(c);
  return it == slots_.end() ? nullptr : &it->second.plants;
}

void World::mark_ring(const ChunkCoord& c) {
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dx = -1; dx <= 1; ++dx) mark_dirty(c.offset(dx, dy, dz));
    }
  }
}

void World::mark_dirty(const ChunkCoord& c) {
  auto it = slots_.find(c);
  if (it == slots_.end()) return;
  it->second.dirty = true;
  ++it->second.revision;
}

void World::for_each_chunk(const std::function<void(const ChunkCoord&, const Chunk&)>& fn) const {
  for (const auto& [c, slot] : slots_) fn(c, slot.chunk);
}

std::vector<ChunkCoord> World::chunk_coords() const {
  std::vector<ChunkCoord> out;
  out.reserve(slots_.size());
  for (const auto& [c, slot] : slots_) out.push_back(c);
  std::sort(out.begin(), out.end());
  return out;
}

void World::gather_padded(const ChunkCoord& c, PaddedBlocks& out) const {
  constexpr int n = kChunkSize;
  if (out.n != n) out = PaddedBlocks(n);
  // 27 boxes: for each axis, offset -1 covers padded coordinate -1 (neighbour's n-1), 0 covers
  // [0, n), +1 covers n (neighbour's 0).
  for (int oy = -1; oy <= 1; ++oy) {
    for (int oz = -1; oz <= 1; ++oz) {
      for (int ox = -1; ox <= 1; ++ox) {
        const Chunk* src = find(c.offset(ox, oy, oz));
        auto span = [](int o, int& lo, int& hi, int& src0) {
          if (o < 0) { lo = -1; hi = -1; src0 = n - 1; }
          else if (o > 0) { lo = n; hi = n; src0 = 0; }
          else { lo = 0; hi = n - 1; src0 = 0; }
        };
        int x0, x1, sx, y0, y1, sy, z0, z1, sz;
        span(ox, x0, x1, sx);
        span(oy, y0, y1, sy);
        span(oz, z0, z1, sz);
        if (!src || src->is_uniform()) {
          const BlockId fill = src ? src->uniform_id() : kAir;
          for (int y = y0; y <= y1; ++y)
            for (int z = z0; z <= z1; ++z)
              for (int x = x0; x <= x1; ++x) out.set(x, y, z, fill);
          continue;
        }
        const auto blocks = src->blocks();
        for (int y = y0; y <= y1; ++y) {
          for (int z = z0; z <= z1; ++z) {
            const BlockId* row = blocks.data() + local_index(sx, sy + (y - y0), sz + (z - z0));
            BlockId* dst = out.ids.data() + out.index(x0, y, z);
            std::copy(row, row + (x1 - x0 + 1), dst);
          }
        }
      }
    }
  }
}

std::vector<ChunkCoord> World::dirty_chunks() const {
  std::vector<ChunkCoord> out;
  for (const auto& [c, slot] : slots_) {
    if (slot.dirty) out.push_back(c);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<ChunkCoord> World::remesh(Mesher& mesher) {
  std::vector<ChunkCoord> done = dirty_chunks();
  PaddedBlocks padded(kChunkSize);
  for (const ChunkCoord& c : done) {
    Slot& slot = slots_.at(c);
    gather_padded(c, padded);
    mesher.mesh(padded, *palette_, slot.mesh);
    slot.dirty = false;
  }
  if (!done.empty()) ++mesh_epoch_;
  return done;
}

bool World::store_mesh(const ChunkCoord& c, ChunkMesh mesh, std::uint64_t revision) {
  auto it = slots_.find(c);
  if (it == slots_.end() || it->second.revision != revision) return false;
  it->second.mesh = std::move(mesh);
  it->second.dirty = false;
  ++mesh_epoch_;
  return true;
}

const ChunkMesh* World::mesh(const ChunkCoord& c) const {
  auto it = slots_.find(c);
  return it == slots_.end() ? nullptr : &it->second.mesh;
}

std::uint64_t World::revision(const ChunkCoord& c) const {
  auto it = slots_.find(c);
  return it == slots_.end() ? 0 : it->second.revision;
}

}  // namespace sylva::voxel

#pragma once
// World: the unbounded map of chunks, block edits, and which chunk meshes are stale.
//
// Invariant (tested): after set(), exactly the loaded chunks whose padded ring contains the edited
// block are marked for re-meshing: the block's own chunk, plus for each axis on which the block
// lies on the chunk border the neighbour across it (faces, edges and corners of the 3x3x3
// neighbourhood, because per-vertex AO reads diagonal neighbours). Nothing else is re-meshed.
// Not thread-safe: world generation builds chunks on workers and inserts them on one thread.

#include <sylva/voxel/block.hpp>
#include <sylva/voxel/chunk.hpp>
#include <sylva/voxel/coords.hpp>
#include <sylva/voxel/flora.hpp>
#include <sylva/voxel/mesher.hpp>

#include <functional>
#include <memory>
#include <unordered_map>
#include <vector>

namespace sylva::voxel {

class World {
 public:
  explicit World(const BlockPalette& palette = BlockPalette::standard());

  const BlockPalette& palette() const { return *palette_; }

  // Air where no chunk is loaded.
  BlockId get(const BlockPos& p) const;
  // Creates the chunk when needed. Returns true when the block changed (and meshes were marked).
  // Changing the ground block of a plant removes that plant.
  bool set(const BlockPos& p, BlockId id);

  Chunk* find(const ChunkCoord& c);
  const Chunk* find(const ChunkCoord& c) const;
  // Inserts or replaces a chunk; marks it and its 26 loaded neighbours for re-meshing.
  Chunk& insert(const ChunkCoord& c, Chunk chunk);
  // Unloads a chunk and its mesh; marks its loaded neighbours. False when it was not loaded.
  bool erase(const ChunkCoord& c);
  std::size_t chunk_count() const { return slots_.size(); }
  void for_each_chunk(const std::function<void(const ChunkCoord&, const Chunk&)>& fn) const;
  std::vector<ChunkCoord> chunk_coords() const;  // sorted

  // The chunk plus a one-block ring from its neighbours (missing neighbours read as air).
  void gather_padded(const ChunkCoord& c, PaddedBlocks& out) const;

  // Chunks whose mesh is stale, sorted.
  std::vector<ChunkCoord> dirty_chunks() const;
  void mark_dirty(const ChunkCoord& c);
  // Re-meshes every stale chunk with `mesher`; returns their coordinates, sorted.
  std::vector<ChunkCoord> remesh(Mesher& mesher);
  // Stores a mesh built elsewhere (e.g. on a worker) if the chunk is still at `revision`;
  // returns false (and keeps it dirty) when the chunk changed meanwhile.
  bool store_mesh(const ChunkCoord& c, ChunkMesh mesh, std::uint64_t revision);
  // The mesh of a loaded chunk (empty before its first remesh), or nullptr.
  const ChunkMesh* mesh(const ChunkCoord& c) const;
  // A counter that changes whenever any mesh is stored (renderer upload trigger).
  std::uint64_t mesh_epoch() const { return mesh_epoch_; }

  // Mesh revision of a chunk: bumped whenever its own blocks or its border ring change.
  std::uint64_t revision(const ChunkCoord& c) const;

  // L-system plants standing in a loaded chunk (instanced, not voxels). Setting them bumps
  // plant_epoch(). Plants of chunks that are not loaded are dropped. Plants are not saved in
  // region files: they are a pure function of the seed and the chunk's generated blocks, and
  // populate() regenerates them, dropping those whose ground block an edit changed (see
  // world_builder.hpp). Plants set here by other means are therefore not persistent.
  void set_plants(const ChunkCoord& c, std::vector<PlantInstance> plants);
  const std::vector<PlantInstance>* plants(const ChunkCoord& c) const;
  std::uint64_t plant_epoch() const { return plant_epoch_; }

 private:
  struct Slot {
    Chunk chunk;
    ChunkMesh mesh;
    std::vector<PlantInstance> plants;
    bool dirty = true;
    std::uint64_t revision = 0;  // bumped with every change affecting the mesh
  };
  void mark_ring(const ChunkCoord& c);

  const BlockPalette* palette_;
  std::unordered_map<ChunkCoord, Slot, ChunkCoordHash> slots_;
  std::uint64_t mesh_epoch_ = 0;
  std::uint64_t plant_epoch_ = 0;
};

}  // namespace sylva::voxel

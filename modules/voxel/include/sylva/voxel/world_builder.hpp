#pragma once
// Filling a World from region files and the generator on a worker pool, and re-meshing in
// parallel. Generation and meshing run on the workers; the World is only written on the calling
// thread, so it needs no locks.

#include <sylva/core/result.hpp>
#include <sylva/voxel/mesher.hpp>
#include <sylva/voxel/region.hpp>
#include <sylva/voxel/world.hpp>
#include <sylva/voxel/worker_pool.hpp>
#include <sylva/voxel/worldgen.hpp>

#include <atomic>
#include <functional>
#include <span>
#include <vector>

namespace sylva::voxel {

struct PopulateReport {
  std::size_t generated = 0;    // chunks made by the generator (never saved before)
  std::size_t loaded = 0;       // chunks read back from region files
  std::size_t regenerated = 0;  // chunks whose saved copy was unreadable, generated again
  std::vector<Error> region_errors;  // what was unreadable (file and chunk named)
  bool cancelled = false;
  double milliseconds = 0.0;
};

// Chunk coordinates of a box of chunks around `center`: |dx|, |dz| <= radius_xz, dy in [y_min, y_max].
std::vector<ChunkCoord> chunk_box(const ChunkCoord& center, int radius_xz, std::int64_t y_min, std::int64_t y_max);
// The chunk-y range that can hold ground and plants for these settings.
void chunk_y_range(const WorldGenSettings& settings, std::int64_t& y_min, std::int64_t& y_max);

// Loads (store may be null) or generates every listed chunk that is not loaded yet and inserts it
// with its plants. A corrupt region or chunk is reported in the result and regenerated, never
// fatal. progress(done, total) is called on the calling thread after each batch.
PopulateReport populate(World& world, const WorldGenerator& generator, std::span<const ChunkCoord> chunks,
                        WorkerPool& pool, RegionStore* store = nullptr, const std::atomic<bool>* cancel = nullptr,
                        const std::function<void(std::size_t, std::size_t)>& progress = {});

// Re-meshes every stale chunk on the pool (one mesher per worker); returns their coordinates.
std::vector<ChunkCoord> remesh_parallel(World& world, WorkerPool& pool, MesherKind kind);

}  // namespace sylva::voxel

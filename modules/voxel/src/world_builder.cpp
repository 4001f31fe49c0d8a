#include <sylva/voxel/world_builder.hpp>

#include <sylva/core/log.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

namespace sylva::voxel {

std::vector<ChunkCoord> chunk_box(const ChunkCoord& center, int radius_xz, std::int64_t y_min, std::int64_t y_max) {
  std::vector<ChunkCoord> out;
  for (std::int64_t y = y_min; y <= y_max; ++y)
    for (int dz = -radius_xz; dz <= radius_xz; ++dz)
      for (int dx = -radius_xz; dx <= radius_xz; ++dx) out.push_back({center.x + dx, y, center.z + dz});
  return out;
}

void chunk_y_range(const WorldGenSettings& s, std::int64_t& y_min, std::int64_t& y_max) {
  const double lo = s.base_height - 1.7 * s.height_amplitude - 4.0;
  const double hi = s.base_height + 1.7 * s.height_amplitude + 2.0;
  y_min = static_cast<std::int64_t>(std::floor(lo)) >> kChunkShift;
  y_max = static_cast<std::int64_t>(std::floor(hi)) >> kChunkShift;
}

PopulateReport populate(World& world, const WorldGenerator& generator, std::span<const ChunkCoord> chunks,
                        WorkerPool& pool, RegionStore* store, const std::atomic<bool>* cancel,
                        const std::function<void(std::size_t, std::size_t)>& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  PopulateReport report;
  std::vector<ChunkCoord> todo;
  for (const auto& c : chunks) {
    if (!world.find(c)) todo.push_back(c);
  }
  // Region reads happen here on the calling thread (the store caches decoded regions).
  struct Job {
    ChunkCoord coord;
    std::optional<Chunk> saved;
    bool was_corrupt = false;
    GeneratedChunk result;
  };
  std::vector<Job> jobs(todo.size());
  for (std::size_t i = 0; i < todo.size(); ++i) {
    jobs[i].coord = todo[i];
    if (!store) continue;
    auto loaded = store->load(todo[i]);
    if (!loaded.ok()) {
      jobs[i].was_corrupt = true;
      report.region_errors.push_back(loaded.error());
      log_warn("voxel: {}; regenerating", loaded.error().message);
    } else if (loaded->has_value()) {
      jobs[i].saved = std::move(**loaded);
    }
  }
  // Generate in batches so progress can be reported and cancellation is prompt.
  const std::size_t batch = std::max<std::size_t>(8, static_cast<std::size_t>(pool.size()) * 4);
  for (std::size_t start = 0; start < jobs.size(); start += batch) {
    const std::size_t count = std::min(batch, jobs.size() - start);
    const std::size_t ran = pool.parallel_for(
        count,
        [&](std::size_t k, int) {
          Job& job = jobs[start + k];
          // Plants always come from the generator (they are a pure function of the seed); on a
          // saved chunk, those whose ground block was edited are gone, as World::set removes them.
          job.result = generator.generate(job.coord);
          if (job.saved) {
            const Chunk& generated = job.result.blocks;
            const Chunk& saved = *job.saved;
            std::erase_if(job.result.plants, [&](const PlantInstance& p) {
              const int x = local_of(p.ground.x), y = local_of(p.ground.y), z = local_of(p.ground.z);
              return saved.get(x, y, z) != generated.get(x, y, z);
            });
            job.result.blocks = std::move(*job.saved);
          }
        },
        cancel);
    for (std::size_t k = 0; k < ran; ++k) {
      Job& job = jobs[start + k];
      if (job.saved) {
        ++report.loaded;
      } else if (job.was_corrupt) {
        ++report.regenerated;
      } else {
        ++report.generated;
      }
      world.insert(job.coord, std::move(job.result.blocks));
      world.set_plants(job.coord, std::move(job.result.plants));
    }
    if (progress) progress(start + ran, jobs.size());
    if (ran < count || (cancel && cancel->load())) {
      report.cancelled = true;
      break;
    }
  }
  report.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return report;
}

std::vector<ChunkCoord> remesh_parallel(World& world, WorkerPool& pool, MesherKind kind) {
  const std::vector<ChunkCoord> dirty = world.dirty_chunks();
  std::vector<std::unique_ptr<Mesher>> meshers;
  for (int i = 0; i < pool.size(); ++i) meshers.push_back(make_mesher(kind));
  std::vector<PaddedBlocks> scratch(static_cast<std::size_t>(pool.size()));
  std::vector<ChunkMesh> meshes(dirty.size());
  std::vector<std::uint64_t> revisions(dirty.size());
  for (std::size_t i = 0; i < dirty.size(); ++i) revisions[i] = world.revision(dirty[i]);
  // Workers only read the world (gather_padded is const); results are stored afterwards.
  const World& view = world;
  pool.parallel_for(dirty.size(), [&](std::size_t i, int worker) {
    PaddedBlocks& padded = scratch[static_cast<std::size_t>(worker)];
    view.gather_padded(dirty[i], padded);
    meshers[static_cast<std::size_t>(worker)]->mesh(padded, view.palette(), meshes[i]);
  });
  for (std::size_t i = 0; i < dirty.size(); ++i) (void)world.store_mesh(dirty[i], std::move(meshes[i]), revisions[i]);
  return dirty;
}

}  // namespace sylva::voxel

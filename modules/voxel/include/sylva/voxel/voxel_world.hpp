#pragma once
// A streamed voxel world as one render::Drawable: the object a scene creates for a voxel world.
// It owns the generator, the block store, the worker pool and the renderer. Each update() loads
// (region files) or generates the missing chunks nearest the camera within view_radius, at most
// chunks_per_update of them, unloads chunks beyond view_radius + 2 (saving edited ones when a
// region folder is set), re-meshes stale chunks on the pool and updates the renderer. Objects are
// generated around the player and dropped behind it, as in seed 004 §3.5.

#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>
#include <sylva/render/drawable.hpp>
#include <sylva/voxel/region.hpp>
#include <sylva/voxel/voxel_renderer.hpp>
#include <sylva/voxel/worker_pool.hpp>
#include <sylva/voxel/world.hpp>
#include <sylva/voxel/world_builder.hpp>
#include <sylva/voxel/worldgen.hpp>

#include <map>
#include <memory>
#include <optional>
#include <string>

namespace sylva::voxel {

struct VoxelWorldSettings {
  WorldGenSettings generation;
  VoxelRenderSettings render;
  MesherKind mesher = MesherKind::kBitmask;
  int view_radius = 6;          // chunks around the camera (x/z) kept loaded
  int chunks_per_update = 48;   // most chunks loaded or generated per update()
  int threads = 0;              // worker threads (0 = hardware concurrency)
  std::string region_folder;    // where edited chunks are saved; empty = nothing is saved

  template <class V>
  void visit(V& v) {
    v(generation, "generation");
    v(render, "render");
    v(mesher, "mesher", {.help = "Meshing algorithm: culled, greedy or bitmask", .rebuild = Rebuild::kGpu});
    v(view_radius, "view_radius", {.min = 1, .max = 64, .unit = "chunks", .help = "Chunks kept around the camera"});
    v(chunks_per_update, "chunks_per_update", {.min = 1, .max = 4096, .help = "Most chunks loaded per frame"});
    v(threads, "threads", {.min = 0, .max = 256, .help = "Worker threads (0 = all cores)"});
    v(region_folder, "region_folder", {.min = 0, .max = 4096, .help = "Folder for saved chunks (empty: no saving)"});
  }
};

class VoxelWorld final : public render::Drawable {
 public:
  // Needs a current GL context. Errors: bad settings (naming voxel.<path>), grammar or shader
  // failures.
  static Result<std::unique_ptr<VoxelWorld>> create(const VoxelWorldSettings& settings);
  ~VoxelWorld() override;

  void update(const render::FrameContext& frame) override;
  void draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) override;

  // Streams around a position without rendering (tests, tools, headless warm-up).
  void stream_around(const glm::dvec3& position);

  World& world() { return *world_; }
  const WorldGenerator& generator() const { return *generator_; }
  VoxelRenderer& renderer() { return *renderer_; }
  // Saves every loaded chunk edited since it was loaded or generated (no-op without a folder).
  Status save();
  // Counters of the last update.
  const PopulateReport& last_populate() const { return last_populate_; }
  std::size_t unloaded_last_update() const { return unloaded_; }

 private:
  VoxelWorld() = default;
  bool edited(const ChunkCoord& c) const;

  VoxelWorldSettings settings_;
  std::shared_ptr<const WorldGenerator> generator_;
  std::unique_ptr<World> world_;
  std::unique_ptr<WorkerPool> pool_;
  std::unique_ptr<RegionStore> store_;
  std::unique_ptr<VoxelRenderer> renderer_;
  std::map<ChunkCoord, std::uint64_t> loaded_revision_;  // chunk revision right after loading
  PopulateReport last_populate_;
  std::size_t unloaded_ = 0;
  std::int64_t y_min_ = 0, y_max_ = 0;
};

}  // namespace sylva::voxel

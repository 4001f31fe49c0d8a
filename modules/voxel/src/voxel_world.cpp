#include <sylva/voxel/voxel_world.hpp>

#include <sylva/core/log.hpp>
#include <sylva/voxel/world_builder.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace sylva::voxel {

VoxelWorld::~VoxelWorld() = default;

Result<std::unique_ptr<VoxelWorld>> VoxelWorld::create(const VoxelWorldSettings& settings) {
  auto bad = [](const char* field, const std::string& what) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("voxel.{}: {}", field, what));
  };
  if (settings.view_radius < 1 || settings.view_radius > 64) {
    return bad("view_radius", fmt::format("{} outside [1, 64]", settings.view_radius));
  }
  if (settings.chunks_per_update < 1 || settings.chunks_per_update > 4096) {
    return bad("chunks_per_update", fmt::format("{} outside [1, 4096]", settings.chunks_per_update));
  }
  if (settings.threads < 0 || settings.threads > 256) return bad("threads", fmt::format("{} outside [0, 256]", settings.threads));
  auto generator = WorldGenerator::create(settings.generation);
  if (!generator.ok()) return generator.error();
  std::unique_ptr<VoxelWorld> w(new VoxelWorld());
  w->settings_ = settings;
  w->generator_ = *generator;
  w->world_ = std::make_unique<World>(w->generator_->palette());
  w->pool_ = std::make_unique<WorkerPool>(settings.threads);
  if (!settings.region_folder.empty()) {
    w->store_ = std::make_unique<RegionStore>(settings.region_folder, w->generator_->palette());
  }
  auto renderer = VoxelRenderer::create(*w->world_, w->generator_, settings.render);
  if (!renderer.ok()) return renderer.error();
  w->renderer_ = std::move(*renderer);
  chunk_y_range(settings.generation, w->y_min_, w->y_max_);
  return w;
}

bool VoxelWorld::edited(const ChunkCoord& c) const {
  const Chunk* chunk = world_->find(c);
  if (!chunk) return false;
  auto it = loaded_revision_.find(c);
  // A chunk created by an edit outside the streamed area has no load record.
  return it == loaded_revision_.end() ? chunk->revision() > 0 : chunk->revision() != it->second;
}

void VoxelWorld::stream_around(const glm::dvec3& position) {
  const BlockPos p{static_cast<std::int64_t>(std::floor(position.x)), static_cast<std::int64_t>(std::floor(position.y)),
                   static_cast<std::int64_t>(std::floor(position.z))};
  const ChunkCoord center = chunk_of(p);
  const int radius = settings_.view_radius;

  // Unload what fell out of range (with a margin, so walking along a border does not thrash).
  unloaded_ = 0;
  std::vector<ChunkCoord> far;
  for (const auto& c : world_->chunk_coords()) {
    if (std::abs(c.x - center.x) > radius + 2 || std::abs(c.z - center.z) > radius + 2) far.push_back(c);
  }
  if (!far.empty()) {
    std::vector<std::pair<ChunkCoord, const Chunk*>> keep;
    for (const auto& c : far) {
      if (store_ && edited(c)) keep.emplace_back(c, world_->find(c));
    }
    if (!keep.empty()) {
      const Status st = store_->save(keep);
      if (!st.ok()) log_warn("voxel: saving unloaded chunks failed: {}", st.error().message);
    }
    for (const auto& c : far) {
      world_->erase(c);
      loaded_revision_.erase(c);
      ++unloaded_;
    }
  }

  // Load or generate the nearest missing chunks.
  std::vector<ChunkCoord> wanted;
  for (const auto& c : chunk_box(center, radius, y_min_, y_max_)) {
    if (!world_->find(c)) wanted.push_back(c);
  }
  std::sort(wanted.begin(), wanted.end(), [&center](const ChunkCoord& a, const ChunkCoord& b) {
    const auto da = (a.x - center.x) * (a.x - center.x) + (a.z - center.z) * (a.z - center.z);
    const auto db = (b.x - center.x) * (b.x - center.x) + (b.z - center.z) * (b.z - center.z);
    return da != db ? da < db : a < b;
  });
  if (wanted.size() > static_cast<std::size_t>(settings_.chunks_per_update)) {
    wanted.resize(static_cast<std::size_t>(settings_.chunks_per_update));
  }
  last_populate_ = {};
  if (!wanted.empty()) {
    last_populate_ = populate(*world_, *generator_, wanted, *pool_, store_.get());
    for (const auto& c : wanted) {
      if (const Chunk* chunk = world_->find(c)) loaded_revision_[c] = chunk->revision();
    }
  }
  (void)remesh_parallel(*world_, *pool_, settings_.mesher);
}

void VoxelWorld::update(const render::FrameContext& frame) {
  stream_around(frame.camera.position());
  renderer_->update(frame);
}

void VoxelWorld::draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) {
  renderer_->draw(pass, frame, stats);
}

Status VoxelWorld::save() {
  if (!store_) return ok_status();
  std::vector<std::pair<ChunkCoord, const Chunk*>> list;
  for (const auto& c : world_->chunk_coords()) {
    if (edited(c)) list.emplace_back(c, world_->find(c));
  }
  if (list.empty()) return ok_status();
  SYLVA_TRY(store_->save(list));
  for (const auto& [c, chunk] : list) loaded_revision_[c] = chunk->revision();
  return ok_status();
}

}  // namespace sylva::voxel

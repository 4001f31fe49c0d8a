// The "terrain" section: the scene's ground drawn by the terrain module (seed 002: chunk quadtree
// with measured errors, screen-space-error selection, seams or skirts, morphing). The section
// lists the ground's height source (the same fields as "ground": size, resolution, generator,
// noise, map_scale, map_offset, maps.height), the offline chunk-tree settings and the per-frame
// render settings. The scene builds the one HeightField from the source; grass and trees stand
// on it and the terrain renderer shades from it.
//
// Edits: the terrain module builds its chunk tree as a whole (it has no partial rebuild), so a
// painted height region marks the tree stale and it is rebuilt once at the next frame; the
// number and CPU time of rebuilds are in the stats. Other modules standing on the ground re-seat
// only what the region touches.

#include "modules/module_factories.hpp"

#include <sylva/core/log.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/scene/module_instance.hpp>
#include <sylva/terrain/chunk_tree.hpp>
#include <sylva/terrain/renderer.hpp>
#include <sylva/terrain/settings.hpp>

#include <fmt/format.h>

namespace sylva::scene::detail {
namespace {

struct TerrainSectionSettings {
  HeightSourceSettings source;
  terrain::ChunkTreeSettings tree;
  terrain::TerrainRenderSettings render;

  template <class V>
  void visit(V& v) {
    source.visit(v);  // flat, like "ground": "terrain.size", "terrain.noise.octaves", ...
    v(tree, "tree");
    v(render, "render");
  }
};

using Settings = SettingsOf<TerrainSectionSettings>;

class TerrainInstance final : public ModuleInstance {
 public:
  static Result<std::unique_ptr<ModuleInstance>> create(const ModuleBuildContext& ctx) {
    if (!ctx.ground) return make_error(ErrorCode::kInvalidArgument, "terrain: the scene built no ground height field");
    auto inst = std::unique_ptr<TerrainInstance>(new TerrainInstance(ctx));
    SYLVA_TRY(inst->build());
    return std::unique_ptr<ModuleInstance>(std::move(inst));
  }

  std::vector<render::Drawable*> drawables() override { return {renderer_.get()}; }

  void sync_settings() override {
    if (stale_) {
      stale_ = false;
      Status s = build();
      if (!s.ok()) log_warn("terrain: rebuilding after an edit failed: {}", s.error().message);
    }
    const terrain::TerrainRenderSettings& wanted = settings().render;
    terrain::TerrainRenderSettings& live = renderer_->settings();
    const bool receive = live.receive_shadows;  // kGpu: changes only on a rebuild
    live = wanted;
    live.receive_shadows = receive;
    // The scene's debug views.
    if (ctx_.debug->lod_colors && live.debug_view == terrain::DebugView::kShaded) live.debug_view = terrain::DebugView::kLodColors;
    live.chunk_bounds = live.chunk_bounds || ctx_.debug->chunk_bounds;
  }

  Status rebuild(Rebuild what) override {
    if (what == Rebuild::kNone) return {};
    return build();
  }

  Status on_map_changed(const std::string& map_id, const WorldArea& area) override {
    (void)map_id;
    (void)area;
    stale_ = true;
    return {};
  }

  nlohmann::json stats() const override {
    const terrain::TerrainFrameStats& s = renderer_->frame_stats();
    nlohmann::json per_level = nlohmann::json::object();
    for (std::size_t l = 0; l < s.selection.chunks_per_level.size(); ++l) {
      per_level[fmt::format("level{}", l)] = s.selection.chunks_per_level[l];
    }
    return {{"chunks_drawn", s.selection.chunks},
            {"chunks_culled", s.selection.culled},
            {"chunks_visited", s.selection.visited},
            {"triangles", s.selection.triangles},
            {"seam_triangles", s.seam_triangles},
            {"skirt_triangles", s.skirt_triangles},
            {"max_level_difference", s.selection.max_level_difference},
            {"uploads", s.uploads},
            {"gpu_bytes", s.gpu_bytes},
            {"select_ms", s.update_ms},
            {"instances_per_lod", per_level},
            {"tree_chunks", renderer_->tree().chunk_count()},
            {"tree_levels", renderer_->tree().levels()},
            {"tree_rebuilds", rebuilds_},
            {"tree_build_ms", last_build_ms_}};
  }

  std::vector<render::Aabb> debug_bounds() const override {
    // The terrain draws its own chunk bounds (render.chunk_bounds), for the drawn chunks only.
    return {};
  }

 private:
  explicit TerrainInstance(const ModuleBuildContext& ctx) : ModuleInstance("terrain"), ctx_(ctx) {}

  const TerrainSectionSettings& settings() const { return static_cast<const Settings&>(*ctx_.section->settings).value; }

  Status build() {
    Stopwatch watch;
    const TerrainSectionSettings& s = settings();
    auto tree = terrain::ChunkTree::build(*ctx_.ground, s.tree);
    if (!tree.ok()) return make_error(tree.error().code, "terrain: " + tree.error().message);
    auto renderer = terrain::TerrainRenderer::create(std::make_shared<const terrain::ChunkTree>(std::move(*tree)), ctx_.ground,
                                                     s.render);
    if (!renderer.ok()) return make_error(renderer.error().code, "terrain: " + renderer.error().message);
    renderer_ = std::move(*renderer);
    ++rebuilds_;
    last_build_ms_ = watch.elapsed_ms();
    return {};
  }

  ModuleBuildContext ctx_;
  std::unique_ptr<terrain::TerrainRenderer> renderer_;
  bool stale_ = false;
  std::uint64_t rebuilds_ = 0;
  double last_build_ms_ = 0.0;
};

}  // namespace

ModuleDescriptor terrain_module() {
  ModuleDescriptor d;
  d.name = "terrain";
  d.description = "chunked-LOD terrain with certified screen-space error, seams and morphing (seed 002)";
  d.provides_ground = true;
  d.make_settings = [] {
    return std::make_unique<Settings>(std::vector<MapSlot>{{"height", MapKind::kHeight, "Terrain height in metres"}});
  };
  d.height_source = [](const ModuleSettings& s) { return static_cast<const Settings&>(s).value.source; };
  d.create = &TerrainInstance::create;
  return d;
}

}  // namespace sylva::scene::detail

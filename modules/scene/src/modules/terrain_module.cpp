// The "terrain" section: the scene's ground drawn by the terrain module (seed 002: chunk quadtree
// with measured errors, screen-space-error selection, seams or skirts, morphing). The section
// lists the ground's height source (the same fields as "ground": size, resolution, generator,
// noise, map_scale, map_offset, maps.height), the offline chunk-tree settings and the per-frame
// render settings. The scene builds the one HeightField from the source; grass and trees stand
// on it and the terrain renderer shades from it.
//
// Edits (issue 9, live height painting): a painted height region is collected (the union of the
// changed areas, as field samples) and applied once at the next frame with
// TerrainRenderer::apply_height_edit, which re-triangulates only the chunks the region can change
// (ChunkTree::rebuild_region) and re-uploads only those; a failure falls back to a full rebuild.
// The number and CPU time of rebuilds and the chunks rebuilt by the last edit are in the stats.
// Other modules standing on the ground re-seat only what the region touches. A tree of the seed's
// hq grids (terrain.tree.tessellation = hq0/hq1/hq2) has no partial rebuild: it is rebuilt whole.
//
// Tree cache (issue 15, terrain/tree_cache.hpp): "terrain.tree_cache" names the folder where a
// built chunk tree is kept, keyed by the field's samples and the tree settings, so the next launch
// of the same scene reopens it instead of rebuilding (a 4097^2 map: seconds). Painting changes the
// live tree in place and writes nothing; a later full rebuild of a painted field (a tree setting
// changed in the editor) is cached under that field's own key. stats(): "tree_cache" = hit, miss
// or off, of the last full build.
//
// Baked terrain (issue 15, "bake once, stream always"): "terrain.baked_file" names a chunk file
// (`sylva-bake terrain`, relative to the scene file). The section then opens it (header and
// directory only) and draws it through the ChunkStreamer within "terrain.stream.budget_mb": a
// loader thread reads chunks requested by projected error, a chunk whose children are not resident
// is drawn instead of them (never a hole), and the frame never waits on disk. The file carries the
// field's heights (chunk_file.hpp, version 2), and the descriptor names the baked file as the
// section's elevation source, so the scene's ground (grass, trees, the camera's above-ground
// height, Scene::ground_height) is the baked field, where its chunks are (../baked_ground.hpp;
// every 2nd/4th... sample above 8193^2). The section checks the ground on the grid and the root
// chunk's vertices (exact field samples): when they match, the ground also shades the terrain
// (normals, materials); a coarser ground shades from the triangles. Painting a baked terrain
// rebuilds the chunks a stroke reaches from the painted ground (ChunkStreamer::apply_height_edit,
// terrain/stream_edits.hpp); the scene saves the painted tiles as its edit layer
// (../baked_edits.hpp), and opening applies them before the first frame. A ground of every n-th
// sample (a field above the ground limit) is painted too: the chunks are rebuilt from the field's
// exact samples painted the same way (terrain/decimated_ground_edits.hpp), read from the file at the
// first stroke, not before. Streaming numbers are in
// stats() ("stream_*"; "stream_edited_chunks").

#include "modules/module_factories.hpp"

#include <sylva/core/log.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/scene/module_instance.hpp>
#include <sylva/terrain/chunk_file.hpp>
#include <sylva/terrain/chunk_tree.hpp>
#include <sylva/terrain/decimated_ground_edits.hpp>
#include <sylva/terrain/edit_layer.hpp>
#include <sylva/terrain/renderer.hpp>
#include <sylva/terrain/settings.hpp>
#include <sylva/terrain/streaming.hpp>
#include <sylva/terrain/tree_cache.hpp>
#include <sylva/terrain/water.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>

namespace sylva::scene::detail {
namespace {

struct TerrainSectionSettings {
  HeightSourceSettings source;
  terrain::ChunkTreeSettings tree;
  terrain::TreeCacheSettings tree_cache;
  terrain::TerrainRenderSettings render;
  std::string baked_file;              // a chunk file to stream instead of building the tree
  terrain::StreamingSettings stream;   // its memory budget
  terrain::WaterSettings water;        // a water plane (terrain/water.hpp), off by default

  template <class V>
  void visit(V& v) {
    source.visit(v);  // flat, like "ground": "terrain.size", "terrain.noise.octaves", ...
    v(tree, "tree");
    v(tree_cache, "tree_cache");
    v(render, "render");
    v(baked_file, "baked_file", {.max = 4096.0, .help = "Baked chunk file (sylva-bake terrain) to stream, relative to "
                                 "the scene file; empty = build the tree from the ground", .rebuild = Rebuild::kOffline});
    v(stream, "stream");
    v(water, "water");
  }
};

using Settings = SettingsOf<TerrainSectionSettings>;

// Keys of the material before issue 19, which placed sand and snow at shares of the map's relief
// (a 300 m lowland got snow on its highest hill). Their meaning cannot be carried over, so a scene
// that sets them is refused with the key that replaces each.
Status refuse_retired_keys(const ModuleBuildContext& ctx) {
  if (ctx.document == nullptr) return {};
  const struct {
    const char* pointer;
    const char* replacement;
  } retired[] = {
      {"/terrain/render/material/snow_height", "snow_line_m (altitude in metres at 45 deg latitude in summer)"},
      {"/terrain/render/material/sand_height", "water_level_m and beach_height_m (metres)"},
      {"/terrain/render/material/rock_slope", "rock_slope_deg (degrees)"},
      {"/terrain/render/material/detail_frequency", "detail_scale_m (tile of the finest detail, metres)"},
  };
  const nlohmann::json& unknown = ctx.document->unknown();
  for (const auto& key : retired) {
    if (!unknown.contains(key.pointer)) continue;
    std::string path = std::string(key.pointer).substr(1);
    std::replace(path.begin(), path.end(), '/', '.');
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: no longer supported (a share of the map's relief); use terrain.render.material.{}",
                                  path, key.replacement));
  }
  return {};
}

class TerrainInstance final : public ModuleInstance {
 public:
  static Result<std::unique_ptr<ModuleInstance>> create(const ModuleBuildContext& ctx) {
    if (!ctx.ground) return make_error(ErrorCode::kInvalidArgument, "terrain: the scene built no ground height field");
    SYLVA_TRY(refuse_retired_keys(ctx));
    auto inst = std::unique_ptr<TerrainInstance>(new TerrainInstance(ctx));
    SYLVA_TRY(inst->build());
    return std::unique_ptr<ModuleInstance>(std::move(inst));
  }

  std::vector<render::Drawable*> drawables() override {
    if (water_) return {renderer_.get(), water_.get()};
    return {renderer_.get()};
  }

  void sync_settings() override {
    if (stale_) {
      stale_ = false;
      apply_edit();
    }
    const terrain::TerrainRenderSettings& wanted = settings().render;
    terrain::TerrainRenderSettings& live = renderer_->settings();
    const bool receive = live.receive_shadows;  // kGpu: changes only on a rebuild
    live = wanted;
    live.receive_shadows = receive;
    // The scene's debug views.
    if (ctx_.debug->lod_colors && live.debug_view == terrain::DebugView::kShaded) live.debug_view = terrain::DebugView::kLodColors;
    live.chunk_bounds = live.chunk_bounds || ctx_.debug->chunk_bounds;
    // The material's snow line follows the scene's latitude and season (terrain/material.hpp).
    if (ctx_.environment != nullptr) renderer_->set_climate({ctx_.environment->latitude_deg, ctx_.environment->season});
    terrain::sync_water(water_, settings().water, "terrain.water");
  }

  Status rebuild(Rebuild what) override {
    if (what == Rebuild::kNone) return {};
    return build();
  }

  Status on_map_changed(const std::string& map_id, const WorldArea& area) override {
    (void)map_id;
    // The changed samples, grown by one sample each way so rounding never leaves one out.
    const HeightField& f = *ctx_.ground;
    const auto lo = glm::floor((area.min - f.origin()) / f.spacing()) - 1.0;
    const auto hi = glm::ceil((area.max - f.origin()) / f.spacing()) + 2.0;  // exclusive
    const int x0 = static_cast<int>(std::clamp(lo.x, 0.0, static_cast<double>(f.columns())));
    const int z0 = static_cast<int>(std::clamp(lo.y, 0.0, static_cast<double>(f.rows())));
    const int x1 = static_cast<int>(std::clamp(hi.x, 0.0, static_cast<double>(f.columns())));
    const int z1 = static_cast<int>(std::clamp(hi.y, 0.0, static_cast<double>(f.rows())));
    if (x0 >= x1 || z0 >= z1) return {};
    if (!stale_) {
      dirty_ = {x0, z0, x1, z1};
    } else {
      dirty_ = {std::min(dirty_[0], x0), std::min(dirty_[1], z0), std::max(dirty_[2], x1), std::max(dirty_[3], z1)};
    }
    stale_ = true;
    return {};
  }

  nlohmann::json stats() const override {
    const terrain::TerrainFrameStats& s = renderer_->frame_stats();
    nlohmann::json per_level = nlohmann::json::object();
    for (std::size_t l = 0; l < s.selection.chunks_per_level.size(); ++l) {
      per_level[fmt::format("level{}", l)] = s.selection.chunks_per_level[l];
    }
    nlohmann::json out = {{"chunks_drawn", s.selection.chunks},
            {"chunks_culled", s.selection.culled},
            {"chunks_visited", s.selection.visited},
            {"triangles", s.selection.triangles},
            {"seam_triangles", s.seam_triangles},
            // issue 18: chunks shaded from the baked far material / without shadow receiving
            {"far_baked_chunks", s.far_baked_chunks},
            {"beyond_shadow_chunks", s.beyond_shadow_chunks},
            {"far_material_texels_baked", renderer_->far_material_texels_baked()},
            {"skirt_triangles", s.skirt_triangles},
            {"max_level_difference", s.selection.max_level_difference},
            {"uploads", s.uploads},
            {"gpu_bytes", s.gpu_bytes},
            {"select_ms", s.update_ms},
            {"instances_per_lod", per_level},
            {"tree_chunks", renderer_->tree().chunk_count()},
            {"tree_levels", renderer_->tree().levels()},
            {"tree_rebuilds", rebuilds_},
            {"tree_partial_rebuilds", partial_rebuilds_},
            {"chunks_rebuilt", chunks_rebuilt_},
            {"chunks_updated", chunks_updated_},
            {"tree_build_ms", last_build_ms_},
            {"tree_cache", terrain::to_string(tree_cache_)},
            // Numbers for sylva-bench's columns (it keeps numeric facts only): 1 on a hit, 0 else.
            {"tree_cache_hit", tree_cache_ == terrain::TreeCacheOutcome::kHit ? 1 : 0},
            {"tree_cache_load_ms", cache_load_ms_},
            {"tree_cache_save_ms", cache_save_ms_}};
    if (terrain::ChunkStreamer* streamer = renderer_->streamer()) {
      const terrain::StreamingStats st = streamer->stats();
      out["stream_resident_bytes"] = st.resident_bytes;
      out["stream_budget_bytes"] = st.budget_bytes;
      out["stream_resident_chunks"] = st.resident_chunks;
      out["stream_requests"] = st.requests;
      out["stream_pending"] = st.pending_requests;
      out["stream_loads"] = st.loads;
      out["stream_misses"] = st.misses;
      out["stream_misses_frame"] = s.selection.substituted;
      out["stream_evictions"] = st.evictions;
      out["stream_dropped"] = st.dropped;
      out["stream_budget_refused"] = st.budget_refused;
      out["stream_budget_limited"] = st.budget_limited ? 1 : 0;
      out["stream_failures"] = st.failures;
      if (!st.last_error.empty()) out["stream_last_error"] = st.last_error;  // names the file and chunk
      out["stream_edited_chunks"] = streamer->edited_chunks();
      out["baked_file_bytes"] = baked_bytes_;
      out["baked_ground_matches"] = ground_matches_ ? 1 : 0;
      // The painted exact field of a ground of every n-th sample (0 until the first stroke).
      out["baked_exact_bytes"] = decimated_ ? decimated_->bytes() : 0;
    }
    return out;
  }

  std::vector<render::Aabb> debug_bounds() const override {
    // The terrain draws its own chunk bounds (render.chunk_bounds), for the drawn chunks only.
    return {};
  }

 private:
  explicit TerrainInstance(const ModuleBuildContext& ctx) : ModuleInstance("terrain"), ctx_(ctx) {}

  const TerrainSectionSettings& settings() const { return static_cast<const Settings&>(*ctx_.section->settings).value; }

  Status build() {
    if (!settings().baked_file.empty()) return open_baked();
    Stopwatch watch;
    const TerrainSectionSettings& s = settings();
    const std::filesystem::path base = ctx_.document != nullptr ? ctx_.document->directory() : std::filesystem::path();
    auto tree = terrain::build_or_load_chunk_tree(*ctx_.ground, s.tree, s.tree_cache, base);
    if (!tree.ok()) return make_error(tree.error().code, "terrain: " + tree.error().message);
    tree_cache_ = tree->cache;
    cache_load_ms_ = tree->key_ms + tree->load_ms;
    cache_save_ms_ = tree->save_ms;
    auto renderer = terrain::TerrainRenderer::create(std::make_shared<const terrain::ChunkTree>(std::move(tree->tree)),
                                                     ctx_.ground, s.render);
    if (!renderer.ok()) return make_error(renderer.error().code, "terrain: " + renderer.error().message);
    renderer_ = std::move(*renderer);
    ++rebuilds_;
    last_build_ms_ = watch.elapsed_ms();
    return {};
  }

  // The baked chunk file, streamed (header). Errors name the key and the file.
  Status open_baked() {
    Stopwatch watch;
    const TerrainSectionSettings& s = settings();
    const std::filesystem::path path =
        ctx_.document != nullptr ? ctx_.document->resolve(s.baked_file) : std::filesystem::path(s.baked_file);
    const auto fail = [&](const Error& e) {
      // ChunkFile's messages name the file; the key says where it came from.
      return make_error(e.code, fmt::format("terrain.baked_file: {}", e.message));
    };
    auto file = terrain::ChunkFile::open(path);
    if (!file.ok()) return fail(file.error());
    std::error_code ec;
    baked_bytes_ = static_cast<std::uint64_t>(std::filesystem::file_size(path, ec));
    auto streamer = terrain::ChunkStreamer::create(*file, s.stream);
    if (!streamer.ok()) return fail(Error{streamer.error().code, fmt::format("{}: {}", path.string(), streamer.error().message)});
    baked_file_ = *file;
    decimated_.reset();  // read again at the next stroke (or now, for a painted ground)
    apply_painted_ground(**file, **streamer);
    const std::string mismatch = ground_mismatch(**streamer);
    const HeightField* field = mismatch.empty() ? ctx_.ground : nullptr;
    if (field != nullptr) {
      ground_matches_ = true;
    } else if (coarse_baked_ground((*streamer)->tree())) {
      ground_matches_ = false;  // the baked heights every n-th sample: shaded from the triangles
    } else {
      ground_matches_ = false;
      log_warn("terrain: the scene's ground (grass, trees, camera height) is not the field baked into {}: {}",
               path.string(), mismatch);
    }
    auto renderer = terrain::TerrainRenderer::create(std::move(*streamer), field, s.render);
    if (!renderer.ok()) return make_error(renderer.error().code, "terrain: " + renderer.error().message);
    renderer_ = std::move(*renderer);
    stale_ = false;  // a rebuild starts from the ground as it is now
    tree_cache_ = terrain::TreeCacheOutcome::kOff;
    cache_load_ms_ = cache_save_ms_ = 0.0;
    ++rebuilds_;
    last_build_ms_ = watch.elapsed_ms();
    return {};
  }

  // A painted ground (the scene's edit layer, or strokes before this rebuild) over a baked file:
  // the chunks of the tiles where it differs from the baked heights are rebuilt from it
  // (ChunkStreamer::apply_height_edit), so the first frame already shows the edits.
  void apply_painted_ground(const terrain::ChunkFile& file, terrain::ChunkStreamer& streamer) {
    bool painted = ctx_.section->maps.count("height") != 0;  // an edit layer
    if (ctx_.maps != nullptr) {
      const auto map = ctx_.maps->find("terrain.height");
      painted = painted || (map != ctx_.maps->end() && map->second.unsaved());
    }
    const HeightField& f = *ctx_.ground;
    const terrain::ChunkTree& t = file.tree();
    if (painted && coarse_baked_ground(t)) {
      // Every n-th sample: the painted ground against the baked one at its stride (the overview);
      // the exact field is read only when they differ.
      auto baked = file.read_heights(ground_stride(t));
      if (!baked.ok()) return;
      const auto rects = terrain::changed_rects(baked->samples(), f.samples(), f.columns(), f.rows());
      if (rects.empty()) return;
      auto changed = apply_decimated_edit(streamer, rects);
      if (!changed.ok()) {
        log_warn("terrain: the painted ground is not drawn: {}", changed.error().message);
        return;
      }
      chunks_rebuilt_ = changed->rebuilt.size();
      return;
    }
    if (!painted || f.columns() != t.field_columns() || f.rows() != t.field_rows() || f.spacing() != t.spacing() ||
        f.origin() != t.origin()) {
      return;
    }
    auto baked = file.read_heights(1);
    if (!baked.ok()) return;  // the ground came from the same heights; read errors were reported then
    const auto rects = terrain::changed_rects(baked->samples(), f.samples(), f.columns(), f.rows());
    if (rects.empty()) return;
    auto changed = streamer.apply_height_edit(f, rects);
    if (!changed.ok()) {
      log_warn("terrain: the painted ground is not drawn: {}", changed.error().message);
      return;
    }
    chunks_rebuilt_ = changed->rebuilt.size();
  }

  // Why the scene's ground is not the field the file was baked from ("" when it is): same grid,
  // and the root chunk's vertices (exact samples of that field) at the ground's heights.
  std::string ground_mismatch(const terrain::ChunkStreamer& streamer) const {
    const HeightField& f = *ctx_.ground;
    const terrain::ChunkTree& t = streamer.tree();
    if (f.columns() != t.field_columns() || f.rows() != t.field_rows() || f.spacing() != t.spacing()) {
      return fmt::format("the ground has {} x {} samples {} m apart, the file {} x {} samples {} m apart", f.columns(),
                         f.rows(), f.spacing(), t.field_columns(), t.field_rows(), t.spacing());
    }
    if (f.origin() != t.origin()) {
      // sylva-bake keeps a raster's origin at (0, 0); the scene centres its ground on terrain.center.
      const glm::dvec2 centre = t.origin() + 0.5 * glm::dvec2(t.field_columns() - 1, t.field_rows() - 1) * t.spacing();
      return fmt::format("the ground starts at ({}, {}), the file at ({}, {}): set terrain.center to [{}, {}]",
                         f.origin().x, f.origin().y, t.origin().x, t.origin().y, centre.x, centre.y);
    }
    const terrain::ChunkMesh* root = streamer.mesh(0);
    if (root == nullptr) return "the file's root chunk is not resident";
    for (const terrain::ChunkVertex& v : root->vertices) {
      if (v.outside || v.centre) continue;
      const float h = f.sample_clamped(static_cast<int>(v.gx), static_cast<int>(v.gz));
      if (std::abs(h - v.height) > 1e-3f * std::max(1.0f, std::abs(v.height))) {
        return fmt::format("at sample ({}, {}) the ground is {} m high, the file {} m: name the source it was baked "
                           "from in the section's height keys", v.gx, v.gz, h, v.height);
      }
    }
    return {};
  }

  // Whether the ground is the file's heights every n-th sample (a field too big to read whole).
  bool coarse_baked_ground(const terrain::ChunkTree& t) const {
    const HeightField& f = *ctx_.ground;
    const int n = ground_stride(t);
    return n > 1 && f.spacing() == n * t.spacing() && f.origin() == t.origin() &&
           f.columns() == (t.field_columns() - 1) / n + 1 && f.rows() == (t.field_rows() - 1) / n + 1;
  }
  int ground_stride(const terrain::ChunkTree& t) const {
    return static_cast<int>(std::lround(ctx_.ground->spacing() / t.spacing()));
  }

  // A stroke on a ground of every n-th sample (`rects`: ground samples): the painted exact field
  // brought up to the ground there (read from the file at the first stroke: 4 bytes per field
  // sample, decimated_ground_edits.hpp), then the chunks it reaches rebuilt from it.
  Result<terrain::RegionRebuild> apply_decimated_edit(terrain::ChunkStreamer& streamer,
                                                      const std::vector<terrain::SampleRect>& rects) {
    if (!decimated_) {
      Stopwatch watch;
      auto opened = terrain::DecimatedGroundEdits::open(*baked_file_, ground_stride(baked_file_->tree()));
      if (!opened.ok()) return opened.error();
      decimated_ = std::move(*opened);
      log_info("terrain: painting the baked field's exact {}x{} samples (every {}th is the ground): read them in "
               "{:.0f} ms, {} MiB held while the scene is open",
               decimated_->field().columns(), decimated_->field().rows(), decimated_->stride(), watch.elapsed_ms(),
               decimated_->field().samples().size() * sizeof(float) >> 20);
    }
    std::vector<terrain::SampleRect> exact;
    for (const terrain::SampleRect& r : rects) {
      auto e = decimated_->apply(ctx_.ground->samples(), r);
      if (!e.ok()) return e.error();
      if (e->x0 < e->x1 && e->z0 < e->z1) exact.push_back(*e);
    }
    // At open the section's renderer is not made yet (or is the one being replaced): the streamer.
    if (renderer_ == nullptr || renderer_->streamer() != &streamer) return streamer.apply_height_edit(decimated_->field(), exact);
    terrain::RegionRebuild all;
    for (const terrain::SampleRect& e : exact) {
      auto changed = renderer_->apply_height_edit(decimated_->field(), e.x0, e.z0, e.x1, e.z1);
      if (!changed.ok()) return changed.error();
      all.rebuilt.insert(all.rebuilt.end(), changed->rebuilt.begin(), changed->rebuilt.end());
    }
    return all;
  }

  // Applies the collected edit rectangle to the live tree; falls back to a full rebuild.
  void apply_edit() {
    Stopwatch watch;
    if (terrain::ChunkStreamer* streamer = renderer_->streamer()) {
      // A baked terrain: the chunks the edit reaches are rebuilt from the painted ground
      // (terrain/streaming.hpp), or from the exact field painted like a ground of every n-th
      // sample. No full-rebuild fallback: that would reopen the file unpainted.
      auto changed = coarse_baked_ground(streamer->tree())
                         ? apply_decimated_edit(*streamer, {{dirty_[0], dirty_[1], dirty_[2], dirty_[3]}})
                         : renderer_->apply_height_edit(*ctx_.ground, dirty_[0], dirty_[1], dirty_[2], dirty_[3]);
      if (!changed.ok()) {
        log_warn("terrain: the stroke is not drawn on the baked terrain: {}", changed.error().message);
        return;
      }
      ++partial_rebuilds_;
      chunks_rebuilt_ = changed->rebuilt.size();
      chunks_updated_ = 0;
      last_build_ms_ = watch.elapsed_ms();
      return;
    }
    if (settings().tree.tessellation != terrain::Tessellation::kRtin) {
      // The seed's hq grids have no partial rebuild (chunk_tree.hpp): rebuild the whole tree.
      Status s = build();
      if (!s.ok()) log_warn("terrain: rebuilding after an edit failed: {}", s.error().message);
      chunks_rebuilt_ = renderer_->tree().chunk_count();
      chunks_updated_ = 0;
      return;
    }
    auto changed = renderer_->apply_height_edit(*ctx_.ground, dirty_[0], dirty_[1], dirty_[2], dirty_[3]);
    if (changed.ok()) {
      ++partial_rebuilds_;
      chunks_rebuilt_ = changed->rebuilt.size();
      chunks_updated_ = changed->updated.size();
      last_build_ms_ = watch.elapsed_ms();
      return;
    }
    log_warn("terrain: partial rebuild after an edit failed ({}); rebuilding the whole tree", changed.error().message);
    Status s = build();
    if (!s.ok()) log_warn("terrain: rebuilding after an edit failed: {}", s.error().message);
    chunks_rebuilt_ = renderer_->tree().chunk_count();
    chunks_updated_ = 0;
  }

  ModuleBuildContext ctx_;
  std::unique_ptr<terrain::TerrainRenderer> renderer_;
  std::unique_ptr<terrain::WaterRenderer> water_;  // created when terrain.water.enabled is first set
  bool stale_ = false;
  std::array<int, 4> dirty_{0, 0, 0, 0};  // edited samples x0, z0, x1, z1 (x1/z1 exclusive)
  std::uint64_t partial_rebuilds_ = 0;
  std::size_t chunks_rebuilt_ = 0, chunks_updated_ = 0;
  std::uint64_t rebuilds_ = 0;
  double last_build_ms_ = 0.0;
  terrain::TreeCacheOutcome tree_cache_ = terrain::TreeCacheOutcome::kOff;  // of the last full build
  double cache_load_ms_ = 0.0, cache_save_ms_ = 0.0;  // hashing + reading / writing, last full build
  std::uint64_t baked_bytes_ = 0;                      // size of the baked chunk file streamed
  bool ground_matches_ = false;                        // the scene's ground is the baked field
  std::shared_ptr<const terrain::ChunkFile> baked_file_;  // the file streamed (baked_file)
  // The painted exact field of a ground of every n-th sample: null until the first stroke.
  std::unique_ptr<terrain::DecimatedGroundEdits> decimated_;
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
  d.height_source = [](const ModuleSettings& s) {
    const TerrainSectionSettings& v = static_cast<const Settings&>(s).value;
    HeightSourceSettings source = v.source;
    // A baked file carries its ground (chunk_file.hpp); make_height_grid reads it by its magic.
    if (!v.baked_file.empty()) source.elevation.file = v.baked_file;
    return source;
  };
  d.create = &TerrainInstance::create;
  return d;
}

}  // namespace sylva::scene::detail

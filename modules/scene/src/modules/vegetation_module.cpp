// The "vegetation" section: a forest of one procedural species (vegetation::generate_tree, LOD0
// with hierarchical wind bending and leaf shading by vegetation::TreeRenderer) placed by the
// scene's world-anchored forest placement (forest_placement.hpp) over a rectangle, standing on
// the scene's ground, swaying in the scene's wind, coloured by the scene's season.
// Map: density (tree placement probability in [0, 1]).
//
// Edits: a changed density or ground area re-places only the trees of the grid cells it touches
// (their instance records are rebuilt on the CPU; the tree asset is untouched).
// Per frame: trees outside the view frustum or beyond max_distance are culled on the CPU, the
// survivors' instance records (camera-relative, with the wind at each tree) are uploaded and
// drawn in one instanced call per pass.

#include "modules/module_factories.hpp"

#include <sylva/core/log.hpp>
#include <sylva/core/params_json.hpp>
#include <sylva/render/buffer.hpp>
#include <sylva/scene/forest_placement.hpp>
#include <sylva/scene/module_instance.hpp>
#include <sylva/vegetation/animation.hpp>
#include <sylva/vegetation/generator.hpp>
#include <sylva/vegetation/tree_mesh.hpp>
#include <sylva/vegetation/tree_renderer.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

namespace sylva::scene::detail {
namespace {

struct ForestSectionSettings {
  glm::dvec2 area_min{-40.0, -40.0};
  glm::dvec2 area_max{40.0, 40.0};
  float trees_per_hectare = 30.0f;
  float min_spacing = 5.0f;
  float scale_min = 0.8f;
  float scale_max = 1.2f;
  std::uint32_t seed = 1;
  int map_resolution = 128;
  vegetation::SpeciesPreset species = vegetation::SpeciesPreset::kBroadleaf;
  std::uint32_t species_seed = 1;
  int leaf_texture_size = 128;
  vegetation::MeshSettings mesh;
  vegetation::AnimationLevel animation = vegetation::AnimationLevel::kLeaves;
  vegetation::AnimationSettings motion;
  vegetation::ShadingSettings shading;
  bool season_from_environment = true;
  float max_distance = 800.0f;

  template <class V>
  void visit(V& v) {
    v(area_min, "area_min", {.min = -1.0e8, .max = 1.0e8, .unit = "m", .help = "Corner of the forest (x, z)", .rebuild = Rebuild::kOffline});
    v(area_max, "area_max", {.min = -1.0e8, .max = 1.0e8, .unit = "m", .help = "Opposite corner of the forest (x, z)", .rebuild = Rebuild::kOffline});
    v(trees_per_hectare, "trees_per_hectare", {.min = 0.01, .max = 2000.0, .unit = "1/ha", .help = "Trees per hectare where the density map is 1", .rebuild = Rebuild::kOffline, .log_scale = true});
    v(min_spacing, "min_spacing", {.min = 0.0, .max = 1000.0, .unit = "m", .help = "Smallest distance between trunks", .rebuild = Rebuild::kOffline});
    v(scale_min, "scale_min", {.min = 0.05, .max = 20.0, .help = "Smallest random tree scale", .rebuild = Rebuild::kOffline});
    v(scale_max, "scale_max", {.min = 0.05, .max = 20.0, .help = "Largest random tree scale", .rebuild = Rebuild::kOffline});
    v(seed, "seed", {.min = 0.0, .max = 4294967295.0, .help = "Placement seed", .rebuild = Rebuild::kOffline});
    v(map_resolution, "map_resolution", {.min = 1, .max = 8192, .help = "Texels of a new density map along the longer side", .rebuild = Rebuild::kOffline});
    v(species, "species", {.help = "broadleaf, conifer, birch or shrub", .rebuild = Rebuild::kOffline});
    v(species_seed, "species_seed", {.min = 0.0, .max = 4294967295.0, .help = "Seed of the generated tree", .rebuild = Rebuild::kOffline});
    v(leaf_texture_size, "leaf_texture_size", {.min = 16, .max = 2048, .unit = "px", .help = "Procedural leaf texture size (power of two)", .rebuild = Rebuild::kGpu});
    v(mesh, "mesh");
    v(animation, "animation", {.help = "static, trunk, branches or leaves"});
    v(motion, "motion");
    v(shading, "shading");
    v(season_from_environment, "season_from_environment", {.help = "Leaf colours follow environment.season"});
    v(max_distance, "max_distance", {.min = 1.0, .max = 1.0e6, .unit = "m", .help = "Trees farther than this are not drawn", .log_scale = true});
  }
};

Status check_forest(const ForestSectionSettings& s, std::string_view prefix) {
  if (!(s.area_max.x > s.area_min.x && s.area_max.y > s.area_min.y)) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}.area_max: must be above area_min on both axes", prefix));
  }
  if (s.scale_min > s.scale_max) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}.scale_min: {} is above {}.scale_max ({})", prefix, s.scale_min, prefix, s.scale_max));
  }
  const int n = s.leaf_texture_size;
  if ((n & (n - 1)) != 0) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}.leaf_texture_size: {} is not a power of two", prefix, n));
  }
  const double area_ha = (s.area_max.x - s.area_min.x) * (s.area_max.y - s.area_min.y) / 1.0e4;
  if (area_ha * s.trees_per_hectare > 200000.0) {
    return make_error(ErrorCode::kLimit, fmt::format("{}.trees_per_hectare: {} trees on {:.1f} ha is above the 200000 tree cap",
                                                     prefix, area_ha * s.trees_per_hectare, area_ha));
  }
  return {};
}

using Settings = SettingsOf<ForestSectionSettings>;
const MapSlot kDensitySlot{"density", MapKind::kUnit, "Tree placement density, 1 = trees_per_hectare"};

// The scene's season counts from the spring equinox; the vegetation's from 1 January.
constexpr float kEquinoxYearFraction = 79.0f / 365.0f;

class ForestDrawable final : public render::Drawable {
 public:
  ForestDrawable(vegetation::TreeRenderer& renderer, vegetation::TreeAsset& asset, const ForestSectionSettings& settings,
                 const EnvironmentSettings& environment, const DebugView& debug)
      : renderer_(renderer), asset_(asset), settings_(settings), environment_(environment), debug_(debug) {
    instances_ = render::Buffer::dynamic(sizeof(vegetation::InstanceGpu) * 64, GL_STREAM_DRAW);
  }

  std::map<std::pair<int, int>, std::vector<PlacedTree>>& cells() { return cells_; }

  void update(const render::FrameContext& frame) override {
    gpu_.clear();
    if (!(debug_.freeze_culling && !frozen_.empty())) {
      visible_.clear();
      const render::Frustum frustum = frame.camera.frustum();
      const glm::vec3 lo = asset_.bounds_min(), hi = asset_.bounds_max();
      const double max_d2 = static_cast<double>(settings_.max_distance) * settings_.max_distance;
      for (const auto& [cell, trees] : cells_) {
        for (const PlacedTree& t : trees) {
          const glm::dvec3 d = t.position - frame.camera.position();
          if (glm::dot(d, d) > max_d2) continue;
          // Rotation about y can move the box by its horizontal radius: test the enclosing box.
          const double r = std::max({std::abs(lo.x), std::abs(hi.x), std::abs(lo.z), std::abs(hi.z)}) * t.scale;
          const render::Aabb box{t.position + glm::dvec3(-r, lo.y * t.scale, -r), t.position + glm::dvec3(r, hi.y * t.scale, r)};
          if (!frustum.intersects(box)) continue;
          visible_.push_back(t);
        }
      }
      frozen_ = visible_;
    }
    const vegetation::AnimationSettings& motion = settings_.motion;
    for (const PlacedTree& t : visible_) {
      vegetation::TreeInstance ti;
      ti.position = t.position;
      ti.yaw = t.yaw;
      ti.scale = t.scale;
      ti.time_offset = t.phase * 100.0f;
      ti.season_offset = (t.random - 0.5f) * 0.04f;
      ti.color_variation = glm::vec3(t.random - 0.5f, t.phase - 0.5f, 0.0f) * 0.06f;
      ti.number = t.random;
      gpu_.push_back(vegetation::make_instance_gpu(ti, frame.camera.position(), frame.wind, frame.time, motion));
    }
    if (!gpu_.empty()) instances_.upload(std::span<const vegetation::InstanceGpu>(gpu_));
    renderer_.set_frame(vegetation::make_animation_gpu(motion, frame.time), frame.wind.frame(frame.time, frame.camera.position()).gpu);
  }

  void draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) override {
    if (gpu_.empty() || pass == render::Pass::kTransparent) return;
    vegetation::TreeDrawParams params;
    params.view_proj = frame.camera.view_projection();
    params.shading = settings_.shading;
    if (settings_.season_from_environment) params.shading.season = environment_.season + kEquinoxYearFraction;
    params.level = settings_.animation;
    Status s = renderer_.draw(pass, asset_, instances_, 0, static_cast<std::uint32_t>(gpu_.size()), params, stats);
    if (!s.ok() && !warned_) {
      log_warn("vegetation: {}", s.error().message);
      warned_ = true;
    }
  }

  std::size_t visible() const { return visible_.size(); }

 private:
  vegetation::TreeRenderer& renderer_;
  vegetation::TreeAsset& asset_;
  const ForestSectionSettings& settings_;
  const EnvironmentSettings& environment_;
  const DebugView& debug_;
  std::map<std::pair<int, int>, std::vector<PlacedTree>> cells_;
  std::vector<PlacedTree> visible_, frozen_;
  std::vector<vegetation::InstanceGpu> gpu_;
  render::Buffer instances_;
  bool warned_ = false;
};

class ForestInstance final : public ModuleInstance {
 public:
  static Result<std::unique_ptr<ModuleInstance>> create(const ModuleBuildContext& ctx) {
    auto inst = std::unique_ptr<ForestInstance>(new ForestInstance(ctx));
    SYLVA_TRY(inst->build_asset());
    SYLVA_TRY(inst->place_all());
    return std::unique_ptr<ModuleInstance>(std::move(inst));
  }

  std::vector<render::Drawable*> drawables() override { return {drawable_.get()}; }

  Status rebuild(Rebuild what) override {
    if (what == Rebuild::kNone) return {};
    // Placement changes (area, density, seed) keep the tree asset; species or mesh changes rebuild it.
    if (asset_key() != built_key_) SYLVA_TRY(build_asset());
    return place_all();
  }

  Status on_map_changed(const std::string& map_id, const WorldArea& area) override {
    (void)map_id;
    SYLVA_TRY(density_map());
    const ForestPlacement p = placement();
    glm::ivec2 cmin, cmax;
    forest_cells(p, area.min, area.max, cmin, cmax);
    auto& cells = drawable_->cells();
    for (int k = cmin.y; k <= cmax.y; ++k)
      for (int i = cmin.x; i <= cmax.x; ++i) cells.erase({i, k});
    const double c = forest_cell_size(p);
    // Re-place exactly the cells the area touches (region = their union).
    for (const PlacedTree& t : place_trees(p, &map_->grid, ctx_.ground, glm::dvec2(cmin) * c, (glm::dvec2(cmax) + 0.999) * c)) {
      cells[{t.cell.x, t.cell.y}].push_back(t);
    }
    cells_replaced_ += static_cast<std::uint64_t>((cmax.x - cmin.x + 1) * std::max(cmax.y - cmin.y + 1, 0));
    return {};
  }

  nlohmann::json stats() const override {
    std::size_t trees = 0;
    for (const auto& [cell, list] : drawable_->cells()) trees += list.size();
    return {{"trees", trees},
            {"trees_drawn", drawable_->visible()},
            {"triangles_per_tree", asset_.triangles()},
            {"cells_replaced", cells_replaced_},
            {"instances_per_lod", {{"lod0", drawable_->visible()}}}};
  }

  std::vector<glm::dvec3> placed_positions(std::size_t max_count) const override {
    std::vector<glm::dvec3> out;
    for (const auto& [cell, list] : drawable_->cells()) {
      for (const PlacedTree& t : list) {
        if (out.size() >= max_count) return out;
        out.push_back(t.position);
      }
    }
    return out;
  }

  std::vector<render::Aabb> debug_bounds() const override {
    std::vector<render::Aabb> out;
    const glm::vec3 lo = asset_.bounds_min(), hi = asset_.bounds_max();
    for (const auto& [cell, list] : drawable_->cells()) {
      for (const PlacedTree& t : list) {
        out.push_back({t.position + glm::dvec3(lo) * static_cast<double>(t.scale), t.position + glm::dvec3(hi) * static_cast<double>(t.scale)});
      }
    }
    return out;
  }

 private:
  explicit ForestInstance(const ModuleBuildContext& ctx) : ModuleInstance("vegetation"), ctx_(ctx) {}

  const ForestSectionSettings& settings() const { return static_cast<const Settings&>(*ctx_.section->settings).value; }

  ForestPlacement placement() const {
    const ForestSectionSettings& s = settings();
    return {s.area_min, s.area_max, s.trees_per_hectare, s.min_spacing, s.scale_min, s.scale_max, s.seed};
  }

  Status density_map() {
    const ForestSectionSettings& s = settings();
    auto map = ensure_area_map(ctx_, kDensitySlot, s.area_min, s.area_max, s.map_resolution, 1.0f);
    if (!map.ok()) return map.error();
    map_ = *map;
    return {};
  }

  std::string asset_key() const {
    const ForestSectionSettings& s = settings();
    return fmt::format("{} {} {} {}", static_cast<int>(s.species), s.species_seed, s.leaf_texture_size,
                       params_to_json(s.mesh).dump());
  }

  Status build_asset() {
    const ForestSectionSettings& s = settings();
    auto model = vegetation::generate_tree(vegetation::species_preset(s.species, s.species_seed));
    if (!model.ok()) return make_error(model.error().code, "vegetation: " + model.error().message);
    const vegetation::TreeMesh mesh = vegetation::build_tree_mesh(*model, s.mesh);
    auto textures = vegetation::make_texture_set(s.species, s.species_seed, s.leaf_texture_size, s.leaf_texture_size);
    if (!textures.ok()) return make_error(textures.error().code, "vegetation: " + textures.error().message);
    auto asset = vegetation::TreeAsset::create(mesh, *textures);
    if (!asset.ok()) return make_error(asset.error().code, "vegetation: " + asset.error().message);
    if (!renderer_) {
      auto renderer = vegetation::TreeRenderer::create();
      if (!renderer.ok()) return make_error(renderer.error().code, "vegetation: " + renderer.error().message);
      renderer_ = std::move(*renderer);
    }
    asset_ = std::move(*asset);
    drawable_ = std::make_unique<ForestDrawable>(*renderer_, asset_, settings(), *ctx_.environment, *ctx_.debug);
    built_key_ = asset_key();
    return {};
  }

  Status place_all() {
    SYLVA_TRY(density_map());
    auto& cells = drawable_->cells();
    cells.clear();
    const ForestSectionSettings& s = settings();
    for (const PlacedTree& t : place_trees(placement(), &map_->grid, ctx_.ground, s.area_min, s.area_max)) {
      cells[{t.cell.x, t.cell.y}].push_back(t);
    }
    return {};
  }

  ModuleBuildContext ctx_;
  std::optional<vegetation::TreeRenderer> renderer_;
  vegetation::TreeAsset asset_;
  std::unique_ptr<ForestDrawable> drawable_;
  SceneMap* map_ = nullptr;
  std::uint64_t cells_replaced_ = 0;
  std::string built_key_;
};

}  // namespace

ModuleDescriptor vegetation_module() {
  ModuleDescriptor d;
  d.name = "vegetation";
  d.description = "forests of procedural trees with hierarchical wind animation and leaf shading (seed 000)";
  d.needs_ground = true;
  d.make_settings = [] { return std::make_unique<Settings>(std::vector<MapSlot>{kDensitySlot}, &check_forest); };
  d.create = &ForestInstance::create;
  return d;
}

}  // namespace sylva::scene::detail

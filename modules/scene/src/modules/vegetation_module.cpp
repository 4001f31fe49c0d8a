// The "vegetation" section: a vegetation::Forest of procedural species (generate_tree; LOD0
// with hierarchical wind bending and leaf shading; the forest culls, animates, draws instanced
// and casts shadows) whose trees are placed by the scene's world-anchored forest placement
// (forest_placement.hpp) over a rectangle, standing on the scene's ground, swaying in the scene's
// wind, coloured by the scene's season. Map: density (tree placement probability in [0, 1]).
// One species (`species`) or a mixed stand (`mix`: a weight per preset, plus up to four species
// files `species_files.0..3.file` with their `weight`, paths relative to the scene file); each
// placed tree picks its species from a hash of its position, so a mix is stable under edits and
// reloads. A species file that fails to load is left out with a warning (the editor's messages
// panel shows it); the scene fails only when no species is left.
//
// Edits: a changed density or ground area re-places only the trees of the grid cells it touches
// on the CPU; the species (model, mesh, textures on the GPU) is untouched, and the instance list
// is handed to the forest once at the next frame.

#include "modules/module_factories.hpp"

#include <sylva/core/log.hpp>
#include <sylva/core/params_json.hpp>
#include <sylva/core/rng.hpp>
#include <sylva/scene/forest_placement.hpp>
#include <sylva/scene/module_instance.hpp>
#include <sylva/vegetation/animation.hpp>
#include <sylva/vegetation/forest.hpp>
#include <sylva/vegetation/generator.hpp>
#include <sylva/vegetation/species_file.hpp>
#include <sylva/vegetation/tree_mesh.hpp>
#include <sylva/vegetation/tree_renderer.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>

namespace sylva::scene::detail {
namespace {

// Relative share of each preset in a mixed stand; all zero = the single `species`.
struct SpeciesMix {
  float broadleaf = 0.0f;
  float conifer = 0.0f;
  float birch = 0.0f;
  float shrub = 0.0f;

  template <class V>
  void visit(V& v) {
    const ParamInfo info{.min = 0.0, .max = 1000.0, .help = "Relative share of this species (all 0: use `species`)",
                         .rebuild = Rebuild::kOffline};
    v(broadleaf, "broadleaf", info);
    v(conifer, "conifer", info);
    v(birch, "birch", info);
    v(shrub, "shrub", info);
  }
};

// Species files (vegetation/species_file.hpp) in a fixed number of slots: the parameter system has
// no list kind, and four named slots show in the editor's panel, take --set
// (`vegetation.species_files.1.file=oak.json`) and save like every other parameter.
struct SpeciesFileSlot {
  std::string file;  // relative to the scene file; "" = unused slot
  float weight = 1.0f;

  template <class V>
  void visit(V& v) {
    v(file, "file", {.max = 4096.0, .help = "Species file (JSON, see the vegetation README) relative to the scene file", .rebuild = Rebuild::kOffline});
    v(weight, "weight", {.min = 0.0, .max = 1000.0, .help = "Relative share of this species in the stand", .rebuild = Rebuild::kOffline});
  }
};

constexpr int kSlots = 4;
constexpr const char* kSlotNames[kSlots] = {"0", "1", "2", "3"};

struct SpeciesFiles {
  std::array<SpeciesFileSlot, kSlots> slot;

  template <class V>
  void visit(V& v) {
    for (int i = 0; i < kSlots; ++i) v(slot[static_cast<std::size_t>(i)], kSlotNames[i]);
  }
};

// A tree at a given spot (seed 000's experiments need one tree at a known place, §5), besides or
// instead of the placed stand (give every species file weight 0 for single trees only).
struct SingleTree {
  std::string species;        // a stand species: a preset's name or a species file's name; "" = unused
  glm::dvec2 position{0.0};   // x, z [m]; y = the ground there
  float yaw_deg = 0.0f;
  float scale = 1.0f;

  template <class V>
  void visit(V& v) {
    v(species, "species", {.max = 64.0, .help = "Species of this tree (a preset or a species file's name); empty = none", .rebuild = Rebuild::kOffline});
    v(position, "position", {.min = -1.0e8, .max = 1.0e8, .unit = "m", .help = "Trunk position (x, z)", .rebuild = Rebuild::kOffline});
    v(yaw_deg, "yaw_deg", {.min = -360.0, .max = 360.0, .unit = "deg", .help = "Turn about the vertical", .rebuild = Rebuild::kOffline});
    v(scale, "scale", {.min = 0.05, .max = 20.0, .help = "Uniform scale", .rebuild = Rebuild::kOffline});
  }
};

struct SingleTrees {
  std::array<SingleTree, kSlots> slot;

  template <class V>
  void visit(V& v) {
    for (int i = 0; i < kSlots; ++i) v(slot[static_cast<std::size_t>(i)], kSlotNames[i]);
  }
};

struct ForestSectionSettings {
  glm::dvec2 area_min{-40.0, -40.0};
  glm::dvec2 area_max{40.0, 40.0};
  float trees_per_hectare = 30.0f;
  float min_spacing = 5.0f;
  float scale_min = 0.8f;
  float scale_max = 1.2f;
  std::uint32_t seed = 1;
  float clearings = 0.0f;
  float clearing_size = 150.0f;
  ForestLayout layout = ForestLayout::kJittered;
  int map_resolution = 128;
  vegetation::SpeciesPreset species = vegetation::SpeciesPreset::kBroadleaf;
  std::uint32_t species_seed = 1;
  SpeciesMix mix;
  SpeciesFiles species_files;
  SingleTrees trees;
  int leaf_texture_size = 128;
  vegetation::MeshSettings mesh;
  vegetation::ForestSettings forest;  // animation, shading, culling of vegetation::Forest
  bool season_from_environment = true;

  template <class V>
  void visit(V& v) {
    v(area_min, "area_min", {.min = -1.0e8, .max = 1.0e8, .unit = "m", .help = "Corner of the forest (x, z)", .rebuild = Rebuild::kOffline});
    v(area_max, "area_max", {.min = -1.0e8, .max = 1.0e8, .unit = "m", .help = "Opposite corner of the forest (x, z)", .rebuild = Rebuild::kOffline});
    v(trees_per_hectare, "trees_per_hectare", {.min = 0.01, .max = 2000.0, .unit = "1/ha", .help = "Trees per hectare where the density map is 1", .rebuild = Rebuild::kOffline, .log_scale = true});
    v(min_spacing, "min_spacing", {.min = 0.0, .max = 1000.0, .unit = "m", .help = "Smallest distance between trunks", .rebuild = Rebuild::kOffline});
    v(scale_min, "scale_min", {.min = 0.05, .max = 20.0, .help = "Smallest random tree scale", .rebuild = Rebuild::kOffline});
    v(scale_max, "scale_max", {.min = 0.05, .max = 20.0, .help = "Largest random tree scale", .rebuild = Rebuild::kOffline});
    v(seed, "seed", {.min = 0.0, .max = 4294967295.0, .help = "Placement seed", .rebuild = Rebuild::kOffline});
    v(clearings, "clearings", {.min = 0.0, .max = 0.95, .help = "Share of the area left open in natural clearings", .rebuild = Rebuild::kOffline});
    v(layout, "layout", {.help = "jittered (a natural stand) or grid (multiples of the cell side: exact layouts; a small area round the origin is one tree)", .rebuild = Rebuild::kOffline});
    v(clearing_size, "clearing_size", {.min = 1.0, .max = 1.0e5, .unit = "m", .help = "Feature size of the clearings", .rebuild = Rebuild::kOffline, .log_scale = true});
    v(map_resolution, "map_resolution", {.min = 1, .max = 8192, .help = "Texels of a new density map along the longer side", .rebuild = Rebuild::kOffline});
    v(species, "species", {.help = "broadleaf, conifer, birch or shrub", .rebuild = Rebuild::kOffline});
    v(species_seed, "species_seed", {.min = 0.0, .max = 4294967295.0, .help = "Seed of the generated tree", .rebuild = Rebuild::kOffline});
    v(mix, "mix");
    v(species_files, "species_files");
    v(trees, "trees");
    v(leaf_texture_size, "leaf_texture_size", {.min = 16, .max = 2048, .unit = "px", .help = "Procedural leaf and bark texture size (power of two)", .rebuild = Rebuild::kGpu});
    v(mesh, "mesh");
    v(forest, "forest");
    v(season_from_environment, "season_from_environment", {.help = "Leaf colours follow environment.season"});
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

const char* preset_name(vegetation::SpeciesPreset p) {
  return enum_table<vegetation::SpeciesPreset>().name_of(static_cast<std::int64_t>(p));
}

// One species of the stand: a preset or a species file (its slot and path as written).
struct StandEntry {
  std::string name;  // stats key: the preset's name or the species file's name
  float weight = 1.0f;
  std::optional<vegetation::SpeciesPreset> preset;
  int slot = -1;
  std::string file;
};

// The stand's species with their weights: the mix's non-zero presets in preset order, then the
// named species files in slot order (weight 0: only for single trees); the single `species` when
// both are empty.
std::vector<StandEntry> stand_species(const ForestSectionSettings& s) {
  using vegetation::SpeciesPreset;
  const std::pair<SpeciesPreset, float> all[] = {{SpeciesPreset::kBroadleaf, s.mix.broadleaf},
                                                 {SpeciesPreset::kConifer, s.mix.conifer},
                                                 {SpeciesPreset::kBirch, s.mix.birch},
                                                 {SpeciesPreset::kShrub, s.mix.shrub}};
  std::vector<StandEntry> out;
  for (const auto& [preset, weight] : all) {
    if (weight > 0.0f) out.push_back({preset_name(preset), weight, preset, -1, {}});
  }
  for (int i = 0; i < kSlots; ++i) {
    const SpeciesFileSlot& slot = s.species_files.slot[static_cast<std::size_t>(i)];
    if (!slot.file.empty()) out.push_back({slot.file, slot.weight, std::nullopt, i, slot.file});
  }
  if (out.empty()) out.push_back({preset_name(s.species), 1.0f, s.species, -1, {}});
  return out;
}

// Index into the stand of a tree: a weighted pick by a hash of its trunk position (in
// centimetres) and the placement seed, independent of the randoms that drive scale and colour.
// stand.size() (no species) when every weight is 0: the stand then has single trees only.
std::size_t species_of(const PlacedTree& t, const std::vector<StandEntry>& stand, std::uint32_t seed) {
  float total = 0.0f;
  for (const StandEntry& entry : stand) total += entry.weight;
  if (!(total > 0.0f)) return stand.size();
  const float u = hash_to_unit_float(hash_i32(static_cast<std::int32_t>(std::floor(t.position.x * 100.0)),
                                              static_cast<std::int32_t>(std::floor(t.position.z * 100.0)), seed ^ 0x9e3779b9u)) *
                  total;
  float upto = 0.0f;
  for (std::size_t i = 0; i < stand.size(); ++i) {
    upto += stand[i].weight;
    if (u < upto && stand[i].weight > 0.0f) return i;
  }
  for (std::size_t i = stand.size(); i-- > 0;) {
    if (stand[i].weight > 0.0f) return i;
  }
  return stand.size();
}

using Settings = SettingsOf<ForestSectionSettings>;
const MapSlot kDensitySlot{"density", MapKind::kUnit, "Tree placement density, 1 = trees_per_hectare"};

// The scene's season counts from the spring equinox; the vegetation's from 1 January.
constexpr float kEquinoxYearFraction = 79.0f / 365.0f;

vegetation::TreeInstance to_instance(const PlacedTree& t) {
  vegetation::TreeInstance ti;
  ti.position = t.position;
  ti.yaw = t.yaw;
  ti.scale = t.scale;
  ti.time_offset = t.phase * 100.0f;
  ti.season_offset = -0.04f * t.random;
  ti.color_variation = glm::vec3(t.random - 0.5f, t.phase - 0.5f, 0.0f) * 0.06f;
  ti.number = t.random;
  return ti;
}

// Instances drawn per level. The forest counts LOD0 and its image-based levels separately once it
// has them (ForestStats::lod); before that every drawn tree is LOD0.
template <class Stats>
nlohmann::json instances_per_lod(const Stats& fs) {
  if constexpr (requires { fs.lod[0]; }) {
    nlohmann::json out = nlohmann::json::object();
    for (std::size_t i = 0; i < fs.lod.size(); ++i) out[fmt::format("lod{}", i)] = fs.lod[i];
    return out;
  } else {
    return {{"lod0", fs.visible}};
  }
}

// The forest's LOD settings as text, once vegetation::ForestSettings has them.
template <class ForestSettingsT>
std::string lod_key(const ForestSettingsT& f) {
  if constexpr (requires { f.lod; }) {
    return params_to_json(f.lod).dump();
  } else {
    return {};
  }
}

class ForestInstance final : public ModuleInstance {
 public:
  static Result<std::unique_ptr<ModuleInstance>> create(const ModuleBuildContext& ctx) {
    auto inst = std::unique_ptr<ForestInstance>(new ForestInstance(ctx));
    SYLVA_TRY(inst->build_forest());
    SYLVA_TRY(inst->place_all());
    return std::unique_ptr<ModuleInstance>(std::move(inst));
  }

  std::vector<render::Drawable*> drawables() override { return {&*forest_}; }

  void sync_settings() override {
    if (instances_dirty_) {
      instances_dirty_ = false;
      std::vector<std::vector<vegetation::TreeInstance>> per_species(stand_.size());
      for_each_tree([&](const PlacedTree& t, std::size_t species) { per_species[species].push_back(to_instance(t)); });
      for (std::size_t i = 0; i < per_species.size(); ++i) {
        Status s = forest_->set_instances(static_cast<int>(i), std::move(per_species[i]));
        if (!s.ok()) log_warn("vegetation: {}", s.error().message);
      }
    }
    const ForestSectionSettings& s = settings();
    vegetation::ForestSettings& live = forest_->settings();
    live = s.forest;
    if (s.season_from_environment) live.shading.season = ctx_.environment->season + kEquinoxYearFraction;
    if (ctx_.debug->freeze_culling) live.frustum_culling = false;
  }

  Status rebuild(Rebuild what) override {
    if (what == Rebuild::kNone) return {};
    // Placement changes (area, density, seed) keep the species; species or mesh changes rebuild it.
    if (asset_key() != built_key_) SYLVA_TRY(build_forest());
    return place_all();
  }

  Status on_map_changed(const std::string& map_id, const WorldArea& area) override {
    (void)map_id;
    SYLVA_TRY(density_map());
    place_singles(/*warn=*/false);  // a ground edit anywhere may move them up or down
    instances_dirty_ = true;
    const ForestPlacement p = placement();
    glm::ivec2 cmin, cmax;
    forest_cells(p, area.min, area.max, cmin, cmax);
    if (cmax.x < cmin.x || cmax.y < cmin.y) return {};
    for (int k = cmin.y; k <= cmax.y; ++k)
      for (int i = cmin.x; i <= cmax.x; ++i) cells_.erase({i, k});
    const double c = forest_cell_size(p);
    // Re-place exactly the cells the area touches (region = their union).
    for (const PlacedTree& t : place_trees(p, &map_->grid, ctx_.ground, glm::dvec2(cmin) * c, (glm::dvec2(cmax) + 0.999) * c)) {
      cells_[{t.cell.x, t.cell.y}].push_back(t);
    }
    cells_replaced_ += static_cast<std::uint64_t>(cmax.x - cmin.x + 1) * static_cast<std::uint64_t>(cmax.y - cmin.y + 1);
    instances_dirty_ = true;
    return {};
  }

  nlohmann::json stats() const override {
    std::size_t trees = 0;
    const vegetation::ForestStats& fs = forest_->stats();
    nlohmann::json triangles_per_tree = nlohmann::json::object(), trees_per_species = nlohmann::json::object();
    std::vector<std::size_t> counts(stand_.size(), 0);
    for_each_tree([&](const PlacedTree&, std::size_t species) {
      ++counts[species];
      ++trees;
    });
    for (std::size_t i = 0; i < stand_.size(); ++i) {
      triangles_per_tree[stand_[i].name] = forest_->asset(static_cast<int>(i)).triangles();
      trees_per_species[stand_[i].name] = counts[i];
    }
    return {{"trees", trees},
            {"trees_drawn", fs.visible},
            {"trees_per_species", trees_per_species},
            {"triangles_per_tree", triangles_per_tree},
            {"cells_replaced", cells_replaced_},
            {"cull_ms", fs.update_cpu_ms},
            {"instances_per_lod", instances_per_lod(fs)}};
  }

  std::vector<glm::dvec3> placed_positions(std::size_t max_count) const override {
    std::vector<glm::dvec3> out;
    for_each_tree([&](const PlacedTree& t, std::size_t) {
      if (out.size() < max_count) out.push_back(t.position);
    });
    return out;
  }

  std::vector<render::Aabb> debug_bounds() const override {
    std::vector<render::Aabb> out;
    for_each_tree([&](const PlacedTree& t, std::size_t species) {
      const vegetation::TreeAsset& asset = forest_->asset(static_cast<int>(species));
      const glm::vec3 lo = asset.bounds_min(), hi = asset.bounds_max();
      out.push_back({t.position + glm::dvec3(lo) * static_cast<double>(t.scale), t.position + glm::dvec3(hi) * static_cast<double>(t.scale)});
    });
    return out;
  }

 private:
  explicit ForestInstance(const ModuleBuildContext& ctx) : ModuleInstance("vegetation"), ctx_(ctx) {}

  const ForestSectionSettings& settings() const { return static_cast<const Settings&>(*ctx_.section->settings).value; }

  ForestPlacement placement() const {
    const ForestSectionSettings& s = settings();
    return {s.area_min, s.area_max, s.trees_per_hectare, s.min_spacing, s.scale_min, s.scale_max, s.seed, s.clearings, s.clearing_size, s.layout};
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
    // The image-based levels are baked when a species is added, so a change of forest.lod (e.g.
    // enabled, bake resolution) needs a new forest; its other settings are applied live.
    return fmt::format("{} {} {} {} {} {} {}", static_cast<int>(s.species), s.species_seed, params_to_json(s.mix).dump(),
                       params_to_json(s.species_files).dump(), s.leaf_texture_size, params_to_json(s.mesh).dump(), lod_key(s.forest));
  }

  // A preset's generated model and textures, or a species file's (vegetation/species_file.hpp).
  struct SpeciesData {
    vegetation::TreeModel model;
    vegetation::TreeTextureSet textures;
    vegetation::SpeciesTuning tuning;  // a species file's "lod" and "animation"
  };
  Result<SpeciesData> species_data(StandEntry& entry) const {
    const ForestSectionSettings& s = settings();
    if (entry.preset) {
      auto model = vegetation::generate_tree(vegetation::species_preset(*entry.preset, s.species_seed));
      if (!model.ok()) return model.error();
      auto textures = vegetation::make_texture_set(*entry.preset, s.species_seed, s.leaf_texture_size, s.leaf_texture_size);
      if (!textures.ok()) return textures.error();
      return SpeciesData{std::move(model).value(), std::move(textures).value(), {}};
    }
    std::vector<std::string> warnings;
    auto file = vegetation::load_species_file(ctx_.document->resolve(entry.file), warnings);
    for (const std::string& w : warnings) log_warn("vegetation.species_files.{}.file: {}", entry.slot, w);
    if (!file.ok()) return file.error();
    auto textures = vegetation::make_species_textures(*file, s.leaf_texture_size);
    if (!textures.ok()) return textures.error();
    entry.name = file->name;
    return SpeciesData{std::move(file->model), std::move(textures).value(), file->tuning};
  }

  Status build_forest() {
    const ForestSectionSettings& s = settings();
    auto forest = vegetation::Forest::create(s.forest);
    if (!forest.ok()) return make_error(forest.error().code, "vegetation: " + forest.error().message);
    std::vector<StandEntry> stand;
    for (StandEntry& entry : stand_species(s)) {
      auto data = species_data(entry);
      if (!data.ok() && !entry.preset) {
        // A user's species file: leave it out, keep the scene (issue #16).
        log_warn("vegetation.species_files.{}.file: {}; the species is left out", entry.slot, data.error().message);
        continue;
      }
      if (!data.ok()) return make_error(data.error().code, fmt::format("vegetation ({}): {}", entry.name, data.error().message));
      auto species = forest->add_species(data->model, data->textures, s.mesh);
      if (!species.ok()) return make_error(species.error().code, fmt::format("vegetation ({}): {}", entry.name, species.error().message));
      SYLVA_TRY(forest->set_species_tuning(*species, data->tuning));
      // Two species with one name would share a stats key.
      for (const StandEntry& other : stand) {
        if (other.name == entry.name) entry.name += fmt::format(" ({})", entry.slot);
      }
      stand.push_back(std::move(entry));
    }
    if (stand.empty()) {
      return make_error(ErrorCode::kInvalidArgument,
                        "vegetation.species_files: no species left (every named species file failed to load; see the warnings)");
    }
    forest_ = std::move(*forest);
    stand_ = std::move(stand);
    built_key_ = asset_key();
    instances_dirty_ = true;
    return {};
  }

  Status place_all() {
    SYLVA_TRY(density_map());
    cells_.clear();
    const ForestSectionSettings& s = settings();
    for (const PlacedTree& t : place_trees(placement(), &map_->grid, ctx_.ground, s.area_min, s.area_max)) {
      cells_[{t.cell.x, t.cell.y}].push_back(t);
    }
    place_singles(/*warn=*/true);
    instances_dirty_ = true;
    return {};
  }

  // The single trees (`trees.N`), standing on the ground; one naming no stand species is left
  // out with a warning (when `warn`: not again at every brush dab) that lists the names there are.
  void place_singles(bool warn) {
    singles_.clear();
    const ForestSectionSettings& s = settings();
    for (int i = 0; i < kSlots; ++i) {
      const SingleTree& st = s.trees.slot[static_cast<std::size_t>(i)];
      if (st.species.empty()) continue;
      const auto it = std::find_if(stand_.begin(), stand_.end(), [&](const StandEntry& e) { return e.name == st.species; });
      if (it == stand_.end()) {
        if (!warn) continue;
        std::string names;
        for (const StandEntry& e : stand_) names += (names.empty() ? "" : ", ") + e.name;
        log_warn("vegetation.trees.{}.species: no species '{}' in the stand ({}); the tree is left out", i, st.species, names);
        continue;
      }
      PlacedTree t;
      t.position = {st.position.x, ctx_.ground ? ctx_.ground->height(st.position.x, st.position.y) : 0.0, st.position.y};
      t.yaw = glm::radians(st.yaw_deg);
      t.scale = st.scale;
      t.phase = hash_to_unit_float(hash_i32(i, 0, s.seed ^ 0x51a6u));
      t.random = hash_to_unit_float(hash_i32(i, 1, s.seed ^ 0x51a6u));
      singles_.push_back({t, static_cast<std::size_t>(it - stand_.begin())});
    }
  }

  // Every tree with its stand species: the placed ones (those with a species), then the singles.
  template <class F>
  void for_each_tree(F&& f) const {
    const std::uint32_t seed = settings().seed;
    for (const auto& [cell, list] : cells_) {
      for (const PlacedTree& t : list) {
        const std::size_t species = species_of(t, stand_, seed);
        if (species < stand_.size()) f(t, species);
      }
    }
    for (const auto& [t, species] : singles_) f(t, species);
  }

  ModuleBuildContext ctx_;
  std::optional<vegetation::Forest> forest_;
  std::vector<StandEntry> stand_;  // index = forest species
  std::map<std::pair<int, int>, std::vector<PlacedTree>> cells_;
  std::vector<std::pair<PlacedTree, std::size_t>> singles_;  // single trees with their stand species
  SceneMap* map_ = nullptr;
  bool instances_dirty_ = true;
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

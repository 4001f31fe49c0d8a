// The "grass" section: one field of tessellated blades (grass::GrassField) with the seed-003 far
// field (grass::FarField) over a world rectangle, standing on the scene's ground HeightField (or
// on flat ground at y = 0 when the scene has none), reading the scene's wind and lighting.
// Maps: density (blade count) and height (blade height scale), both [0, 1] over the area, and
// tint_r/tint_g/tint_b (colour multiplier of blades, clumps and far ground layer, 1 = unchanged),
// all painted and undone like any scene map. Two file-only slots fill them (seed 001 §3.3):
//  - maps.control, seed 001's RGB control texture: its channels named by control.channels
//    (default "rg": R density, G blade height) fill the density and height maps. Seed 001's B
//    (terrain height, inverted: y = mix(0, max, 1 - B)) is not read here: a Sylva scene's ground
//    comes from its terrain/ground section and its own height map;
//  - maps.tint, an RGB image: its R, G, B fill tint_r, tint_g, tint_b.
// A slot's own file (maps.density, maps.tint_r, ..., what saving an edited map writes) wins over
// the channel of control/tint. Without a tint map (all three 1 everywhere) the field has none.
//
// Edits (issue 16): the map edits of a frame are gathered (their union) and, at the next frame
// (sync_settings), only the tiles they reach are regenerated (grass::regenerate_tiles, equal to a
// full regeneration bit for bit because placement is world-anchored per tile) and the blades are
// re-uploaded without rebuilding the programs (GrassField::set_blades); physics restarts. The far
// field updates the same way (grass::FarField::update_region: the clumps of the tiles reached, the
// changed texels of its textures, after a ground edit the changed ground-layer vertices), also equal
// to a full rebuild bit for bit. A ground edit that moves the field's origin (under its centre)
// rebuilds everything.
//
// surface = "mesh" (issue 16, grass on any mesh): the blades grow on every triangle of
// mesh.file instead (see mesh_blades), with a far field when the mesh is a height field (mesh_far);
// a map edit rebuilds them whole.

#include "modules/module_factories.hpp"

#include <sylva/grass/far_field.hpp>
#include <sylva/grass/generator.hpp>
#include <sylva/grass/grass_field.hpp>
#include <sylva/grass/maps.hpp>
#include <sylva/grass/mesh_height_field.hpp>
#include <sylva/grass/settings.hpp>
#include <sylva/grass/uv_density_map.hpp>
#include <sylva/core/log.hpp>
#include <sylva/scene/module_instance.hpp>
#ifdef SYLVA_HAS_TERRAIN
#include <sylva/terrain/mesh.hpp>
#endif

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace sylva::scene::detail {
namespace {

// Which channels of maps.control feed which map (seed 001 §3.3's layout is R density, G height).
struct GrassControlSettings {
  std::string channels = "rg";

  template <class V>
  void visit(V& v) {
    v(channels, "channels", {.max = 2.0,
      .help = "Channels of maps.control that fill the density and height maps, in that order: two of r, g, b, a "
              "or - for none (\"rg\" = seed 001: R density, G height; \"gr\" swaps them)",
      .rebuild = Rebuild::kOffline});
  }
};

// What the blades grow on: the scene's ground height field, or a triangle mesh from a file.
enum class GrassSurface { kGround, kMesh };
constexpr std::array<EnumName<GrassSurface>, 2> enum_names(GrassSurface) {
  return {{{GrassSurface::kGround, "ground"}, {GrassSurface::kMesh, "mesh"}}};
}

// Where the blades on a mesh take their density from (see mesh_blades).
enum class MeshDensitySource { kAuto, kVertexColor, kMapXz, kUvMap };
constexpr std::array<EnumName<MeshDensitySource>, 4> enum_names(MeshDensitySource) {
  return {{{MeshDensitySource::kAuto, "auto"},
           {MeshDensitySource::kVertexColor, "vertex_color"},
           {MeshDensitySource::kMapXz, "map_xz"},
           {MeshDensitySource::kUvMap, "uv_map"}}};
}

// grass.mesh: the mesh of grass.surface = "mesh" (issue 16, grass on any mesh).
struct GrassMeshSettings {
  std::string file;          // OBJ, IV, glTF or GLB, relative to the scene file
  glm::dvec3 offset{0.0};    // added to every vertex [m]
  MeshDensitySource density_source = MeshDensitySource::kAuto;
  std::string density_file;  // uv_map: image over the mesh's UVs, relative to the scene file

  template <class V>
  void visit(V& v) {
    v(file, "file", {.max = 4096.0,
      .help = "Mesh the grass grows on when surface is \"mesh\", relative to the scene file: Wavefront .obj, Open "
              "Inventor ASCII .iv, glTF .gltf or .glb",
      .rebuild = Rebuild::kOffline});
    v(offset, "offset", {.min = -1.0e9, .max = 1.0e9, .unit = "m", .help = "Added to every vertex of grass.mesh.file",
      .rebuild = Rebuild::kOffline});
    v(density_source, "density_source", {.help = "Blade density on the mesh: \"auto\" (vertex colour red if the file "
      "has colours, else map_xz), \"vertex_color\", \"map_xz\" (the density map at the vertices' x/z) or \"uv_map\" "
      "(density_file at each blade's UV; needs texture coordinates)", .rebuild = Rebuild::kOffline});
    v(density_file, "density_file", {.max = 4096.0,
      .help = "Density image over the mesh's UVs for density_source \"uv_map\", relative to the scene file: red "
              "(or grey) 0..1, bilinear, UVs repeat outside 0..1", .rebuild = Rebuild::kOffline});
  }
};

struct GrassSectionSettings {
  GrassSurface surface = GrassSurface::kGround;
  GrassMeshSettings mesh;
  glm::dvec2 area_min{-10.0, -10.0};  // world x/z rectangle of the field [m]
  glm::dvec2 area_max{10.0, 10.0};
  int map_resolution = 128;           // texels along the longer side of a new density/height map
  float map_density_fill = 1.0f;      // value of a new density map (the scene names no density file)
  GrassControlSettings control;
  grass::GrassFieldSettings field;
  grass::BladeSettings blade;
  grass::GrassRenderSettings render;
  bool far_field = true;              // billboard clumps and ground layer beyond the blades (seed 003)
  grass::FarFieldSettings far;

  template <class V>
  void visit(V& v) {
    v(surface, "surface", {.help = "What the blades grow on: \"ground\" (the scene's ground over the area) or \"mesh\" "
      "(every triangle of mesh.file, along its normal; density as mesh.density_source; a far field where the mesh is a height field)",
      .rebuild = Rebuild::kOffline});
    v(mesh, "mesh");
    v(area_min, "area_min", {.min = -1.0e8, .max = 1.0e8, .unit = "m", .help = "Corner of the grass area (x, z)", .rebuild = Rebuild::kOffline});
    v(area_max, "area_max", {.min = -1.0e8, .max = 1.0e8, .unit = "m", .help = "Opposite corner of the grass area (x, z)", .rebuild = Rebuild::kOffline});
    v(map_resolution, "map_resolution", {.min = 1, .max = 8192, .help = "Texels of a new density/height map along the longer side", .rebuild = Rebuild::kOffline});
    v(map_density_fill, "map_density_fill", {.min = 0.0f, .max = 1.0f,
      .help = "Value of a new density map, where the scene names no density map file (painting edits it afterwards)",
      .rebuild = Rebuild::kOffline});
    v(control, "control");
    v(field, "field");
    v(blade, "blade");
    v(render, "render");
    v(far_field, "far_field", {.help = "Billboards and a ground layer beyond the blades", .rebuild = Rebuild::kOffline});
    v(far, "far");
  }
};

Status check_grass(const GrassSectionSettings& s, std::string_view prefix) {
  if (!(s.area_max.x > s.area_min.x && s.area_max.y > s.area_min.y)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}.area_max: ({}, {}) must be above area_min ({}, {}) on both axes", prefix,
                                  s.area_max.x, s.area_max.y, s.area_min.x, s.area_min.y));
  }
  auto ordered = [&](float lo, float hi, const char* lo_name, const char* hi_name) -> Status {
    if (lo <= hi) return {};
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}.blade.{}: {} is above {}.blade.{} ({})", prefix, lo_name, lo, prefix, hi_name, hi));
  };
  if (s.surface == GrassSurface::kMesh && s.mesh.file.empty()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}.mesh.file: {}.surface is \"mesh\" but no mesh is given (an .obj, .iv, .gltf or .glb "
                                  "file relative to the scene file)", prefix, prefix));
  }
  SYLVA_TRY(ordered(s.blade.height_min, s.blade.height_max, "height_min", "height_max"));
  SYLVA_TRY(ordered(s.blade.width_min, s.blade.width_max, "width_min", "width_max"));
  SYLVA_TRY(ordered(s.blade.stiffness_min, s.blade.stiffness_max, "stiffness_min", "stiffness_max"));
  return {};
}

using Settings = SettingsOf<GrassSectionSettings>;

const MapSlot kDensitySlot{"density", MapKind::kUnit, "Blade density, 1 = field.density blades per square metre"};
const MapSlot kHeightSlot{"height", MapKind::kUnit, "Blade height scale, 1 = full blade height"};
const MapSlot kTintSlots[3] = {
    {"tint_r", MapKind::kUnit, "Red multiplier of the grass colour (blades and far field), 1 = unchanged"},
    {"tint_g", MapKind::kUnit, "Green multiplier of the grass colour (blades and far field), 1 = unchanged"},
    {"tint_b", MapKind::kUnit, "Blue multiplier of the grass colour (blades and far field), 1 = unchanged"}};
// File-only slots: their channels fill the maps above (see the header comment).
const MapSlot kControlSlot{"control", MapKind::kUnit,
                           "Seed 001 control texture (RGB file): fills the density and height maps (control.channels)"};
const MapSlot kTintFileSlot{"tint", MapKind::kUnit, "Tint image (RGB file): fills the tint_r, tint_g, tint_b maps"};

Image to_image(const MapGrid& g) {
  Image image(g.width, g.height, 1);
  std::copy(g.values.begin(), g.values.end(), image.data().begin());
  return image;
}

// Largest control, tint or UV density image read, as floats: refused from the header before any
// pixel is decoded. Each fills maps of its size, so 256 MiB (4096^2 RGBA, 8192^2 grey) is the
// most read; a one-colour 16384^2 grey PNG of 1.2 MB would otherwise decode to 1 GiB and then fail
// its channel check, or be kept as a 1 GiB density map (issue 16, "Bad input").
constexpr std::uint64_t kMaxImageBytes = std::uint64_t{256} << 20;

// A control, tint or UV density image: at most 16384 pixels a side and kMaxImageBytes, no NaN.
Result<Image> read_grass_image(const std::filesystem::path& file) {
  ImageReadOptions options;
  options.max_side = 16384;
  options.max_bytes = kMaxImageBytes;
  options.allow_non_finite = false;
  return read_image(file, options);
}

// Largest grass.mesh.file read [bytes]: about four million triangles as OBJ text.
constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t{256} << 20;

// The image file of file-only slot `slot`, read once per build; errors name the key and the file.
Result<Image> read_slot_image(const ModuleBuildContext& ctx, const MapSlot& slot, int channels_needed,
                              const std::string& why) {
  const std::string key = fmt::format("{}.maps.{}", ctx.section->name, slot.name);
  const std::filesystem::path file = ctx.document->resolve(ctx.section->maps.at(slot.name));
  auto image = read_grass_image(file);
  if (!image.ok()) return make_error(image.error().code, fmt::format("{}: {}", key, image.error().message));
  if (image->channels() < channels_needed) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: {} has {} channel(s), {} needs {}", key, file.string(),
                                                               image->channels(), why, channels_needed));
  }
  if (image->width() < 2 || image->height() < 2) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: {} is {} x {} pixels, a map needs at least 2 x 2", key,
                                                               file.string(), image->width(), image->height()));
  }
  return std::move(*image);
}

// Puts channel `channel` of `image` into the scene as map `slot` (an unsaved default: path "",
// written only once edited) unless the scene already holds that map or the section names a file
// for it; ensure_area_map then places it over the area.
void fill_from_channel(const ModuleBuildContext& ctx, const MapSlot& slot, const Image& image, int channel) {
  const std::string id = ctx.section->name + "." + slot.name;
  if (ctx.maps->count(id) || ctx.section->maps.count(slot.name)) return;
  SceneMap map;
  map.module = ctx.section->name;
  map.slot = slot.name;
  map.kind = slot.kind;
  map.grid = MapGrid(image.width(), image.height(), 0.0f, {0.0, 0.0}, {1.0, 1.0});
  for (int j = 0; j < image.height(); ++j)
    for (int i = 0; i < image.width(); ++i) map.grid.at(i, j) = std::clamp(image.at(i, j, channel), 0.0f, 1.0f);
  ctx.maps->emplace(id, std::move(map));
}

// control.channels as channel indices (-1 = none); errors name the key.
Result<std::array<int, 2>> control_channels(const std::string& text, std::string_view prefix) {
  constexpr std::string_view kLetters = "rgba-";
  std::array<int, 2> out{-1, -1};
  bool valid = text.size() == 2;
  for (std::size_t k = 0; valid && k < 2; ++k) {
    const std::size_t c = kLetters.find(text[k]);
    valid = c != std::string_view::npos;
    if (valid && c < 4) out[k] = static_cast<int>(c);
  }
  if (!valid) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}.control.channels: \"{}\" is not two of r, g, b, a, - (density, height)", prefix, text));
  }
  return out;
}

// The blade draw is indirect (the GPU culls and tessellates), so GrassField::draw cannot know its
// triangles. This wrapper adds the primitives its own query counted for the newest completed
// frame (non-stalling, a few frames old, like every GPU counter) to the opaque pass's triangles,
// so the stats overlay and --stats show grass triangles like every other module's.
class CountedBlades final : public render::Drawable {
 public:
  void set(grass::GrassField* field) {
    if (field != field_) last_primitives_ = 0;
    field_ = field;
  }
  std::uint64_t last_primitives() const { return last_primitives_; }

  void update(const render::FrameContext& frame) override { field_->update(frame); }
  void draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) override {
    field_->draw(pass, frame, stats);
    if (pass != render::Pass::kOpaque) return;
    if (auto t = field_->gpu_times()) last_primitives_ = t->primitives;
    stats.triangles += last_primitives_;
  }
  void on_region_changed(const render::WorldRect& world_xz) override { field_->on_region_changed(world_xz); }

 private:
  grass::GrassField* field_ = nullptr;
  std::uint64_t last_primitives_ = 0;
};

class GrassInstance final : public ModuleInstance {
 public:
  static Result<std::unique_ptr<ModuleInstance>> create(const ModuleBuildContext& ctx) {
    auto inst = std::unique_ptr<GrassInstance>(new GrassInstance(ctx));
    SYLVA_TRY(inst->build());
    return std::unique_ptr<ModuleInstance>(std::move(inst));
  }

  std::vector<render::Drawable*> drawables() override {
    std::vector<render::Drawable*> d{&blades_};
    if (far_) d.push_back(&*far_);
    return d;
  }

  void sync_settings() override {
    if (!edits_.empty()) {
      // Dabs since the last frame: only the tiles they reach (issue 16), blades and far field.
      const std::vector<grass::Rect> areas = std::move(edits_);
      const bool ground = ground_edited_;
      edits_.clear();
      ground_edited_ = false;
      Status st = regenerate(areas, ground);
      if (!st.ok()) log_warn("grass: regeneration after an edit failed: {}", st.error().message);
    }
    const GrassSectionSettings& s = settings();
    field_->settings() = s.render;
    if (far_) {
      // Per-frame far-field settings; the ones marked kOffline only change on a rebuild.
      far_->settings() = s.far;
      far_->set_near(s.render.cull.near_distance, s.render.physics.wind_response,
                     0.5f * (s.blade.stiffness_min + s.blade.stiffness_max), s.render.base_color, s.render.tip_color,
                     s.render.shading.ambient, s.render.shading.translucency);
      far_->set_color_motion(s.render.shading.color_motion, s.render.shading.color_motion_hz);
    }
  }

  Status rebuild(Rebuild what) override {
    if (what == Rebuild::kNone) return {};
    return build();
  }

  Status on_map_changed(const std::string& map_id, const WorldArea& area) override {
    const GrassSectionSettings& s = settings();
    // Not one of this section's maps: the ground, which the far field's clumps and ground layer
    // also stand on beyond the area, out to their margins.
    const bool ground = map_id.rfind(ctx_.section->name + ".", 0) != 0;
    const double margin = ground && far_ ? std::max(s.far.clump_margin, s.far.ground_margin) : 0.0;
    const glm::dvec2 lo = s.area_min - margin, hi = s.area_max + margin;
    if (area.max.x < lo.x || area.min.x > hi.x || area.max.y < lo.y || area.min.y > hi.y) {
      return {};  // the edit is outside the field
    }
    const grass::Rect r{glm::max(area.min, lo), glm::min(area.max, hi)};
    if (ground) ground_edited_ = true;
    if (edits_.size() < kMaxEditsPerFrame) {
      edits_.push_back(r);
    } else {  // a flood of edits in one frame: their union
      edits_.back() = {glm::min(edits_.back().min, r.min), glm::max(edits_.back().max, r.max)};
    }
    return {};
  }

  // The blade draw runs its own primitives query (grass_field.cpp), so the scene only times it.
  bool counts_own_primitives() const override { return true; }

  nlohmann::json stats() const override {
    nlohmann::json j = {{"blades", field_->blade_count()},
                        {"tiles", field_->tiles().size()},
                        {"regenerations", regenerations_},
                        {"tile_regenerations", tile_regenerations_},
                        {"last_tiles_regenerated", last_tiles_regenerated_},
                        {"far_tile_updates", far_tile_updates_},
                        {"max_blade_height", field_->max_height()},
                        {"blade_triangles", blades_.last_primitives()}};
    if (!far_off_.empty()) j["far_field_off"] = far_off_;
    if (settings().surface == GrassSurface::kMesh) {
      j["surface"] = "mesh";
      j["mesh_triangles"] = mesh_triangles_;
      j["up_axes"] = up_axes_;
    }
    if (far_) {
      j["clumps"] = far_->clump_count();
      j["clumps_drawn"] = far_->last_clumps_drawn();
      j["ground_chunks_drawn"] = far_->last_ground_chunks_drawn();
      // Seed 003's wide billboards over tile groups (grass.far.wide_billboards, Tab. 4.2).
      j["wide_billboards"] = far_->wide_billboard_count();
      j["wide_billboards_drawn"] = far_->last_wide_billboards_drawn();
      // Seed 003 §4.3's coarser far-ground sub-level (grass.far.coarse_ground).
      j["coarse_ground_chunks_drawn"] = far_->last_coarse_chunks_drawn();
      // The three levels of seed 003: blades near (counted as triangles, see CountedBlades),
      // billboard clumps in the middle, ground-layer chunks far.
      j["instances_per_lod"] = {{"clumps", far_->last_clumps_drawn()}, {"ground_chunks", far_->last_ground_chunks_drawn()}};
    }
    return j;
  }

  std::vector<glm::dvec3> placed_positions(std::size_t max_count) const override {
    const std::vector<grass::Blade> blades = field_->read_blades();
    std::vector<glm::dvec3> out;
    if (blades.empty() || max_count == 0) return out;
    const std::size_t step = std::max<std::size_t>(1, blades.size() / max_count);
    for (std::size_t i = 0; i < blades.size() && out.size() < max_count; i += step) {
      out.push_back(field_->origin() + glm::dvec3(blades[i].root()));
    }
    return out;
  }

  std::vector<render::Aabb> debug_bounds() const override {
    std::vector<render::Aabb> out;
    const glm::dvec3 o = field_->origin();
    for (const grass::GrassTile& t : field_->tiles()) {
      out.push_back({o + glm::dvec3(t.bounds_min), o + glm::dvec3(t.bounds_max)});
    }
    return out;
  }

 private:
  explicit GrassInstance(const ModuleBuildContext& ctx) : ModuleInstance("grass"), ctx_(ctx) {}

  const GrassSectionSettings& settings() const { return static_cast<const Settings&>(*ctx_.section->settings).value; }

  // Fills the density/height/tint maps from maps.control and maps.tint where the scene has none.
  Status fill_from_files() {
    const GrassSectionSettings& s = settings();
    const std::string& name = ctx_.section->name;
    auto channels = control_channels(s.control.channels, name);
    if (!channels.ok()) return channels.error();
    const MapSlot* targets[2] = {&kDensitySlot, &kHeightSlot};
    auto missing = [&](const MapSlot& slot) {
      return !ctx_.maps->count(name + "." + slot.name) && !ctx_.section->maps.count(slot.name);
    };
    if (ctx_.section->maps.count(kControlSlot.name) && (missing(kDensitySlot) || missing(kHeightSlot))) {
      const int needed = std::max((*channels)[0], (*channels)[1]) + 1;
      auto control = read_slot_image(ctx_, kControlSlot, std::max(needed, 1),
                                     fmt::format("{}.control.channels \"{}\"", name, s.control.channels));
      if (!control.ok()) return control.error();
      for (int k = 0; k < 2; ++k) {
        if ((*channels)[k] >= 0) fill_from_channel(ctx_, *targets[k], *control, (*channels)[k]);
      }
    }
    if (ctx_.section->maps.count(kTintFileSlot.name) &&
        std::any_of(std::begin(kTintSlots), std::end(kTintSlots), missing)) {
      auto tint = read_slot_image(ctx_, kTintFileSlot, 3, "a tint (RGB)");
      if (!tint.ok()) return tint.error();
      for (int c = 0; c < 3; ++c) fill_from_channel(ctx_, kTintSlots[c], *tint, c);
    }
    return {};
  }

  // The tint maps as one RGB image; nullopt when all three are 1 everywhere (no tint map, so the
  // default field is what it was without tint maps). Errors when their sizes differ.
  Result<std::optional<Image>> tint_image(const SceneMap* const (&maps)[3]) const {
    const bool white = std::all_of(std::begin(maps), std::end(maps), [](const SceneMap* m) {
      return std::all_of(m->grid.values.begin(), m->grid.values.end(), [](float v) { return v == 1.0f; });
    });
    if (white) return std::optional<Image>();
    const MapGrid& r = maps[0]->grid;
    for (int c = 1; c < 3; ++c) {
      const MapGrid& g = maps[c]->grid;
      if (g.width != r.width || g.height != r.height) {
        return make_error(ErrorCode::kInvalidArgument,
                          fmt::format("{}.maps.{}: {} x {} texels, but {}.maps.tint_r has {} x {}: the tint maps must match",
                                      ctx_.section->name, kTintSlots[c].name, g.width, g.height, ctx_.section->name,
                                      r.width, r.height));
      }
    }
    Image image(r.width, r.height, 3);
    for (int j = 0; j < r.height; ++j)
      for (int i = 0; i < r.width; ++i)
        for (int c = 0; c < 3; ++c) image.at(i, j, c) = maps[c]->grid.at(i, j);
    return std::optional<Image>(std::move(image));
  }

  // What blades are made from: the maps as they are now, the ground and the blade-set origin.
  struct Inputs {
    grass::GrassMaps maps;
    const HeightField* ground = nullptr;
    glm::dvec3 origin{0.0};
  };

  Result<Inputs> inputs() {
    const GrassSectionSettings& s = settings();
    SYLVA_TRY(fill_from_files());
    const SceneMap* tints[3];
    for (int c = 0; c < 3; ++c) {
      auto t = ensure_area_map(ctx_, kTintSlots[c], s.area_min, s.area_max, s.map_resolution, 1.0f);
      if (!t.ok()) return t.error();
      tints[c] = *t;
    }
    auto tint_rgb = tint_image(tints);
    if (!tint_rgb.ok()) return tint_rgb.error();
    auto density = ensure_area_map(ctx_, kDensitySlot, s.area_min, s.area_max, s.map_resolution, s.map_density_fill);
    if (!density.ok()) return density.error();
    auto height = ensure_area_map(ctx_, kHeightSlot, s.area_min, s.area_max, s.map_resolution, 1.0f);
    if (!height.ok()) return height.error();
    const grass::Rect rect{s.area_min, s.area_max};
    const Image density_image = to_image((*density)->grid);
    const Image height_image = to_image((*height)->grid);
    const Image* tint = *tint_rgb ? &**tint_rgb : nullptr;
    auto maps = grass::GrassMaps::from_images(rect, &density_image, &height_image, tint);
    if (!maps.ok()) return make_error(maps.error().code, "grass.maps: " + maps.error().message);

    Inputs in;
    in.maps = std::move(*maps);
    in.ground = ctx_.ground;
    if (!in.ground) {
      // No ground in the scene: a flat one at y = 0 under the area (a few metres beyond it).
      const glm::dvec2 lo = s.area_min - 4.0, hi = s.area_max + 4.0;
      const double spacing = std::max((hi.x - lo.x), (hi.y - lo.y)) / 64.0;
      flat_ = HeightField(static_cast<int>((hi.x - lo.x) / spacing) + 2, static_cast<int>((hi.y - lo.y) / spacing) + 2,
                          spacing, lo);
      in.ground = &*flat_;
    }
    const glm::dvec2 c = 0.5 * (s.area_min + s.area_max);
    in.origin = glm::dvec3(c.x, in.ground->height(c.x, c.y), c.y);
    return in;
  }

  // The far field stands on a height field: the scene's ground, or on a mesh surface the mesh
  // rasterised into one when it is a height field (mesh_far).
  Result<std::optional<grass::FarField>> make_far(const Inputs& in) {
    const GrassSectionSettings& s = settings();
    far_off_.clear();
    if (!s.far_field) return std::optional<grass::FarField>();
    if (s.surface == GrassSurface::kMesh) return mesh_far();
    auto f = grass::FarField::create(s.field, s.blade, in.maps, *in.ground, in.origin, s.far);
    if (!f.ok()) return make_error(f.error().code, "grass.far: " + f.error().message);
    return std::optional<grass::FarField>(std::move(*f));
  }

  Status build() {
    const GrassSectionSettings& s = settings();
    auto in = inputs();
    if (!in.ok()) return in.error();
    auto blades = s.surface == GrassSurface::kMesh ? mesh_blades(in->maps)
                                                   : grass::generate_blades(s.field, s.blade, in->maps, *in->ground, in->origin);
    if (!blades.ok()) return make_error(blades.error().code, "grass: " + blades.error().message);
    up_axes_ = s.surface == GrassSurface::kMesh ? count_up_axes(*blades) : nlohmann::json();
    auto field = grass::GrassField::create(*blades, s.render);
    if (!field.ok()) return make_error(field.error().code, "grass: " + field.error().message);
    auto far = make_far(*in);
    if (!far.ok()) return far.error();
    set_ = std::move(*blades);
    field_ = std::move(*field);
    blades_.set(&*field_);
    far_ = std::move(*far);
    edits_.clear();
    ground_edited_ = false;
    ++regenerations_;
    return {};
  }

  // Tile-local regeneration (grass::regenerate_tiles): equal to build()'s blades bit for bit
  // (grass_tile_edit_gl_test); a full build when the origin moved (a ground edit under the
  // field's centre), since every blade is stored relative to it.
  Status regenerate(const std::vector<grass::Rect>& areas, bool ground_changed) {
    const GrassSectionSettings& s = settings();
    if (s.surface == GrassSurface::kMesh) return build();  // mesh blades are not tiled by x/z
    auto in = inputs();
    if (!in.ok()) return in.error();
    if (in->origin != set_.origin) return build();
    // Each area with the final maps: a tile two dabs reach is made twice, identically.
    last_tiles_regenerated_ = 0;
    for (const grass::Rect& area : areas) {
      auto first = grass::regenerate_tiles(set_, s.field, s.blade, in->maps, *in->ground, area);  // set_ kept on error
      if (!first.ok()) return make_error(first.error().code, "grass: " + first.error().message);
      const auto reached = grass::tiles_overlapping(area.intersect(in->maps.rect()), s.field.tile_size);
      if (reached.ok() && !area.intersect(in->maps.rect()).empty()) {
        last_tiles_regenerated_ += static_cast<std::uint64_t>((reached->x1 - reached->x0) * (reached->z1 - reached->z0));
      }
    }
    if (!field_->set_blades(set_).ok()) return build();  // a tile over the storage limit: as before
    if (far_) {
      Status far = far_->update_region(s.field, s.blade, in->maps, *in->ground, areas, ground_changed);
      if (far.ok()) {
        ++far_tile_updates_;
      } else {  // e.g. a tint map appeared: the far field is made anew
        log_info("grass.far: {}; rebuilding it", far.error().message);
        SYLVA_TRY(rebuild_far());
      }
    }
    ++regenerations_;
    ++tile_regenerations_;
    return {};
  }

  // grass.surface = "mesh": every triangle of grass.mesh.file (terrain's load_mesh: OBJ, IV,
  // glTF, GLB; moved by grass.mesh.offset) grows blades along its face normal (sharp edges keep
  // their walls' normals), Jahrmann & Wimmer 2017 (grass::generate_blades_on_mesh). Density by
  // mesh.density_source: "vertex_color" the red of the vertex colours (OBJ `v x y z r g b`, glTF
  // COLOR_0); "map_xz" the density map at the vertex's world x/z (0 outside area_min..area_max,
  // as on the ground), so the map painted from above thins grass on walls and overhangs below it
  // too; "auto" the first when the file has colours, else the second; "uv_map" mesh.density_file
  // at each blade root's UV (grass::UvDensityMap; a mesh without UVs is an error).
  Result<grass::BladeSet> mesh_blades(const grass::GrassMaps& maps) {
    const std::string key = ctx_.section->name + ".mesh.file";
#ifdef SYLVA_HAS_TERRAIN
    const GrassSectionSettings& s = settings();
    const std::filesystem::path path =
        ctx_.document != nullptr ? ctx_.document->resolve(s.mesh.file) : std::filesystem::path(s.mesh.file);
    // A mesh file is read whole (as text for OBJ): its size is checked first, so a huge file
    // (a 2 GiB OBJ took 6.5 GB and 30 s) is refused unread (issue 16, "Bad input").
    std::error_code size_error;
    if (const std::uintmax_t bytes = std::filesystem::file_size(path, size_error); !size_error && bytes > kMaxMeshFileBytes) {
      return make_error(ErrorCode::kLimit, fmt::format("{}: {} is {} MiB, above the {} MiB limit of a grass mesh file", key,
                                                       path.string(), bytes >> 20, kMaxMeshFileBytes >> 20));
    }
    auto polygons = terrain::load_mesh(path);
    if (!polygons.ok()) {
      const std::string& m = polygons.error().message;
      return make_error(polygons.error().code, m.find(path.filename().string()) != std::string::npos
                                                   ? fmt::format("{}: {}", key, m)
                                                   : fmt::format("{}: {}: {}", key, path.string(), m));
    }
    const terrain::TriangleMesh mesh = terrain::triangulate(*polygons);
    auto uv_map = mesh_uv_density(mesh, path);
    if (!uv_map.ok()) return uv_map.error();
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const glm::vec3& p : mesh.positions) {
      lo = glm::min(lo, glm::dvec3(p) + s.mesh.offset);
      hi = glm::max(hi, glm::dvec3(p) + s.mesh.offset);
    }
    const glm::dvec3 origin = 0.5 * (lo + hi);
    std::vector<glm::vec3> positions;
    std::vector<float> density;
    positions.reserve(mesh.positions.size());
    density.reserve(mesh.positions.size());
    for (const glm::vec3& p : mesh.positions) {
      const glm::dvec3 world = glm::dvec3(p) + s.mesh.offset;
      positions.push_back(glm::vec3(world - origin));
      density.push_back(maps.density(world.x, world.z));
    }
    const MeshDensitySource source = s.mesh.density_source;
    if (source == MeshDensitySource::kVertexColor && polygons->colors.empty()) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}.mesh.density_source: \"vertex_color\" but {} has no vertex colours",
                                    ctx_.section->name, path.string()));
    }
    const bool by_color = source == MeshDensitySource::kVertexColor || (source == MeshDensitySource::kAuto && !polygons->colors.empty());
    if (by_color) {  // R is the density (seed 001's control layout)
      for (std::size_t i = 0; i < density.size(); ++i) density[i] = polygons->colors[i].r;
    }
    mesh_triangles_ = mesh.triangle_count();
    std::optional<grass::MeshUvDensity> uv;
    if (*uv_map) uv.emplace(grass::MeshUvDensity{mesh.corner_uvs, **uv_map});
    auto set = grass::generate_blades_on_mesh(s.field, s.blade, {positions, {}, mesh.indices, density}, origin,
                                              uv ? &*uv : nullptr);
    if (!set.ok()) return make_error(set.error().code, fmt::format("{} ({}): {}", key, path.string(), set.error().message));
    keep_mesh_surface(path, origin, std::move(positions), mesh, std::move(density), *uv_map);
    return set;
#else
    (void)maps;
    return make_error(ErrorCode::kUnsupported,
                      fmt::format("{}: {}.surface \"mesh\" needs the terrain module's mesh loaders, which this build leaves out",
                                  key, ctx_.section->name));
#endif
  }

#ifdef SYLVA_HAS_TERRAIN
  // density_source "uv_map": grass.mesh.density_file read through core's image reader
  // (read_grass_image's limits); nullopt for the other sources. Errors name the setting and the file.
  Result<std::optional<grass::UvDensityMap>> mesh_uv_density(const terrain::TriangleMesh& mesh,
                                                              const std::filesystem::path& mesh_path) const {
    const GrassSectionSettings& s = settings();
    if (s.mesh.density_source != MeshDensitySource::kUvMap) return std::optional<grass::UvDensityMap>();
    const std::string& name = ctx_.section->name;
    if (mesh.corner_uvs.empty()) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}.mesh.density_source: \"uv_map\" needs texture coordinates, but {} has none "
                                    "(OBJ: vt and f v/vt on every face; glTF: TEXCOORD_0 on every primitive)",
                                    name, mesh_path.string()));
    }
    if (s.mesh.density_file.empty()) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}.mesh.density_file: {}.mesh.density_source is \"uv_map\" but no density image "
                                    "is given", name, name));
    }
    const std::filesystem::path file =
        ctx_.document != nullptr ? ctx_.document->resolve(s.mesh.density_file) : std::filesystem::path(s.mesh.density_file);
    auto image = read_grass_image(file);
    if (!image.ok()) return make_error(image.error().code, fmt::format("{}.mesh.density_file: {}", name, image.error().message));
    auto map = grass::UvDensityMap::create(*image, "mesh.density_file");
    if (!map.ok()) return make_error(map.error().code, fmt::format("{}.mesh.density_file: {}: {}", name, file.string(), map.error().message));
    return std::optional<grass::UvDensityMap>(std::move(*map));
  }
#endif

  // Blades of a mesh surface by the axis their up vector is within 0.1 rad of (stats "up_axes").
  static nlohmann::json count_up_axes(const grass::BladeSet& set) {
    static constexpr const char* kNames[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};
    std::array<std::uint64_t, 6> n{};
    std::uint64_t other = 0;
    for (const grass::Blade& b : set.blades) {
      const glm::vec3 u = b.up_dir();
      int axis = -1;
      for (int a = 0; a < 3 && axis < 0; ++a) {
        if (std::abs(u[a]) > std::cos(0.1f)) axis = 2 * a + (u[a] < 0.0f ? 1 : 0);
      }
      if (axis < 0) ++other; else ++n[static_cast<std::size_t>(axis)];
    }
    nlohmann::json j = {{"other", other}};
    for (int a = 0; a < 6; ++a) j[kNames[a]] = n[static_cast<std::size_t>(a)];
    return j;
  }

  // What mesh_far needs of the mesh mesh_blades grew blades on: positions relative to origin,
  // triangles, per-vertex density or the UV density map with the corners' UVs.
  struct MeshSurface {
    std::string file;
    glm::dvec3 origin{0.0};
    std::vector<glm::vec3> positions;
    std::vector<std::uint32_t> indices;
    std::vector<float> density;
    std::vector<glm::vec2> corner_uvs;
    std::optional<grass::UvDensityMap> uv_map;
  };
#ifdef SYLVA_HAS_TERRAIN
  void keep_mesh_surface(const std::filesystem::path& file, const glm::dvec3& origin, std::vector<glm::vec3> positions,
                         const terrain::TriangleMesh& mesh, std::vector<float> density,
                         const std::optional<grass::UvDensityMap>& uv_map) {
    mesh_surface_ = MeshSurface{file.string(), origin, std::move(positions), mesh.indices, std::move(density),
                                uv_map ? mesh.corner_uvs : std::vector<glm::vec2>{}, uv_map};
  }
#endif

  // The far field on a mesh surface (issue 16): the mesh rasterised into a height field and a
  // density map (grass::mesh_height_field) at the finer of far.ground_spacing and 1/64 of the
  // mesh's size, when it is one; margins are 0 (there is no surface beyond the mesh). A mesh that
  // is no height field gets none: a warning names the file and why, and stats "far_field_off".
  Result<std::optional<grass::FarField>> mesh_far() {
    const GrassSectionSettings& s = settings();
    if (!mesh_surface_) return std::optional<grass::FarField>();
    const MeshSurface& m = *mesh_surface_;
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (const glm::vec3& p : m.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    const double size = std::max(static_cast<double>(hi.x - lo.x), static_cast<double>(hi.z - lo.z));
    // At most 2001 samples a side: within mesh_height_field's 2^22 samples.
    const double spacing = std::max(std::min(static_cast<double>(s.far.ground_spacing), size / 64.0), size / 2000.0);
    auto density = [&m](std::uint32_t t, const glm::vec3& w) {
      if (m.uv_map) {
        const glm::vec2* uv = &m.corner_uvs[3 * static_cast<std::size_t>(t)];
        return m.uv_map->sample(w.x * uv[0] + w.y * uv[1] + w.z * uv[2]);
      }
      const std::uint32_t* v = &m.indices[3 * static_cast<std::size_t>(t)];
      return w.x * m.density[v[0]] + w.y * m.density[v[1]] + w.z * m.density[v[2]];
    };
    auto raster = grass::mesh_height_field(m.positions, m.indices, m.origin, spacing, density);
    if (!raster.ok()) {
      far_off_ = fmt::format("{}: {}", m.file, raster.error().message);
      log_warn("{}.far_field: no far field on {}", ctx_.section->name, far_off_);
      return std::optional<grass::FarField>();
    }
    auto maps = grass::GrassMaps::from_images(raster->rect, &raster->density, nullptr, nullptr);
    if (!maps.ok()) return make_error(maps.error().code, "grass.far: " + maps.error().message);
    grass::FarFieldSettings far = s.far;
    far.clump_margin = 0.0f;
    far.ground_margin = 0.0f;
    auto f = grass::FarField::create(s.field, s.blade, *maps, raster->heights, m.origin, far);
    if (!f.ok()) return make_error(f.error().code, fmt::format("grass.far ({}): {}", m.file, f.error().message));
    return std::optional<grass::FarField>(std::move(*f));
  }

  Status rebuild_far() {
    auto in = inputs();
    if (!in.ok()) return in.error();
    auto far = make_far(*in);
    if (!far.ok()) return far.error();
    far_ = std::move(*far);
    return {};
  }

  ModuleBuildContext ctx_;
  std::optional<HeightField> flat_;
  std::optional<grass::GrassField> field_;
  std::optional<grass::FarField> far_;
  CountedBlades blades_;
  grass::BladeSet set_;                 // the blades as generated (the GPU copy moves with physics)
  static constexpr std::size_t kMaxEditsPerFrame = 64;
  std::vector<grass::Rect> edits_;      // the map edits since the last frame
  bool ground_edited_ = false;          // edits_ include an edit of the ground (not our maps)
  std::uint64_t regenerations_ = 0;     // full builds and tile-local regenerations
  std::uint64_t tile_regenerations_ = 0;
  std::uint64_t last_tiles_regenerated_ = 0;
  std::uint64_t far_tile_updates_ = 0;  // edits the far field took tile-locally (update_region)
  std::uint64_t mesh_triangles_ = 0;    // of grass.mesh.file (surface "mesh")
  std::optional<MeshSurface> mesh_surface_;  // the mesh of surface "mesh" (mesh_far)
  std::string far_off_;                 // why a requested far field is not drawn (a mesh that is no height field)
  nlohmann::json up_axes_;              // count_up_axes of the mesh blades
};

}  // namespace

ModuleDescriptor grass_module() {
  ModuleDescriptor d;
  d.name = "grass";
  d.description = "tessellated grass blades with physics and a billboard/ground far field (seeds 001, 003)";
  d.needs_ground = true;
  d.left_out_on_failure = true;  // a bad control, tint, mesh or density file: the scene opens without grass
  d.make_settings = [] { return std::make_unique<Settings>(std::vector<MapSlot>{kDensitySlot, kHeightSlot, kTintSlots[0], kTintSlots[1],
                                                                             kTintSlots[2], kControlSlot, kTintFileSlot}, &check_grass); };
  d.create = &GrassInstance::create;
  return d;
}

}  // namespace sylva::scene::detail

// The "grass" section: one field of tessellated blades (grass::GrassField) with the seed-003 far
// field (grass::FarField) over a world rectangle, standing on the scene's ground HeightField (or
// on flat ground at y = 0 when the scene has none), reading the scene's wind and lighting.
// Maps: density (blade count) and height (blade height scale), both [0, 1] over the area.
//
// Edits: a changed map or ground area marks the field dirty; it is regenerated once at the next
// frame (sync_settings), so a brush stroke of many dabs costs one regeneration per frame. Blade
// placement is world-anchored per tile (grass/generator.hpp), so blades outside the edited area
// come back bit-identical; only their physics state restarts.

#include "modules/module_factories.hpp"

#include <sylva/grass/far_field.hpp>
#include <sylva/grass/generator.hpp>
#include <sylva/grass/grass_field.hpp>
#include <sylva/grass/maps.hpp>
#include <sylva/grass/settings.hpp>
#include <sylva/core/log.hpp>
#include <sylva/scene/module_instance.hpp>

#include <fmt/format.h>

#include <optional>

namespace sylva::scene::detail {
namespace {

struct GrassSectionSettings {
  glm::dvec2 area_min{-10.0, -10.0};  // world x/z rectangle of the field [m]
  glm::dvec2 area_max{10.0, 10.0};
  int map_resolution = 128;           // texels along the longer side of a new density/height map
  float map_density_fill = 1.0f;      // value of a new density map (the scene names no density file)
  grass::GrassFieldSettings field;
  grass::BladeSettings blade;
  grass::GrassRenderSettings render;
  bool far_field = true;              // billboard clumps and ground layer beyond the blades (seed 003)
  grass::FarFieldSettings far;

  template <class V>
  void visit(V& v) {
    v(area_min, "area_min", {.min = -1.0e8, .max = 1.0e8, .unit = "m", .help = "Corner of the grass area (x, z)", .rebuild = Rebuild::kOffline});
    v(area_max, "area_max", {.min = -1.0e8, .max = 1.0e8, .unit = "m", .help = "Opposite corner of the grass area (x, z)", .rebuild = Rebuild::kOffline});
    v(map_resolution, "map_resolution", {.min = 1, .max = 8192, .help = "Texels of a new density/height map along the longer side", .rebuild = Rebuild::kOffline});
    v(map_density_fill, "map_density_fill", {.min = 0.0f, .max = 1.0f,
      .help = "Value of a new density map, where the scene names no density map file (painting edits it afterwards)",
      .rebuild = Rebuild::kOffline});
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
  SYLVA_TRY(ordered(s.blade.height_min, s.blade.height_max, "height_min", "height_max"));
  SYLVA_TRY(ordered(s.blade.width_min, s.blade.width_max, "width_min", "width_max"));
  SYLVA_TRY(ordered(s.blade.stiffness_min, s.blade.stiffness_max, "stiffness_min", "stiffness_max"));
  return {};
}

using Settings = SettingsOf<GrassSectionSettings>;

const MapSlot kDensitySlot{"density", MapKind::kUnit, "Blade density, 1 = field.density blades per square metre"};
const MapSlot kHeightSlot{"height", MapKind::kUnit, "Blade height scale, 1 = full blade height"};

Image to_image(const MapGrid& g) {
  Image image(g.width, g.height, 1);
  std::copy(g.values.begin(), g.values.end(), image.data().begin());
  return image;
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
    if (dirty_) {
      dirty_ = false;
      Status s = build();
      if (!s.ok()) log_warn("grass: regeneration after an edit failed: {}", s.error().message);
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
    (void)map_id;
    const GrassSectionSettings& s = settings();
    if (area.max.x < s.area_min.x || area.min.x > s.area_max.x || area.max.y < s.area_min.y || area.min.y > s.area_max.y) {
      return {};  // the edit is outside the field
    }
    dirty_ = true;
    ++regenerations_requested_;
    return {};
  }

  // The blade draw runs its own primitives query (grass_field.cpp), so the scene only times it.
  bool counts_own_primitives() const override { return true; }

  nlohmann::json stats() const override {
    nlohmann::json j = {{"blades", field_->blade_count()},
                        {"tiles", field_->tiles().size()},
                        {"regenerations", regenerations_},
                        {"blade_triangles", blades_.last_primitives()}};
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

  Status build() {
    const GrassSectionSettings& s = settings();
    auto density = ensure_area_map(ctx_, kDensitySlot, s.area_min, s.area_max, s.map_resolution, s.map_density_fill);
    if (!density.ok()) return density.error();
    auto height = ensure_area_map(ctx_, kHeightSlot, s.area_min, s.area_max, s.map_resolution, 1.0f);
    if (!height.ok()) return height.error();
    const grass::Rect rect{s.area_min, s.area_max};
    const Image density_image = to_image((*density)->grid);
    const Image height_image = to_image((*height)->grid);
    auto maps = grass::GrassMaps::from_images(rect, &density_image, &height_image, nullptr);
    if (!maps.ok()) return make_error(maps.error().code, "grass.maps: " + maps.error().message);

    const HeightField* ground = ctx_.ground;
    if (!ground) {
      // No ground in the scene: a flat one at y = 0 under the area (a few metres beyond it).
      const glm::dvec2 lo = s.area_min - 4.0, hi = s.area_max + 4.0;
      const double spacing = std::max((hi.x - lo.x), (hi.y - lo.y)) / 64.0;
      flat_ = HeightField(static_cast<int>((hi.x - lo.x) / spacing) + 2, static_cast<int>((hi.y - lo.y) / spacing) + 2,
                          spacing, lo);
      ground = &*flat_;
    }
    const glm::dvec2 c = 0.5 * (s.area_min + s.area_max);
    const glm::dvec3 origin(c.x, ground->height(c.x, c.y), c.y);
    auto blades = grass::generate_blades(s.field, s.blade, *maps, *ground, origin);
    if (!blades.ok()) return make_error(blades.error().code, "grass: " + blades.error().message);
    auto field = grass::GrassField::create(std::move(*blades), s.render);
    if (!field.ok()) return make_error(field.error().code, "grass: " + field.error().message);
    std::optional<grass::FarField> far;
    if (s.far_field) {
      auto f = grass::FarField::create(s.field, s.blade, *maps, *ground, origin, s.far);
      if (!f.ok()) return make_error(f.error().code, "grass.far: " + f.error().message);
      far = std::move(*f);
    }
    field_ = std::move(*field);
    blades_.set(&*field_);
    far_ = std::move(far);
    ++regenerations_;
    return {};
  }

  ModuleBuildContext ctx_;
  std::optional<HeightField> flat_;
  std::optional<grass::GrassField> field_;
  std::optional<grass::FarField> far_;
  CountedBlades blades_;
  bool dirty_ = false;
  std::uint64_t regenerations_ = 0;
  std::uint64_t regenerations_requested_ = 0;
};

}  // namespace

ModuleDescriptor grass_module() {
  ModuleDescriptor d;
  d.name = "grass";
  d.description = "tessellated grass blades with physics and a billboard/ground far field (seeds 001, 003)";
  d.needs_ground = true;
  d.make_settings = [] { return std::make_unique<Settings>(std::vector<MapSlot>{kDensitySlot, kHeightSlot}, &check_grass); };
  d.create = &GrassInstance::create;
  return d;
}

}  // namespace sylva::scene::detail

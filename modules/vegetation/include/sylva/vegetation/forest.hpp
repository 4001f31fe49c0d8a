#pragma once
// Forest: many LOD0 trees of several species as one render::Drawable (DESIGN.md §2b).
//
// Per frame, update() evaluates the animation clock and the shared wind (WindField::frame at the
// camera), culls every instance's bounding sphere (rest bounds grown by cull_margin for the wind's
// motion) against the camera frustum and max_distance, computes the surviving instances' GPU records
// (camera-relative translation in double precision, wind at the tree rotated into object space)
// and uploads them; draw(kOpaque) issues one instanced draw per species for the bark and one for
// the leaves. Instances are the seed's per-instance data (§4.5): transform, scale, animation phase
// (time offset), season offset and colour variation.
//
// Shadows (render/shadow_maps.hpp): draw_depth() is the depth-only pass with the very same
// deformation, for a ShadowCaster's draw_shadow(ctx) (ctx.relative_view_projection,
// ctx.light_frustum); draw(kShadow) does the same for the cascade render::active_shadow_cascade()
// names while ShadowMaps::render runs (and nothing otherwise). Culling uses the caster's frustum,
// not the camera's: trees outside the view still cast into it. The opaque pass receives shadows
// when settings().receive_shadows is set (the host binds the maps with ShadowMaps::bind()).
//
// Image-based levels (seed 000 §2.6-2.11, issue "Trees II"): when settings().lod.enabled is set at
// add_species(), the species' LOD1/LOD2 slices are baked from its rest-pose LOD0 tree (or loaded
// from the bake cache, slice_bake.hpp). update() then selects a LOD per instance (lod_selection.hpp:
// distance or screen-size thresholds, hysteresis, fade-in-background transitions), fills one
// instance queue per level ordered near to far, and draw() issues one instanced LOD0 draw (bark +
// leaves) and one instanced draw per image-based level and species. The shadow pass uses the same
// LOD per instance and the same fades (dithered), and every level casts (slices with their baked
// depth offset, §2.13).

#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>
#include <sylva/render/drawable.hpp>
#include <sylva/render/frustum.hpp>
#include <sylva/vegetation/generator.hpp>
#include <sylva/vegetation/lod_selection.hpp>
#include <sylva/vegetation/lod_settings.hpp>
#include <sylva/vegetation/slice_bake.hpp>
#include <sylva/vegetation/slice_renderer.hpp>
#include <sylva/vegetation/tree_renderer.hpp>

#include <memory>
#include <vector>

namespace sylva::vegetation {

struct ForestSettings {
  AnimationSettings animation;
  ShadingSettings shading;
  float season_speed = 0.0f;  // years per second added to shading.season (animated seasons)
  AnimationLevel animation_level = AnimationLevel::kLeaves;
  bool frustum_culling = true;
  bool receive_shadows = true;    // sample the render core's shadow maps in the opaque pass; the
                                  // host must bind them (ShadowMaps::bind(), also when disabled)
  float cull_margin = 0.3f;       // bounding sphere growth for the wind's motion (relative radius)
  float max_distance = 3000.0f;   // trees farther than this from the camera are not drawn [m]
  LodSettings lod;                // image-based levels LOD1/LOD2 and their selection

  template <class V>
  void visit(V& v) {
    v(animation, "animation");
    v(shading, "shading");
    v(season_speed, "season_speed", {.min = -10.0, .max = 10.0, .unit = "1/s", .help = "Seasons (years) per second of scene time"});
    v(animation_level, "animation_level", {.help = "How much of the tree is animated (seed table 5.5)"});
    v(frustum_culling, "frustum_culling", {.help = "Cull instances outside the view frustum"});
    v(receive_shadows, "receive_shadows", {.help = "Receive the sun's cascaded shadows (host binds the maps)"});
    v(cull_margin, "cull_margin", {.min = 0.0, .max = 10.0, .help = "Bounding sphere growth for wind motion"});
    v(max_distance, "max_distance", {.min = 0.0, .max = 1.0e6, .unit = "m", .help = "Farthest drawn tree"});
    v(lod, "lod");
  }
};

// One species' changes to the forest's settings (a species file's "lod" and "animation",
// species_file.hpp). The forest's settings stay live (editor, --set); these apply on top.
struct SpeciesTuning {
  float wind_scale = 1.0f;  // multiplies animation.wind_scale for this species' trees, [0, 100]
  // LOD thresholds replacing lod.v1 / v2 [m] and lod.s1 / s2 [px] for this species; < 0 = the
  // forest's (a shrub can turn into slices nearer than a tall tree).
  float v1 = -1.0f;
  float v2 = -1.0f;
  float s1 = -1.0f;
  float s2 = -1.0f;
};

struct ForestStats {
  struct Species {
    std::size_t instances = 0;
    std::size_t visible = 0;
    std::array<std::size_t, kLodLevels> lod{};  // instances drawn at LOD0/1/2 (a transition counts twice)
    double bake_ms = 0.0;                       // slice bake of this species (0: cache hit or no LOD)
    bool bake_from_cache = false;
  };
  std::vector<Species> species;
  std::size_t instances = 0;
  std::size_t visible = 0;                       // instances drawn (each once)
  std::array<std::size_t, kLodLevels> lod{};     // instances per LOD over all species
  std::size_t transitions = 0;                   // instances drawn at two levels (cross-fading)
  double update_cpu_ms = 0.0;  // LOD selection, culling, sorting + instance records of the last update()
  double select_cpu_ms = 0.0;  // of that, LOD selection + culling + sorting (select_lods)
};

class Forest : public render::Drawable {
 public:
  // Needs a current GL 4.5 context; compiles the tree programs.
  static Result<Forest> create(const ForestSettings& settings = {});
  Forest();
  Forest(Forest&&) noexcept;
  Forest& operator=(Forest&&) noexcept;
  ~Forest() override;

  // Adds a species; returns its index.
  Result<int> add_species(const TreeModel& model, const TreeTextureSet& textures, const MeshSettings& mesh = {},
                          const TreeAssetOptions& options = {});
  // Generates the preset's model and textures (texture_size: leaf and bark side, a power of two).
  Result<int> add_preset(SpeciesPreset preset, std::uint32_t seed = 1, int texture_size = 256);
  // kInvalidArgument for a bad index or a non-finite value, wind_scale outside [0, 100].
  Status set_species_tuning(int species, const SpeciesTuning& tuning);
  const SpeciesTuning& species_tuning(int species) const;
  // Replaces the instances of a species (kInvalidArgument for a bad index or a non-positive scale).
  Status set_instances(int species, std::vector<TreeInstance> instances);

  std::size_t species_count() const;
  const TreeModel& model(int species) const;
  const TreeMesh& mesh(int species) const;
  const TreeAsset& asset(int species) const;
  // The species' baked slices (nullptr when the LOD was disabled at add_species()).
  const SliceAsset* slices(int species) const;
  const BakedTree* baked(int species) const;
  // Per-instance LOD coordinates of the last update() (lod_selection.hpp), indexed like instances().
  const std::vector<float>& lod_state(int species) const;
  const std::vector<TreeInstance>& instances(int species) const;
  // Indices (into instances(species)) of the instances the last update() kept, in draw order.
  const std::vector<std::uint32_t>& visible(int species) const;

  ForestSettings& settings();
  const ForestSettings& settings() const;
  // The season used in the last update (shading.season + season_speed * time).
  float current_season() const;

  void update(const render::FrameContext& frame) override;
  void draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) override;
  // Depth-only pass for shadow casters: `relative_view_proj` is camera-relative like the
  // camera's matrices (the instance records are relative to the camera of the last update()).
  // Culls against `cull` (e.g. ShadowCasterContext::light_frustum), or the matrix's own frustum.
  Status draw_depth(const glm::mat4& relative_view_proj, render::PassStats& stats);
  Status draw_depth(const glm::mat4& relative_view_proj, const render::Frustum& cull, render::PassStats& stats);

  const ForestStats& stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sylva::vegetation

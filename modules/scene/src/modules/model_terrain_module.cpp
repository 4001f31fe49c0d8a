// The "model_terrain" section: the general-model terrain of seed 002 §4, a triangle mesh with
// overhangs and arches (an OBJ, Open Inventor ASCII .iv or glTF .gltf/.glb file relative to the
// scene file, chosen by its extension: terrain/mesh.hpp load_mesh), optionally refined from a
// coarse control cage by OpenSubdiv ("subdivision": scheme, level; level 0, the default, keeps
// the file's mesh; terrain/subdivision.hpp), split into a quadtree of
// segments with locked borders and each level reduced (terrain/model_tree.hpp: QEM by default or
// the seed's shortest-edge reducer, keep_per_level or the seed's reduce_per_pass), drawn by
// terrain::ModelRenderer with the height-field terrain's screen-space tau and material.
//
// It is not the scene's ground (grass and trees do not stand on it): it sits beside a "ground"
// or "terrain" section, or alone. "offset" places the mesh in the world (metres added to every
// vertex). stats(): segments drawn and culled, per level, triangles, the selection's largest
// projected error, GPU bytes, and the load and build times (seed §4.5 Tab. 4.6-4.11's axes).

#include "modules/module_factories.hpp"

#include <sylva/core/log.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/scene/module_instance.hpp>
#include <sylva/terrain/mesh.hpp>
#include <sylva/terrain/model_renderer.hpp>
#include <sylva/terrain/model_tree.hpp>
#include <sylva/terrain/subdivision.hpp>
#include <sylva/terrain/water.hpp>

#include <fmt/format.h>

#include <filesystem>

namespace sylva::scene::detail {
namespace {

struct ModelTerrainSectionSettings {
  std::string file;  // OBJ, IV, glTF or GLB, relative to the scene file
  glm::dvec3 offset{0.0};
  terrain::SubdivisionSettings subdivision{.level = 0};  // off unless a level is set
  terrain::ModelTreeSettings tree;
  terrain::ModelRenderSettings render;
  terrain::WaterSettings water;  // a water plane (terrain/water.hpp), off by default

  template <class V>
  void visit(V& v) {
    v(file, "file", {.max = 4096.0,
      .help = "Mesh relative to the scene file: Wavefront .obj, Open Inventor ASCII .iv, glTF .gltf or .glb",
      .rebuild = Rebuild::kOffline});
    v(offset, "offset", {.min = -1.0e9, .max = 1.0e9, .unit = "m", .help = "Added to every vertex of the mesh",
      .rebuild = Rebuild::kOffline});
    v(subdivision, "subdivision");  // a control cage refined before the tree is built (level 0: off)
    v(tree, "tree");
    v(render, "render");
    v(water, "water");
  }
};

using Settings = SettingsOf<ModelTerrainSectionSettings>;

class ModelTerrainInstance final : public ModuleInstance {
 public:
  static Result<std::unique_ptr<ModuleInstance>> create(const ModuleBuildContext& ctx) {
    auto inst = std::unique_ptr<ModelTerrainInstance>(new ModelTerrainInstance(ctx));
    SYLVA_TRY(inst->build());
    return std::unique_ptr<ModuleInstance>(std::move(inst));
  }

  std::vector<render::Drawable*> drawables() override {
    if (water_) return {renderer_.get(), water_.get()};
    return {renderer_.get()};
  }

  void sync_settings() override {
    const terrain::ModelRenderSettings& wanted = settings().render;
    terrain::ModelRenderSettings& live = renderer_->settings();
    const bool receive = live.receive_shadows;  // kGpu: changes only on a rebuild
    live = wanted;
    live.receive_shadows = receive;
    if (ctx_.debug != nullptr) {
      if (ctx_.debug->lod_colors && live.debug_view == terrain::ModelDebugView::kShaded) {
        live.debug_view = terrain::ModelDebugView::kLodColors;
      }
      live.wireframe = live.wireframe || ctx_.debug->wireframe;
    }
    if (ctx_.environment != nullptr) renderer_->set_climate({ctx_.environment->latitude_deg, ctx_.environment->season});
    terrain::sync_water(water_, settings().water, "model_terrain.water");
  }

  Status rebuild(Rebuild what) override {
    if (what == Rebuild::kNone) return {};
    return build();
  }

  Status on_map_changed(const std::string& map_id, const WorldArea& area) override {
    (void)map_id;  // the mesh does not stand on the height field and has no painted maps
    (void)area;
    return {};
  }

  nlohmann::json stats() const override {
    const terrain::ModelFrameStats& s = renderer_->frame_stats();
    const terrain::ModelTree& tree = renderer_->tree();
    nlohmann::json per_level = nlohmann::json::object();
    for (std::size_t l = 0; l < s.segments_per_level.size(); ++l) per_level[fmt::format("level{}", l)] = s.segments_per_level[l];
    nlohmann::json tree_triangles = nlohmann::json::object();
    for (const terrain::ModelLevelReport& l : tree.report().levels) {
      tree_triangles[fmt::format("level{}", l.level)] = l.triangles;
    }
    return {{"segments_drawn", s.segments},
            {"segments_culled", s.culled},
            {"triangles", s.triangles},
            {"instances_per_lod", per_level},
            {"max_projected_error_px", s.max_projected_error_px},
            {"select_ms", s.select_ms},
            {"selections", s.selections},  // LOD selections this frame: 1 (casters share it)
            {"gpu_bytes", s.gpu_bytes},
            {"mesh_vertices", vertices_},
            {"mesh_triangles", triangles_},
            {"tree_levels", tree.levels()},
            {"tree_triangles", tree_triangles},
            {"tree_build_ms", tree.report().total_ms},
            {"load_ms", load_ms_}};
  }

  std::vector<render::Aabb> debug_bounds() const override {
    std::vector<render::Aabb> out;
    for (std::uint32_t i : renderer_->selection().segments) {
      const terrain::Segment& s = renderer_->tree().segment(i);
      out.push_back({glm::dvec3(s.lo), glm::dvec3(s.hi)});
    }
    return out;
  }

 private:
  explicit ModelTerrainInstance(const ModuleBuildContext& ctx) : ModuleInstance("model_terrain"), ctx_(ctx) {}

  const ModelTerrainSectionSettings& settings() const {
    return static_cast<const Settings&>(*ctx_.section->settings).value;
  }

  Status build() {
    const ModelTerrainSectionSettings& s = settings();
    if (s.file.empty()) {
      return make_error(ErrorCode::kInvalidArgument,
                        "model_terrain.file: no mesh given (an .obj, .iv, .gltf or .glb file relative to the scene file)");
    }
    const std::filesystem::path path = ctx_.document != nullptr ? ctx_.document->resolve(s.file) : std::filesystem::path(s.file);
    Stopwatch watch;
    auto polygons = terrain::load_mesh(path);
    if (!polygons.ok()) return make_error(polygons.error().code, "model_terrain.file: " + polygons.error().message);
    if (s.subdivision.level > 0) {
      auto refined = terrain::subdivide(*polygons, s.subdivision);
      if (!refined.ok()) {
        return make_error(refined.error().code, fmt::format("model_terrain.subdivision: {}: {}", path.string(),
                                                            refined.error().message));
      }
      polygons = std::move(*refined);
    }
    terrain::TriangleMesh mesh = terrain::triangulate(*polygons);
    for (glm::vec3& p : mesh.positions) p = glm::vec3(glm::dvec3(p) + s.offset);
    load_ms_ = watch.lap_ms();
    auto tree = terrain::ModelTree::build(mesh, s.tree);
    if (!tree.ok()) return make_error(tree.error().code, fmt::format("model_terrain: {}: {}", path.string(), tree.error().message));
    const terrain::ModelBuildReport& r = tree->report();
    if (r.holes + r.degenerate + r.non_manifold + r.flipped > 0) {
      log_warn("model_terrain: {}: the reduced segments have {} holes, {} degenerate, {} non-manifold and {} flipped "
               "triangles (the {} reducer)", path.string(), r.holes, r.degenerate, r.non_manifold, r.flipped,
               s.tree.reducer == terrain::Reducer::kQem ? "qem" : "shortest_edge");
    }
    auto renderer = terrain::ModelRenderer::create(std::make_shared<const terrain::ModelTree>(std::move(*tree)), s.render);
    if (!renderer.ok()) return make_error(renderer.error().code, "model_terrain: " + renderer.error().message);
    renderer_ = std::move(*renderer);
    vertices_ = mesh.positions.size();
    triangles_ = mesh.triangle_count();
    return {};
  }

  ModuleBuildContext ctx_;
  std::unique_ptr<terrain::ModelRenderer> renderer_;
  std::unique_ptr<terrain::WaterRenderer> water_;  // created when model_terrain.water.enabled is first set
  std::size_t vertices_ = 0, triangles_ = 0;
  double load_ms_ = 0.0;
};

}  // namespace

ModuleDescriptor model_terrain_module() {
  ModuleDescriptor d;
  d.name = "model_terrain";
  d.description = "general-model terrain: an OBJ mesh with overhangs in a quadtree of locked-border segments (seed 002 §4)";
  d.make_settings = [] { return std::make_unique<Settings>(std::vector<MapSlot>{}); };
  d.create = &ModelTerrainInstance::create;
  return d;
}

}  // namespace sylva::scene::detail

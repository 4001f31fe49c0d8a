#pragma once
// The GL side of one module section of a running scene (created by Scene from the module's
// ModuleDescriptor). It owns the module's render::Drawables, reads its section's settings every
// frame (parameters marked Rebuild::kNone take effect at once) and reacts to map edits by
// rebuilding only what an edited region touches.
//
// Every instance is counted per module name (module_registry.hpp: live_module_instances), which
// is how tests prove that a scene only creates the modules it lists.

#include <sylva/core/height_field.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/render/drawable.hpp>
#include <sylva/render/frustum.hpp>
#include <sylva/scene/environment.hpp>
#include <sylva/scene/map_grid.hpp>
#include <sylva/scene/scene_document.hpp>

#include <nlohmann/json.hpp>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace sylva::scene {

// Debug views the editor toggles; modules honour what they can (the scene draws wireframe for
// everyone and the chunk bounds that modules report).
struct DebugView {
  bool wireframe = false;     // every module, opaque pass drawn with glPolygonMode(GL_LINE)
  bool lod_colors = false;    // modules with LOD tint each level (ground: each chunk)
  bool chunk_bounds = false;  // boxes of the modules' chunks / tiles, drawn as lines
  bool freeze_culling = false;  // keep the last culling result while the camera moves
  bool show_holes = false;  // clear to magenta instead of the horizon colour: pixels nothing drew stand out

  template <class V>
  void visit(V& v) {
    v(wireframe, "wireframe", {.help = "Draw triangles as lines"});
    v(lod_colors, "lod_colors", {.help = "Tint geometry by level of detail"});
    v(chunk_bounds, "chunk_bounds", {.help = "Draw the bounding boxes of chunks and tiles"});
    v(freeze_culling, "freeze_culling", {.help = "Keep the current culling while the camera moves"});
    v(show_holes, "show_holes", {.help = "Clear to magenta so pixels that nothing (not even the sky) drew stand out"});
  }
};

// The world services and shared data a module is built with. All pointers outlive the instance.
struct ModuleBuildContext {
  const ModuleSection* section = nullptr;     // the module's settings and map paths
  const SceneDocument* document = nullptr;    // for resolving map paths
  const HeightField* ground = nullptr;        // the scene's ground, null when it has none
  std::map<std::string, SceneMap>* maps = nullptr;  // every map of the scene, by id ("grass.density")
  const WindField* wind = nullptr;
  const EnvironmentSettings* environment = nullptr;
  const DebugView* debug = nullptr;
};

class ModuleInstance {
 public:
  explicit ModuleInstance(std::string module);
  virtual ~ModuleInstance();
  ModuleInstance(const ModuleInstance&) = delete;
  ModuleInstance& operator=(const ModuleInstance&) = delete;

  const std::string& module() const { return module_; }

  // The drawables, in draw order. Pointers stay valid until the next rebuild()/on_map_changed().
  virtual std::vector<render::Drawable*> drawables() = 0;

  // Called before update() every frame: copy per-frame settings (Rebuild::kNone) from the section
  // into the renderers.
  virtual void sync_settings() {}
  // The section's settings changed in a way that needs `what` rebuilt (kGpu or kOffline).
  virtual Status rebuild(Rebuild what) = 0;
  // A map of this module (or the ground, slot "ground") changed inside `area` (world x/z):
  // rebuild only what it touches.
  virtual Status on_map_changed(const std::string& map_id, const WorldArea& area) = 0;

  // Whether the module's draws run their own primitives/samples queries (GL counting queries do
  // not nest, so the scene then measures only GPU time around this module).
  virtual bool counts_own_primitives() const { return false; }
  // Counters the module measured itself during the last draw (primitives, samples), added to
  // the scene's per-module record when counts_own_primitives().
  virtual render::PassStats own_counts() { return {}; }

  // Facts for --stats and the editor overlay: triangles, instances per LOD, culling counts...
  virtual nlohmann::json stats() const { return nlohmann::json::object(); }
  // Bounding boxes of chunks / tiles for the chunk-bounds debug view (world metres).
  virtual std::vector<render::Aabb> debug_bounds() const { return {}; }
  // World positions of up to max_count placed objects (blade roots, tree bases), evenly taken
  // from all of them: how tests check that what stands on the ground stands on it.
  virtual std::vector<glm::dvec3> placed_positions(std::size_t max_count) const {
    (void)max_count;
    return {};
  }

 private:
  std::string module_;
};

// The map `slot` of the context's module laid over the world rectangle [min, max] (x/z), texel
// centres at cell centres. Reuses the scene's copy when it exists (so edits survive a module
// rebuild; it is re-placed when the rectangle changed), else reads the file the section lists
// (any size), else creates default_resolution texels along the longer side filled with `fill`.
// Errors name the file or the section.
Result<SceneMap*> ensure_area_map(const ModuleBuildContext& ctx, const MapSlot& slot, glm::dvec2 min, glm::dvec2 max,
                                  int default_resolution, float fill);

}  // namespace sylva::scene

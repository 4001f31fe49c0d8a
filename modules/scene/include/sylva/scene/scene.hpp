#pragma once
// A running scene: the modules a SceneDocument lists, the glue between them and the frame loop.
// This is the API sylva-player, sylva-editor and sylva-bench drive.
//
//   std::vector<std::string> warnings;
//   auto doc = SceneDocument::load("scenes/meadow.json", warnings);      // GL-free
//   auto scene = Scene::create(std::move(*doc));                          // needs a GL context
//   render::Camera cam = (*scene)->make_camera((*scene)->document().camera, size);
//   render::FrameProfiler profiler;
//   for (each frame) {
//     (*scene)->update(cam, time, dt, size);           // CPU: every module's update()
//     (*scene)->render(framebuffer, profiler);         // GL: shadow hook, opaque, sky, transparent
//   }
//   // camera paths (the bench's fixed flights):
//   auto view = (*scene)->camera_path_view("flyover", t);   // CameraView at t seconds
//
// Assembly (DESIGN.md §2 "Leave out what a scene does not need"): only the sections the document
// lists are created; a module that is not listed compiles no shader and allocates no GPU memory
// (counted: module_registry.hpp). Creation order is known_modules() order: the ground provider
// ("terrain" or "ground") first, so the scene can build its one HeightField from that section's
// height source and map before grass and trees are placed on it.
//
// Glue: every module gets the same HeightField (through ModuleBuildContext), the same WindField
// and, per frame, the same render::Lighting (bound once as the lighting uniform block).
//
// Frame loop (render): profiler frame; the shadow pass: the scene's render::ShadowMaps (document
// "render.shadows") draw every module's Pass::kShadow once per cascade (modules read
// render::active_shadow_cascade()), or a host's shadow hook when one is set; then the lighting
// and shadow uniforms are bound for receivers; into an HDR target (when "render.tone_map"):
// clear to the fog colour, Pass::kOpaque for all modules (wireframe when the debug view asks),
// the sky, Pass::kTransparent, debug lines; finally the tone-mapping pass into the caller's
// target. Each module's work is a profiler scope "<pass>/<module>" inside the pass scope
// (frame_stats.hpp); in the shadow pass only the pass is timed (casters run once per cascade)
// and the modules' counts are recorded.
//
// Editing: parameters are set through set_param() (validated, then whatever the parameter's
// Rebuild says is rebuilt: kNone takes effect next frame, kGpu/kOffline rebuild that module,
// and a ground change rebuilds the modules standing on it). Maps are painted in place through
// map() and announced with map_changed(), which rebuilds only what the changed area touches.
//
// Threading: one thread, the one whose GL context is current. Failure: creation and edits
// return errors naming the section, parameter or file; a failed rebuild leaves the module as it
// was.

#include <sylva/core/height_field.hpp>
#include <sylva/core/result.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/frame_context.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/lighting.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/scene/frame_stats.hpp>
#include <sylva/scene/map_grid.hpp>
#include <sylva/scene/module_instance.hpp>
#include <sylva/scene/scene_document.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::scene {

// Called once per frame inside the "shadow" scope when set: bind the shadow target(s), call
// draw_casters (which draws Pass::kShadow of every module and adds their counts) once per
// cascade, and restore the main target state (the scene rebinds its framebuffer afterwards).
using ShadowHook = std::function<void(const render::FrameContext& frame,
                                      const std::function<void(render::PassStats&)>& draw_casters)>;

class Scene {
 public:
  // Builds the listed modules (needs a current GL 4.5 context). The document is validated
  // first. Errors name the section, the map file or the shader.
  static Result<std::unique_ptr<Scene>> create(SceneDocument document);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  // The document (settings, bookmarks, paths). Edit parameters through set_param() so the
  // modules hear about it; bookmarks and camera paths may be edited directly.
  SceneDocument& document() { return *document_; }
  const SceneDocument& document() const { return *document_; }

  // --- modules and shared services ---
  const std::vector<std::unique_ptr<ModuleInstance>>& modules() const { return modules_; }
  ModuleInstance* module(std::string_view name);
  // True when the document has the section but it failed to build and the scene opened without
  // it (modules with ModuleDescriptor::left_out_on_failure: grass, issue 16).
  // Setting one of its parameters or reloading its files builds it again.
  bool left_out(std::string_view name) const;
  // The scene's ground (null when it lists neither terrain nor ground).
  const HeightField* ground() const { return ground_.get(); }
  // Ground height at world (x, z) [m]; 0 without a ground.
  double ground_height(double x, double z) const;
  const WindField& wind() const { return wind_; }
  const render::Lighting& lighting() const { return lighting_; }
  DebugView& debug() { return debug_; }
  void set_shadow_hook(ShadowHook hook) { shadow_hook_ = std::move(hook); }

  // --- parameters ---
  // Validates and writes `text` to the parameter at `path` ("grass.field.density"), then
  // rebuilds what the parameter's Rebuild level asks for. On failure nothing changes.
  Status set_param(std::string_view path, std::string_view text);
  // Replaces the document (sections added, removed or changed as a whole: the editor's module
  // add/remove and its undo) and rebuilds every module; maps already in the scene are kept with
  // their edits. The new document is validated first; on any failure the scene keeps the old
  // document and modules.
  Status replace_document(SceneDocument document);
  // Re-reads the files a module's settings name (the editor's file watcher): the module is made
  // anew from its section and replaces the old one; on failure the old one stays. The ground
  // provider rebuilds the ground and every module.
  Status reload_module(std::string_view name);
  // Current value as text (round-trips through set_param bit-exactly).
  Result<std::string> get_param(std::string_view path);
  // Every parameter of the document (for panels, sweeps and listings).
  std::vector<ParamDescriptor> describe_params();

  // --- cameras ---
  // The view with an above_ground height resolved to an absolute one.
  CameraView resolve(const CameraView& view) const;
  render::Camera make_camera(const CameraView& view, glm::ivec2 viewport) const;
  // The pose of camera path `name` at t seconds (path clock), resolved. kNotFound names the path
  // and lists the scene's paths.
  Result<CameraView> camera_path_view(std::string_view name, double t) const;
  // A camera's pose as an absolute bookmark.
  static CameraView view_of(const render::Camera& camera);

  // --- frame ---
  // CPU side of a frame: settings sync, wind and lighting for `time`, every drawable's update().
  // dt >= 0 seconds (may be 0 or large); viewport in pixels.
  void update(const render::Camera& camera, double time, float dt, glm::ivec2 viewport);
  // GL side into `target` (binds it and sets the viewport). Call after update().
  void render(const render::Framebuffer& target, render::FrameProfiler& profiler);

  // --- maps ---
  std::map<std::string, SceneMap>& maps() { return maps_; }
  SceneMap* map(std::string_view id);
  // The texels of `rect` of map `id` were written: bumps its revision and tells the modules that
  // read it (the ground map: every module standing on the ground) to rebuild the changed area.
  Status map_changed(std::string_view id, const TexelRect& rect);
  // Maps edited since they were loaded or saved.
  bool maps_unsaved() const;

  // Saves the scene file and its maps as one transaction: every file is written and flushed to a
  // temporary first, then all are renamed into place (the scene last); any failure leaves every
  // old file as it was and this scene unchanged. Edited maps go to the saved scene's own map
  // folder "<stem>_maps/<module>_<slot>.<exr|png>" (height maps float EXR, others 16-bit PNG),
  // never over a source image; a save to another file than document().file() ("save as") also
  // copies the unedited maps there, so two scenes never share a map file. A read-only scene or
  // map file is refused, not replaced. The document's file() becomes `file` (relative map paths
  // are rewritten to stay correct). Errors name the file (src/scene_save.cpp).
  Status save(const std::filesystem::path& file);

  // --- statistics ---
  // Per-module facts: {"<module>": module stats() + "build_ms" (CPU time of its last (re)build)}.
  nlohmann::json module_stats() const;
  // CPU time of each module's update() in the last update() [ms], by module name.
  const std::map<std::string, double>& update_ms() const { return update_ms_; }

 private:
  Scene() = default;
  Status build_ground();
  Status build_modules();
  Result<std::unique_ptr<ModuleInstance>> create_module(const ModuleSection& section);
  Status rebuild_module(std::string_view name, Rebuild what);
  Status build_left_out(std::string_view name);  // builds a left-out section into its place
  ModuleBuildContext context_for(const ModuleSection& section);
  void draw_pass(render::Pass pass, render::FrameProfiler& profiler);
  void draw_debug_lines();

  std::unique_ptr<SceneDocument> document_;
  std::map<std::string, SceneMap> maps_;
  std::unique_ptr<HeightField> ground_;
  std::string ground_map_id_;  // "terrain.height" / "ground.height", "" without a ground
  std::vector<std::unique_ptr<ModuleInstance>> modules_;
  WindField wind_;
  render::Lighting lighting_;
  DebugView debug_;
  ShadowHook shadow_hook_;

  struct Gpu;
  std::unique_ptr<Gpu> gpu_;
  // Per-frame state from update().
  render::Camera camera_;
  double time_ = 0.0;
  float dt_ = 0.0f;
  glm::ivec2 viewport_{1, 1};
  std::uint64_t frame_ = 0;
  std::map<std::string, double> update_ms_;
  std::map<std::string, double> build_ms_;
  std::map<std::string, render::PassStats> shadow_counts_;  // this frame's shadow pass, by module
  bool shadow_warned_ = false;
  bool offscreen_warned_ = false;
  bool msaa_warned_ = false;
};

}  // namespace sylva::scene

#pragma once
// The edited scene and every editing operation, without any UI (GL, no Dear ImGui): what the
// ImGui panels and the --script runner both call. Needs a current GL 4.5 context.
//
// Every change goes through here and lands on the undo stack: parameter changes (ParamEdit, with
// consecutive changes of one parameter during a slider drag merged into one entry), brush strokes
// (MapEdit with the dirty rectangle's before/after values), module sections added or removed
// (SectionEdit) and bookmarks (BookmarkEdit). The session is the undo stack's EditTarget.
//
// Documents: load / new / save / save_as. Saving writes the edited maps and then the scene file,
// each atomically (scene::Scene::save), so an interrupted save leaves the previous files whole.
// unsaved() is what the "unsaved changes" prompt asks.

#include "brush.hpp"
#include "plant_preview.hpp"
#include "source_watcher.hpp"
#include "undo.hpp"

#include <sylva/core/result.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/scene/scene.hpp>

#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sylva::editor {

class EditorSession final : public EditTarget {
 public:
  // An empty scene (sky only) with a viewport of `viewport` pixels.
  static Result<std::unique_ptr<EditorSession>> create(glm::ivec2 viewport);

  // --- documents ---
  Status load(const std::filesystem::path& file);  // replaces the scene, clears the undo history
  Status new_scene();
  // The embedded default scene (terrain + forest + grass meadow as far as built in), without a
  // file: saving it asks for a path (save as).
  Status open_default();
  Status save();                                   // kInvalidArgument when the scene has no file yet
  Status save_as(const std::filesystem::path& file);
  const std::optional<std::filesystem::path>& path() const { return path_; }
  bool unsaved() const { return history_.unsaved(); }
  // Warnings of the last load (unknown keys...).
  const std::vector<std::string>& warnings() const { return warnings_; }

  scene::Scene& scene() { return *scene_; }
  const scene::Scene& scene() const { return *scene_; }

  // --- undoable edits ---
  // merge: fold into the previous entry when it changed the same parameter (slider drags).
  Status set_param(const std::string& path, const std::string& text, bool merge = false);
  Status add_module(const std::string& name);
  Status remove_module(const std::string& name);
  Status add_bookmark(const std::string& name);  // the current camera
  Status remove_bookmark(const std::string& name);

  // --- painting ---
  BrushSettings& brush() { return brush_; }
  // Names of the paintable maps ("ground.height", "grass.density", ...).
  std::vector<std::string> map_ids() const;
  // Colour maps ("grass.tint": maps X_r, X_g, X_b all present); a stroke on one paints all three
  // towards brush().color (brush.hpp, color_channel_brush) as one undo entry.
  std::vector<std::string> color_map_ids() const;
  Status begin_stroke(const std::string& map_id, glm::dvec2 world_xz);
  Status continue_stroke(glm::dvec2 world_xz);
  void end_stroke();  // pushes the stroke's undo entry
  bool stroking() const { return stroke_.has_value(); }
  // A whole stroke through world points.
  Status stroke(const std::string& map_id, const std::vector<glm::dvec2>& points);

  Status undo() { return history_.undo(*this); }
  Status redo() { return history_.redo(*this); }
  UndoStack& history() { return history_; }

  // --- camera and frames ---
  render::Camera& camera() { return camera_; }
  void set_camera(const scene::CameraView& view);
  Status go_to_bookmark(const std::string& name);
  glm::ivec2 viewport() const { return viewport_; }
  Status set_viewport(glm::ivec2 size);
  // update + render into framebuffer(); the scene clock advances by dt seconds. kGl when the
  // frame raised a GL error (out of memory included): its picture cannot be trusted.
  Status render_frame(double dt);
  const render::Framebuffer& framebuffer() const { return framebuffer_; }
  render::FrameProfiler& profiler() { return profiler_; }
  // Renders one frame at `size` (default: the viewport) and saves it. Errors name the file.
  Status screenshot(const std::filesystem::path& file, std::optional<glm::ivec2> size = std::nullopt);
  // Exports the forest's first species (the first species file in vegetation.species_files, else
  // the vegetation.species preset at species_seed) with the scene's leaf_texture_size, mesh and
  // slice settings into `folder`: OBJT, glTF 2.0 and the LOD1/LOD2 slice layers (vegetation
  // README "Export"). Returns a one-line summary. kNotFound without a vegetation section; load
  // and write errors name the species file or the folder; nothing of a failed export replaces an
  // earlier one.
  Result<std::string> export_tree(const std::filesystem::path& folder);
  // World point of the ground under a viewport pixel (top-left origin), by marching the view ray
  // over the scene's ground (the plane y = 0 without one). nullopt when the ray misses.
  std::optional<glm::dvec3> pick_ground(glm::vec2 pixel) const;

  // --- source files (issue #16) ---
  // Polls the files the scene's settings name (source_watcher.hpp; at most twice a second unless
  // `now`; render_frame calls it) and rebuilds the module of each changed one in place
  // (Scene::reload_module), so an edited grammar, species table, palette or tree species file
  // shows without reopening the scene. Each reload adds "reloaded FILE (SETTING)" to messages(),
  // then the warnings the module gave while rebuilding (a broken file's error naming its
  // line:column; the module falls back and the scene keeps running), or "error: ..." when the
  // rebuild failed (the module stays as it was). Not an edit: no undo entry, nothing unsaved.
  void poll_sources(bool now = false);
  // How many times `file` (any spelling of the path) was reloaded since the scene was opened.
  int reloads(const std::filesystem::path& file) const;
  // Every message so far, oldest first (the UI's message log and the script output read new ones).
  const std::vector<std::string>& messages() const { return messages_; }
  const SourceWatcher& sources() const { return watcher_; }

  // --- plant preview (plant_preview.hpp) ---
  // What the "Plant preview" panel and the `preview` script command show; `preview_open` opens
  // the panel. Not part of the scene: no undo, nothing unsaved.
  PlantPreviewSettings& preview_settings() { return preview_settings_; }
  bool& preview_open() { return preview_open_; }
  PlantPreview build_preview() { return build_plant_preview(*scene_, preview_settings_); }

  // --- EditTarget (undo/redo) ---
  Status write_map_rect(const std::string& map_id, const scene::TexelRect& rect, const std::vector<float>& values) override;
  Status write_param(const std::string& path, const std::string& text) override;
  Status write_section(const std::string& module, const nlohmann::json& section) override;
  Status write_bookmark(const std::string& name, const std::optional<scene::CameraView>& view) override;

 private:
  EditorSession() = default;
  Status adopt(scene::SceneDocument document, std::optional<std::filesystem::path> path);
  void dab_to(glm::dvec2 world_xz);

  // One map a stroke paints: a unit/height map, or one channel of a colour map.
  struct StrokeLayer {
    std::string map_id;
    StrokeRecorder recorder;
    BrushSettings brush;
    float target = 0.0f;
  };
  struct Stroke {
    std::string map_id;  // as given: "grass.density" or the colour map "grass.tint"
    std::vector<StrokeLayer> layers;
    glm::dvec2 last_dab{0.0};
  };

  std::unique_ptr<scene::Scene> scene_;
  std::optional<std::filesystem::path> path_;
  std::vector<std::string> warnings_;
  UndoStack history_;
  BrushSettings brush_;
  std::optional<Stroke> stroke_;
  render::Camera camera_;
  glm::ivec2 viewport_{1280, 720};
  render::Framebuffer framebuffer_;
  render::FrameProfiler profiler_;
  double time_ = 0.0;
  SourceWatcher watcher_;
  std::chrono::steady_clock::time_point next_poll_{};
  std::map<std::filesystem::path, int> reloads_;
  std::vector<std::string> messages_;
  PlantPreviewSettings preview_settings_;
  bool preview_open_ = false;
};

}  // namespace sylva::editor

#pragma once
// The Dear ImGui front end of sylva-editor: menu, scene outline, generated parameter panels,
// brush panel, viewport with fly/orbit cameras and painting, debug views, stats overlay, and the
// modal dialogs (open, save as, screenshot, export tree, unsaved changes). All edits go through the
// EditorSession, so they are validated and undoable exactly like scripted ones.

#include "camera_control.hpp"
#include "editor_session.hpp"
#include "terrain_import.hpp"

#include <deque>
#include <string>

struct GLFWwindow;

namespace sylva::editor {

enum class CameraMode { kFly, kOrbit };

class EditorUi {
 public:
  EditorUi(EditorSession& session, GLFWwindow* window);

  // Builds and handles one ImGui frame (between ImGui::NewFrame and ImGui::Render): input, panels,
  // viewport (renders the scene). dt in seconds.
  void frame(double dt);
  // True once the user confirmed quitting (after the unsaved-changes prompt).
  bool quit_requested() const { return quit_confirmed_; }
  // The window's close button: asks about unsaved changes first.
  void request_quit();
  void message(std::string text);
  // File > Import terrain...'s state (a --script run shares it: ScriptHooks::terrain_import).
  TerrainImport& terrain_import() { return import_; }

 private:
  enum class Pending { kNone, kNew, kOpenDefault, kOpen, kQuit };

  void menu_bar();
  void outline_panel();
  void properties_panel();
  void section_params(const std::string& section);
  void brush_panel();
  void plant_preview_panel();  // plant_preview_panel.cpp
  void terrain_import_panel();  // terrain_import_panel.cpp (File > Import terrain...)
  void poll_terrain_import();   // every frame: applies a finished read or bake
  void viewport_panel(double dt);
  void stats_overlay(const glm::vec2& origin);
  void brush_outline(const glm::vec2& origin, const glm::dvec3& centre);
  void dialogs();
  void handle_shortcuts();
  void apply(Status status);
  // Saves to the current file; a read-only file opens "save as" with "<stem>_copy.json" instead.
  // Returns whether the save succeeded.
  bool save_in_place();
  void continue_pending();

  EditorSession& session_;
  GLFWwindow* window_;
  std::string selected_ = "environment";
  CameraMode camera_mode_ = CameraMode::kFly;
  OrbitState orbit_;
  bool paint_ = false;
  std::string paint_map_;
  Pending pending_ = Pending::kNone;
  bool quit_confirmed_ = false;
  bool open_dialog_ = false, save_as_dialog_ = false, screenshot_dialog_ = false, export_tree_dialog_ = false, unsaved_dialog_ = false;
  char path_buffer_[512] = {};
  std::string last_frame_error_;  // the viewport's last GL error, shown once
  char bookmark_buffer_[64] = "view";
  std::deque<std::string> messages_;
  std::size_t session_messages_shown_ = 0;  // of session_.messages()
  // The plant preview: the plant last grown and what it was grown from.
  PlantPreview preview_;
  PlantPreviewSettings preview_settings_;
  const scene::Scene* preview_scene_ = nullptr;
  std::size_t preview_messages_ = 0;
  char preview_file_[256] = {};
  float preview_yaw_deg_ = 0.0f;
  // File > Import terrain... (terrain_import.hpp): its worker, window and paths.
  TerrainImport import_;
  bool import_open_ = false;
  char import_path_[512] = {};
  char import_out_[512] = {};
  std::optional<glm::dvec3> brush_hit_;
  std::string playing_path_;
  // The overlay's memory line, rebuilt twice a second rather than every frame.
  std::string memory_line_;
  double memory_line_time_ = -1.0;
  double path_time_ = 0.0;
};

}  // namespace sylva::editor

#include "editor_ui.hpp"

#include "param_widgets.hpp"

#include <sylva/scene/frame_stats.hpp>
#include <sylva/scene/module_registry.hpp>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

namespace sylva::editor {
namespace {

const char* outline_label(const std::string& module) {
  if (module == "ground") return "Ground";
  if (module == "terrain") return "Terrain";
  if (module == "grass") return "Grass field";
  if (module == "vegetation") return "Forest";
  if (module == "voxel") return "Voxel world";
  if (module == "model_terrain") return "Model terrain (mesh)";
  return module.c_str();
}

// Parameters grouped by path segment, drawn as a tree of collapsing nodes.
struct ParamGroup {
  std::map<std::string, ParamGroup> children;  // sorted by name; order of first appearance kept below
  std::vector<std::string> order;
  std::vector<const ParamDescriptor*> params;
};

void insert(ParamGroup& root, const ParamDescriptor& p, std::size_t skip) {
  ParamGroup* g = &root;
  std::size_t start = skip;
  for (std::size_t dot = p.path.find('.', start); dot != std::string::npos; dot = p.path.find('.', start)) {
    const std::string seg = p.path.substr(start, dot - start);
    if (!g->children.count(seg)) g->order.push_back(seg);
    g = &g->children[seg];
    start = dot + 1;
  }
  g->params.push_back(&p);
}

}  // namespace

EditorUi::EditorUi(EditorSession& session, GLFWwindow* window) : session_(session), window_(window) {
  const auto ids = session_.map_ids();
  if (!ids.empty()) paint_map_ = ids.front();
}

void EditorUi::message(std::string text) {
  messages_.push_back(std::move(text));
  while (messages_.size() > 6) messages_.pop_front();
}

void EditorUi::apply(Status status) {
  if (!status.ok()) message("error: " + status.error().message);
}

void EditorUi::request_quit() {
  pending_ = Pending::kQuit;
  if (session_.unsaved()) {
    unsaved_dialog_ = true;
  } else {
    continue_pending();
  }
}

void EditorUi::continue_pending() {
  switch (pending_) {
    case Pending::kNew:
      apply(session_.new_scene());
      selected_ = "environment";
      break;
    case Pending::kOpenDefault:
      apply(session_.open_default());
      selected_ = "environment";
      break;
    case Pending::kOpen:
      open_dialog_ = true;
      std::snprintf(path_buffer_, sizeof(path_buffer_), "%s", session_.path() ? session_.path()->string().c_str() : "scenes/meadow.json");
      break;
    case Pending::kQuit:
      quit_confirmed_ = true;
      break;
    case Pending::kNone:
      break;
  }
  if (pending_ != Pending::kOpen) pending_ = Pending::kNone;
}

void EditorUi::frame(double dt) {
  // The file watcher's reloads and their warnings (EditorSession::poll_sources).
  for (; session_messages_shown_ < session_.messages().size(); ++session_messages_shown_) {
    message(session_.messages()[session_messages_shown_]);
  }
  poll_terrain_import();
  if (import_.busy()) import_open_ = true;  // also when a script started it
  // A raster read and not used is held in memory (4 bytes a sample): closing the window drops it.
  if (!import_open_ && import_.state() == TerrainImport::State::kRead) import_.reset();
  handle_shortcuts();
  menu_bar();
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  const float menu = ImGui::GetFrameHeight();
  const float left = 250.0f, right = 380.0f;
  const ImGuiWindowFlags fixed = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse;
  ImGui::SetNextWindowPos(ImVec2(vp->Pos.x, vp->Pos.y + menu));
  ImGui::SetNextWindowSize(ImVec2(left, vp->Size.y - menu));
  if (ImGui::Begin("Scene", nullptr, fixed)) outline_panel();
  ImGui::End();
  ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x - right, vp->Pos.y + menu));
  ImGui::SetNextWindowSize(ImVec2(right, vp->Size.y - menu));
  if (ImGui::Begin("Properties", nullptr, fixed)) {
    ImGui::PushItemWidth(-150.0f);  // room for the parameter names
    properties_panel();
    ImGui::PopItemWidth();
  }
  ImGui::End();
  ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + left, vp->Pos.y + menu));
  ImGui::SetNextWindowSize(ImVec2(std::max(vp->Size.x - left - right, 64.0f), vp->Size.y - menu));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
  if (ImGui::Begin("Viewport", nullptr, fixed | ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoTitleBar)) viewport_panel(dt);
  ImGui::End();
  ImGui::PopStyleVar();
  if (session_.preview_open()) {
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + left + 20.0f, vp->Pos.y + menu + 20.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(340.0f, 520.0f), ImGuiCond_FirstUseEver);
    if (ImGui::Begin("Plant preview", &session_.preview_open())) plant_preview_panel();
    ImGui::End();
  }
  if (import_open_) {
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + left + 40.0f, vp->Pos.y + menu + 40.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(460.0f, 220.0f), ImGuiCond_FirstUseEver);
    if (ImGui::Begin("Import terrain", &import_open_)) terrain_import_panel();
    ImGui::End();
  }
  dialogs();
}

void EditorUi::handle_shortcuts() {
  ImGuiIO& io = ImGui::GetIO();
  if (io.WantTextInput) return;
  if (io.KeyCtrl && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Z))) apply(io.KeyShift ? session_.redo() : session_.undo());
  if (io.KeyCtrl && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Y))) apply(session_.redo());
  if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_S)) {
    if (session_.path()) save_in_place();
    else save_as_dialog_ = true;
  }
}

bool EditorUi::save_in_place() {
  Status s = session_.save();
  apply(s);
  if (!s.ok() && s.error().message.find("read-only") != std::string::npos) {
    // The file is protected: offer to save elsewhere instead of replacing it (never forced).
    const std::filesystem::path& p = *session_.path();
    const std::filesystem::path other = p.parent_path() / (p.stem().string() + "_copy" + p.extension().string());
    std::snprintf(path_buffer_, sizeof(path_buffer_), "%s", other.string().c_str());
    save_as_dialog_ = true;
    message("the scene file is read-only: choose another name to save your changes");
  }
  return s.ok();
}

void EditorUi::menu_bar() {
  if (!ImGui::BeginMainMenuBar()) return;
  if (ImGui::BeginMenu("File")) {
    // A running import applies to the scene it was started for: no other scene until it ends.
    ImGui::BeginDisabled(import_.busy());
    if (ImGui::MenuItem("New")) {
      pending_ = Pending::kNew;
      if (session_.unsaved()) unsaved_dialog_ = true;
      else continue_pending();
    }
    if (ImGui::MenuItem("Open default scene")) {
      pending_ = Pending::kOpenDefault;
      if (session_.unsaved()) unsaved_dialog_ = true;
      else continue_pending();
    }
    if (ImGui::MenuItem("Open...")) {
      pending_ = Pending::kOpen;
      if (session_.unsaved()) unsaved_dialog_ = true;
      else continue_pending();
    }
    ImGui::EndDisabled();
    if (ImGui::MenuItem("Save", "Ctrl+S", false, session_.path().has_value())) save_in_place();
    if (ImGui::MenuItem("Save as...")) {
      save_as_dialog_ = true;
      std::snprintf(path_buffer_, sizeof(path_buffer_), "%s", session_.path() ? session_.path()->string().c_str() : "untitled.json");
    }
    if (ImGui::MenuItem("Screenshot...")) {
      screenshot_dialog_ = true;
      std::snprintf(path_buffer_, sizeof(path_buffer_), "screenshot.png");
    }
    if (ImGui::MenuItem("Export tree...", nullptr, false, session_.scene().module("vegetation") != nullptr)) {
      export_tree_dialog_ = true;
      std::snprintf(path_buffer_, sizeof(path_buffer_), "tree_export");
    }
    if (ImGui::MenuItem("Import terrain...")) import_open_ = true;
    ImGui::Separator();
    if (ImGui::MenuItem("Quit")) request_quit();
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit")) {
    const UndoEntry* u = session_.history().next_undo();
    const UndoEntry* r = session_.history().next_redo();
    if (ImGui::MenuItem(u ? ("Undo " + u->label).c_str() : "Undo", "Ctrl+Z", false, u != nullptr)) apply(session_.undo());
    if (ImGui::MenuItem(r ? ("Redo " + r->label).c_str() : "Redo", "Ctrl+Y", false, r != nullptr)) apply(session_.redo());
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    if (ImGui::MenuItem("Fly camera", nullptr, camera_mode_ == CameraMode::kFly)) camera_mode_ = CameraMode::kFly;
    if (ImGui::MenuItem("Orbit camera", nullptr, camera_mode_ == CameraMode::kOrbit)) {
      camera_mode_ = CameraMode::kOrbit;
      orbit_ = orbit_from_camera(session_.camera(), 60.0);
    }
    ImGui::MenuItem("Plant preview", nullptr, &session_.preview_open());
    ImGui::Separator();
    for (const ParamDescriptor& p : describe_params(session_.scene().debug())) {
      bool v = p.value<bool>();
      if (ImGui::MenuItem(p.path.c_str(), nullptr, &v)) (void)p.set(v);
    }
    ImGui::EndMenu();
  }
  const std::string title = fmt::format("{}{}", session_.path() ? session_.path()->filename().string() : "untitled",
                                        session_.unsaved() ? " *" : "");
  ImGui::SameLine(ImGui::GetWindowWidth() - ImGui::CalcTextSize(title.c_str()).x - 20.0f);
  ImGui::TextUnformatted(title.c_str());
  ImGui::EndMainMenuBar();
}

void EditorUi::outline_panel() {
  scene::SceneDocument& doc = session_.scene().document();
  // Wrapped: scene names are often longer than the outline is wide.
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextDisabled("%s", doc.name.empty() ? "(unnamed scene)" : doc.name.c_str());
  ImGui::PopTextWrapPos();
  if (ImGui::Selectable("Environment (sun, wind, time)", selected_ == "environment")) selected_ = "environment";
  if (ImGui::Selectable("Camera", selected_ == "camera")) selected_ = "camera";
  ImGui::Separator();
  ImGui::TextUnformatted("Modules");
  std::string remove;
  for (const scene::ModuleSection& s : doc.modules()) {
    ImGui::PushID(s.name.c_str());
    if (ImGui::Selectable(outline_label(s.name), selected_ == s.name, 0, ImVec2(170, 0))) selected_ = s.name;
    ImGui::SameLine(200);
    if (ImGui::SmallButton("x")) remove = s.name;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Remove %s (undoable)", s.name.c_str());
    ImGui::PopID();
  }
  if (!remove.empty()) {
    apply(session_.remove_module(remove));
    if (selected_ == remove) selected_ = "environment";
  }
  if (ImGui::BeginCombo("##add", "Add module...")) {
    for (const scene::ModuleDescriptor* d : scene::compiled_modules()) {
      if (doc.has_module(d->name)) continue;
      if (ImGui::Selectable(d->name.c_str())) {
        apply(session_.add_module(d->name));
        selected_ = d->name;
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", d->description.c_str());
    }
    ImGui::EndCombo();
  }
  ImGui::Separator();
  ImGui::TextUnformatted("Bookmarks");
  std::string go, erase;
  for (const auto& [name, view] : doc.bookmarks) {
    ImGui::PushID(name.c_str());
    if (ImGui::Selectable(name.c_str(), false, 0, ImVec2(170, 0))) go = name;
    ImGui::SameLine(200);
    if (ImGui::SmallButton("x")) erase = name;
    ImGui::PopID();
  }
  if (!go.empty()) {
    apply(session_.go_to_bookmark(go));
    orbit_ = orbit_from_camera(session_.camera(), orbit_.distance);
  }
  if (!erase.empty()) apply(session_.remove_bookmark(erase));
  ImGui::SetNextItemWidth(140);
  ImGui::InputText("##bm", bookmark_buffer_, sizeof(bookmark_buffer_));
  ImGui::SameLine();
  if (ImGui::Button("Add view")) apply(session_.add_bookmark(bookmark_buffer_));
  ImGui::Separator();
  ImGui::TextUnformatted("Camera paths");
  for (const auto& [name, path] : doc.camera_paths) {
    const bool playing = playing_path_ == name;
    if (ImGui::Selectable(fmt::format("{} ({:.1f} s){}", name, path.duration(), playing ? "  [playing]" : "").c_str(), playing)) {
      playing_path_ = playing ? "" : name;
      path_time_ = path.start_time();
    }
  }
  ImGui::Separator();
  ImGui::TextUnformatted("Messages");
  for (const std::string& m : messages_) ImGui::TextWrapped("%s", m.c_str());
  for (const std::string& w : session_.warnings()) ImGui::TextWrapped("warning: %s", w.c_str());
}

void EditorUi::section_params(const std::string& section) {
  std::vector<ParamDescriptor> all = session_.scene().describe_params();
  std::vector<ParamDescriptor> mine;
  for (ParamDescriptor& p : all) {
    if (p.path.rfind(section + ".", 0) == 0) mine.push_back(std::move(p));
  }
  ParamGroup root;
  for (const ParamDescriptor& p : mine) insert(root, p, section.size() + 1);
  // Values to apply after drawing (applying may rebuild the module and invalidate descriptors).
  std::optional<std::pair<std::string, ParamWidgetResult>> change;
  std::function<void(const ParamGroup&)> draw = [&](const ParamGroup& g) {
    for (const ParamDescriptor* p : g.params) {
      const std::string label = p->path.substr(p->path.rfind('.') + 1);
      ParamWidgetResult r = param_widget(*p, label.c_str());
      if (r.new_text && !change) change = std::make_pair(p->path, r);
    }
    for (const std::string& name : g.order) {
      if (ImGui::TreeNodeEx(name.c_str(), ImGuiTreeNodeFlags_None)) {
        draw(g.children.at(name));
        ImGui::TreePop();
      }
    }
  };
  draw(root);
  if (change) apply(session_.set_param(change->first, *change->second.new_text, change->second.continuing));
}

void EditorUi::properties_panel() {
  if (ImGui::CollapsingHeader("Selection", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (selected_ == "environment") {
      for (const char* s : {"environment", "sun", "wind"}) {
        if (ImGui::TreeNodeEx(s, ImGuiTreeNodeFlags_DefaultOpen)) {
          section_params(s);
          ImGui::TreePop();
        }
      }
    } else if (selected_ == "camera") {
      ImGui::TextWrapped("Where the player starts (saving stores the editor's current view here).");
      section_params("camera");
    } else if (session_.scene().document().has_module(selected_)) {
      ImGui::TextDisabled("%s", outline_label(selected_));
      section_params(selected_);
    }
  }
  if (ImGui::CollapsingHeader("Brush", ImGuiTreeNodeFlags_DefaultOpen)) brush_panel();
  if (ImGui::CollapsingHeader("Debug views")) {
    for (const ParamDescriptor& p : describe_params(session_.scene().debug())) {
      ParamWidgetResult r = param_widget(p, p.path.c_str());
      if (r.new_text) apply(p.set_string(*r.new_text));
    }
  }
}

void EditorUi::brush_panel() {
  ImGui::Checkbox("Paint (left mouse in the viewport)", &paint_);
  std::vector<std::string> ids = session_.map_ids();
  const std::vector<std::string> colors = session_.color_map_ids();  // "grass.tint": one stroke paints tint_r/g/b
  const bool color = std::find(colors.begin(), colors.end(), paint_map_) != colors.end();
  ids.insert(ids.end(), colors.begin(), colors.end());
  if (std::find(ids.begin(), ids.end(), paint_map_) == ids.end()) paint_map_ = ids.empty() ? "" : ids.front();
  if (ImGui::BeginCombo("map", paint_map_.empty() ? "(no maps)" : (paint_map_ + (color ? " (colour)" : "")).c_str())) {
    for (const std::string& id : ids) {
      const bool is_color = std::find(colors.begin(), colors.end(), id) != colors.end();
      if (ImGui::Selectable((id + (is_color ? " (colour)" : "")).c_str(), id == paint_map_)) paint_map_ = id;
    }
    ImGui::EndCombo();
  }
  if (color) ImGui::ColorEdit3("colour", &session_.brush().color.x);  // paint: towards it; erase: towards white
  for (const ParamDescriptor& p : describe_params(session_.brush())) {
    if (p.path == "color") continue;  // the colour picker above, for colour maps only
    ParamWidgetResult r = param_widget(p, p.path.c_str());
    if (r.new_text) apply(p.set_string(*r.new_text));
  }
}

void EditorUi::viewport_panel(double dt) {
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const glm::ivec2 size(std::max(16, static_cast<int>(avail.x)), std::max(16, static_cast<int>(avail.y)));
  apply(session_.set_viewport(size));
  ImGuiIO& io = ImGui::GetIO();
  const ImVec2 origin = ImGui::GetCursorScreenPos();

  // Camera path playback drives the camera.
  if (!playing_path_.empty()) {
    path_time_ += dt;
    auto view = session_.scene().camera_path_view(playing_path_, path_time_);
    if (view.ok()) session_.set_camera(*view);
    else playing_path_.clear();
  }

  // A GL error is shown once per kind of message, not every frame: the user keeps working and
  // can save; the viewport may be wrong until the cause (a size, a map) is undone.
  if (Status frame = session_.render_frame(dt); !frame.ok() && frame.error().message != last_frame_error_) {
    last_frame_error_ = frame.error().message;
    apply(frame);
  }
  const GLuint tex = session_.framebuffer().color_texture().id();
  ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(tex)), ImVec2(static_cast<float>(size.x), static_cast<float>(size.y)),
               ImVec2(0, 1), ImVec2(1, 0));
  const bool hovered = ImGui::IsItemHovered();
  const glm::vec2 mouse(io.MousePos.x - origin.x, io.MousePos.y - origin.y);
  const glm::vec2 delta(io.MouseDelta.x, io.MouseDelta.y);

  // Camera: right drag looks (fly) or orbits; middle drag pans (orbit); wheel zooms; WASD flies.
  if (hovered || ImGui::IsMouseDown(ImGuiMouseButton_Right)) {
    if (camera_mode_ == CameraMode::kFly) {
      render::FlyInput in;
      const bool look = ImGui::IsMouseDown(ImGuiMouseButton_Right);
      in.look = look;
      in.mouse_delta = look ? delta : glm::vec2(0.0f);
      if (!io.WantTextInput) {
        in.forward = ImGui::IsKeyDown(GLFW_KEY_W);
        in.back = ImGui::IsKeyDown(GLFW_KEY_S) && !io.KeyCtrl;
        in.left = ImGui::IsKeyDown(GLFW_KEY_A);
        in.right = ImGui::IsKeyDown(GLFW_KEY_D);
        in.up = ImGui::IsKeyDown(GLFW_KEY_E);
        in.down = ImGui::IsKeyDown(GLFW_KEY_Q);
        in.fast = io.KeyShift;
      }
      render::FlySettings fly;
      fly.speed = 20.0f;
      render::fly_step(session_.camera(), in, fly, dt);
      if (hovered && io.MouseWheel != 0.0f) {
        session_.camera().set_position(session_.camera().position() + glm::dvec3(session_.camera().forward()) * (5.0 * io.MouseWheel));
      }
    } else {
      if (ImGui::IsMouseDown(ImGuiMouseButton_Right)) orbit_rotate(orbit_, delta);
      if (ImGui::IsMouseDown(ImGuiMouseButton_Middle)) orbit_pan(orbit_, delta, session_.camera().perspective().fov_y, size.y);
      if (hovered && io.MouseWheel != 0.0f) orbit_zoom(orbit_, io.MouseWheel);
      apply_orbit(orbit_, session_.camera());
    }
  }

  // Painting: left drag on the ground.
  brush_hit_.reset();
  if (hovered && paint_ && !paint_map_.empty()) {
    brush_hit_ = session_.pick_ground(mouse);
    if (brush_hit_) {
      const glm::dvec2 p(brush_hit_->x, brush_hit_->z);
      if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) apply(session_.begin_stroke(paint_map_, p));
      else if (ImGui::IsMouseDown(ImGuiMouseButton_Left) && session_.stroking()) apply(session_.continue_stroke(p));
    }
  }
  if (!ImGui::IsMouseDown(ImGuiMouseButton_Left) && session_.stroking()) session_.end_stroke();
  if (brush_hit_) brush_outline(glm::vec2(origin.x, origin.y), *brush_hit_);
  stats_overlay(glm::vec2(origin.x, origin.y));
}

void EditorUi::brush_outline(const glm::vec2& origin, const glm::dvec3& centre) {
  const render::Camera& cam = session_.camera();
  const glm::mat4 vp = cam.view_projection();
  const glm::ivec2 size = session_.viewport();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  std::vector<ImVec2> pts;
  const double r = session_.brush().radius;
  for (int k = 0; k <= 48; ++k) {
    const double a = 2.0 * 3.14159265358979 * k / 48.0;
    glm::dvec3 p = centre + glm::dvec3(std::cos(a) * r, 0.0, std::sin(a) * r);
    if (const HeightField* g = session_.scene().ground()) p.y = g->height(p.x, p.z) + 0.05;
    const glm::vec4 clip = vp * glm::vec4(cam.to_relative(p), 1.0f);
    if (clip.w <= 0.0f) return;
    pts.emplace_back(origin.x + (clip.x / clip.w * 0.5f + 0.5f) * static_cast<float>(size.x),
                     origin.y + (0.5f - clip.y / clip.w * 0.5f) * static_cast<float>(size.y));
  }
  draw->AddPolyline(pts.data(), static_cast<int>(pts.size()), IM_COL32(255, 230, 80, 220), 0, 1.5f);
}

void EditorUi::stats_overlay(const glm::vec2& origin) {
  ImGui::SetNextWindowPos(ImVec2(origin.x + 8, origin.y + 8));
  ImGui::SetNextWindowBgAlpha(0.55f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove;
  if (ImGui::Begin("##stats", nullptr, flags)) {
    const auto& latest = session_.profiler().latest();
    ImGui::Text("%.1f fps  %dx%d  %s camera", ImGui::GetIO().Framerate, session_.viewport().x, session_.viewport().y,
                camera_mode_ == CameraMode::kFly ? "fly" : "orbit");
    if (latest) {
      const scene::SceneFrameStats s = scene::split_frame_stats(*latest);
      // Wall: between buffer swaps, what the user waits for. GPU: timer queries, which a software
      // rasteriser's work escapes. CPU: update and submission.
      ImGui::Text("frame (wall) %.2f ms   GPU (queries) %.2f ms   CPU %.2f ms", 1000.0 * ImGui::GetIO().DeltaTime,
                  s.gpu_ms, s.cpu_ms);
      // Tracked GPU memory and the process's peak RSS (render/gpu_memory.hpp, issue #20), rebuilt
      // twice a second: the report walks every owner and calls getrusage.
      if (memory_line_time_ < 0.0 || ImGui::GetTime() - memory_line_time_ >= 0.5) {
        memory_line_time_ = ImGui::GetTime();
        const nlohmann::json memory = scene::memory_report();
        constexpr double kMiB = 1.0 / (1024.0 * 1024.0);
        std::string per_owner;
        for (const auto& [owner, bytes] : memory["gpu_bytes"].items()) {
          const double mib = bytes["total"].get<double>() * kMiB;
          if (mib >= 0.05) per_owner += fmt::format("  {} {:.1f}", owner, mib);
        }
        memory_line_ = fmt::format("GPU memory {:.1f} MiB (peak {:.1f}):{}   process peak RSS {:.0f} MiB",
                                   memory["gpu_total_bytes"].get<double>() * kMiB,
                                   memory["gpu_peak_bytes"].get<double>() * kMiB, per_owner,
                                   memory["peak_rss_bytes"].get<double>() * kMiB);
      }
      ImGui::TextUnformatted(memory_line_.c_str());
      if (ImGui::BeginTable("passes", 5, ImGuiTableFlags_SizingFixedFit)) {
        ImGui::TableSetupColumn("module/pass");
        ImGui::TableSetupColumn("GPU ms");
        ImGui::TableSetupColumn("triangles");
        ImGui::TableSetupColumn("instances");
        ImGui::TableSetupColumn("draws");
        ImGui::TableHeadersRow();
        for (const auto& [module, passes] : s.modules) {
          for (const auto& [pass, st] : passes) {
            if (st.gpu_ms < 0.001 && st.triangles == 0 && st.draw_calls == 0) continue;
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::Text("%s/%s", module.c_str(), pass.c_str());
            ImGui::TableNextColumn();
            ImGui::Text("%.3f", st.gpu_ms);
            ImGui::TableNextColumn();
            ImGui::Text("%llu", static_cast<unsigned long long>(st.triangles));
            ImGui::TableNextColumn();
            ImGui::Text("%llu", static_cast<unsigned long long>(st.instances));
            ImGui::TableNextColumn();
            ImGui::Text("%llu", static_cast<unsigned long long>(st.draw_calls));
          }
        }
        ImGui::EndTable();
      }
    }
    // Module facts: culling and LOD counters as the modules report them.
    const nlohmann::json facts = session_.scene().module_stats();
    for (const auto& [module, info] : facts.items()) {
      std::string line = module + ":";
      for (const auto& [k, v] : info.items()) {
        if (v.is_number() || v.is_boolean()) line += fmt::format(" {}={}", k, v.dump());
        else if (v.is_object() || v.is_array()) line += fmt::format(" {}={}", k, v.dump());
      }
      ImGui::TextWrapped("%s", line.c_str());
    }
  }
  ImGui::End();
}

void EditorUi::dialogs() {
  auto path_modal = [&](const char* id, bool& open, const char* button, auto&& on_ok) {
    if (open) {
      ImGui::OpenPopup(id);
      open = false;
    }
    if (ImGui::BeginPopupModal(id, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
      ImGui::SetNextItemWidth(420);
      const bool enter = ImGui::InputText("path", path_buffer_, sizeof(path_buffer_), ImGuiInputTextFlags_EnterReturnsTrue);
      if (ImGui::Button(button) || enter) {
        on_ok(std::string(path_buffer_));
        ImGui::CloseCurrentPopup();
      }
      ImGui::SameLine();
      if (ImGui::Button("Cancel")) ImGui::CloseCurrentPopup();
      ImGui::EndPopup();
    }
  };
  path_modal("Open scene", open_dialog_, "Open", [&](const std::string& p) {
    Status s = session_.load(p);
    apply(s);
    if (s.ok()) {
      message("opened " + p);
      selected_ = "environment";
    }
    pending_ = Pending::kNone;
  });
  path_modal("Save scene as", save_as_dialog_, "Save", [&](const std::string& p) {
    Status s = session_.save_as(p);
    apply(s);
    if (s.ok()) message("saved " + p);
    if (s.ok() && pending_ != Pending::kNone) continue_pending();
  });
  path_modal("Screenshot", screenshot_dialog_, "Save", [&](const std::string& p) {
    Status s = session_.screenshot(p);
    apply(s);
    if (s.ok()) message("wrote " + p);
  });
  // The forest's first species as OBJT + glTF + slice layers into a folder (vegetation README, "Export").
  path_modal("Export tree to folder", export_tree_dialog_, "Export", [&](const std::string& p) {
    Result<std::string> r = session_.export_tree(p);
    if (r.ok()) message(*r);
    else apply(r.error());
  });
  if (unsaved_dialog_) {
    ImGui::OpenPopup("Unsaved changes");
    unsaved_dialog_ = false;
  }
  if (ImGui::BeginPopupModal("Unsaved changes", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::TextUnformatted("The scene has unsaved changes.");
    if (ImGui::Button("Save")) {
      if (session_.path()) {
        if (save_in_place()) continue_pending();
      } else {
        save_as_dialog_ = true;
        std::snprintf(path_buffer_, sizeof(path_buffer_), "untitled.json");
      }
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Discard")) {
      continue_pending();
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) {
      pending_ = Pending::kNone;
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
}

}  // namespace sylva::editor

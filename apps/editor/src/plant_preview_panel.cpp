// The "Plant preview" window of EditorUi (plant_preview.hpp): a species of the scene's table or a
// grammar file, sliders for seed, derivation count and angle variation, the plant drawn as a 2D
// side view of its blocks (ImGui's draw list, coloured by block, far blocks first), its block
// counts, and the grammar's error with its file:line:column when it does not grow.
#include "editor_ui.hpp"

#include <imgui.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::editor {
namespace {

// One colour per output 0..9 (trunk brown, leaves green, then distinct hues).
constexpr std::array<ImU32, 10> kOutputColours = {
    IM_COL32(130, 90, 50, 255),  IM_COL32(70, 160, 60, 255),  IM_COL32(220, 200, 80, 255), IM_COL32(200, 80, 80, 255),
    IM_COL32(90, 140, 220, 255), IM_COL32(200, 120, 220, 255), IM_COL32(90, 200, 200, 255), IM_COL32(230, 150, 60, 255),
    IM_COL32(170, 170, 170, 255), IM_COL32(240, 240, 240, 255)};

}  // namespace

void EditorUi::plant_preview_panel() {
  PlantPreviewSettings& s = session_.preview_settings();
  // Regrown when a setting changes, another scene is opened or the file watcher reloaded a file.
  if (!(s == preview_settings_) || &session_.scene() != preview_scene_ || session_.messages().size() != preview_messages_) {
    preview_ = session_.build_preview();
    preview_settings_ = s;
    preview_scene_ = &session_.scene();
    preview_messages_ = session_.messages().size();
  }
  const std::vector<std::string> species = preview_species(session_.scene());
  if (ImGui::BeginCombo("species", s.species.c_str())) {
    for (const std::string& name : species) {
      if (ImGui::Selectable(name.c_str(), name == s.species)) s.species = name;
    }
    ImGui::EndCombo();
  }
  if (ImGui::InputText("grammar file", preview_file_, sizeof(preview_file_), ImGuiInputTextFlags_EnterReturnsTrue)) {
    s.species = preview_file_;
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("A .lsys file relative to the scene (Enter to grow it)");
  if (s.species.ends_with(".lsys")) ImGui::SliderInt("system", &s.system, 0, 16);
  int seed = static_cast<int>(std::min<std::uint32_t>(s.seed, 100000));
  if (ImGui::SliderInt("seed", &seed, 0, 1000)) s.seed = static_cast<std::uint32_t>(seed);
  ImGui::SliderInt("derivations", &s.derivations, 0, 12);
  ImGui::SliderFloat("angle variation", &s.angle_variation, 0.0f, 1.0f, "%.2f");
  ImGui::SliderFloat("view yaw", &preview_yaw_deg_, -180.0f, 180.0f, "%.0f deg");
  ImGui::Separator();
  if (!preview_.error.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(255, 110, 110, 255));
    ImGui::TextWrapped("%s", preview_.error.c_str());
    ImGui::PopStyleColor();
    return;
  }
  ImGui::Text("%zu blocks, %zu symbols, %d derivations", preview_.blocks.size(), preview_.symbols, preview_.derivations);
  for (std::size_t o = 0; o < preview_.output_blocks.size(); ++o) {
    const auto it = preview_.block_counts.find(preview_.output_blocks[o]);
    if (preview_.output_blocks[o].empty() || it == preview_.block_counts.end()) continue;
    ImGui::ColorButton(("##out" + std::to_string(o)).c_str(), ImGui::ColorConvertU32ToFloat4(kOutputColours[o]),
                       ImGuiColorEditFlags_NoTooltip, ImVec2(12, 12));
    ImGui::SameLine();
    ImGui::Text("%s  %zu", preview_.output_blocks[o].c_str(), it->second);
  }

  // The side view: blocks projected on the plane facing the view yaw, scaled to fit, far first.
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const float side = std::max(64.0f, std::min(avail.x, std::max(avail.y, 64.0f)));
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(origin, ImVec2(origin.x + side, origin.y + side), IM_COL32(25, 28, 34, 255));
  const float yaw = glm::radians(preview_yaw_deg_);
  const glm::vec3 right(std::cos(yaw), 0.0f, std::sin(yaw)), toward(-std::sin(yaw), 0.0f, std::cos(yaw));
  const glm::vec3 centre = 0.5f * (preview_.bounds_min + preview_.bounds_max);
  const float extent = std::max(glm::length(preview_.bounds_max - preview_.bounds_min), 1.0f);
  const float scale = 0.92f * side / extent;
  std::vector<const PreviewBlock*> order;
  order.reserve(preview_.blocks.size());
  for (const PreviewBlock& b : preview_.blocks) order.push_back(&b);
  std::sort(order.begin(), order.end(),
            [&](const PreviewBlock* a, const PreviewBlock* b) { return glm::dot(a->position, toward) < glm::dot(b->position, toward); });
  for (const PreviewBlock* b : order) {
    const glm::vec3 d = b->position - centre;
    const float x = origin.x + 0.5f * side + glm::dot(d, right) * scale, y = origin.y + 0.5f * side - d.y * scale;
    const float h = std::max(0.5f * b->size * scale, 0.5f);
    draw->AddRectFilled(ImVec2(x - h, y - h), ImVec2(x + h, y + h), kOutputColours[static_cast<std::size_t>(b->output) % 10]);
  }
  ImGui::Dummy(ImVec2(side, side));
}

}  // namespace sylva::editor

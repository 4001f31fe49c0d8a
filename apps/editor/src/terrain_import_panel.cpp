// The "Import terrain" window of EditorUi (File > Import terrain..., terrain_import.hpp): a file
// path, what was read (size, spacing, height range, nodata filled; or a mesh's vertex and face
// counts), "Use directly" or "Bake for streaming" into a chunk file with a progress bar (percent,
// ETA) and Cancel. The work runs on TerrainImport's worker thread: EditorUi::frame polls it every
// frame, so the viewport and panels keep drawing while a large raster bakes.
#include "editor_ui.hpp"

#include <imgui.h>

#include <fmt/format.h>

#include <cstdio>

namespace sylva::editor {

void EditorUi::poll_terrain_import() {
  if (auto result = import_.poll(session_)) {
    if (result->ok()) message(**result);
    else apply(result->error());
  }
}

void EditorUi::terrain_import_panel() {
  const bool busy = import_.busy();
  ImGui::TextWrapped("An elevation raster (GeoTIFF, .hgt, .asc, PNG, EXR) for the terrain, or a mesh (.obj, .iv, "
                     ".gltf, .glb) for model_terrain. Relative paths start in the working directory.");
  ImGui::SetNextItemWidth(-60.0f);
  ImGui::InputText("source", import_path_, sizeof(import_path_));
  ImGui::BeginDisabled(busy);
  if (ImGui::Button("Read")) {
    const std::filesystem::path source(import_path_);
    // Default output: next to the scene (next to the source for a scene without a file).
    const std::filesystem::path folder = session_.path() ? session_.path()->parent_path() : source.parent_path();
    std::snprintf(import_out_, sizeof(import_out_), "%s",
                  (folder / (source.stem().string() + ".sylvaterrain")).string().c_str());
    apply(import_.start_read(session_, source));
  }
  ImGui::EndDisabled();

  switch (import_.state()) {
    case TerrainImport::State::kIdle:
      break;
    case TerrainImport::State::kReading:
      ImGui::TextUnformatted("reading...");
      break;
    case TerrainImport::State::kRead: {
      const TerrainSourceInfo& info = *import_.info();
      ImGui::Separator();
      ImGui::TextWrapped("%s", info.summary().c_str());
      const bool mesh = info.kind == TerrainSourceInfo::Kind::kMesh;
      if (ImGui::Button(mesh ? "Use as model terrain" : "Use directly")) {
        const std::string file = info.file.string();
        Status used = import_.use_directly(session_);
        apply(used);
        if (used.ok()) message(fmt::format("import: {} set as the {}", file, mesh ? "model_terrain.file" : "ground's elevation.file"));
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("Points the scene at the file (one undo step)");
      if (!mesh) {
        ImGui::Separator();
        ImGui::SetNextItemWidth(-60.0f);
        ImGui::InputText("baked file", import_out_, sizeof(import_out_));
        if (ImGui::Button("Bake for streaming")) apply(import_.start_bake(session_, import_out_));
        if (ImGui::IsItemHovered()) {
          ImGui::SetTooltip("Bakes the chunk tree into the file (as sylva-bake terrain) and sets terrain.baked_file");
        }
      }
      break;
    }
    case TerrainImport::State::kBaking: {
      const float f = import_.progress();
      const double eta = import_.eta_s();
      const std::string overlay =
          eta < 0.0 ? fmt::format("{:.0f} %", 100.0f * f) : fmt::format("{:.0f} %  (ETA {:.1f} s)", 100.0f * f, eta);
      ImGui::TextWrapped("baking %s", import_.bake_output().string().c_str());
      ImGui::ProgressBar(f, ImVec2(-1.0f, 0.0f), overlay.c_str());
      if (ImGui::Button("Cancel")) import_.cancel();
      break;
    }
  }
}

}  // namespace sylva::editor

#include "golden_scene.hpp"

#include <algorithm>

namespace sylva::golden {

namespace fs = std::filesystem;

std::vector<ShippedScene> shipped_scenes(const fs::path& scenes_dir) {
  std::vector<ShippedScene> scenes;
  for (const auto& entry : fs::directory_iterator(scenes_dir)) {
    if (entry.path().extension() == ".json") scenes.push_back({entry.path().stem().string(), entry.path()});
  }
  std::sort(scenes.begin(), scenes.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  scenes.insert(scenes.begin(), ShippedScene{"default", {}});
  return scenes;
}

std::string player_arguments(const ShippedScene& scene, const fs::path& screenshot) {
  std::string args = scene.file.empty() ? std::string() : "'" + scene.file.string() + "' ";
  // The player's own headless default of 8 frames at a fixed 1/30 s step: the picture is
  // byte-identical run to run on one machine (wind and streaming advance by frame, not by clock).
  args += "--headless --size " + std::to_string(kGoldenWidth) + "x" + std::to_string(kGoldenHeight);
  args += " --screenshot '" + screenshot.string() + "'";
  return args;
}

}  // namespace sylva::golden

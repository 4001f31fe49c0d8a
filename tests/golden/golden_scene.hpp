#pragma once
// The shipped scenes the golden-image tests and the gallery render, and how they are rendered:
// one list and one set of player arguments, so the committed goldens, the test and
// scripts/update-goldens can never drift apart.

#include <filesystem>
#include <string>
#include <vector>

namespace sylva::golden {

struct ShippedScene {
  std::string name;            // "default" for the embedded scene, else the file's stem
  std::filesystem::path file;  // empty for the embedded default scene
};

// Every scenes/*.json (sorted by name) and the embedded default scene (first).
std::vector<ShippedScene> shipped_scenes(const std::filesystem::path& scenes_dir);

// Small enough for CI (every scene in a few seconds on llvmpipe), large enough that SSIM sees
// leaves and blades. Default render settings (MSAA 4x, tone mapping): what a user gets.
inline constexpr int kGoldenWidth = 384;
inline constexpr int kGoldenHeight = 216;

// The player's arguments that render `scene` headless into `screenshot`.
std::string player_arguments(const ShippedScene& scene, const std::filesystem::path& screenshot);

}  // namespace sylva::golden

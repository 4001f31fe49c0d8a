#pragma once
// Loads the player's scene settings: the embedded default, or a JSON file of the same shape,
// then applies --set overrides. Errors name the file (with line:column for malformed JSON), the
// JSON path, or the --set path.

#include "ground_scene.hpp"

#include <sylva/core/result.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sylva::player {

struct LoadedScene {
  GroundSceneSettings settings;
  std::vector<std::string> warnings;  // unknown keys and the like: shown, never fatal
};

Result<LoadedScene> load_scene(const std::optional<std::string>& path,
                               const std::vector<std::pair<std::string, std::string>>& overrides);

}  // namespace sylva::player

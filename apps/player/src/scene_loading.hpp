#pragma once
// Loads the player's scene document: the embedded default (scene/scene_document.hpp), or a scene
// file, then applies --set overrides by parameter path. Errors name the file (with line:column
// for malformed JSON), the JSON path, or the --set path; a module the player was built without
// is named with its CMake option.

#include <sylva/core/result.hpp>
#include <sylva/scene/scene_document.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sylva::player {

struct LoadedScene {
  scene::SceneDocument document;
  std::vector<std::string> warnings;  // unknown keys and the like: shown, never fatal
};

Result<LoadedScene> load_scene(const std::optional<std::string>& path,
                               const std::vector<std::pair<std::string, std::string>>& overrides);

}  // namespace sylva::player

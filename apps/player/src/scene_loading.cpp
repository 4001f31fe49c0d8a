#include "scene_loading.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/params.hpp>
#include <sylva/core/params_json.hpp>

#include <fmt/format.h>


namespace sylva::player {

Result<LoadedScene> load_scene(const std::optional<std::string>& path,
                               const std::vector<std::pair<std::string, std::string>>& overrides) {
  LoadedScene scene;
  if (path) {
    auto text = read_file(*path);
    if (!text.ok()) return text.error();
    auto json = parse_json_text(*text, *path);
    if (!json.ok()) return json.error();
    if (!json->is_object()) {
      return make_error(ErrorCode::kParse, fmt::format("{}: a scene file must hold a JSON object", *path));
    }
    Status loaded = params_from_json(scene.settings, *json, scene.warnings);
    if (!loaded.ok()) return make_error(loaded.error().code, fmt::format("{}: {}", *path, loaded.error().message));
    for (std::string& w : scene.warnings) w = fmt::format("{}: {}", *path, w);
  }
  for (const auto& [param_path, value] : overrides) {
    Status set = set_param(scene.settings, param_path, value);
    if (!set.ok()) return make_error(set.error().code, fmt::format("--set {}={}: {}", param_path, value, set.error().message));
  }
  return scene;
}

}  // namespace sylva::player

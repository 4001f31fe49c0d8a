#include "scene_loading.hpp"

#include <fmt/format.h>

namespace sylva::player {

Result<LoadedScene> load_scene(const std::optional<std::string>& path,
                               const std::vector<std::pair<std::string, std::string>>& overrides) {
  LoadedScene loaded;
  auto document = path ? scene::SceneDocument::load(*path, loaded.warnings) : scene::default_scene(loaded.warnings);
  if (!document.ok()) return document.error();
  loaded.document = std::move(*document);
  ParamRegistry params = loaded.document.params();
  for (const auto& [param_path, value] : overrides) {
    Status set = params.set(param_path, value);
    if (!set.ok()) return make_error(set.error().code, fmt::format("--set {}={}: {}", param_path, value, set.error().message));
  }
  // Overrides may break a cross-field rule (min above max): check the whole document again.
  Status valid = loaded.document.validate();
  if (!valid.ok()) return make_error(valid.error().code, fmt::format("after --set: {}", valid.error().message));
  return loaded;
}

}  // namespace sylva::player

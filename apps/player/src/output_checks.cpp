#include "output_checks.hpp"

#include <sylva/core/output_check.hpp>

#include <vector>

namespace sylva::player {

Status check_outputs(const PlayerOptions& options) {
  if (options.screenshot_path) SYLVA_TRY(check_output_image(*options.screenshot_path));
  if (options.stats_path) SYLVA_TRY(check_output_file(*options.stats_path));
  return ok_status();
}

Status check_outputs_are_not_inputs(const PlayerOptions& options, const scene::SceneDocument& document) {
  std::vector<std::filesystem::path> inputs;
  if (options.scene_path) inputs.emplace_back(*options.scene_path);
  for (const scene::ModuleSection& section : document.modules()) {
    for (const auto& [slot, path] : section.maps) inputs.push_back(document.resolve(path));
  }
  for (const auto& output : {options.screenshot_path, options.stats_path}) {
    if (output) SYLVA_TRY(check_not_an_input(*output, inputs));
  }
  return ok_status();
}

}  // namespace sylva::player

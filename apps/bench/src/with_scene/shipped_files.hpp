#pragma once
// Files the suites read from the source tree (scenes/model_terrain.obj, scenes/species/*.json,
// modules/voxel/data/species.json): found under the working directory or under an ancestor of
// the executable, so a build folder inside the checkout finds them.

#include <sylva/core/result.hpp>

#include <filesystem>
#include <string>

namespace sylva::bench {

// The absolute path of `relative` (e.g. "scenes/model_terrain.obj") below the first of the
// working directory, the executable's folder and up to five of their ancestors that holds it.
// kNotFound naming `relative` and `who` (the suite that reads it) when none does.
Result<std::filesystem::path> find_shipped_file(const std::filesystem::path& relative, const std::string& who);

}  // namespace sylva::bench

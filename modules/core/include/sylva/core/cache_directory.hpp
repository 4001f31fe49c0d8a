#pragma once
// Where a cache lives, from the value of a scene's cache-folder parameter (the vegetation slice
// cache, the terrain chunk-tree cache): "auto" = <system temp folder>/<auto_name>, "" = no cache,
// anything else is a folder, relative paths taken from `base` when it is given (the scene file's
// folder, DESIGN.md §2) and from the working directory otherwise.
#include <filesystem>
#include <string>

namespace sylva {

// Empty path = caching off (also when "auto" but the system has no temp folder).
std::filesystem::path resolve_cache_directory(const std::string& setting, const std::string& auto_name,
                                              const std::filesystem::path& base = {});

}  // namespace sylva

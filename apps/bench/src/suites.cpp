#include "suites.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

namespace sylva::bench {

#ifdef SYLVA_BENCH_WITH_SCENE
// with_scene/scene_suites.cpp: the suites as scene files driven through modules/scene.
Result<SuiteSpec> make_scene_suite(const std::string& name);
#endif
#ifdef SYLVA_BENCH_WITH_TERRAIN
// with_terrain/terrain_suite.cpp: the terrain module's LOD pipeline on the bench's own target
// (builtin:terrain), for builds whose scene module lacks the terrain section.
Result<SuiteSpec> make_terrain_suite();
#endif

std::vector<std::string> suite_names() { return {"terrain", "grass", "trees", "voxel", "model"}; }

Result<SuiteSpec> make_suite(const std::string& name) {
  const std::vector<std::string> names = suite_names();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    return make_error(ErrorCode::kNotFound, fmt::format("unknown suite \"{}\"; suites are terrain, grass, trees, voxel, model", name));
  }
  if (name == "terrain") {
#if defined(SYLVA_BENCH_WITH_SCENE) && defined(SYLVA_BENCH_WITH_TERRAIN)
    // The scene's terrain (what the player draws) when the scene module integrates it.
    auto scene_suite = make_scene_suite(name);
    if (scene_suite.ok() || scene_suite.error().code != ErrorCode::kUnsupported) return scene_suite;
#endif
#ifdef SYLVA_BENCH_WITH_TERRAIN
    return make_terrain_suite();
#else
    return make_error(ErrorCode::kUnsupported, "module not available: the terrain suite needs the terrain module, "
                                               "which is not part of this build (SYLVA_WITH_TERRAIN=OFF)");
#endif
  }
#ifdef SYLVA_BENCH_WITH_SCENE
  return make_scene_suite(name);
#else
  const std::string module = name == "trees" ? "vegetation" : name == "model" ? "terrain" : name;
  return make_error(ErrorCode::kUnsupported,
                    fmt::format("module not available: the {} suite renders through the scene module, which is not part "
                                "of this build, so {} cannot be assembled (build modules/scene with SYLVA_WITH_{}=ON)",
                                name, module, module == "vegetation" ? "VEGETATION" : fmt::format("{}", [&] {
                                  std::string up = module;
                                  for (char& c : up) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
                                  return up;
                                }())));
#endif
}

}  // namespace sylva::bench

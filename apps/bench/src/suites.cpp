#include "suites.hpp"

#include <fmt/format.h>

namespace sylva::bench {

#ifdef SYLVA_BENCH_WITH_SCENE
// with_scene/scene_suites.cpp: the suites as scene files driven through modules/scene.
Result<SuiteSpec> make_scene_suite(const std::string& name);
#endif

std::vector<std::string> suite_names() { return {"terrain", "grass", "trees", "voxel"}; }

Result<SuiteSpec> make_suite(const std::string& name) {
  const std::vector<std::string> names = suite_names();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    return make_error(ErrorCode::kNotFound, fmt::format("unknown suite \"{}\"; suites are terrain, grass, trees, voxel", name));
  }
#ifdef SYLVA_BENCH_WITH_SCENE
  return make_scene_suite(name);
#else
  const std::string module = name == "trees" ? "vegetation" : name;
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

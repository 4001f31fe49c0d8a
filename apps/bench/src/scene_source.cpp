#include "scene_source.hpp"

#include "ground_target.hpp"

#include <fmt/format.h>

#include <filesystem>

#ifdef SYLVA_BENCH_WITH_SCENE
#include "with_scene/scene_target.hpp"
#endif
#ifdef SYLVA_BENCH_WITH_TERRAIN
#include "with_terrain/terrain_target.hpp"
#endif

namespace sylva::bench {

Result<TargetFactory> open_scene(const std::string& scene) {
  if (scene == kBuiltinGround) {
    return TargetFactory([]() -> Result<std::unique_ptr<BenchTarget>> { return make_ground_target(); });
  }
#ifdef SYLVA_BENCH_WITH_TERRAIN
  if (scene == kBuiltinTerrain) {
    return TargetFactory([]() -> Result<std::unique_ptr<BenchTarget>> { return make_terrain_target(); });
  }
  constexpr const char* kBuiltins = "builtin:ground, builtin:terrain";
#else
  constexpr const char* kBuiltins = "builtin:ground (builtin:terrain needs the terrain module)";
#endif
  if (scene.rfind("builtin:", 0) == 0) {
    return make_error(ErrorCode::kNotFound, fmt::format("{}: unknown built-in scene; built-in scenes are {}", scene,
                                                        kBuiltins));
  }
  if (!std::filesystem::exists(scene)) {
    return make_error(ErrorCode::kNotFound, fmt::format("{}: scene file not found", scene));
  }
#ifdef SYLVA_BENCH_WITH_SCENE
  return scene_file_factory(scene);
#else
  return make_error(ErrorCode::kUnsupported,
                    fmt::format("{}: scene files need the scene module, which is not part of this build "
                                "(use {} or build modules/scene)", scene, kBuiltinGround));
#endif
}

}  // namespace sylva::bench

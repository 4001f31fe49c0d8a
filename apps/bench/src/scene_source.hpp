#pragma once
// Resolves the SCENE argument to a target factory: "builtin:ground" (ground_target.hpp) or a
// scene JSON file, which needs modules/scene (scene_target.hpp). Errors name the scene.

#include "bench_target.hpp"

#include <string>

namespace sylva::bench {

inline constexpr const char* kBuiltinGround = "builtin:ground";

Result<TargetFactory> open_scene(const std::string& scene);

}  // namespace sylva::bench

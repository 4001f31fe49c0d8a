#pragma once
// What every Drawable sees during one frame (DESIGN.md §2b). Read-only for the frame; the scene
// owns the referenced objects and keeps them alive until the frame ends.

#include <sylva/core/wind.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/lighting.hpp>

#include <glm/glm.hpp>

#include <cstdint>

namespace sylva::render {

enum class Pass { kShadow, kOpaque, kTransparent };

const char* to_string(Pass pass);

struct FrameContext {
  const Camera& camera;        // double-precision origin, camera-relative matrices
  double time = 0.0;           // seconds since the scene started (monotonic)
  float dt = 0.0f;             // seconds since the last frame; may be 0 or huge (>= 0)
  const WindField& wind;       // one wind for trees and grass (core)
  const Lighting& lighting;
  glm::ivec2 viewport{0, 0};   // target size in pixels
  std::uint64_t frame = 0;     // frame number, for query rings and temporal effects
};

}  // namespace sylva::render

#pragma once
// The interface terrain, grass, forests and voxel worlds implement so the scene can drive them
// without knowing them (DESIGN.md §2b).
//
// Per frame the scene calls update() on every drawable, then draw() once per pass. update()
// is CPU work (LOD selection, culling, streaming, simulation) and must be stable for any dt
// >= 0. draw() only issues GL commands for the given pass into the bound framebuffer and adds
// what it submitted (draw calls, instances, triangles) to `stats`; GPU time and counters are
// measured around it by the scene (queries.hpp).

#include <sylva/render/frame_context.hpp>
#include <sylva/render/queries.hpp>

#include <glm/glm.hpp>

namespace sylva::render {

// An axis-aligned rectangle in the world x/z plane, metres (min <= max).
struct WorldRect {
  glm::dvec2 min{0.0};
  glm::dvec2 max{0.0};
};

class Drawable {
 public:
  virtual ~Drawable() = default;
  virtual void update(const FrameContext& frame) = 0;
  virtual void draw(Pass pass, const FrameContext& frame, PassStats& stats) = 0;
  // An edited map (height, density) changed inside `world_xz`: rebuild only what it touches.
  virtual void on_region_changed(const WorldRect& world_xz) { (void)world_xz; }
};

}  // namespace sylva::render

#pragma once
// One frame of a scene at 64 x 36 with its own camera, for tests that read the modules' stats
// and GPU memory afterwards (not the picture).
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/scene/scene.hpp>

namespace sylva::scene::testing {

inline void render_once(Scene& scene) {
  auto fb = render::Framebuffer::create({.width = 64, .height = 36}).value();
  render::FrameProfiler profiler;
  const render::Camera camera = scene.make_camera(scene.document().camera, {64, 36});
  scene.update(camera, 0.0, 0.0f, {64, 36});
  scene.render(fb, profiler);
}

}  // namespace sylva::scene::testing

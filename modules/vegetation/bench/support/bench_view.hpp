#pragma once
// What every vegetation GL benchmark draws into: one headless context for the process, and a
// view (target, lighting block, camera, wind) sized for the benchmark.

#include <sylva/core/wind.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/gl_context.hpp>
#include <sylva/render/lighting_uniforms.hpp>

namespace sylva::vegetation::bench {

// The process's headless GL context, created on first use; nullptr when none can be made.
render::GlContext* gl_context();

struct BenchView {
  render::Framebuffer target;
  render::LightingUniforms lighting_ubo;
  render::Lighting lighting;
  render::Camera camera;
  WindField wind{WindSettings{.strength = 6.0f, .gust_amplitude = 3.0f}};
};

// Makes the target (width x height), the lighting block and the camera's aspect. False when
// there is no GL context or the target cannot be created.
bool init_view(BenchView& view, int width, int height);

}  // namespace sylva::vegetation::bench

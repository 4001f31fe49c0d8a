#include "support/bench_view.hpp"

#include <memory>

namespace sylva::vegetation::bench {

render::GlContext* gl_context() {
  static std::unique_ptr<render::GlContext> ctx = [] {
    auto created = render::GlContext::create_headless({.debug = false});
    return created.ok() ? std::make_unique<render::GlContext>(std::move(created).value()) : nullptr;
  }();
  return ctx.get();
}

bool init_view(BenchView& view, int width, int height) {
  if (gl_context() == nullptr) return false;
  auto fb = render::Framebuffer::create({.width = width, .height = height});
  if (!fb.ok()) return false;
  view.target = std::move(fb).value();
  view.lighting_ubo = render::LightingUniforms::create();
  view.camera.set_aspect(width, height);
  return true;
}

}  // namespace sylva::vegetation::bench

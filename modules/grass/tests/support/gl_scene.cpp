#include "support/gl_scene.hpp"

#include <sylva/core/log.hpp>
#include <sylva/render/frame_context.hpp>
#include <sylva/render/readback.hpp>

#include <epoxy/gl.h>

namespace sylva::grass::testing {

GlScene GlScene::create(int width, int height) {
  GlScene s;
  render::FramebufferDesc desc;
  desc.width = width;
  desc.height = height;
  s.target = render::Framebuffer::create(desc).value();
  s.lighting_ubo = render::LightingUniforms::create();
  s.lighting.fog_density = 0.0f;
  s.camera.set_aspect(width, height);
  s.camera.perspective().near_plane = 0.05f;
  render::ShadowSettings off;
  off.enabled = false;
  off.cascade_count = 1;
  off.resolution = 64;
  s.shadows = render::ShadowMaps::create(off).value();
  return s;
}

void GlScene::begin(double time) {
  target.bind();
  target.clear(clear_color, 0.0f);
  lighting_ubo.update(lighting, camera.position().y, time);
  lighting_ubo.bind();
  shadows.bind();
}

void GlScene::render_shadows(GrassField& field, std::span<render::ShadowCaster* const> extra) {
  const render::FrameContext frame{camera, 0.0, 0.0f, wind, lighting, size(), 0};
  render::CallbackShadowCaster grass([&](const render::ShadowCasterContext& c) {
    field.draw(render::Pass::kShadow, frame, *c.stats);
  });
  shadows.add_caster(&grass);
  for (render::ShadowCaster* c : extra) shadows.add_caster(c);
  const Status s = shadows.render(camera, lighting.sun_direction, &frame, nullptr);
  if (!s.ok()) log_warn("shadows: {}", s.error().message);
  shadows.remove_caster(&grass);
  for (render::ShadowCaster* c : extra) shadows.remove_caster(c);
}

Image GlScene::read() const { return render::read_color(target).value(); }

Image GlScene::render(GrassField& field, double time, float dt) {
  begin(time);
  field.update(camera, size(), time, dt, wind);
  target.bind();
  field.draw_blades(camera);
  return read();
}

void save_png(const Image& image, const std::string& name) {
  const Status s = write_image(name + ".png", image);
  if (!s.ok()) log_warn("could not save {}: {}", name, s.error().message);
}

}  // namespace sylva::grass::testing

#include "voxel_gl_scene.hpp"

#include <sylva/core/log.hpp>
#include <sylva/render/readback.hpp>

namespace sylva::voxel::testing {

VoxelGlScene VoxelGlScene::create(int width, int height) {
  VoxelGlScene s;
  render::FramebufferDesc desc;
  desc.width = width;
  desc.height = height;
  s.target = render::Framebuffer::create(desc).value();
  s.lighting_ubo = render::LightingUniforms::create();
  s.lighting.fog_density = 0.0f;
  s.camera.set_aspect(width, height);
  s.camera.perspective().near_plane = 0.1f;
  return s;
}

void VoxelGlScene::render(VoxelRenderer& renderer, double time,
                          const std::function<void(const render::FrameContext&)>& after_update) {
  render::apply_reversed_z_state();
  target.bind();
  target.clear(clear_color, 0.0f);
  lighting_ubo.update(lighting, camera.position().y, time);
  lighting_ubo.bind();
  const render::FrameContext frame{camera, time, 0.0f, wind, lighting, target.size(), 0};
  renderer.update(frame);
  if (after_update) {
    after_update(frame);
    render::apply_reversed_z_state();  // a shadow pass leaves its own viewport and FBO bound
    target.bind();
  }
  last_stats = {};
  renderer.draw(render::Pass::kOpaque, frame, last_stats);
  renderer.draw(render::Pass::kTransparent, frame, last_stats);
}

Image VoxelGlScene::color() const { return render::read_color(target).value(); }
Image VoxelGlScene::depth() const { return render::read_depth(target).value(); }

void save_png(const Image& image, const std::string& name) {
  const Status s = write_image(name + ".png", image, PixelFormat::kU8);
  if (!s.ok()) log_warn("could not save {}: {}", name, s.error().message);
}

}  // namespace sylva::voxel::testing

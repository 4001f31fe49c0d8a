#pragma once
// GL test support: an off-screen target with the frame's lighting bound, rendering a
// VoxelRenderer and reading colour and depth back (GL tests only).

#include <sylva/core/image.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/lighting.hpp>
#include <sylva/render/lighting_uniforms.hpp>
#include <sylva/voxel/voxel_renderer.hpp>

#include <functional>
#include <string>

namespace sylva::voxel::testing {

struct VoxelGlScene {
  render::Framebuffer target;
  render::LightingUniforms lighting_ubo;
  render::Lighting lighting;
  render::Camera camera;
  WindField wind;
  glm::vec4 clear_color{0.55f, 0.7f, 0.9f, 1.0f};
  render::PassStats last_stats;

  static VoxelGlScene create(int width = 256, int height = 144);
  // update() + draw(kOpaque) + draw(kTransparent) into the target; `after_update` runs between
  // update() and the colour passes, where a host runs its shadow pass.
  void render(VoxelRenderer& renderer, double time = 0.0,
              const std::function<void(const render::FrameContext&)>& after_update = {});
  Image color() const;
  Image depth() const;
};

void save_png(const Image& image, const std::string& name);

}  // namespace sylva::voxel::testing

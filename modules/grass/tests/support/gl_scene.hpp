#pragma once
// GL test support: a small off-screen target with the frame's lighting bound, and helpers to
// render a grass field and read the picture back (GL tests only).

#include <sylva/core/image.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/grass/grass_field.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/lighting.hpp>
#include <sylva/render/lighting_uniforms.hpp>
#include <sylva/render/shadow_maps.hpp>

#include <span>
#include <string>

namespace sylva::grass::testing {

struct GlScene {
  render::Framebuffer target;
  render::LightingUniforms lighting_ubo;
  render::Lighting lighting;
  // Bound by begin() so receivers read a defined block (disabled until shadows.render() runs).
  render::ShadowMaps shadows;
  render::Camera camera;
  WindField wind;
  glm::vec4 clear_color{0.35f, 0.25f, 0.15f, 1.0f};  // soil

  static GlScene create(int width = 256, int height = 144);
  glm::ivec2 size() const { return target.size(); }
  // Clears, runs update (physics + cull) and draws the field; returns the colour image.
  Image render(GrassField& field, double time = 0.0, float dt = 0.0f);
  // Renders `shadows` for the current camera and sun with `field` as the only caster (through
  // draw(kShadow) inside ShadowMaps::render, as the scene does) plus `extra` casters.
  void render_shadows(GrassField& field, std::span<render::ShadowCaster* const> extra = {});
  // Binds the target, the lighting block and the shadow maps, clears.
  void begin(double time = 0.0);
  Image read() const;
};

// Writes `image` as PNG under the test's working directory (for a person to look at).
void save_png(const Image& image, const std::string& name);

}  // namespace sylva::grass::testing

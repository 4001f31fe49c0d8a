#pragma once
// The physically based sky (atmosphere.hpp) with a limb-darkened sun disk, drawn as one
// full-screen triangle at the far plane (reversed-Z depth 0, so it is drawn after opaque
// geometry with GL_GEQUAL and only where nothing was drawn). The shader uses
// render/lib/sky.glsl, so every module's aerial perspective (fog.glsl) fades into exactly
// this sky. The CPU side derives the frame's ambient and sky colours from the same model.

#include <sylva/core/result.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/lighting.hpp>
#include <sylva/render/lighting_uniforms.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/vertex_array.hpp>

#include <glm/glm.hpp>

namespace sylva::render {

// The sun's engine radiance above the atmosphere for `lighting` (its sun_color * intensity is
// what reaches the viewer): divided by the atmosphere's transmittance toward the sun (at
// least 1e-4 per channel, so a sun on the horizon stays finite).
glm::vec3 sun_top_of_atmosphere(const Lighting& lighting);

// The sky table for `lighting` (its atmosphere, sun direction and sun). Cached: the last table
// per thread is reused while these inputs stay bit-identical (a table costs ~1 ms).
const SkyTable& sky_table(const Lighting& lighting);

// CPU twin of sky.glsl's atmosphere_radiance(direction): the sky without the sun disk for a
// unit world direction (below the horizon: the horizon's haze). Engine radiance, linear RGB.
glm::vec3 sky_radiance(const Lighting& lighting, const glm::vec3& direction);

// Fills lighting.ambient (sky irradiance * ambient_scale), ground_color (ground bounce),
// horizon_color (mean over azimuth), zenith_color and fog_color (= horizon_color, the clear
// colour) from the atmosphere and the sun already set in `lighting`. ambient_scale >= 0.
void derive_sky_lighting(Lighting& lighting, float ambient_scale = 1.0f);

class SkyRenderer {
 public:
  // Builds the program ("render/sky.vert", "render/sky.frag"). Errors: kGl from the compiler.
  static Result<SkyRenderer> create();
  SkyRenderer() = default;

  // Draws into the bound framebuffer (viewport already set) with GL_GEQUAL and no depth
  // writes, then restores GL_GREATER and depth writes. Updates its own LightingUniforms from
  // `lighting` and leaves them bound at kLightingBinding.
  void draw(const Camera& camera, const Lighting& lighting, double time = 0.0);

  Program& program() { return program_; }

 private:
  Program program_;
  VertexArray vao_;
  LightingUniforms uniforms_;
};

}  // namespace sylva::render

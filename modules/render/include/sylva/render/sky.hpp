#pragma once
// The physically based sky (atmosphere.hpp) with a limb-darkened sun disk, drawn as a dome
// around the camera at the far plane (reversed-Z depth 0, so it is drawn after opaque geometry
// with GL_GEQUAL and only where nothing was drawn). The dome's vertices look the sky table up
// and its pixels apply the phase functions and the sun disk (sky_dome.hpp, shaders/sky.vert):
// the same render/lib/sky.glsl every module's aerial perspective (fog.glsl) fades into. The CPU side derives the frame's ambient and sky colours from the same model.

#include <sylva/core/result.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/lighting.hpp>
#include <sylva/render/lighting_uniforms.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/buffer.hpp>
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
  // Builds the programs ("render/sky.vert" with "render/sky.frag", and with
  // "render/sky_nadir.frag" for the cap around the nadir) and the dome's buffers. Errors: kGl
  // from the compiler.
  static Result<SkyRenderer> create();
  SkyRenderer() = default;

  // Draws into the bound framebuffer (viewport already set) with GL_GEQUAL and no depth
  // writes (face culling off, clip distance 0 on for the draw), then restores GL_GREATER, depth
  // writes, culling and clip distance 0. Updates its own LightingUniforms from
  // `lighting` and leaves them bound at kLightingBinding.
  void draw(const Camera& camera, const Lighting& lighting, double time = 0.0);

  Program& program() { return program_; }

 private:
  Program program_;
  Program nadir_program_;
  std::size_t nadir_cap_indices_ = 0;
  VertexArray vao_;
  Buffer vertices_;
  Buffer indices_;
  int index_count_ = 0;
  LightingUniforms uniforms_;
};

}  // namespace sylva::render

#pragma once
// Sky gradient with a sun disk, drawn as one full-screen triangle at the far plane (reversed-Z
// depth 0, so it is drawn after opaque geometry with GL_GEQUAL and only where nothing was
// drawn). The shader uses render/lib/sky.glsl, so other modules' shaders (fog, reflections)
// see the same sky colours.

#include <sylva/core/result.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/lighting.hpp>
#include <sylva/render/lighting_uniforms.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/vertex_array.hpp>

namespace sylva::render {

// CPU twin of sky.glsl's sky_color(direction): the gradient (without the sun disk) for a unit
// world direction. Used by tests and by the player for clear colours.
glm::vec3 sky_gradient(const Lighting& lighting, const glm::vec3& direction);

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

#pragma once
// The Lighting of a frame as a std140 uniform block at a fixed binding point, so every module's
// shader reads the same sun, sky and fog by including "render/lib/lighting.glsl" (which declares
// the block) without per-program uniform plumbing. The scene updates and binds it once per frame.

#include <sylva/render/buffer.hpp>
#include <sylva/render/lighting.hpp>

namespace sylva::render {

// Uniform-buffer binding index of the SylvaLighting block (render/lib/lighting.glsl).
inline constexpr GLuint kLightingBinding = 0;

class LightingUniforms {
 public:
  static LightingUniforms create();
  LightingUniforms() = default;

  // camera_height: world y of the camera [m] (height fog is evaluated relative to it);
  // time: scene time [s], exposed to shaders as sylva_time.
  void update(const Lighting& lighting, double camera_height, double time);
  // glBindBufferBase(GL_UNIFORM_BUFFER, kLightingBinding, ...).
  void bind() const;

 private:
  Buffer buffer_;
};

}  // namespace sylva::render

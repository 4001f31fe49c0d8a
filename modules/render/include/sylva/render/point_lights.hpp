#pragma once
// Point lights for every module (seed 004 §2.3.3.2, extraction §3.3): colour * intensity times
// the seed's attenuation F = 1 / (Kc + Kl d + Kq d^2) (defaults Kc = 1, Kl = 0.045,
// Kq = 0.0075: the Ogre3D constants for a range of about 100 m), multiplied by a smooth window
// (1 - (d / range)^4)^2 so a light ends exactly at its range instead of lighting the whole
// world at 1 % (the seed's formula never reaches zero). Kc >= 1 keeps F <= 1 (no amplification
// at d -> 0, seed §10).
//
// At most kMaxPointLights = 16 lights per frame, in a std140 block at UBO binding 3
// (kPointLightBinding; lighting uses 0, shadows 2), read through "render/lib/point_lights.glsl":
//   vec3 sylva_point_lights_diffuse(vec3 rel_pos, vec3 normal)   // summed irradiance, linear RGB
// Positions are world (double) on the CPU and uploaded camera-relative.

#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>
#include <sylva/render/buffer.hpp>

#include <glm/glm.hpp>

#include <span>

namespace sylva::render {

inline constexpr GLuint kPointLightBinding = 3;

// A SylvaPointLights block holding no lights, sized from the std140 mirror PointLights uploads:
// for shaders drawn where no host bound point lights.
Buffer make_empty_point_light_block();
inline constexpr int kMaxPointLights = 16;

struct PointLightAttenuation {
  float constant = 1.0f;     // Kc, >= 1 so the light is never amplified
  float linear = 0.045f;     // Kl [1/m]
  float quadratic = 0.0075f; // Kq [1/m^2]

  template <class V>
  void visit(V& v) {
    v(constant, "constant", {.min = 1.0, .max = 100.0, .help = "Kc of 1/(Kc + Kl d + Kq d^2)"});
    v(linear, "linear", {.min = 0.0, .max = 100.0, .unit = "1/m", .help = "Kl"});
    v(quadratic, "quadratic", {.min = 0.0, .max = 100.0, .unit = "1/m^2", .help = "Kq"});
  }
};

struct PointLight {
  glm::dvec3 position{0.0};   // world [m]
  glm::vec3 color{1.0f};      // linear RGB
  float intensity = 1.0f;     // multiplier on color, >= 0
  float range = 100.0f;       // [m] > 0: contribution is exactly 0 beyond
  PointLightAttenuation attenuation{};
};

// CPU twin of the shader: the seed's attenuation times the range window, for distance d [m].
float point_light_attenuation(const PointLightAttenuation& a, float range, float d);

class PointLightUniforms {
 public:
  static PointLightUniforms create();  // needs a current GL context
  PointLightUniforms() = default;

  // Uploads `lights` relative to the camera. Errors (the block then holds the lights before the
  // failing one, so a frame never shows garbage): kLimit when more than kMaxPointLights are
  // given (the first 16 are kept; callers should sort by importance), kInvalidArgument naming
  // the light index for non-finite values, negative intensity or range <= 0.
  Status update(std::span<const PointLight> lights, const glm::dvec3& camera_position);
  void bind() const;  // glBindBufferBase(GL_UNIFORM_BUFFER, kPointLightBinding, ...)
  int count() const { return count_; }

 private:
  Buffer buffer_;
  int count_ = 0;
};

}  // namespace sylva::render

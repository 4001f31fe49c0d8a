// Sun direction, fog maths and the lighting uniform block (lighting.hpp, lighting_uniforms.hpp).
#include <sylva/render/lighting.hpp>
#include <sylva/render/lighting_uniforms.hpp>
#include <sylva/render/sky.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace sylva::render {
namespace {

// std140 layout of SylvaLighting in render/lib/lighting.glsl: every member a vec4.
struct LightingBlock {
  glm::vec4 sun_direction;   // xyz unit toward the sun
  glm::vec4 sun_radiance;    // rgb = colour * intensity
  glm::vec4 ambient;         // rgb
  glm::vec4 horizon;         // rgb
  glm::vec4 zenith;          // rgb
  glm::vec4 ground;          // rgb ambient of downward faces
  glm::vec4 fog;             // rgb colour, a = density [1/m]
  glm::vec4 params;          // x = height falloff [1/m], y = camera height [m], z = time [s]
  glm::vec4 rayleigh;        // rgb = air scattering at sea level [1/m], w = 1 / scale height [1/m]
  glm::vec4 mie;             // x = aerosol extinction [1/m], y = 1 / scale height, z = g, w = cos(sun radius)
  std::array<glm::vec4, SkyTable::kRows * SkyTable::kCols * 2> sky;  // SkyTable::cells
};
static_assert(sizeof(LightingBlock) == (10 + SkyTable::kRows * SkyTable::kCols * 2) * 16);

// The sun's angular radius seen from the Earth: 0.2666 deg.
constexpr float kCosSunRadius = 0.99998918f;

}  // namespace

glm::vec3 sun_direction(float azimuth, float elevation) {
  const double ce = std::cos(elevation);
  return glm::normalize(glm::vec3(glm::dvec3(std::sin(azimuth) * ce, std::sin(elevation), -std::cos(azimuth) * ce)));
}

float fog_transmittance(float density, float distance) {
  return std::clamp(std::exp(-std::max(density, 0.0f) * std::max(distance, 0.0f)), 0.0f, 1.0f);
}

LightingUniforms LightingUniforms::create() {
  LightingUniforms u;
  u.buffer_ = Buffer::immutable(sizeof(LightingBlock), nullptr, true);
  return u;
}

void LightingUniforms::update(const Lighting& l, double camera_height, double time) {
  LightingBlock b{};
  const float len = glm::length(l.sun_direction);
  const glm::vec3 sun = len > 1.0e-6f ? l.sun_direction / len : glm::vec3(0.0f, 1.0f, 0.0f);
  b.sun_direction = glm::vec4(sun, 0.0f);
  b.sun_radiance = glm::vec4(l.sun_color * l.sun_intensity, 0.0f);
  b.ambient = glm::vec4(l.ambient, 0.0f);
  b.horizon = glm::vec4(l.horizon_color, 0.0f);
  b.zenith = glm::vec4(l.zenith_color, 0.0f);
  b.ground = glm::vec4(l.ground_color, 0.0f);
  b.fog = glm::vec4(l.fog_color, std::max(l.fog_density, 0.0f));
  // Time wraps after a day so float keeps millisecond resolution in shaders.
  b.params = glm::vec4(std::max(l.fog_height_falloff, 0.0f), static_cast<float>(camera_height),
                       static_cast<float>(std::fmod(time, 86400.0)), 0.0f);
  const AtmosphereSettings& a = l.atmosphere;
  b.rayleigh = glm::vec4(glm::max(a.rayleigh_scattering, glm::vec3(0.0f)), 1.0f / std::max(a.rayleigh_scale_height, 1.0f));
  b.mie = glm::vec4(std::max(a.mie_scattering + a.mie_absorption, 0.0f), 1.0f / std::max(a.mie_scale_height, 1.0f),
                    std::clamp(a.mie_g, -0.99f, 0.99f), kCosSunRadius);
  b.sky = sky_table(l).cells;
  buffer_.update(0, sizeof(b), &b);
}

void LightingUniforms::bind() const { buffer_.bind_base(GL_UNIFORM_BUFFER, kLightingBinding); }

}  // namespace sylva::render

// Point-light uniform block; see point_lights.hpp.
#include <sylva/render/point_lights.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace sylva::render {
namespace {

// std140 mirror of SylvaPointLights in shaders/lib/point_lights.glsl.
struct PointLightBlock {
  glm::vec4 position[kMaxPointLights];     // xyz camera-relative [m], w range [m]
  glm::vec4 color[kMaxPointLights];        // rgb colour * intensity
  glm::vec4 attenuation[kMaxPointLights];  // x Kc, y Kl, z Kq
  glm::ivec4 count;                        // x number of lights
};
static_assert(sizeof(PointLightBlock) == 3 * kMaxPointLights * 16 + 16, "std140 layout of SylvaPointLights");

bool finite3(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

Buffer make_empty_point_light_block() {
  const PointLightBlock empty{};  // count.x = 0
  return Buffer::immutable(sizeof(empty), &empty);
}

float point_light_attenuation(const PointLightAttenuation& a, float range, float d) {
  const float denom = std::max(a.constant + a.linear * d + a.quadratic * d * d, 1.0f);
  const float x = std::clamp(d / range, 0.0f, 1.0f);
  const float x2 = x * x;
  const float window = (1.0f - x2 * x2) * (1.0f - x2 * x2);
  return window / denom;
}

PointLightUniforms PointLightUniforms::create() {
  PointLightUniforms u;
  PointLightBlock zero{};
  u.buffer_ = Buffer::immutable(sizeof(PointLightBlock), &zero, true);
  return u;
}

Status PointLightUniforms::update(std::span<const PointLight> lights, const glm::dvec3& camera_position) {
  PointLightBlock b{};
  Status status = ok_status();
  int n = 0;
  for (const PointLight& l : lights) {
    if (n == kMaxPointLights) {
      status = make_error(ErrorCode::kLimit, fmt::format("point lights: {} given, at most {} per frame (kMaxPointLights); "
                                                         "the first {} are used, pass the most important first",
                                                         lights.size(), kMaxPointLights, kMaxPointLights));
      break;
    }
    const PointLightAttenuation& a = l.attenuation;
    if (!finite3(l.position) || !finite3(glm::dvec3(l.color)) || !std::isfinite(l.intensity) || l.intensity < 0.0f ||
        !std::isfinite(l.range) || l.range <= 0.0f || !std::isfinite(a.constant) || a.constant < 1.0f ||
        !std::isfinite(a.linear) || a.linear < 0.0f || !std::isfinite(a.quadratic) || a.quadratic < 0.0f) {
      status = make_error(ErrorCode::kInvalidArgument,
                          fmt::format("point light {}: position, colour, intensity >= 0, range > 0 and attenuation "
                                      "(Kc >= 1, Kl >= 0, Kq >= 0) must be finite",
                                      n));
      break;
    }
    const glm::vec3 rel(l.position - camera_position);
    b.position[n] = glm::vec4(rel, l.range);
    b.color[n] = glm::vec4(l.color * l.intensity, 0.0f);
    b.attenuation[n] = glm::vec4(a.constant, a.linear, a.quadratic, 0.0f);
    ++n;
  }
  b.count = glm::ivec4(n, 0, 0, 0);
  count_ = n;
  buffer_.update(0, sizeof(b), &b);
  return status;
}

void PointLightUniforms::bind() const { buffer_.bind_base(GL_UNIFORM_BUFFER, kPointLightBinding); }

}  // namespace sylva::render

#include <sylva/vegetation/shading.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva::vegetation {

float beckmann(float nh, float sigma) {
  nh = std::max(nh, 1.0e-4f);
  const float nh2 = nh * nh;
  const float s2 = sigma * sigma;
  return std::exp((nh2 - 1.0f) / (s2 * nh2)) / (s2 * nh2 * nh2);
}

float fresnel_cook_torrance(float c, float n) {
  c = std::clamp(c, 0.0f, 1.0f);
  const float g = std::sqrt(std::max(n * n + c * c - 1.0f, 0.0f));
  const float a = (g - c) / (g + c);
  const float b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
  return 0.5f * a * a * (1.0f + b * b);
}

float geometric_attenuation(float nh, float ne, float nl, float eh) {
  eh = std::max(eh, 1.0e-4f);
  return std::min({1.0f, 2.0f * nh * ne / eh, 2.0f * nh * nl / eh});
}

float cook_torrance_specular(const glm::vec3& n, const glm::vec3& l, const glm::vec3& e, float sigma, float ior) {
  const float nl = glm::dot(n, l);
  const float ne = glm::dot(n, e);
  if (nl <= 0.0f || ne <= 0.0f) return 0.0f;
  const glm::vec3 h = glm::normalize(l + e);
  const float nh = std::max(glm::dot(n, h), 0.0f);
  const float eh = std::max(glm::dot(e, h), 0.0f);
  const float r = beckmann(nh, sigma);
  const float f = fresnel_cook_torrance(eh, ior);
  const float g = geometric_attenuation(nh, ne, nl, eh);
  return r * f * g / (std::numbers::pi_v<float> * std::max(ne, 1.0e-4f));
}

}  // namespace sylva::vegetation

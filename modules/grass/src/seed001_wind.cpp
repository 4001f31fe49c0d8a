#include <sylva/grass/seed001_wind.hpp>

#include <cmath>
#include <numbers>

namespace sylva::grass {

float seed001_wind_time(double t) {
  constexpr double kPeriod = 2.0 * std::numbers::pi * 1000.0;
  if (!std::isfinite(t)) return 0.0f;
  return static_cast<float>(t - kPeriod * std::floor(t / kPeriod));
}

glm::vec3 seed001_wind(const glm::vec3& p, float t, const Seed001WindSettings& s) {
  constexpr float kPi = std::numbers::pi_v<float>;
  constexpr float kK = kPi / 4.0f, kEps = 0.05f;
  const float a = kPi * p.x + t + kK / (std::abs(std::cos(s.k2 * kPi * p.z)) + kEps);
  const float short_wave = std::sin(s.k1 * a) * std::cos(s.k3 * a);
  const float c = p.x + p.y + p.z + t;
  const float long_x = 2.0f * std::sin(c) + 1.0f, long_z = std::sin(2.0f * c) + 0.5f;
  return s.strength * glm::vec3(short_wave + long_x, 0.0f, short_wave + long_z);
}

}  // namespace sylva::grass

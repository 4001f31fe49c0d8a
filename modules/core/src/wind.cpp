// The wind field. The per-sample function evaluate(frame, local) is mirrored one-to-one by
// modules/render/shaders/lib/wind.glsl (sylva_wind); change both together.
#include <sylva/core/noise.hpp>
#include <sylva/core/params.hpp>
#include <sylva/core/rng.hpp>
#include <sylva/core/wind.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva {

namespace {

// Lowest gust front speed, so that calm air has finite-length gusts (continuous in strength).
constexpr double kMinGustFrontSpeed = 1.0;

float clamp_finite(float v, float lo, float hi, float fallback) {
  if (!std::isfinite(v)) return fallback;
  return std::clamp(v, lo, hi);
}

WindSettings sanitized(WindSettings s) {
  const WindSettings d;
  s.direction_deg = std::isfinite(s.direction_deg) ? std::fmod(s.direction_deg, 360.0f) : d.direction_deg;
  s.strength = clamp_finite(s.strength, 0.0f, 100.0f, d.strength);
  s.gust_amplitude = clamp_finite(s.gust_amplitude, 0.0f, 100.0f, d.gust_amplitude);
  s.gust_period = clamp_finite(s.gust_period, 0.1f, 3600.0f, d.gust_period);
  s.turbulence_amplitude = clamp_finite(s.turbulence_amplitude, 0.0f, 100.0f, d.turbulence_amplitude);
  s.turbulence_scale = clamp_finite(s.turbulence_scale, 0.05f, 10000.0f, d.turbulence_scale);
  s.turbulence_evolution = clamp_finite(s.turbulence_evolution, 0.0f, 100.0f, d.turbulence_evolution);
  s.turbulence_vertical = clamp_finite(s.turbulence_vertical, 0.0f, 1.0f, d.turbulence_vertical);
  s.turbulence_octaves = std::clamp(s.turbulence_octaves, 1, 4);
  return s;
}

glm::dvec3 direction_of(float degrees) {
  const double a = static_cast<double>(degrees) * std::numbers::pi / 180.0;
  return {std::cos(a), 0.0, std::sin(a)};
}

double finite_or_zero(double v) { return std::isfinite(v) ? v : 0.0; }

void set4(float (&dst)[4], float x, float y, float z, float w) {
  dst[0] = x;
  dst[1] = y;
  dst[2] = z;
  dst[3] = w;
}

// fBm of the turbulence: lacunarity 2 and persistence 0.5, so octave k sits on the lattice
// 2^k * (cell + offset) = (cell << k) + offset * 2^k, exact in integer + float.
float turbulence_fbm(glm::ivec3 cell, glm::vec3 offset, int octaves, std::uint32_t seed) {
  float sum = 0.0f;
  float amp = 1.0f;
  float norm = 0.0f;
  float scale = 1.0f;
  for (int k = 0; k < octaves; ++k) {
    const glm::ivec3 c(static_cast<std::int32_t>(static_cast<std::uint32_t>(cell.x) << k),
                       static_cast<std::int32_t>(static_cast<std::uint32_t>(cell.y) << k),
                       static_cast<std::int32_t>(static_cast<std::uint32_t>(cell.z) << k));
    sum += amp * gradient_noise3(c, offset * scale, octave_seed(seed, k));
    norm += amp;
    amp *= 0.5f;
    scale *= 2.0f;
  }
  return sum / norm;
}

}  // namespace

WindField::WindField(const WindSettings& settings) : settings_(sanitized(settings)) {
  direction_ = glm::vec3(direction_of(settings_.direction_deg));
}

Status WindField::validate(const WindSettings& settings) { return validate_params(settings, "wind"); }

float WindField::max_speed() const {
  const WindSettings& s = settings_;
  return s.strength + s.gust_amplitude +
         s.turbulence_amplitude * std::sqrt(2.0f + s.turbulence_vertical * s.turbulence_vertical);
}

WindFrame WindField::frame(double t, glm::dvec3 origin) const {
  const WindSettings& s = settings_;
  t = finite_or_zero(t);
  origin = {finite_or_zero(origin.x), finite_or_zero(origin.y), finite_or_zero(origin.z)};
  const glm::dvec3 d = direction_of(s.direction_deg);

  WindFrame f;
  f.origin = origin;
  f.time = t;
  WindGpuParams& g = f.gpu;

  // Gusts: s = (t - dot(p, d) / c) / T, split at the origin.
  const double c = std::max(static_cast<double>(s.strength), kMinGustFrontSpeed);
  const double period = s.gust_period;
  const NoiseCoord1 gust = split_noise_coord((t - glm::dot(origin, d) / c) / period);
  const glm::dvec3 gust_spatial = d / (c * period);

  // Turbulence: q = (p - d * strength * t - (0, evolution * t, 0)) / scale, split at the origin.
  const double inv_scale = 1.0 / static_cast<double>(s.turbulence_scale);
  const glm::dvec3 drift = d * (static_cast<double>(s.strength) * t) +
                           glm::dvec3(0.0, static_cast<double>(s.turbulence_evolution) * t, 0.0);
  const NoiseCoord3 turb = split_noise_coord((origin - drift) * inv_scale);

  set4(g.direction_strength, static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z), s.strength);
  set4(g.gust, s.gust_amplitude, gust.offset, 0.0f, 0.0f);
  set4(g.gust_spatial, static_cast<float>(gust_spatial.x), static_cast<float>(gust_spatial.y),
       static_cast<float>(gust_spatial.z), 0.0f);
  set4(g.turbulence, s.turbulence_amplitude, s.turbulence_vertical, static_cast<float>(inv_scale),
       static_cast<float>(s.turbulence_octaves));
  set4(g.turbulence_offset, turb.offset.x, turb.offset.y, turb.offset.z, 0.0f);
  g.cells[0] = turb.cell.x;
  g.cells[1] = turb.cell.y;
  g.cells[2] = turb.cell.z;
  g.cells[3] = gust.cell;
  g.seeds[0] = hash_u32(1u, s.seed);
  g.seeds[1] = hash_u32(2u, s.seed);
  g.seeds[2] = hash_u32(3u, s.seed);
  g.seeds[3] = hash_u32(4u, s.seed);
  return f;
}

glm::vec3 WindField::evaluate(const WindFrame& frame, glm::vec3 local) {
  const WindGpuParams& g = frame.gpu;
  if (!std::isfinite(local.x) || !std::isfinite(local.y) || !std::isfinite(local.z)) local = glm::vec3(0.0f);
  const glm::vec3 d(g.direction_strength[0], g.direction_strength[1], g.direction_strength[2]);

  // Directional part with gusts travelling downwind.
  const glm::vec3 gust_spatial(g.gust_spatial[0], g.gust_spatial[1], g.gust_spatial[2]);
  const float s = g.gust[1] - glm::dot(local, gust_spatial);
  const float gust = 0.5f + 0.5f * gradient_noise1(g.cells[3], s, g.seeds[0]);
  const float speed = g.direction_strength[3] + g.gust[0] * gust;

  // Turbulence advected with the wind.
  const glm::vec3 offset = glm::vec3(g.turbulence_offset[0], g.turbulence_offset[1], g.turbulence_offset[2]) +
                           local * g.turbulence[2];
  const glm::ivec3 cell(g.cells[0], g.cells[1], g.cells[2]);
  const int octaves = static_cast<int>(g.turbulence[3]);
  const glm::vec3 turb(turbulence_fbm(cell, offset, octaves, g.seeds[1]),
                       g.turbulence[1] * turbulence_fbm(cell, offset, octaves, g.seeds[2]),
                       turbulence_fbm(cell, offset, octaves, g.seeds[3]));
  return d * speed + g.turbulence[0] * turb;
}

glm::vec3 WindField::evaluate(glm::dvec3 pos, double t) const { return evaluate(frame(t, pos), glm::vec3(0.0f)); }

glm::vec3 WindField::evaluate(glm::vec3 pos, double t) const { return evaluate(glm::dvec3(pos), t); }

}  // namespace sylva

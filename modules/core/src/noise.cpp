// Gradient noise, fBm and ridged fBm. Every float operation here is mirrored one-to-one in
// modules/render/shaders/lib/noise.glsl (same order, same constants), which is what makes the
// CPU and GPU agree to float rounding. Change both files together.
#include <sylva/core/noise.hpp>
#include <sylva/core/rng.hpp>

#include <algorithm>
#include <cmath>

namespace sylva {

namespace {

constexpr float kPeriod = 65536.0f;
constexpr float kInvPeriod = 1.0f / 65536.0f;
constexpr double kPeriodD = 65536.0;
constexpr std::uint32_t kMask = 0xFFFFu;
constexpr int kMaxOctaves = 16;

// Analytic bound of N-dimensional Perlin noise with unit gradients is sqrt(N)/2; these map it to
// 1. 2D gradients have length sqrt(5): sqrt(2)/sqrt(5). 3D gradients have length sqrt(2):
// (2/sqrt(3))/sqrt(2). 1D gradients lie in [-1, 1] and the 1D bound is 1/2.
constexpr float kScale1 = 2.0f;
constexpr float kScale2 = 0.632455532f;
constexpr float kScale3 = 0.816496581f;

// Lattice index modulo the period, for a whole-number float. Exact: the scaling is by a power of
// two and the difference of the two integers is an integer in [0, 65536), hence representable.
inline float wrap_period(float whole) { return whole - kPeriod * std::floor(whole * kInvPeriod); }

inline float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }
inline float mix(float a, float b, float t) { return a + t * (b - a); }

inline float grad1(std::uint32_t h, float x) {
  const float g = static_cast<float>(h >> 8u) * (2.0f / 16777216.0f) - 1.0f;  // exact, in [-1, 1)
  return g * x;
}

// Gradient tables, indexed by the low hash bits. They are the branch-free form of the selects in
// noise.glsl (2D: +-u +- 2v with (u, v) = (x, y) or (y, x); 3D: Perlin's improved-noise edges).
// Multiplying by +-1, +-2 or 0 is exact and adding a zero changes nothing, so the results are
// bit-identical to the GLSL selects; tables avoid branch mispredictions on the CPU.
constexpr float kGrad2[8][2] = {{1, 2}, {-1, 2}, {1, -2}, {-1, -2}, {2, 1}, {2, -1}, {-2, 1}, {-2, -1}};
constexpr float kGrad3[16][3] = {{1, 1, 0},  {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1},  {-1, 0, 1},
                                 {1, 0, -1}, {-1, 0, -1}, {0, 1, 1},  {0, -1, 1}, {0, 1, -1}, {0, -1, -1},
                                 {1, 1, 0},  {0, -1, 1}, {-1, 1, 0}, {0, -1, -1}};

inline float grad2(std::uint32_t h, float x, float y) {
  const float* g = kGrad2[h & 7u];
  return g[0] * x + g[1] * y;
}

inline float grad3(std::uint32_t h, float x, float y, float z) {
  const float* g = kGrad3[h & 15u];
  return g[0] * x + g[1] * y + g[2] * z;
}

// Cell index (already wrapped) and in-cell fraction of one axis.
struct Axis {
  std::uint32_t cell;
  float frac;
};

// The fraction offset - floor(offset) is exact for |offset| >= 1 (Sterbenz) and the best float
// otherwise; only the whole part is wrapped, so precision is never lost to the period.
inline Axis axis_from(std::uint32_t base_cell, float offset) {
  const float fl = std::floor(offset);
  const auto cell = static_cast<std::uint32_t>(static_cast<std::int32_t>(wrap_period(fl)));
  return {(base_cell + cell) & kMask, offset - fl};
}

inline Axis axis_from_double(double p) {
  const double fl = std::floor(p);
  const double cell = fl - kPeriodD * std::floor(fl / kPeriodD);
  return {static_cast<std::uint32_t>(static_cast<std::int32_t>(cell)) & kMask, static_cast<float>(p - fl)};
}

float noise1_impl(Axis ax, std::uint32_t seed) {
  const std::uint32_t s = pcg_hash(seed);
  const std::uint32_t c1 = (ax.cell + 1u) & kMask;
  const float n0 = grad1(pcg_hash(ax.cell + s), ax.frac);
  const float n1 = grad1(pcg_hash(c1 + s), ax.frac - 1.0f);
  return mix(n0, n1, fade(ax.frac)) * kScale1;
}

float noise2_impl(Axis ax, Axis ay, std::uint32_t seed) {
  const std::uint32_t s = pcg_hash(seed);
  const std::uint32_t x1 = (ax.cell + 1u) & kMask;
  const std::uint32_t y1 = (ay.cell + 1u) & kMask;
  const std::uint32_t hy0 = pcg_hash(ay.cell + s);
  const std::uint32_t hy1 = pcg_hash(y1 + s);
  const float fx = ax.frac;
  const float fy = ay.frac;
  const float n00 = grad2(pcg_hash(ax.cell + hy0), fx, fy);
  const float n10 = grad2(pcg_hash(x1 + hy0), fx - 1.0f, fy);
  const float n01 = grad2(pcg_hash(ax.cell + hy1), fx, fy - 1.0f);
  const float n11 = grad2(pcg_hash(x1 + hy1), fx - 1.0f, fy - 1.0f);
  const float u = fade(fx);
  const float v = fade(fy);
  return mix(mix(n00, n10, u), mix(n01, n11, u), v) * kScale2;
}

float noise3_impl(Axis ax, Axis ay, Axis az, std::uint32_t seed) {
  const std::uint32_t s = pcg_hash(seed);
  const std::uint32_t x1 = (ax.cell + 1u) & kMask;
  const std::uint32_t y1 = (ay.cell + 1u) & kMask;
  const std::uint32_t z1 = (az.cell + 1u) & kMask;
  const std::uint32_t hz0 = pcg_hash(az.cell + s);
  const std::uint32_t hz1 = pcg_hash(z1 + s);
  const std::uint32_t hy00 = pcg_hash(ay.cell + hz0);
  const std::uint32_t hy10 = pcg_hash(y1 + hz0);
  const std::uint32_t hy01 = pcg_hash(ay.cell + hz1);
  const std::uint32_t hy11 = pcg_hash(y1 + hz1);
  const float fx = ax.frac;
  const float fy = ay.frac;
  const float fz = az.frac;
  const float n000 = grad3(pcg_hash(ax.cell + hy00), fx, fy, fz);
  const float n100 = grad3(pcg_hash(x1 + hy00), fx - 1.0f, fy, fz);
  const float n010 = grad3(pcg_hash(ax.cell + hy10), fx, fy - 1.0f, fz);
  const float n110 = grad3(pcg_hash(x1 + hy10), fx - 1.0f, fy - 1.0f, fz);
  const float n001 = grad3(pcg_hash(ax.cell + hy01), fx, fy, fz - 1.0f);
  const float n101 = grad3(pcg_hash(x1 + hy01), fx - 1.0f, fy, fz - 1.0f);
  const float n011 = grad3(pcg_hash(ax.cell + hy11), fx, fy - 1.0f, fz - 1.0f);
  const float n111 = grad3(pcg_hash(x1 + hy11), fx - 1.0f, fy - 1.0f, fz - 1.0f);
  const float u = fade(fx);
  const float v = fade(fy);
  const float w = fade(fz);
  const float nx00 = mix(n000, n100, u);
  const float nx10 = mix(n010, n110, u);
  const float nx01 = mix(n001, n101, u);
  const float nx11 = mix(n011, n111, u);
  return mix(mix(nx00, nx10, v), mix(nx01, nx11, v), w) * kScale3;
}

inline bool finite(float x) { return std::isfinite(x); }
inline bool finite(double x) { return std::isfinite(x); }

int clamp_octaves(int octaves) { return std::clamp(octaves, 1, kMaxOctaves); }

// The fractal sums, written once for float and double coordinates. Noise is the 1-argument
// sampler for the coordinate type; the accumulation itself is always float, as in GLSL.
template <class Vec, class Scalar, class Noise>
float fbm_sum(Vec p, const FbmSettings& s, Noise noise) {
  Vec q = p * static_cast<Scalar>(s.frequency);
  const auto lacunarity = static_cast<Scalar>(s.lacunarity);
  float sum = 0.0f;
  float amp = 1.0f;
  float norm = 0.0f;
  const int octaves = clamp_octaves(s.octaves);
  for (int k = 0; k < octaves; ++k) {
    sum += amp * noise(q, octave_seed(s.seed, k));
    norm += std::abs(amp);
    amp *= s.persistence;
    q *= lacunarity;
  }
  return sum / norm;
}

template <class Vec, class Scalar, class Noise>
float ridged_sum(Vec p, const FbmSettings& s, Noise noise) {
  Vec q = p * static_cast<Scalar>(s.frequency);
  const auto lacunarity = static_cast<Scalar>(s.lacunarity);
  float sum = 0.0f;
  float amp = 1.0f;
  float norm = 0.0f;
  float weight = 1.0f;
  const int octaves = clamp_octaves(s.octaves);
  for (int k = 0; k < octaves; ++k) {
    float r = 1.0f - std::abs(noise(q, octave_seed(s.seed, k)));
    r = r * r * weight;
    sum += amp * r;
    norm += std::abs(amp);
    weight = std::clamp(r * s.ridge_gain, 0.0f, 1.0f);
    amp *= s.persistence;
    q *= lacunarity;
  }
  return sum / norm;
}

}  // namespace

std::uint32_t octave_seed(std::uint32_t seed, int octave) {
  return hash_u32(static_cast<std::uint32_t>(octave), seed);
}

float gradient_noise1(float x, std::uint32_t seed) {
  if (!finite(x)) return 0.0f;
  return noise1_impl(axis_from(0u, x), seed);
}

float gradient_noise1(std::int32_t cell, float offset, std::uint32_t seed) {
  if (!finite(offset)) return 0.0f;
  return noise1_impl(axis_from(static_cast<std::uint32_t>(cell), offset), seed);
}

float gradient_noise2(glm::vec2 p, std::uint32_t seed) {
  if (!finite(p.x) || !finite(p.y)) return 0.0f;
  return noise2_impl(axis_from(0u, p.x), axis_from(0u, p.y), seed);
}

float gradient_noise3(glm::vec3 p, std::uint32_t seed) {
  if (!finite(p.x) || !finite(p.y) || !finite(p.z)) return 0.0f;
  return noise3_impl(axis_from(0u, p.x), axis_from(0u, p.y), axis_from(0u, p.z), seed);
}

float gradient_noise3(glm::ivec3 cell, glm::vec3 offset, std::uint32_t seed) {
  if (!finite(offset.x) || !finite(offset.y) || !finite(offset.z)) return 0.0f;
  return noise3_impl(axis_from(static_cast<std::uint32_t>(cell.x), offset.x),
                     axis_from(static_cast<std::uint32_t>(cell.y), offset.y),
                     axis_from(static_cast<std::uint32_t>(cell.z), offset.z), seed);
}

float gradient_noise2(glm::dvec2 p, std::uint32_t seed) {
  if (!finite(p.x) || !finite(p.y)) return 0.0f;
  return noise2_impl(axis_from_double(p.x), axis_from_double(p.y), seed);
}

float gradient_noise3(glm::dvec3 p, std::uint32_t seed) {
  if (!finite(p.x) || !finite(p.y) || !finite(p.z)) return 0.0f;
  return noise3_impl(axis_from_double(p.x), axis_from_double(p.y), axis_from_double(p.z), seed);
}

NoiseCoord1 split_noise_coord(double p) {
  if (!finite(p)) return {};
  const Axis a = axis_from_double(p);
  return {static_cast<std::int32_t>(a.cell), a.frac};
}

NoiseCoord3 split_noise_coord(glm::dvec3 p) {
  const NoiseCoord1 x = split_noise_coord(p.x);
  const NoiseCoord1 y = split_noise_coord(p.y);
  const NoiseCoord1 z = split_noise_coord(p.z);
  return {{x.cell, y.cell, z.cell}, {x.offset, y.offset, z.offset}};
}

float fbm2(glm::vec2 p, const FbmSettings& s) {
  return fbm_sum<glm::vec2, float>(p, s, [](glm::vec2 q, std::uint32_t k) { return gradient_noise2(q, k); });
}
float fbm3(glm::vec3 p, const FbmSettings& s) {
  return fbm_sum<glm::vec3, float>(p, s, [](glm::vec3 q, std::uint32_t k) { return gradient_noise3(q, k); });
}
float fbm2(glm::dvec2 p, const FbmSettings& s) {
  return fbm_sum<glm::dvec2, double>(p, s, [](glm::dvec2 q, std::uint32_t k) { return gradient_noise2(q, k); });
}
float fbm3(glm::dvec3 p, const FbmSettings& s) {
  return fbm_sum<glm::dvec3, double>(p, s, [](glm::dvec3 q, std::uint32_t k) { return gradient_noise3(q, k); });
}

float ridged2(glm::vec2 p, const FbmSettings& s) {
  return ridged_sum<glm::vec2, float>(p, s, [](glm::vec2 q, std::uint32_t k) { return gradient_noise2(q, k); });
}
float ridged3(glm::vec3 p, const FbmSettings& s) {
  return ridged_sum<glm::vec3, float>(p, s, [](glm::vec3 q, std::uint32_t k) { return gradient_noise3(q, k); });
}
float ridged2(glm::dvec2 p, const FbmSettings& s) {
  return ridged_sum<glm::dvec2, double>(p, s, [](glm::dvec2 q, std::uint32_t k) { return gradient_noise2(q, k); });
}
float ridged3(glm::dvec3 p, const FbmSettings& s) {
  return ridged_sum<glm::dvec3, double>(p, s, [](glm::dvec3 q, std::uint32_t k) { return gradient_noise3(q, k); });
}

}  // namespace sylva

#pragma once
// Gradient noise (Perlin-style) in 1, 2 and 3 dimensions, fBm and ridged fBm.
//
// Used for generated height fields (seed 002 §"Perlin noise": the thesis gives no details, so
// this is improved Perlin noise with a quintic fade), the wind's turbulence (seed 000 §2.4), and
// procedural textures. The GLSL twin modules/render/shaders/lib/noise.glsl computes the same
// values from the same float operations (tested by the render module's wind GL test), so a
// shader can sample exactly the field the CPU sees.
//
// Lattice and hashing. Coordinates are in lattice units (one cell per unit). The gradient of
// lattice corner (i, j[, k]) is picked by hash_u32(i, j[, k], seed) from <sylva/core/rng.hpp>,
// so there are no permutation tables and the GPU needs no textures. 2D uses the 8 gradients
// (+-1, +-2), (+-2, +-1); 3D uses the 12 cube-edge gradients of Perlin's improved noise.
//
// Period. Every noise function is exactly periodic with period kNoisePeriod (65536) cells along
// each axis: the whole part floor(p) is reduced modulo 65536 (exact in float: it is an integer)
// and corner indices are masked with 0xFFFF, while the in-cell fraction p - floor(p) keeps full
// float precision. The period is invisible in practice and it is what lets a long-running
// animation wrap its phase (see split_noise_coord and wind.hpp).
//
// Ranges (documented and tested):
//   gradient_noise1/2/3 in [-1, 1]. The raw sums are scaled by the analytic bound of Perlin
//     noise with unit gradients (sqrt(N)/2, reached only at a cell centre when every gradient
//     points at it), so [-1, 1] is guaranteed. Extremes actually reached: 1D +-1 (the bound is
//     tight), 2D about +-0.96 (exhaustive search over all gradient combinations), 3D about +-0.75
//     (sampled); standard deviation about 0.2-0.3. Value 0 at every lattice point. Mean 0.
//     Slope: at most about 2.6 per lattice unit (measured; the tests assert < 4).
//   fbm2/3 in [-1, 1] (octaves are normalised by the sum of their amplitudes).
//   ridged2/3 in [0, 1], 1 on ridge crests.
//
// Precision. The float overloads are what GLSL reproduces. A float coordinate carries about 24
// bits, so at |p| = 1e6 cells the sample spacing is 1/16 cell; use the double overloads (CPU only)
// or the split (cell + offset) form for far-from-origin work. Beyond 2^24 cells every float is a
// lattice point and the float overloads return 0 (finite, never NaN).
// Non-finite inputs return 0 on the CPU (GLSL: undefined, as for any NaN input).

#include <glm/glm.hpp>

#include <cstdint>

namespace sylva {

inline constexpr std::int32_t kNoisePeriod = 65536;

// Gradient noise in [-1, 1]; p in lattice units.
float gradient_noise1(float x, std::uint32_t seed);
float gradient_noise2(glm::vec2 p, std::uint32_t seed);
float gradient_noise3(glm::vec3 p, std::uint32_t seed);

// Double-precision coordinates (CPU only): wrapped in double, so 1e12 cells still resolve.
float gradient_noise2(glm::dvec2 p, std::uint32_t seed);
float gradient_noise3(glm::dvec3 p, std::uint32_t seed);

// Split coordinates: the sample position is cell + offset. A far-away position or a long time
// offset is carried exactly in the integer cell while the float offset stays small; GLSL has the
// same overloads. Any cell value is allowed (it wraps); offset must be finite.
float gradient_noise1(std::int32_t cell, float offset, std::uint32_t seed);
float gradient_noise3(glm::ivec3 cell, glm::vec3 offset, std::uint32_t seed);

// Splits a double position into (cell wrapped into [0, 65536), offset in [0, 1]) so that
// gradient_noise*(cell, offset) equals the noise at p up to float rounding of the offset.
struct NoiseCoord1 {
  std::int32_t cell = 0;
  float offset = 0.0f;
};
struct NoiseCoord3 {
  glm::ivec3 cell{0};
  glm::vec3 offset{0.0f};
};
NoiseCoord1 split_noise_coord(double p);
NoiseCoord3 split_noise_coord(glm::dvec3 p);

// Fractal sum settings (DESIGN.md §2 parameters). Octave k samples noise at
// p * frequency * lacunarity^k with amplitude persistence^k and its own seed hash_u32(k, seed).
struct FbmSettings {
  int octaves = 6;            // number of noise layers [1, 16]
  float persistence = 0.5f;   // amplitude ratio between successive octaves [0, 1]
  float lacunarity = 2.0f;    // frequency ratio between successive octaves [1, 4]
  float frequency = 1.0f;     // cycles (lattice cells) per input unit of the first octave
  std::uint32_t seed = 0;     // any value; different seeds give uncorrelated fields
  float ridge_gain = 2.0f;    // ridged only: how much a ridge in one octave lets the next through

  template <class V>
  void visit(V& v) {
    v(octaves, "octaves", {.min = 1, .max = 16, .help = "Number of noise layers summed"});
    v(persistence, "persistence", {.min = 0.0, .max = 1.0,
      .help = "Amplitude ratio between successive octaves (roughness)"});
    v(lacunarity, "lacunarity", {.min = 1.0, .max = 4.0,
      .help = "Frequency ratio between successive octaves"});
    v(frequency, "frequency", {.min = 1e-6, .max = 1e4, .unit = "1/unit",
      .help = "Lattice cells per input unit of the first octave (1 / feature size)", .log_scale = true});
    v(seed, "seed", {.min = 0.0, .max = 4294967295.0, .help = "Random seed of the field"});
    v(ridge_gain, "ridge_gain", {.min = 0.0, .max = 8.0,
      .help = "Ridged fBm: weight passed from one octave to the next (Musgrave's gain)"});
  }
};

// fBm in [-1, 1]: sum_k persistence^k * noise(p * frequency * lacunarity^k) / sum_k persistence^k.
float fbm2(glm::vec2 p, const FbmSettings& settings);
float fbm3(glm::vec3 p, const FbmSettings& settings);
float fbm2(glm::dvec2 p, const FbmSettings& settings);
float fbm3(glm::dvec3 p, const FbmSettings& settings);

// Ridged fBm in [0, 1] (after Musgrave's ridged multifractal): each octave contributes
// r_k = w_k * (1 - |noise_k|)^2, where w_0 = 1 and w_{k+1} = clamp(r_k * ridge_gain, 0, 1), so
// detail gathers on the ridges and valleys stay smooth. Normalised by sum_k persistence^k.
float ridged2(glm::vec2 p, const FbmSettings& settings);
float ridged3(glm::vec3 p, const FbmSettings& settings);
float ridged2(glm::dvec2 p, const FbmSettings& settings);
float ridged3(glm::dvec3 p, const FbmSettings& settings);

// The per-octave seed (also used by the GLSL fBm).
std::uint32_t octave_seed(std::uint32_t seed, int octave);

}  // namespace sylva

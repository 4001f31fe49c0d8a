#pragma once
// Deterministic random numbers for everything procedural in Sylva (placement, generators,
// per-blade and per-tile variation). Two tools with different jobs:
//
//  * Pcg32: a sequential generator (O'Neill's PCG-XSH-RR, 64-bit state, 32-bit output, period
//    2^64 per stream, 2^63 selectable streams). Same seed + stream => same sequence on every
//    platform and build type. Use it where values are drawn one after another.
//  * hash_u32(...): a stateless integer hash (the "PCG hash" permutation of Jarzynski & Olano,
//    "Hash Functions for GPU Rendering", JCGT 2020), chained over its arguments. Use it where a
//    value must be derived from coordinates without order dependence, e.g. a per-tile or
//    per-blade seed hash_u32(x, y, seed). It uses only 32-bit unsigned wrap-around arithmetic, so
//    modules/render/shaders/lib/noise.glsl reproduces it bit-exactly (sylva_hash(...)).
//
// Nothing here is cryptographic.

#include <cstdint>

namespace sylva {

class Pcg32 {
 public:
  using result_type = std::uint32_t;

  // seed selects the starting point, stream selects one of 2^63 independent sequences.
  explicit Pcg32(std::uint64_t seed = 0x853c49e6748fea9bULL, std::uint64_t stream = 0xda3e39cb94b95bdbULL);

  void seed(std::uint64_t seed, std::uint64_t stream = 0xda3e39cb94b95bdbULL);

  // Next 32 uniformly distributed bits.
  std::uint32_t next_u32();
  std::uint32_t operator()() { return next_u32(); }
  static constexpr std::uint32_t min() { return 0u; }
  static constexpr std::uint32_t max() { return 0xffffffffu; }

  // Uniform in [0, bound) without modulo bias (rejection sampling). bound == 0 returns 0.
  std::uint32_t next_below(std::uint32_t bound);
  // Uniform integer in the closed range [lo, hi]; lo > hi is a programming error (asserted).
  // Covers the full int32 range without overflow.
  std::int32_t uniform_int(std::int32_t lo, std::int32_t hi);
  // Uniform float in [0, 1): 24 random mantissa bits, so every value is a multiple of 2^-24.
  float next_float();
  // Uniform double in [0, 1) with 53 random bits (two draws).
  double next_double();
  // Uniform float in [lo, hi) (returns lo when lo == hi; lo > hi is asserted).
  float uniform(float lo, float hi);

  // Jumps the generator ahead by `delta` draws in O(log delta) (also backwards via wrap-around).
  void advance(std::uint64_t delta);

  bool operator==(const Pcg32& other) const = default;

 private:
  std::uint64_t state_ = 0;
  std::uint64_t inc_ = 1;
};

// One round of the PCG hash permutation: a bijection on uint32 with good avalanche.
constexpr std::uint32_t pcg_hash(std::uint32_t v) {
  const std::uint32_t state = v * 747796405u + 2891336453u;
  const std::uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// Chained hashes. Arguments are combined as hash(a, b) = pcg_hash(a + pcg_hash(b)), innermost
// last argument first, so hash_u32(x, y, seed) = pcg_hash(x + pcg_hash(y + pcg_hash(seed))).
// Signed coordinates are reinterpreted as two's-complement uint32 (the GLSL uint(int) rule).
constexpr std::uint32_t hash_u32(std::uint32_t a) { return pcg_hash(a); }
constexpr std::uint32_t hash_u32(std::uint32_t a, std::uint32_t b) { return pcg_hash(a + pcg_hash(b)); }
constexpr std::uint32_t hash_u32(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  return pcg_hash(a + pcg_hash(b + pcg_hash(c)));
}
constexpr std::uint32_t hash_u32(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  return pcg_hash(a + pcg_hash(b + pcg_hash(c + pcg_hash(d))));
}
constexpr std::uint32_t hash_i32(std::int32_t x, std::int32_t y, std::uint32_t seed) {
  return hash_u32(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y), seed);
}
constexpr std::uint32_t hash_i32(std::int32_t x, std::int32_t y, std::int32_t z, std::uint32_t seed) {
  return hash_u32(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y), static_cast<std::uint32_t>(z), seed);
}

// A hash mapped to [0, 1): the top 24 bits times 2^-24 (exact in float, same in GLSL).
constexpr float hash_to_unit_float(std::uint32_t h) { return static_cast<float>(h >> 8u) * (1.0f / 16777216.0f); }

}  // namespace sylva

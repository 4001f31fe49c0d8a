#include <sylva/core/assert.hpp>
#include <sylva/core/rng.hpp>

namespace sylva {

namespace {
constexpr std::uint64_t kMultiplier = 6364136223846793005ULL;
}  // namespace

Pcg32::Pcg32(std::uint64_t seed_value, std::uint64_t stream) { seed(seed_value, stream); }

void Pcg32::seed(std::uint64_t seed_value, std::uint64_t stream) {
  // The increment must be odd for the LCG to have full period; the stream picks which odd value.
  state_ = 0;
  inc_ = (stream << 1u) | 1u;
  next_u32();
  state_ += seed_value;
  next_u32();
}

std::uint32_t Pcg32::next_u32() {
  const std::uint64_t old = state_;
  state_ = old * kMultiplier + inc_;
  // XSH-RR output permutation: xorshift the high bits down, then rotate by the top 5 bits.
  const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
  const auto rot = static_cast<std::uint32_t>(old >> 59u);
  return (xorshifted >> rot) | (xorshifted << ((0u - rot) & 31u));
}

std::uint32_t Pcg32::next_below(std::uint32_t bound) {
  if (bound == 0) return 0;
  // Reject the lowest (2^32 mod bound) values so every residue is equally likely.
  const std::uint32_t threshold = (0u - bound) % bound;
  for (;;) {
    const std::uint32_t r = next_u32();
    if (r >= threshold) return r % bound;
  }
}

std::int32_t Pcg32::uniform_int(std::int32_t lo, std::int32_t hi) {
  SYLVA_ASSERT(lo <= hi, "uniform_int: lo={} > hi={}", lo, hi);
  // Work in uint32 so hi - lo + 1 cannot overflow; the full range (span 2^32) wraps to 0.
  const std::uint32_t span = static_cast<std::uint32_t>(hi) - static_cast<std::uint32_t>(lo) + 1u;
  const std::uint32_t offset = span == 0 ? next_u32() : next_below(span);
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(lo) + offset);
}

float Pcg32::next_float() { return static_cast<float>(next_u32() >> 8u) * (1.0f / 16777216.0f); }

double Pcg32::next_double() {
  const std::uint64_t hi = next_u32() >> 5u;  // 27 bits
  const std::uint64_t lo = next_u32() >> 6u;  // 26 bits
  return static_cast<double>((hi << 26u) | lo) * (1.0 / 9007199254740992.0);
}

float Pcg32::uniform(float lo, float hi) {
  SYLVA_ASSERT(lo <= hi, "uniform: lo={} > hi={}", lo, hi);
  const float v = lo + (hi - lo) * next_float();
  // Rounding can land exactly on hi for some ranges; keep the half-open promise.
  return v < hi ? v : lo;
}

void Pcg32::advance(std::uint64_t delta) {
  // Brown's "random number generation with arbitrary strides": compose the affine map
  // x -> m x + c with itself by repeated squaring.
  std::uint64_t cur_mult = kMultiplier;
  std::uint64_t cur_plus = inc_;
  std::uint64_t acc_mult = 1u;
  std::uint64_t acc_plus = 0u;
  while (delta > 0) {
    if (delta & 1u) {
      acc_mult *= cur_mult;
      acc_plus = acc_plus * cur_mult + cur_plus;
    }
    cur_plus = (cur_mult + 1u) * cur_plus;
    cur_mult *= cur_mult;
    delta >>= 1u;
  }
  state_ = acc_mult * state_ + acc_plus;
}

}  // namespace sylva

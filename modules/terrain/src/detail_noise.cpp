// The terrain's tiling detail noise (material.hpp): generated once per renderer so the fragment
// shader reads detail from a small mipmapped texture (a few filtered fetches, free of shimmer by
// construction) instead of evaluating procedural noise octaves per pixel (issue 18: frame cost).
#include <sylva/core/assert.hpp>
#include <sylva/core/rng.hpp>
#include <sylva/terrain/material.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::terrain {
namespace {

// Gradient noise whose lattice wraps every `period` cells (period divides the tile), so the tile
// repeats seamlessly. Unit gradients at 8 angles; value in about [-0.7, 0.7].
float tiled_noise(float x, float y, int period, std::uint32_t seed) {
  const float fx = std::floor(x), fy = std::floor(y);
  const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);
  const float tx = x - fx, ty = y - fy;
  auto corner = [&](int cx, int cy, float dx, float dy) {
    const int wx = ((cx % period) + period) % period, wy = ((cy % period) + period) % period;
    const float angle = static_cast<float>(hash_u32(static_cast<std::uint32_t>(wx), static_cast<std::uint32_t>(wy), seed) & 7u) *
                        0.785398163f + 0.3926991f;
    return std::cos(angle) * dx + std::sin(angle) * dy;
  };
  auto fade = [](float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); };
  const float a = corner(ix, iy, tx, ty), b = corner(ix + 1, iy, tx - 1.0f, ty);
  const float c = corner(ix, iy + 1, tx, ty - 1.0f), d = corner(ix + 1, iy + 1, tx - 1.0f, ty - 1.0f);
  const float u = fade(tx), v = fade(ty);
  return (a + (b - a) * u) + ((c + (d - c) * u) - (a + (b - a) * u)) * v;
}

// fBm over the tile: octave k has first_period * 2^k cells across the tile, amplitude 0.55^k.
float tiled_fbm(float u, float v, int first_period, int octaves, std::uint32_t seed) {
  float sum = 0.0f, norm = 0.0f, amplitude = 1.0f;
  int period = first_period;
  for (int k = 0; k < octaves; ++k) {
    sum += amplitude * tiled_noise(u * static_cast<float>(period), v * static_cast<float>(period), period, hash_u32(k, seed));
    norm += amplitude;
    amplitude *= 0.55f;
    period *= 2;
  }
  return sum / norm;
}

}  // namespace

Image make_detail_noise(int size, std::uint32_t seed) {
  SYLVA_ASSERT(size >= 16 && (size & (size - 1)) == 0, "make_detail_noise: size {} is not a power of two >= 16", size);
  Image out(size, size, 4);
  const float inv = 1.0f / static_cast<float>(size);
  std::vector<float> relief(static_cast<std::size_t>(size) * size);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float u = static_cast<float>(x) * inv, v = static_cast<float>(y) * inv;
      out.at(x, y, 0) = tiled_fbm(u, v, 4, 5, hash_u32(1u, seed));
      out.at(x, y, 1) = tiled_fbm(u, v, 2, 4, hash_u32(2u, seed));
      relief[static_cast<std::size_t>(y) * size + x] = tiled_fbm(u, v, 8, 5, hash_u32(3u, seed));
    }
  }
  // Central differences on the torus.
  auto r = [&](int x, int y) { return relief[static_cast<std::size_t>((y + size) % size) * size + (x + size) % size]; };
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      out.at(x, y, 2) = r(x + 1, y) - r(x - 1, y);
      out.at(x, y, 3) = r(x, y + 1) - r(x, y - 1);
    }
  }
  // Fixed statistics, whatever the seed: r and g with standard deviation 0.4 (so +-1 is 2.5
  // sigma), the relief gradient with unit RMS (the shader's strengths are in those units).
  double sum[4] = {0, 0, 0, 0}, sum2[4] = {0, 0, 0, 0};
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      for (int c = 0; c < 4; ++c) {
        sum[c] += out.at(x, y, c);
        sum2[c] += static_cast<double>(out.at(x, y, c)) * out.at(x, y, c);
      }
  const double n = static_cast<double>(size) * size;
  float offset[4], gain[4];
  for (int c = 0; c < 2; ++c) {
    const double mean = sum[c] / n;
    offset[c] = static_cast<float>(mean);
    gain[c] = static_cast<float>(0.4 / std::sqrt(std::max(sum2[c] / n - mean * mean, 1e-12)));
  }
  const float rms = static_cast<float>(std::sqrt(std::max((sum2[2] + sum2[3]) / (2.0 * n), 1e-12)));
  offset[2] = offset[3] = 0.0f;
  gain[2] = gain[3] = 1.0f / rms;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      for (int c = 0; c < 4; ++c) out.at(x, y, c) = (out.at(x, y, c) - offset[c]) * gain[c];
  return out;
}

}  // namespace sylva::terrain

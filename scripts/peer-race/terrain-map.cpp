// The terrain race's height map (issue 18, vs BaronVerde/cdlod): 4096 x 4096 samples of 8-octave
// value-noise fBm, quantised to 16 bits in 3278..6552 (metres at height_scale 65535), written to
// stdout as raw big-endian samples, row by row. scripts/peer-race/terrain-scene wraps it in a PNG
// that both programs read. Deterministic: the same bytes on every machine.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

namespace {

constexpr int kSize = 4096;
constexpr int kLowest = 3278, kHighest = 6552;

float lattice(int x, int y) {
  uint32_t h = static_cast<uint32_t>(x) * 374761393u + static_cast<uint32_t>(y) * 668265263u;
  h = (h ^ (h >> 13)) * 1274126177u;
  return static_cast<float>(h ^ (h >> 16)) / 4294967295.0f;
}

float value_noise(float x, float y) {
  const int xi = static_cast<int>(std::floor(x)), yi = static_cast<int>(std::floor(y));
  float fx = x - static_cast<float>(xi), fy = y - static_cast<float>(yi);
  fx = fx * fx * (3.0f - 2.0f * fx);
  fy = fy * fy * (3.0f - 2.0f * fy);
  const float bottom = lattice(xi, yi) + (lattice(xi + 1, yi) - lattice(xi, yi)) * fx;
  const float top = lattice(xi, yi + 1) + (lattice(xi + 1, yi + 1) - lattice(xi, yi + 1)) * fx;
  return bottom + (top - bottom) * fy;
}

float fbm(int i, int j) {
  float sum = 0.0f, amplitude = 1.0f, frequency = 1.0f / 512.0f;
  for (int octave = 0; octave < 8; ++octave) {
    sum += amplitude * value_noise(static_cast<float>(i) * frequency, static_cast<float>(j) * frequency);
    amplitude *= 0.5f;
    frequency *= 2.0f;
  }
  return sum;
}

}  // namespace

int main() {
  std::vector<float> heights(static_cast<size_t>(kSize) * kSize);
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i) heights[static_cast<size_t>(j) * kSize + i] = fbm(i, j);
  const auto [lo, hi] = std::minmax_element(heights.begin(), heights.end());
  const float low = *lo, range = *hi - *lo;
  std::vector<uint8_t> out(heights.size() * 2);
  for (size_t k = 0; k < heights.size(); ++k) {
    const long q = std::lround(kLowest + (heights[k] - low) / range * (kHighest - kLowest));
    out[2 * k] = static_cast<uint8_t>(q >> 8);
    out[2 * k + 1] = static_cast<uint8_t>(q & 0xFF);
  }
  return std::fwrite(out.data(), 1, out.size(), stdout) == out.size() ? 0 : 1;
}

#include <sylva/grass/field_color.hpp>

#include <sylva/core/noise.hpp>
#include <sylva/core/rng.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva::grass {

glm::vec3 field_color(double x, double z, const BladeSettings& blade, std::uint32_t seed) {
  if (!std::isfinite(x) || !std::isfinite(z)) return glm::vec3(1.0f);
  // Patches: two octaves are enough for soft-edged patches (finer detail comes from the clumps).
  FbmSettings patches;
  patches.octaves = 3;
  patches.frequency = 1.0f / std::max(blade.patch_size, 0.01f);
  patches.seed = hash_u32(seed, 0x9a7c4u);
  FbmSettings lightness = patches;
  lightness.frequency *= 1.7f;
  lightness.seed = hash_u32(seed, 0x11947u);
  // fBm of 3 octaves rarely leaves [-0.6, 0.6]: scale to about [-1, 1].
  const float dry = std::clamp(1.7f * fbm2(glm::dvec2(x, z), patches), -1.0f, 1.0f);
  const float light = std::clamp(1.7f * fbm2(glm::dvec2(x, z), lightness), -1.0f, 1.0f);
  // Lush -> dry axis: red up, blue down (green to yellow-green), a little lighter when dry.
  glm::vec3 m = 1.0f + blade.patch_variation * (dry * glm::vec3(0.55f, 0.12f, -0.55f) + light * glm::vec3(0.25f));

  // Clumps: one offset per cell of the world grid.
  const double cs = std::max(static_cast<double>(blade.clump_size), 0.01);
  const auto cx = static_cast<std::uint32_t>(static_cast<std::int64_t>(std::floor(x / cs)));
  const auto cz = static_cast<std::uint32_t>(static_cast<std::int64_t>(std::floor(z / cs)));
  const std::uint32_t h = hash_u32(cx, cz, hash_u32(seed, 0xc1u));
  const float hue = 2.0f * hash_to_unit_float(h) - 1.0f;
  const float value = 2.0f * hash_to_unit_float(hash_u32(h, 0x5au)) - 1.0f;
  m *= 1.0f + blade.clump_variation * (hue * glm::vec3(0.4f, 0.05f, -0.4f) + value * glm::vec3(0.3f));
  return glm::clamp(m, glm::vec3(0.3f), glm::vec3(1.7f));
}

glm::vec2 color_motion_uniform(float amplitude, float hz, double time) {
  const double turns = std::isfinite(time) ? static_cast<double>(hz) * time : 0.0;
  const double phase = 2.0 * std::numbers::pi * (turns - std::floor(turns));
  return {amplitude, static_cast<float>(std::isfinite(phase) ? phase : 0.0)};
}

}  // namespace sylva::grass

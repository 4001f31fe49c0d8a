#include <sylva/scene/forest_placement.hpp>

#include <sylva/core/noise.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::scene {
namespace {

// 32-bit integer hash (lowbias32 by Chris Wellons), combined per key component.
std::uint32_t mix(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

std::uint32_t hash(std::uint32_t seed, int i, int k, std::uint32_t salt) {
  std::uint32_t h = mix(seed ^ 0x9e3779b9U);
  h = mix(h ^ static_cast<std::uint32_t>(i));
  h = mix(h ^ static_cast<std::uint32_t>(k) * 0x85ebca6bU);
  return mix(h ^ salt * 0xc2b2ae35U);
}

float unit(std::uint32_t h) { return static_cast<float>(h >> 8) * (1.0f / 16777216.0f); }

float sample_density(const MapGrid& g, glm::dvec2 world) {
  const glm::dvec2 t = glm::clamp(g.texel(world), glm::dvec2(0.0), glm::dvec2(g.width - 1, g.height - 1));
  const int i0 = static_cast<int>(std::floor(t.x)), j0 = static_cast<int>(std::floor(t.y));
  const int i1 = std::min(i0 + 1, g.width - 1), j1 = std::min(j0 + 1, g.height - 1);
  const double fx = t.x - i0, fy = t.y - j0;
  const double a = g.at(i0, j0) * (1.0 - fx) + g.at(i1, j0) * fx;
  const double b = g.at(i0, j1) * (1.0 - fx) + g.at(i1, j1) * fx;
  return static_cast<float>(a * (1.0 - fy) + b * fy);
}

FbmSettings clearing_noise(const ForestPlacement& p) {
  return {.octaves = 4, .persistence = 0.5f, .lacunarity = 2.0f,
          .frequency = 1.0f / std::max(p.clearing_size, 1.0f), .seed = p.seed ^ 0x51ea4u};
}

// The noise value below which the area is open: its `clearings` quantile over a 64x64 lattice
// of the whole area (deterministic, independent of the region being placed).
float clearing_threshold(const ForestPlacement& p) {
  constexpr int kSide = 64;
  std::vector<float> values;
  values.reserve(kSide * kSide);
  const FbmSettings noise = clearing_noise(p);
  for (int j = 0; j < kSide; ++j) {
    for (int i = 0; i < kSide; ++i) {
      const glm::dvec2 t((i + 0.5) / kSide, (j + 0.5) / kSide);
      values.push_back(fbm2(p.area_min + t * (p.area_max - p.area_min), noise));
    }
  }
  const auto k = static_cast<std::size_t>(std::clamp(p.clearings, 0.0f, 0.95f) * float(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

}  // namespace

double forest_cell_size(const ForestPlacement& p) {
  return 100.0 / std::sqrt(std::max(static_cast<double>(p.trees_per_hectare), 1e-6));
}

void forest_cells(const ForestPlacement& p, glm::dvec2 region_min, glm::dvec2 region_max, glm::ivec2& cell_min,
                  glm::ivec2& cell_max) {
  const double c = forest_cell_size(p);
  const glm::dvec2 lo = glm::max(region_min, p.area_min), hi = glm::min(region_max, p.area_max);
  cell_min = glm::ivec2(static_cast<int>(std::floor(lo.x / c)), static_cast<int>(std::floor(lo.y / c)));
  cell_max = glm::ivec2(static_cast<int>(std::floor(hi.x / c)), static_cast<int>(std::floor(hi.y / c)));
}

std::vector<PlacedTree> place_trees(const ForestPlacement& p, const MapGrid* density, const HeightField* ground,
                                    glm::dvec2 region_min, glm::dvec2 region_max) {
  std::vector<PlacedTree> out;
  if (!(p.trees_per_hectare > 0.0f) || !(p.area_max.x > p.area_min.x && p.area_max.y > p.area_min.y)) return out;
  const glm::dvec2 lo = glm::max(region_min, p.area_min), hi = glm::min(region_max, p.area_max);
  if (!(hi.x >= lo.x && hi.y >= lo.y)) return out;
  const double c = forest_cell_size(p);
  const double margin = std::min(0.5 * static_cast<double>(p.min_spacing), 0.5 * c);
  glm::ivec2 cmin, cmax;
  forest_cells(p, region_min, region_max, cmin, cmax);
  // Guard against absurd regions (the scene validates trees_per_hectare and the area).
  const std::int64_t cells = static_cast<std::int64_t>(cmax.x - cmin.x + 1) * static_cast<std::int64_t>(cmax.y - cmin.y + 1);
  if (cells > 50'000'000) return out;
  const bool clearings = p.clearings > 0.0f;
  const float threshold = clearings ? clearing_threshold(p) : 0.0f;
  const FbmSettings noise = clearing_noise(p);
  for (int k = cmin.y; k <= cmax.y; ++k) {
    for (int i = cmin.x; i <= cmax.x; ++i) {
      const bool grid = p.layout == ForestLayout::kGrid;
      const double jx = grid ? 0.0 : margin + unit(hash(p.seed, i, k, 1)) * (c - 2.0 * margin);
      const double jz = grid ? 0.0 : margin + unit(hash(p.seed, i, k, 2)) * (c - 2.0 * margin);
      const glm::dvec2 xz(i * c + jx, k * c + jz);
      if (xz.x < p.area_min.x || xz.x >= p.area_max.x || xz.y < p.area_min.y || xz.y >= p.area_max.y) continue;
      float d = density ? std::clamp(sample_density(*density, xz), 0.0f, 1.0f) : 1.0f;
      // Soft edges: the stand thins over a band of the noise rather than ending on a contour.
      if (clearings) d *= glm::smoothstep(threshold - 0.04f, threshold + 0.04f, fbm2(xz, noise));
      if (grid ? !(d >= 0.5f) : !(unit(hash(p.seed, i, k, 3)) < d)) continue;
      PlacedTree t;
      t.position = {xz.x, ground ? ground->height(xz.x, xz.y) : 0.0, xz.y};
      t.yaw = unit(hash(p.seed, i, k, 4)) * 6.2831853f;
      t.scale = p.scale_min + (p.scale_max - p.scale_min) * unit(hash(p.seed, i, k, 5));
      t.phase = unit(hash(p.seed, i, k, 6));
      t.random = unit(hash(p.seed, i, k, 7));
      t.cell = {i, k};
      out.push_back(t);
    }
  }
  return out;
}

}  // namespace sylva::scene

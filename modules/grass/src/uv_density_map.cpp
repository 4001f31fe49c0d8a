#include <sylva/grass/uv_density_map.hpp>

#include <cmath>

namespace sylva::grass {

Result<UvDensityMap> UvDensityMap::create(const Image& image, const char* what) {
  // ScalarMap clamps to [0, 1] and counts NaN as 0, like the density map over x/z.
  auto map = ScalarMap::create(image, 0, Rect{{0.0, 0.0}, {1.0, 1.0}}, what);
  if (!map.ok()) return map.error();
  UvDensityMap out;
  out.map_ = std::move(*map);
  return out;
}

float UvDensityMap::sample(glm::vec2 uv) const {
  if (map_.empty() || !std::isfinite(uv.x) || !std::isfinite(uv.y)) return 0.0f;
  // Repeat outside [0, 1]; 1.0 itself stays the right/bottom edge of the tile.
  auto wrap = [](double t) { return t >= 0.0 && t <= 1.0 ? t : t - std::floor(t); };
  return map_.sample(wrap(uv.x), wrap(uv.y), 0.0f);
}

}  // namespace sylva::grass

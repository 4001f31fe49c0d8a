// Per-sample shape of the height field for the material (material.hpp): the normal (so the
// shader reads one filtered texel instead of four height fetches) and the curvature, measured as
// the mean height of a square neighbourhood minus the height (the "topographic position index"
// of geomorphometry, Weiss 2001): positive in hollows and gullies, where dirt, scree and snow
// collect, negative on ridges, which the wind and the weather strip to rock.
#include <sylva/core/noise.hpp>
#include <sylva/terrain/material.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::terrain {

void compute_terrain_shape(const HeightField& field, float radius_m, int x0, int z0, int x1, int z1,
                           std::vector<float>& out) {
  const int cols = field.columns(), rows = field.rows();
  x0 = std::clamp(x0, 0, cols), x1 = std::clamp(x1, 0, cols);
  z0 = std::clamp(z0, 0, rows), z1 = std::clamp(z1, 0, rows);
  out.assign(static_cast<std::size_t>(std::max(x1 - x0, 0)) * std::max(z1 - z0, 0) * 4, 0.0f);
  if (x0 >= x1 || z0 >= z1) return;
  const int r = std::isfinite(radius_m) ? static_cast<int>(std::lround(std::min(radius_m / field.spacing(), 4096.0))) : 0;
  // Summed-area table over the rectangle grown by r (clamped samples beyond the field's edge).
  const int gx0 = x0 - r, gz0 = z0 - r, gw = x1 - x0 + 2 * r, gh = z1 - z0 + 2 * r;
  std::vector<double> sat;
  if (r >= 1) {
    sat.assign(static_cast<std::size_t>(gw + 1) * (gh + 1), 0.0);
    for (int j = 0; j < gh; ++j) {
      double row = 0.0;
      for (int i = 0; i < gw; ++i) {
        row += field.sample_clamped(gx0 + i, gz0 + j);
        sat[static_cast<std::size_t>(j + 1) * (gw + 1) + i + 1] = sat[static_cast<std::size_t>(j) * (gw + 1) + i + 1] + row;
      }
    }
  }
  const double window = static_cast<double>(2 * r + 1) * (2 * r + 1);
  // Macro variation (~400 m features) per sample: the shader reads it with the shape for free
  // instead of fetching a fourth, coarsest detail scale.
  FbmSettings macro;
  macro.octaves = 3;
  macro.frequency = 1.0f / 400.0f;
  macro.seed = 19u;
  const double inv_radius = r >= 1 ? 1.0 / (r * field.spacing()) : 0.0;
  for (int j = z0; j < z1; ++j) {
    for (int i = x0; i < x1; ++i) {
      const glm::vec3 n = field.sample_normal(i, j);
      float curvature = 0.0f;
      if (r >= 1) {
        // Window [i - r, i + r] x [j - r, j + r] in the grown rectangle's coordinates.
        const std::size_t a = static_cast<std::size_t>(j - z0) * (gw + 1) + (i - x0);
        const std::size_t b = a + static_cast<std::size_t>(2 * r + 1);
        const std::size_t c = a + static_cast<std::size_t>(2 * r + 1) * (gw + 1);
        const std::size_t d = c + static_cast<std::size_t>(2 * r + 1);
        const double mean = (sat[d] - sat[b] - sat[c] + sat[a]) / window;
        curvature = static_cast<float>((mean - field.sample(i, j)) * inv_radius);
      }
      float* o = &out[(static_cast<std::size_t>(j - z0) * (x1 - x0) + (i - x0)) * 4];
      o[0] = n.x, o[1] = n.z, o[2] = curvature;
      o[3] = fbm2(glm::dvec2(i, j) * field.spacing(), macro);
    }
  }
}

}  // namespace sylva::terrain

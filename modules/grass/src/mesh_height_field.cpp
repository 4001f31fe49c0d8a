#include <sylva/grass/mesh_height_field.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <vector>

namespace sylva::grass {

namespace {

constexpr double kFlat = 1e-4;  // |normal y| at most this: a vertical face without footprint

}  // namespace

Result<MeshHeightField> mesh_height_field(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices,
                                          const glm::dvec3& origin, double spacing, const MeshDensityAt& density,
                                          std::size_t max_samples) {
  if (!(spacing > 0.0) || !std::isfinite(spacing)) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("mesh height field: spacing {} is not above 0", spacing));
  }
  if (indices.size() % 3 != 0) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("mesh height field: {} indices is not a multiple of 3", indices.size()));
  }
  for (const std::uint32_t i : indices) {
    if (i >= positions.size()) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("mesh height field: index {} is beyond the {} vertices", i, positions.size()));
    }
  }
  auto world = [&](std::uint32_t v) { return origin + glm::dvec3(positions[v]); };
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const glm::vec3& p : positions) {
    lo = glm::min(lo, origin + glm::dvec3(p));
    hi = glm::max(hi, origin + glm::dvec3(p));
  }
  // Faces with a footprint: all must face up; their x/z bounds are the grid's.
  const std::size_t triangles = indices.size() / 3;
  std::vector<std::uint32_t> up;
  glm::dvec2 ulo(std::numeric_limits<double>::infinity()), uhi(-std::numeric_limits<double>::infinity());
  for (std::size_t t = 0; t < triangles; ++t) {
    const glm::dvec3 a = world(indices[3 * t]), b = world(indices[3 * t + 1]), c = world(indices[3 * t + 2]);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double len = glm::length(n);
    if (!(len > 0.0)) continue;
    const double ny = n.y / len;
    if (ny < -kFlat) {
      const glm::dvec3 m = (a + b + c) / 3.0;
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("not a height field: triangle {} near ({:.2f}, {:.2f}, {:.2f}) faces down (normal y "
                                    "{:.2f}), an overhang or the underside of a solid",
                                    t, m.x, m.y, m.z, ny));
    }
    if (ny <= kFlat) continue;
    up.push_back(static_cast<std::uint32_t>(t));
    ulo = glm::min(ulo, glm::min(glm::dvec2(a.x, a.z), glm::min(glm::dvec2(b.x, b.z), glm::dvec2(c.x, c.z))));
    uhi = glm::max(uhi, glm::max(glm::dvec2(a.x, a.z), glm::max(glm::dvec2(b.x, b.z), glm::dvec2(c.x, c.z))));
  }
  if (up.empty()) return make_error(ErrorCode::kInvalidArgument, "not a height field: no triangle faces up");
  // Samples from the lower bound on until one reaches the upper bound.
  const double columns_d = std::ceil((uhi.x - ulo.x) / spacing - 1e-9) + 1.0, rows_d = std::ceil((uhi.y - ulo.y) / spacing - 1e-9) + 1.0;
  if (columns_d * rows_d > static_cast<double>(max_samples)) {
    return make_error(ErrorCode::kLimit, fmt::format("mesh height field: {:.0f} x {:.0f} m at {} m spacing is more than {} samples",
                                                     uhi.x - ulo.x, uhi.y - ulo.y, spacing, max_samples));
  }
  const int columns = static_cast<int>(columns_d), rows = static_cast<int>(rows_d);
  const std::size_t count = static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows);
  std::vector<double> height(count, std::numeric_limits<double>::quiet_NaN());
  std::vector<std::uint32_t> face(count, 0);
  MeshHeightField out;
  out.density = Image(columns, rows, 1);
  const double tolerance = 1e-4 * glm::length(hi - lo) + 1e-4;
  for (const std::uint32_t t : up) {
    const glm::dvec3 a = world(indices[3 * t]), b = world(indices[3 * t + 1]), c = world(indices[3 * t + 2]);
    const double d = (b.z - c.z) * (a.x - c.x) + (c.x - b.x) * (a.z - c.z);
    if (d == 0.0) continue;
    const double x0 = std::min({a.x, b.x, c.x}), x1 = std::max({a.x, b.x, c.x});
    const double z0 = std::min({a.z, b.z, c.z}), z1 = std::max({a.z, b.z, c.z});
    const int i0 = std::max(0, static_cast<int>(std::ceil((x0 - ulo.x) / spacing - 1e-9)));
    const int i1 = std::min(columns - 1, static_cast<int>(std::floor((x1 - ulo.x) / spacing + 1e-9)));
    const int j0 = std::max(0, static_cast<int>(std::ceil((z0 - ulo.y) / spacing - 1e-9)));
    const int j1 = std::min(rows - 1, static_cast<int>(std::floor((z1 - ulo.y) / spacing + 1e-9)));
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const double px = ulo.x + i * spacing, pz = ulo.y + j * spacing;
        const double w0 = ((b.z - c.z) * (px - c.x) + (c.x - b.x) * (pz - c.z)) / d;
        const double w1 = ((c.z - a.z) * (px - c.x) + (a.x - c.x) * (pz - c.z)) / d;
        const double w2 = 1.0 - w0 - w1;
        if (w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9) continue;
        const double y = w0 * a.y + w1 * b.y + w2 * c.y;
        const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(columns) + static_cast<std::size_t>(i);
        if (!std::isnan(height[k])) {
          if (std::abs(height[k] - y) > tolerance) {
            return make_error(ErrorCode::kInvalidArgument,
                              fmt::format("not a height field: triangles {} and {} lie over (x {:.2f}, z {:.2f}) at heights "
                                          "{:.3f} and {:.3f} m",
                                          face[k], t, px, pz, height[k], y));
          }
          continue;  // a shared edge or vertex: the first face's values
        }
        height[k] = y;
        face[k] = t;
        out.density.at(i, j, 0) = std::clamp(density(t, glm::vec3(w0, w1, w2)), 0.0f, 1.0f);
        ++out.covered;
      }
    }
  }
  if (out.covered == 0) return make_error(ErrorCode::kInvalidArgument, "not a height field: no grid sample lies on an upward triangle");
  // Uncovered samples: the height of the nearest covered one (breadth first over the grid).
  std::deque<std::size_t> queue;
  for (std::size_t k = 0; k < count; ++k)
    if (!std::isnan(height[k])) queue.push_back(k);
  while (!queue.empty()) {
    const std::size_t k = queue.front();
    queue.pop_front();
    const int i = static_cast<int>(k % static_cast<std::size_t>(columns)), j = static_cast<int>(k / static_cast<std::size_t>(columns));
    const int ni[4] = {i - 1, i + 1, i, i}, nj[4] = {j, j, j - 1, j + 1};
    for (int e = 0; e < 4; ++e) {
      if (ni[e] < 0 || ni[e] >= columns || nj[e] < 0 || nj[e] >= rows) continue;
      const std::size_t m = static_cast<std::size_t>(nj[e]) * static_cast<std::size_t>(columns) + static_cast<std::size_t>(ni[e]);
      if (!std::isnan(height[m])) continue;
      height[m] = height[k];
      queue.push_back(m);
    }
  }
  out.heights = HeightField(columns, rows, spacing, ulo);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i)
      out.heights.sample(i, j) = static_cast<float>(height[static_cast<std::size_t>(j) * static_cast<std::size_t>(columns) + static_cast<std::size_t>(i)]);
  out.heights.update_range();
  out.rect = {ulo - 0.5 * spacing, ulo + (glm::dvec2(columns, rows) - 0.5) * spacing};
  return out;
}

}  // namespace sylva::grass

#include <sylva/terrain/simplify.hpp>

#include "simplify_mesh_ops.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace sylva::terrain {

namespace {

using detail::point_triangle_dist2;

// Uniform grid over a triangle set for nearest-surface queries.
class TriangleGrid {
 public:
  TriangleGrid(std::span<const glm::vec3> pos, std::span<const std::uint32_t> idx) : pos_(pos), idx_(idx) {
    lo_ = glm::dvec3(std::numeric_limits<double>::max());
    hi_ = -lo_;
    const std::size_t n = idx.size() / 3;
    for (std::uint32_t i : idx) {
      lo_ = glm::min(lo_, glm::dvec3(pos[i]));
      hi_ = glm::max(hi_, glm::dvec3(pos[i]));
    }
    const glm::dvec3 ext = glm::max(hi_ - lo_, glm::dvec3(1e-6));
    // About two triangles per cell on a surface: cells ~ sqrt(n) per horizontal side.
    const double area = std::max({ext.x * ext.y, ext.y * ext.z, ext.x * ext.z});
    cell_ = std::max(std::sqrt(area / std::max<double>(1.0, static_cast<double>(n) / 2.0)), 1e-6);
    dims_ = glm::ivec3(glm::min(glm::dvec3(256.0), glm::floor(ext / cell_) + 1.0));
    cell_ = std::max({ext.x / dims_.x, ext.y / dims_.y, ext.z / dims_.z}) * (1.0 + 1e-9);
    cells_.resize(static_cast<std::size_t>(dims_.x) * dims_.y * dims_.z);
    for (std::uint32_t t = 0; t < n; ++t) {
      glm::dvec3 a(pos[idx[3 * t]]), b(pos[idx[3 * t + 1]]), c(pos[idx[3 * t + 2]]);
      const glm::ivec3 c0 = cell_of(glm::min(a, glm::min(b, c))), c1 = cell_of(glm::max(a, glm::max(b, c)));
      for (int z = c0.z; z <= c1.z; ++z)
        for (int y = c0.y; y <= c1.y; ++y)
          for (int x = c0.x; x <= c1.x; ++x) cells_[flat(x, y, z)].push_back(t);
    }
  }

  // Distance from p to the nearest triangle: visits shells of cells around p's cell until the
  // unvisited cells are farther than the best distance found.
  double distance(const glm::dvec3& p) const {
    const glm::ivec3 c = cell_of(p);
    double best2 = std::numeric_limits<double>::infinity();
    const int max_ring = std::max({dims_.x, dims_.y, dims_.z});
    auto visit = [&](int x, int y, int z) {
      if (x < 0 || y < 0 || z < 0 || x >= dims_.x || y >= dims_.y || z >= dims_.z) return;
      for (std::uint32_t t : cells_[flat(x, y, z)]) {
        const double d2 = point_triangle_dist2(p, glm::dvec3(pos_[idx_[3 * t]]), glm::dvec3(pos_[idx_[3 * t + 1]]),
                                               glm::dvec3(pos_[idx_[3 * t + 2]]));
        best2 = std::min(best2, d2);
      }
    };
    for (int r = 0; r <= max_ring; ++r) {
      if (r == 0) {
        visit(c.x, c.y, c.z);
      } else {
        // The two z faces of the shell, then the four side walls without their z rows.
        for (int y = c.y - r; y <= c.y + r; ++y)
          for (int x = c.x - r; x <= c.x + r; ++x) {
            visit(x, y, c.z - r);
            visit(x, y, c.z + r);
          }
        for (int z = c.z - r + 1; z <= c.z + r - 1; ++z) {
          for (int x = c.x - r; x <= c.x + r; ++x) {
            visit(x, c.y - r, z);
            visit(x, c.y + r, z);
          }
          for (int y = c.y - r + 1; y <= c.y + r - 1; ++y) {
            visit(c.x - r, y, z);
            visit(c.x + r, y, z);
          }
        }
      }
      // Every cell not yet visited lies at least r * cell away (p may sit anywhere in its cell).
      const double reach = static_cast<double>(r) * cell_;
      if (best2 <= reach * reach) break;
    }
    return std::sqrt(best2);
  }

 private:
  glm::ivec3 cell_of(const glm::dvec3& p) const {
    const glm::ivec3 c = glm::ivec3(glm::floor((p - lo_) / cell_));
    return glm::clamp(c, glm::ivec3(0), dims_ - 1);
  }
  std::size_t flat(int x, int y, int z) const {
    return (static_cast<std::size_t>(z) * dims_.y + y) * dims_.x + x;
  }
  std::span<const glm::vec3> pos_;
  std::span<const std::uint32_t> idx_;
  glm::dvec3 lo_, hi_;
  double cell_ = 1.0;
  glm::ivec3 dims_{1};
  std::vector<std::vector<std::uint32_t>> cells_;
};

// Each used vertex once, then each triangle's centroid and, when the triangle is longer than the
// spacing, a barycentric grid of about that spacing (at most 48 steps per side).
template <class Fn>
void sample_surface(std::span<const glm::vec3> pos, std::span<const std::uint32_t> idx, double spacing, Fn&& fn) {
  std::vector<std::uint32_t> verts(idx.begin(), idx.end());
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
  for (std::uint32_t v : verts) fn(glm::dvec3(pos[v]));
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
    const glm::dvec3 a(pos[idx[t]]), b(pos[idx[t + 1]]), c(pos[idx[t + 2]]);
    const double longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
    fn((a + b + c) / 3.0);
    const int n = std::min(static_cast<int>(std::ceil(longest / spacing)), 48);
    if (n < 2) continue;
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j <= n - i; ++j) {
        if ((i == 0 && j == 0) || (i == n) || (j == n)) continue;  // the corners are sampled above
        const double u = static_cast<double>(i) / n, v = static_cast<double>(j) / n;
        fn(a + (b - a) * u + (c - a) * v);
      }
    }
  }
}

}  // namespace

HausdorffDistance hausdorff_distance(std::span<const glm::vec3> positions, std::span<const std::uint32_t> original,
                                     std::span<const std::uint32_t> reduced, double sample_spacing) {
  HausdorffDistance h;
  if (original.empty() || reduced.empty()) return h;
  if (sample_spacing <= 0.0) {
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t t = 0; t + 2 < original.size(); t += 3) {
      for (int k = 0; k < 3; ++k) {
        sum += glm::length(glm::dvec3(positions[original[t + static_cast<std::size_t>(k)]]) -
                           glm::dvec3(positions[original[t + static_cast<std::size_t>((k + 1) % 3)]]));
        ++n;
      }
    }
    sample_spacing = std::max(sum / static_cast<double>(n), 1e-6);
  }
  const TriangleGrid g_reduced(positions, reduced), g_original(positions, original);
  sample_surface(positions, original, sample_spacing, [&](const glm::dvec3& p) {
    h.original_to_reduced = std::max(h.original_to_reduced, g_reduced.distance(p));
  });
  sample_surface(positions, reduced, sample_spacing, [&](const glm::dvec3& p) {
    h.reduced_to_original = std::max(h.reduced_to_original, g_original.distance(p));
  });
  return h;
}

}  // namespace sylva::terrain

#include "support/crown_metrics.hpp"

#include <sylva/core/assert.hpp>

#include <algorithm>
#include <vector>

namespace sylva::vegetation::testing {
namespace {

using P = glm::dvec2;

double cross(const P& o, const P& a, const P& b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

// Andrew's monotone chain; counter-clockwise, no repeated end point.
std::vector<P> hull_of(std::vector<P> pts) {
  std::sort(pts.begin(), pts.end(), [](const P& a, const P& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  if (pts.size() < 3) return pts;
  std::vector<P> h(2 * pts.size());
  std::size_t k = 0;
  for (const P& p : pts) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p) <= 0.0) --k;
    h[k++] = p;
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], pts[i]) <= 0.0) --k;
    h[k++] = pts[i];
  }
  h.resize(k - 1);
  return h;
}

}  // namespace

Image convex_hull_mask(const Image& mask) {
  // Only the leftmost and rightmost pixel of each row can be hull vertices.
  std::vector<P> pts;
  for (int y = 0; y < mask.height(); ++y) {
    int lo = -1;
    int hi = -1;
    for (int x = 0; x < mask.width(); ++x)
      if (mask.at(x, y) > 0.5f) {
        if (lo < 0) lo = x;
        hi = x;
      }
    if (lo >= 0) {
      pts.emplace_back(lo, y);
      pts.emplace_back(hi, y);
    }
  }
  Image out(mask.width(), mask.height(), 1);
  const std::vector<P> h = hull_of(std::move(pts));
  if (h.empty()) return out;
  for (int y = 0; y < mask.height(); ++y)
    for (int x = 0; x < mask.width(); ++x) {
      const P p(x, y);
      bool inside = true;
      if (h.size() >= 3) {
        for (std::size_t i = 0; i < h.size() && inside; ++i) inside = cross(h[i], h[(i + 1) % h.size()], p) >= -1e-9;
      } else {
        // A point or a segment: its pixels.
        const P a = h.front();
        const P b = h.back();
        inside = std::abs(cross(a, b, p)) < 0.5 && p.x >= std::min(a.x, b.x) && p.x <= std::max(a.x, b.x) &&
                 p.y >= std::min(a.y, b.y) && p.y <= std::max(a.y, b.y);
      }
      out.at(x, y) = inside ? 1.0f : 0.0f;
    }
  return out;
}

CrownStats crown_stats(const Image& coverage, const Image& picture) {  // picture: over black
  SYLVA_ASSERT(coverage.width() == picture.width() && coverage.height() == picture.height() && picture.channels() >= 3,
               "crown_stats: coverage {}x{} vs picture {}x{}x{}", coverage.width(), coverage.height(), picture.width(),
               picture.height(), picture.channels());
  const Image hull = convex_hull_mask(coverage);
  CrownStats s;
  glm::dvec3 color(0.0);
  for (int y = 0; y < hull.height(); ++y)
    for (int x = 0; x < hull.width(); ++x) {
      if (hull.at(x, y) < 0.5f) continue;
      const double c = coverage.at(x, y);
      s.hull_pixels += 1.0;
      s.covered += c;
      color += glm::dvec3(picture.at(x, y, 0), picture.at(x, y, 1), picture.at(x, y, 2));
    }
  if (s.hull_pixels > 0.0) s.closure = s.covered / s.hull_pixels;
  if (s.covered > 0.0) s.mean_color = color / s.covered;
  return s;
}

}  // namespace sylva::vegetation::testing

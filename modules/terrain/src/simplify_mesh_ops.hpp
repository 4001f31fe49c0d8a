#pragma once
// Mesh helpers shared by the pass-wise QEM reducer (simplify_qem_passes.cpp), its edge-flip repair
// (simplify_flip.cpp) and the Hausdorff measurement (hausdorff.cpp): vertex fans in CSR form, the
// validity tests of a new triangle, and the point-triangle distance.

#include <glm/glm.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace sylva::terrain::detail {

// A new triangle may turn its normal by at most ~70 degrees (cos > 0.35), as in simplify_qem.
constexpr double kCosLimit = 0.35;

// One corner of a vertex's fan: triangle (v, next, prev) in the triangle's winding. Storing the
// two other vertices directly (not the triangle index) saves an indirection in the hot loops.
struct Corner {
  std::uint32_t next, prev;
};

// Vertex -> fan corners of `tris` (3 vertex ids < nv each) by counting sort into CSR: the corners
// of v are fans[offset[v] .. offset[v + 1]).
inline void build_fans(const std::vector<std::uint32_t>& tris, std::size_t nv, std::vector<std::uint32_t>& offset,
                       std::vector<Corner>& fans) {
  offset.assign(nv + 1, 0u);
  for (std::uint32_t v : tris) ++offset[v + 1];
  for (std::size_t i = 0; i < nv; ++i) offset[i + 1] += offset[i];
  fans.resize(tris.size());
  // Fill from the back using the end offsets; offset[v + 1] is decremented once per corner of v,
  // ending at v's start, and is shifted back below.
  for (std::size_t t = tris.size(); t > 0;) {
    t -= 3;
    const std::uint32_t a = tris[t], b = tris[t + 1], c = tris[t + 2];
    fans[--offset[c + 1]] = {a, b};
    fans[--offset[b + 1]] = {c, a};
    fans[--offset[a + 1]] = {b, c};
  }
  for (std::size_t i = 0; i < nv; ++i) offset[i] = offset[i + 1];
  offset[nv] = static_cast<std::uint32_t>(tris.size());
}

// Triangle (p, b, c) is degenerate when its smallest angle (between the two longest edges) has
// sin^2 <= 1e-10, which is stricter than check_mesh's 1e-12 whichever corner it measures from.
// n = cross(b - p, c - p).
inline bool degenerate_triangle(const glm::dvec3& p, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& n) {
  const glm::dvec3 e1 = b - p, e2 = c - p, e3 = c - b;
  const double d1 = glm::dot(e1, e1), d2 = glm::dot(e2, e2), d3 = glm::dot(e3, e3);
  return glm::dot(n, n) <= 1e-10 * std::max({d1 * d2, d1 * d3, d2 * d3});
}

// A new triangle with normal n faces the original surface whose summed corner normals are `ref`,
// with a margin covering the float rounding of the normals.
inline bool faces_surface(const glm::dvec3& n, const glm::dvec3& ref) {
  const double f = glm::dot(n, ref);
  return f > 0.0 && f * f > 1e-12 * glm::dot(n, n) * glm::dot(ref, ref);
}

// Squared distance from p to triangle (a, b, c): closest point by Voronoi regions (Ericson,
// Real-Time Collision Detection §5.1.5).
inline double point_triangle_dist2(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return glm::dot(ap, ap);
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return glm::dot(bp, bp);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const glm::dvec3 q = a + ab * (d1 / (d1 - d3));
    return glm::dot(p - q, p - q);
  }
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return glm::dot(cp, cp);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const glm::dvec3 q = a + ac * (d2 / (d2 - d6));
    return glm::dot(p - q, p - q);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const glm::dvec3 q = b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    return glm::dot(p - q, p - q);
  }
  const double denom = 1.0 / (va + vb + vc);
  const glm::dvec3 q = a + ab * (vb * denom) + ac * (vc * denom);
  return glm::dot(p - q, p - q);
}

}  // namespace sylva::terrain::detail

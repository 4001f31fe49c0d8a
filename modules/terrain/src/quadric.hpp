#pragma once
// Garland–Heckbert error quadric shared by the two QEM reducers (simplify_qem.cpp,
// simplify_qem_passes.cpp): the sum of squared distances to a set of weighted planes.

#include <glm/glm.hpp>

#include <array>
#include <cstddef>

namespace sylva::terrain::detail {

struct Quadric {
  // Symmetric 4x4: a00 a01 a02 a03 a11 a12 a13 a22 a23 a33.
  std::array<double, 10> m{};

  // Adds w * (n·p + d)² for the plane n·p + d = 0 (n unit).
  void add_plane(const glm::dvec3& n, double d, double w) {
    const double a = n.x, b = n.y, c = n.z;
    m[0] += w * a * a; m[1] += w * a * b; m[2] += w * a * c; m[3] += w * a * d;
    m[4] += w * b * b; m[5] += w * b * c; m[6] += w * b * d;
    m[7] += w * c * c; m[8] += w * c * d; m[9] += w * d * d;
  }
  void operator+=(const Quadric& o) {
    for (std::size_t i = 0; i < 10; ++i) m[i] += o.m[i];
  }
  double error(const glm::dvec3& p) const { return evaluate(m, p); }
  // (this + o) evaluated at p, without forming the sum.
  double error_sum(const Quadric& o, const glm::dvec3& p) const {
    std::array<double, 10> s;
    for (std::size_t i = 0; i < 10; ++i) s[i] = m[i] + o.m[i];
    return evaluate(s, p);
  }

 private:
  static double evaluate(const std::array<double, 10>& s, const glm::dvec3& p) {
    const double x = p.x, y = p.y, z = p.z;
    return s[0] * x * x + 2 * s[1] * x * y + 2 * s[2] * x * z + 2 * s[3] * x + s[4] * y * y + 2 * s[5] * y * z +
           2 * s[6] * y + s[7] * z * z + 2 * s[8] * z + s[9];
  }
};

}  // namespace sylva::terrain::detail

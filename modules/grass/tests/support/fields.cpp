#include "support/fields.hpp"

#include <cmath>
#include <numbers>

namespace sylva::grass::testing {

Image make_density_image(int w, int h) {
  Image img(w, h, 1);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const double x = (i + 0.5) / w, z = (j + 0.5) / h;
      double d = 0.25 + 0.5 * x;                                   // gradient
      const double r = std::hypot(x - 0.65, z - 0.35);
      if (r < 0.2) d = 1.0;                                        // dense disc
      if (z > 0.8 && z < 0.9) d = 0.0;                             // empty strip
      img.at(i, j) = static_cast<float>(d);
    }
  }
  return img;
}

HeightField make_ground(double lo, double hi) {
  const int n = static_cast<int>(hi - lo) + 1;
  HeightField field(n, n, 1.0, {lo, lo});
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double x = lo + i, z = lo + j;
      field.sample(i, j) = static_cast<float>(0.6 * std::sin(0.11 * x) + 0.4 * std::cos(0.07 * z + 0.3 * std::sin(0.05 * x)));
    }
  }
  field.update_range();
  return field;
}

double SphereMesh::area() const {
  double a = 0.0;
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const glm::dvec3 p0(positions[indices[t]]), p1(positions[indices[t + 1]]), p2(positions[indices[t + 2]]);
    a += 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
  }
  return a;
}

SphereMesh make_sphere(float radius, int rings, int segments, const glm::vec3& center) {
  SphereMesh m;
  for (int r = 0; r <= rings; ++r) {
    const float theta = std::numbers::pi_v<float> * static_cast<float>(r) / static_cast<float>(rings);
    for (int s = 0; s <= segments; ++s) {
      const float phi = 2.0f * std::numbers::pi_v<float> * static_cast<float>(s) / static_cast<float>(segments);
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      m.positions.push_back(center + radius * n);
      m.normals.push_back(n);
    }
  }
  const auto idx = [&](int r, int s) { return static_cast<std::uint32_t>(r * (segments + 1) + s); };
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      // Counter-clockwise seen from outside, so face normals point outwards.
      if (r > 0) {
        m.indices.insert(m.indices.end(), {idx(r, s), idx(r, s + 1), idx(r + 1, s)});
      }
      if (r < rings - 1) {
        m.indices.insert(m.indices.end(), {idx(r, s + 1), idx(r + 1, s + 1), idx(r + 1, s)});
      }
    }
  }
  return m;
}

}  // namespace sylva::grass::testing

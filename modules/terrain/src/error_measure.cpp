#include <sylva/terrain/error_measure.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva::terrain {
namespace {
template <class Fn>
void rasterise(const HeightField& field, const VertexFrame& frame, const FrameMesh& mesh, bool bodies_only, Fn&& fn) {
  const double sp = frame.spacing;
  for (std::size_t t = 0; t < mesh.triangles(); ++t) {
    if (mesh.kind[t] == PieceKind::kSkirt) continue;
    if (bodies_only && mesh.kind[t] != PieceKind::kBody) continue;
    glm::dvec2 g[3];
    double y[3];
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 p = mesh.positions[3 * t + static_cast<std::size_t>(k)];
      g[k] = glm::dvec2((static_cast<double>(p.x) + frame.camera.x) / sp + frame.origin.x,
                        (static_cast<double>(p.z) + frame.camera.z) / sp + frame.origin.y);
      y[k] = static_cast<double>(p.y) + frame.camera.y;
    }
    const double det = (g[1].y - g[0].y) * (g[2].x - g[0].x) - (g[1].x - g[0].x) * (g[2].y - g[0].y);
    if (std::fabs(det) < 1e-9) continue;  // vertical seam triangle: no area in x/z
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({g[0].x, g[1].x, g[2].x}) - 1e-6)));
    const int x1 = std::min(field.columns() - 1, static_cast<int>(std::ceil(std::max({g[0].x, g[1].x, g[2].x}) + 1e-6)));
    const int z0 = std::max(0, static_cast<int>(std::floor(std::min({g[0].y, g[1].y, g[2].y}) - 1e-6)));
    const int z1 = std::min(field.rows() - 1, static_cast<int>(std::ceil(std::max({g[0].y, g[1].y, g[2].y}) + 1e-6)));
    for (int z = z0; z <= z1; ++z) {
      for (int x = x0; x <= x1; ++x) {
        const double w0 = ((g[1].y - z) * (g[2].x - x) - (g[1].x - x) * (g[2].y - z)) / det;
        const double w1 = ((z - g[0].y) * (g[2].x - g[0].x) - (x - g[0].x) * (g[2].y - g[0].y)) / det;
        const double w2 = 1.0 - w0 - w1;
        if (w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9) continue;
        fn(x, z, w0 * y[0] + w1 * y[1] + w2 * y[2]);
      }
    }
  }
}
}  // namespace

ProjectedError measure_projected_error(const HeightField& field, const VertexFrame& frame, const FrameMesh& mesh,
                                       double k) {
  ProjectedError r;
  const double sp = frame.spacing;
  rasterise(field, frame, mesh, false, [&](int x, int z, double y) {
    const double h = field.sample(x, z);
    const double dx = (x - frame.origin.x) * sp - frame.camera.x;
    const double dz = (z - frame.origin.y) * sp - frame.camera.z;
    const double dy = y - frame.camera.y;
    const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
    const double err = std::fabs(y - h);
    const double px = d > 0.0 ? k * err / d : (err > 0.0 ? 1e30 : 0.0);
    ++r.samples;
    r.max_m = std::max(r.max_m, err);
    if (px > r.max_px) {
      r.max_px = px;
      r.worst = {x, z};
    }
  });
  return r;
}

std::vector<float> drawn_heights(const HeightField& field, const VertexFrame& frame, const FrameMesh& mesh) {
  std::vector<float> out(static_cast<std::size_t>(field.columns()) * static_cast<std::size_t>(field.rows()),
                         std::numeric_limits<float>::quiet_NaN());
  rasterise(field, frame, mesh, true, [&](int x, int z, double y) {
    out[static_cast<std::size_t>(z) * static_cast<std::size_t>(field.columns()) + static_cast<std::size_t>(x)] =
        static_cast<float>(y);
  });
  return out;
}

}  // namespace sylva::terrain

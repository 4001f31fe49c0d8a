#include <sylva/terrain/vertex_position.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::terrain {

VertexFrame make_vertex_frame(const ChunkTree& tree, const LodView& view, const LodSettings& settings) {
  VertexFrame f;
  const double spacing = tree.spacing();
  const glm::dvec2 rel = (glm::dvec2(view.position.x, view.position.z) - tree.origin()) / spacing;
  // Clamp the origin to a range where (grid point - origin) stays an exact float integer.
  const double limit = 4.0e6;
  f.origin = glm::ivec2(static_cast<int>(std::clamp(std::floor(rel.x), -limit, limit)),
                        static_cast<int>(std::clamp(std::floor(rel.y), -limit, limit)));
  const glm::dvec2 origin_world = tree.origin() + glm::dvec2(f.origin) * spacing;
  f.camera = glm::vec3(static_cast<float>(view.position.x - origin_world.x), static_cast<float>(view.position.y),
                       static_cast<float>(view.position.z - origin_world.y));
  f.spacing = static_cast<float>(spacing);
  f.morph = settings.criterion == LodCriterion::kScreenSpaceError && settings.morph_fraction > 0.0f;
  f.k_over_tau = static_cast<float>(view.k / static_cast<double>(settings.max_pixel_error));
  f.morph_start = 1.0f - settings.morph_fraction;
  return f;
}

namespace {
// Kept in one place so morph_weight and vertex_position cannot drift apart.
inline float weight(const VertexFrame& f, float rx, float ry, float rz, const ChunkVertex& v) {
  if (!f.morph) return 0.0f;
  // Distance to the nearest point of the vertical segment between the field (h) and the morph
  // target (G): a lower bound for the drawn point, wherever the morph has moved it.
  const float d = std::sqrt(rx * rx + ry * ry + rz * rz) - std::fabs(v.morph_target - v.height);
  const float morph_error = v.morph_error;
  const float m1 = f.k_over_tau * morph_error;
  const float m0 = f.morph_start * m1;
  if (d >= m1) return 1.0f;
  if (d <= m0) return 0.0f;
  return (d - m0) / (m1 - m0);
}
// + 0.5 for an hq2 leaf centre; + 0.0 leaves every other point's float unchanged (bit for bit).
inline float rel_x(const VertexFrame& f, const ChunkVertex& v) {
  const float half = 0.5f * static_cast<float>(v.centre);
  return (static_cast<float>(static_cast<std::int32_t>(v.gx) - f.origin.x) + half) * f.spacing - f.camera.x;
}
inline float rel_z(const VertexFrame& f, const ChunkVertex& v) {
  const float half = 0.5f * static_cast<float>(v.centre);
  return (static_cast<float>(static_cast<std::int32_t>(v.gz) - f.origin.y) + half) * f.spacing - f.camera.z;
}
}  // namespace

float morph_weight(const VertexFrame& f, const ChunkVertex& v) {
  return weight(f, rel_x(f, v), v.height - f.camera.y, rel_z(f, v), v);
}

glm::vec3 vertex_position(const VertexFrame& f, const ChunkVertex& v) {
  const float rx = rel_x(f, v);
  const float rz = rel_z(f, v);
  const float mu = weight(f, rx, v.height - f.camera.y, rz, v);
  const float y = v.height + (v.morph_target - v.height) * mu;
  return {rx, y - f.camera.y, rz};
}

}  // namespace sylva::terrain

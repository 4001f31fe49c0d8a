#include <sylva/terrain/lod_view.hpp>

#include <sylva/core/assert.hpp>

#include <cmath>
#include <limits>

namespace sylva::terrain {

LodView LodView::perspective(const glm::dvec3& position, const glm::dvec3& forward, const glm::dvec3& up,
                             double fov_y, int viewport_width, int viewport_height, double near_m, double far_m) {
  SYLVA_ASSERT(fov_y > 0.0 && fov_y < 3.14159265358979, "fov_y={} rad", fov_y);
  SYLVA_ASSERT(viewport_width > 0 && viewport_height > 0, "viewport {}x{}", viewport_width, viewport_height);
  SYLVA_ASSERT(near_m > 0.0 && far_m > near_m, "near={} far={}", near_m, far_m);
  const glm::dvec3 f = glm::normalize(forward);
  glm::dvec3 r = glm::cross(f, up);
  if (glm::dot(r, r) < 1e-24) r = glm::cross(f, std::fabs(f.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0));
  r = glm::normalize(r);
  const glm::dvec3 u = glm::cross(r, f);
  const double tan_y = std::tan(fov_y * 0.5);
  const double tan_x = tan_y * static_cast<double>(viewport_width) / static_cast<double>(viewport_height);

  LodView v;
  v.position = position;
  v.viewport_width = viewport_width;
  v.viewport_height = viewport_height;
  v.k = static_cast<double>(viewport_height) / (2.0 * tan_y);
  auto plane_through_eye = [&](glm::dvec3 n) {
    n = glm::normalize(n);
    return glm::dvec4(n, -glm::dot(n, position));
  };
  v.planes[0] = plane_through_eye(r + tan_x * f);
  v.planes[1] = plane_through_eye(-r + tan_x * f);
  v.planes[2] = plane_through_eye(u + tan_y * f);
  v.planes[3] = plane_through_eye(-u + tan_y * f);
  v.planes[4] = glm::dvec4(f, -glm::dot(f, position) - near_m);
  v.has_far_plane = std::isfinite(far_m);
  v.planes[5] = v.has_far_plane ? glm::dvec4(-f, glm::dot(f, position) + far_m) : glm::dvec4(0, 0, 0, 1);
  return v;
}

bool LodView::box_visible(const glm::dvec3& lo, const glm::dvec3& hi) const {
  for (int i = 0; i < 6; ++i) {
    const glm::dvec4& p = planes[static_cast<std::size_t>(i)];
    const glm::dvec3 corner(p.x >= 0 ? hi.x : lo.x, p.y >= 0 ? hi.y : lo.y, p.z >= 0 ? hi.z : lo.z);
    if (p.x * corner.x + p.y * corner.y + p.z * corner.z + p.w < 0.0) return false;
  }
  return true;
}

bool LodView::box_visible(const glm::dvec3& lo, const glm::dvec3& hi, std::uint8_t& mask) const {
  for (int i = 0; i < 6; ++i) {
    if ((mask & (1u << i)) == 0) continue;
    const glm::dvec4& p = planes[static_cast<std::size_t>(i)];
    const double far_d = p.x * (p.x >= 0 ? hi.x : lo.x) + p.y * (p.y >= 0 ? hi.y : lo.y) + p.z * (p.z >= 0 ? hi.z : lo.z) + p.w;
    if (far_d < 0.0) return false;
    const double near_d = p.x * (p.x >= 0 ? lo.x : hi.x) + p.y * (p.y >= 0 ? lo.y : hi.y) + p.z * (p.z >= 0 ? lo.z : hi.z) + p.w;
    if (near_d >= 0.0) mask = static_cast<std::uint8_t>(mask & ~(1u << i));  // wholly inside this plane
  }
  return true;
}

double LodView::distance_to_box(const glm::dvec3& lo, const glm::dvec3& hi) const {
  const glm::dvec3 nearest = glm::clamp(position, lo, hi);
  return glm::length(position - nearest);
}

}  // namespace sylva::terrain

#pragma once
// What the LOD selection needs to know about the camera, in double precision world space (x/z
// ground, y up, metres). GL-free, so selection and its tests need no context; the renderer
// builds one from render::Camera.

#include <glm/glm.hpp>

#include <array>
#include <cstdint>

namespace sylva::terrain {

struct LodView {
  glm::dvec3 position{0.0};
  // World-space frustum planes (xyz = normal, w = offset); a point p is inside when
  // dot(normal, p) + w >= 0 for all six. Order: left, right, bottom, top, near, far.
  std::array<glm::dvec4, 6> planes{};
  bool has_far_plane = true;
  // K of Ulrich 2002: pixels covered by one metre seen face-on at one metre,
  // viewport_width / (2 tan(fov_x / 2)) (= viewport_height / (2 tan(fov_y / 2)) for square pixels).
  double k = 1.0;
  int viewport_width = 1;
  int viewport_height = 1;

  // A perspective view. forward and up need not be unit or orthogonal (up is made orthogonal),
  // fov_y in radians in (0, pi), near > 0, far > near or +infinity. Asserts on invalid input.
  static LodView perspective(const glm::dvec3& position, const glm::dvec3& forward, const glm::dvec3& up,
                             double fov_y, int viewport_width, int viewport_height, double near_m, double far_m);

  // Whether an axis-aligned box may be visible (conservative: true when in doubt).
  bool box_visible(const glm::dvec3& lo, const glm::dvec3& hi) const;
  // The same test for hierarchies: `mask` (bit i = plane i still to test) is narrowed to the
  // planes the box straddles, so children of a box wholly inside a plane skip that plane.
  // Returns false when the box is outside.
  bool box_visible(const glm::dvec3& lo, const glm::dvec3& hi, std::uint8_t& mask) const;
  // Distance from the camera to the nearest point of the box (0 inside).
  double distance_to_box(const glm::dvec3& lo, const glm::dvec3& hi) const;
};

}  // namespace sylva::terrain

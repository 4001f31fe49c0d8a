#pragma once
// View-frustum planes and CPU culling of boxes and spheres. GL-free (unit-testable).
//
// Large worlds: planes live in camera-relative space (origin = camera position, in double), so
// a box 1e7 m from the world origin is tested with its offset from the camera, computed in
// double, and no precision is lost to the absolute coordinates (DESIGN.md §2 "Large
// coordinates"). Planes are extracted from a clip matrix (Gribb & Hartmann) for GL's
// zero-to-one depth range; a degenerate far plane (infinite reversed-Z projection) is
// replaced by one that accepts everything.

#include <glm/glm.hpp>

#include <array>
#include <span>

namespace sylva::render {

struct Aabb {
  glm::dvec3 min{0.0};  // world metres, min <= max per axis
  glm::dvec3 max{0.0};
  glm::dvec3 center() const { return (min + max) * 0.5; }
  glm::dvec3 half_extent() const { return (max - min) * 0.5; }
};

struct Sphere {
  glm::dvec3 center{0.0};  // world metres
  double radius = 0.0;     // >= 0
};

enum class Containment { kOutside, kIntersecting, kInside };

class Frustum {
 public:
  enum PlaneIndex { kLeft = 0, kRight, kBottom, kTop, kNear, kFar, kPlaneCount };

  Frustum() = default;

  // From a camera-relative clip matrix (projection * view-without-translation) and the camera's
  // world position. Planes point inward and are normalised.
  static Frustum from_matrix(const glm::mat4& relative_clip, const glm::dvec3& origin);

  const glm::dvec3& origin() const { return origin_; }
  // (normal.xyz, d) with dot(normal, p_relative) + d >= 0 inside.
  const std::array<glm::vec4, kPlaneCount>& planes() const { return planes_; }

  // World-space tests (subtract the origin in double first).
  Containment classify(const Aabb& box) const;
  bool intersects(const Aabb& box) const { return classify(box) != Containment::kOutside; }
  Containment classify(const Sphere& sphere) const;
  bool intersects(const Sphere& sphere) const { return classify(sphere) != Containment::kOutside; }

  // Camera-relative tests (centre relative to origin(), half extent >= 0).
  bool intersects_relative(const glm::vec3& center, const glm::vec3& half_extent) const;
  bool intersects_relative_sphere(const glm::vec3& center, float radius) const;

  // Culls many boxes: visible[i] = intersects(boxes[i]). Returns the visible count.
  // visible.size() must equal boxes.size() (asserted).
  std::size_t cull(std::span<const Aabb> boxes, std::span<unsigned char> visible) const;

 private:
  glm::dvec3 origin_{0.0};
  std::array<glm::vec4, kPlaneCount> planes_{};
};

}  // namespace sylva::render

// Gribb-Hartmann plane extraction and box/sphere tests (frustum.hpp).
#include <sylva/render/frustum.hpp>

#include <sylva/core/assert.hpp>

#include <cmath>

namespace sylva::render {
namespace {

glm::vec4 normalise_plane(const glm::dvec4& p) {
  const double len = glm::length(glm::dvec3(p));
  // A plane with no normal (the far plane of an infinite projection) accepts every point.
  if (!(len > 1.0e-12)) return {0.0f, 0.0f, 0.0f, 1.0f};
  return glm::vec4(p / len);
}

}  // namespace

Frustum Frustum::from_matrix(const glm::mat4& relative_clip, const glm::dvec3& origin) {
  const glm::dmat4 m(relative_clip);
  auto row = [&](int i) { return glm::dvec4(m[0][i], m[1][i], m[2][i], m[3][i]); };
  const glm::dvec4 r0 = row(0), r1 = row(1), r2 = row(2), r3 = row(3);
  Frustum f;
  f.origin_ = origin;
  // Clip volume for GL_ZERO_TO_ONE: -w <= x, y <= w and 0 <= z <= w. With reversed-Z, z = w
  // is the near plane and z = 0 the far plane.
  f.planes_[kLeft] = normalise_plane(r3 + r0);
  f.planes_[kRight] = normalise_plane(r3 - r0);
  f.planes_[kBottom] = normalise_plane(r3 + r1);
  f.planes_[kTop] = normalise_plane(r3 - r1);
  f.planes_[kNear] = normalise_plane(r3 - r2);
  f.planes_[kFar] = normalise_plane(r2);
  return f;
}

bool Frustum::intersects_relative(const glm::vec3& c, const glm::vec3& e) const {
  for (const glm::vec4& p : planes_) {
    const float dist = p.x * c.x + p.y * c.y + p.z * c.z + p.w;
    const float radius = std::abs(p.x) * e.x + std::abs(p.y) * e.y + std::abs(p.z) * e.z;
    if (dist < -radius) return false;
  }
  return true;
}

bool Frustum::intersects_relative_sphere(const glm::vec3& c, float radius) const {
  for (const glm::vec4& p : planes_) {
    if (p.x * c.x + p.y * c.y + p.z * c.z + p.w < -radius) return false;
  }
  return true;
}

Containment Frustum::classify(const Aabb& box) const {
  const glm::vec3 c(box.center() - origin_);
  const glm::vec3 e(box.half_extent());
  Containment result = Containment::kInside;
  for (const glm::vec4& p : planes_) {
    const float dist = glm::dot(glm::vec3(p), c) + p.w;
    const float radius = glm::dot(glm::abs(glm::vec3(p)), e);
    if (dist < -radius) return Containment::kOutside;
    if (dist < radius) result = Containment::kIntersecting;
  }
  return result;
}

Containment Frustum::classify(const Sphere& sphere) const {
  const glm::vec3 c(sphere.center - origin_);
  const float r = static_cast<float>(sphere.radius);
  Containment result = Containment::kInside;
  for (const glm::vec4& p : planes_) {
    const float dist = glm::dot(glm::vec3(p), c) + p.w;
    if (dist < -r) return Containment::kOutside;
    if (dist < r) result = Containment::kIntersecting;
  }
  return result;
}

std::size_t Frustum::cull(std::span<const Aabb> boxes, std::span<unsigned char> visible) const {
  SYLVA_ASSERT(boxes.size() == visible.size(), "boxes={} visible={}", boxes.size(), visible.size());
  std::size_t count = 0;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const Aabb& b = boxes[i];
    const glm::vec3 c((b.min + b.max) * 0.5 - origin_);
    const glm::vec3 e((b.max - b.min) * 0.5);
    const bool v = intersects_relative(c, e);
    visible[i] = v ? 1 : 0;
    count += v ? 1 : 0;
  }
  return count;
}

}  // namespace sylva::render

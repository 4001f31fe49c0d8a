#include <sylva/grass/blade.hpp>

#include <algorithm>
#include <cstdint>
#include <cmath>

namespace sylva::grass {

void tangent_frame(const glm::vec3& up, glm::vec3& t1, glm::vec3& t2) {
  // Duff et al., "Building an Orthonormal Basis, Revisited" (JCGT 2017), rotated so that for
  // up = +y the frame is (+x, -z): orientation 0 points along +x on a height field.
  const glm::vec3 n(up.x, up.z, up.y);  // treat y as the "z" axis of the paper's frame
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  const glm::vec3 b1(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const glm::vec3 b2(b, sign + n.y * n.y * a, -n.y);
  // Back to y-up coordinates.
  t1 = glm::vec3(b1.x, b1.z, b1.y);
  t2 = -glm::vec3(b2.x, b2.z, b2.y);
}

glm::vec3 blade_width_dir(const glm::vec3& up, float orientation) {
  glm::vec3 t1, t2;
  tangent_frame(up, t1, t2);
  return std::cos(orientation) * t1 + std::sin(orientation) * t2;
}

glm::vec3 blade_front_dir(const glm::vec3& up, float orientation) {
  return glm::normalize(glm::cross(blade_width_dir(up, orientation), up));
}

glm::vec3 bezier_point(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, float t) {
  const glm::vec3 a = p0 + t * (p1 - p0);
  const glm::vec3 b = p1 + t * (p2 - p1);
  return a + t * (b - a);
}

float bezier_length(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) {
  // B'(t) = 2 (A + t B) with A = p1 - p0, B = p2 - 2 p1 + p0, so the length is
  // 2 int_0^1 sqrt(a t^2 + 2 b t + c) dt with a = B.B, b = A.B, c = A.A. Substituting u = t + b/a
  // gives 2 sqrt(a) [F(u1) - F(u0)], F(u) = (u s + k ln(u + s)) / 2, s = sqrt(u^2 + k). Written to
  // avoid cancellation (shaders/physics.comp evaluates the same expressions in float):
  //  - k = (ac - b^2) / a^2 = |A x B|^2 / a^2 (Lagrange's identity) instead of a difference;
  //  - ln(u + s) = ln(k) - ln(s - u) for u < 0, where u + s would cancel.
  const glm::dvec3 A = glm::dvec3(p1) - glm::dvec3(p0);
  const glm::dvec3 B = glm::dvec3(p2) - 2.0 * glm::dvec3(p1) + glm::dvec3(p0);
  const double a = glm::dot(B, B);
  const double c = glm::dot(A, A);
  const double chord = glm::length(glm::dvec3(p2) - glm::dvec3(p0));
  if (!(a > 1e-12 * c) || a <= 0.0) return static_cast<float>(chord);  // (nearly) uniform speed: a straight line
  const double b = glm::dot(A, B);
  const double k = glm::dot(glm::cross(A, B), glm::cross(A, B)) / (a * a);
  const double u0 = b / a;
  const double u1 = 1.0 + b / a;
  double integral;
  if (k <= 1e-14 * std::max({1.0, u0 * u0, u1 * u1})) {
    // Collinear control points: |A + tB| = sqrt(a) |u|.
    integral = 0.5 * (u1 * std::abs(u1) - u0 * std::abs(u0));
  } else {
    const double s0 = std::sqrt(u0 * u0 + k), s1 = std::sqrt(u1 * u1 + k);
    const auto log_us = [k](double u, double s) { return u >= 0.0 ? std::log(u + s) : std::log(k) - std::log(s - u); };
    integral = 0.5 * ((u1 * s1 - u0 * s0) + k * (log_us(u1, s1) - log_us(u0, s0)));
  }
  const double length = 2.0 * std::sqrt(a) * integral;
  return static_cast<float>(std::isfinite(length) ? std::max(length, chord) : chord);
}

ControlJitter control_jitter_randoms(float shape_random) {
  const float s = shape_random - std::floor(shape_random);
  const float low = 4096.0f * s;  // exact: a power-of-two scale
  ControlJitter j;
  j.r3 = 0.25f * (2.0f * s - 1.0f);
  j.r4 = 0.75f + 0.5f * (low - std::floor(low));
  return j;
}

glm::vec3 jitter_control_point(const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2, const glm::vec3& up,
                               const ControlJitter& jitter) {
  // Seed 001 eq. 2.4 on Sylva's control point (blade.hpp).
  const glm::vec3 d = v2 - v0;
  const glm::vec3 side = d - up * glm::dot(d, up);
  return v1 + up * ((jitter.r4 - 1.0f) * glm::dot(v1 - v0, up)) + jitter.r3 * side;
}

glm::vec3 drawn_control(const Blade& blade) {
  if (!has_control_jitter(blade)) return blade.control();
  return jitter_control_point(blade.root(), blade.control(), blade.tip(), blade.up_dir(), control_jitter_randoms(blade.attr.w));
}

float pack_color(const glm::vec3& rgb) {
  // 8 bits per channel in a 24-bit integer stored as an exact float value (never NaN or a
  // denormal, so no driver or CPU path can flush or canonicalise it).
  const glm::vec3 c = glm::clamp(rgb, 0.0f, 1.0f);
  const auto q = [](float v) { return static_cast<std::uint32_t>(std::lround(v * 255.0f)); };
  return static_cast<float>(q(c.r) | (q(c.g) << 8u) | (q(c.b) << 16u));
}

glm::vec3 unpack_color(float packed) {
  const auto bits = static_cast<std::uint32_t>(std::clamp(packed, 0.0f, 16777215.0f));
  return glm::vec3(static_cast<float>(bits & 255u), static_cast<float>((bits >> 8u) & 255u),
                   static_cast<float>((bits >> 16u) & 255u)) / 255.0f;
}

}  // namespace sylva::grass

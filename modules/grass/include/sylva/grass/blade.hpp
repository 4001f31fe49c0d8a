#pragma once
// One grass blade: a quadratic Bezier curve v0 (root) - v1 (control) - v2 (tip), after Jahrmann
// & Wimmer 2017 §3, plus the per-blade randoms of seed 001 §3.5. The same layout is the GPU
// storage buffer element (std430, 6 x vec4 = 96 bytes; shaders/blade.glsl mirrors it), so the
// CPU reference and the compute shaders operate on identical data.
//
// Positions are in metres relative to the owning BladeSet's origin (a double-precision world
// position), so float precision is kept however far the field is from the world origin.

#include <glm/glm.hpp>

#include <cstdint>

namespace sylva::grass {

struct Blade {
  glm::vec4 v0;    // xyz root;          w orientation about `up` [rad], in [0, 2pi)
  glm::vec4 v1;    // xyz control point; w height (Bezier arc length kept by physics) [m]
  glm::vec4 v2;    // xyz tip;           w width at the root [m]
  glm::vec4 up;    // xyz unit up;       w stiffness (recovery rate) [1/s]
  glm::vec4 rest;  // xyz rest tip minus root (|rest| = height); w collision strength eta in [0, 1]
  glm::vec4 attr;  // x rank in its tile [0, 1) (thinning order), y colour variation seed [0, 1),
                   // z colour, 8-bit RGB packed into an exact float integer, w shape random [0, 1)

  glm::vec3 root() const { return glm::vec3(v0); }
  glm::vec3 control() const { return glm::vec3(v1); }
  glm::vec3 tip() const { return glm::vec3(v2); }
  glm::vec3 up_dir() const { return glm::vec3(up); }
  float orientation() const { return v0.w; }
  float height() const { return v1.w; }
  float width() const { return v2.w; }
  float stiffness() const { return up.w; }
  float collision() const { return rest.w; }
  float rank() const { return attr.x; }
};
static_assert(sizeof(Blade) == 96, "Blade must match the std430 layout in shaders/blade.glsl");

// Unit vector across the blade (the "bitangent" of seed 001 eq. 2.6) for an orientation angle
// about `up`: cos(theta) * t1 + sin(theta) * t2 with (t1, t2, up) the frame of tangent_frame().
glm::vec3 blade_width_dir(const glm::vec3& up, float orientation);

// A deterministic orthonormal tangent pair (t1, t2) for a unit `up` (Frisvad-style branchless
// frame by Duff et al. 2017). For up = +y it returns t1 = +x, t2 = -z, so orientation 0 is +x.
void tangent_frame(const glm::vec3& up, glm::vec3& t1, glm::vec3& t2);

// Front direction (normal of the blade plane), towards which front gravity pulls:
// normalize(cross(width_dir, up)).
glm::vec3 blade_front_dir(const glm::vec3& up, float orientation);

// Arc length of the quadratic Bezier p0-p1-p2 in closed form (exact up to rounding; falls back to
// the chord for collinear control points).
float bezier_length(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2);

// Point and unit tangent of the blade's centre curve at t in [0, 1] (De Casteljau, seed 001 eq. 2.5).
glm::vec3 bezier_point(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, float t);

// 8-bit RGB packed as r | g << 8 | b << 16 in an exactly representable float (Blade::attr.z);
// shaders/blade.glsl unpacks it the same way.
float pack_color(const glm::vec3& rgb);
glm::vec3 unpack_color(float packed);

}  // namespace sylva::grass

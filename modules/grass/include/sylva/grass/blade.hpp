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
                   // z colour, 8-bit RGB packed into an exact float integer, w shape random [0, 1),
                   // plus 1 when the drawn control point is jittered (see drawn_control)

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

// Seed 001 eq. 2.4 control-point jitter (grass.blade.control_jitter). The seed computes the
// extra control point per side as h = (t_x r3 + b_x (1 - r3), t_y r4 + b_y (1 - r4),
// t_z r3 + b_z (1 - r3)) with t the tip and b the root (the thesis's code order, see the seed's
// geometry warning in §2.6), r3 in [-0.25, 0.25], r4 in [0.75, 1.25] (§3.5 table): r4 scales the
// control point's height above the root and r3 moves it by a share of the tip's sideways offset.
// Sylva's control point is the physics' (v1, on the root's up axis, below the tip the more the
// blade leans), so the jitter is applied to it where the blade is drawn, on every pose:
//   drawn = v1 + up ((r4 - 1) dot(v1 - v0, up)) + r3 (d - up dot(d, up)),  d = v2 - v0,
// which is exactly the seed's h for an upright unbent control point (v1 = v0 + up height).
// The record is unchanged (physics, invariants); only the drawn curve (TCS, cull hull, tile
// bounds) follows it. A blade is jittered when its attr.w >= 1 (the generator stores the shape
// random s as 1 + s then); r3 and r4 come from s alone, so they are fixed per blade.
struct ControlJitter {
  float r3 = 0.0f;  // [-0.25, 0.25): sideways, share of the tip's offset across up
  float r4 = 1.0f;  // [0.75, 1.25): height factor
};
// r3 = 0.25 (2 s - 1) from the high bits of s, r4 = 0.75 + 0.5 fract(4096 s) from its low bits
// (exact in float on the CPU and the GPU; shaders/blade.glsl grass_control_jitter).
ControlJitter control_jitter_randoms(float shape_random);
inline bool has_control_jitter(const Blade& blade) { return blade.attr.w >= 1.0f; }
glm::vec3 jitter_control_point(const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2, const glm::vec3& up,
                               const ControlJitter& jitter);
// The control point the blade is drawn with: control() when not jittered (bit for bit).
glm::vec3 drawn_control(const Blade& blade);
// Half the side of a root-centred cube holding every drawn pose, per metre of height: 1 without
// jitter (arc length = height), sqrt(1.25^2 + 0.25^2) < 1.3 with it.
inline float drawn_reach(const Blade& blade) { return has_control_jitter(blade) ? 1.3f : 1.0f; }

// 8-bit RGB packed as r | g << 8 | b << 16 in an exactly representable float (Blade::attr.z);
// shaders/blade.glsl unpacks it the same way.
float pack_color(const glm::vec3& rgb);
glm::vec3 unpack_color(float packed);

}  // namespace sylva::grass

#pragma once
// Branch bending of seed 000 §3.1.1: the Euler-Bernoulli cantilever shape of a tapered cone,
// replaced by the fitted polynomial u(x) = c2 x^2 + c4 x^4 (eq. 3.8), and the approximate length
// correction of eq. 3.9. GL-free; shaders/lib/tree_animation.glsl repeats bend_profile() operation
// for operation.
//
// Shape. For a cone of taper alpha = r_tip / r_base under a uniform load the deflection satisfies
//   ((alpha - 1) x + 1)^4 u''(x) = (2 / pi) (1 - x)^2,   u(0) = u'(0) = 0
// which is the closed form of eq. 3.7 with the prefactor dropped (the extraction checked it with
// sympy; its second derivative gives the load 4/pi). We integrate this ODE numerically instead of
// evaluating eq. 3.7, which divides by (alpha - 1)^4 and is singular for a uniform branch. The
// least-squares fit on 401 uniform samples reproduces the seed's constants for alpha = 0.2
// (0.374570 / 0.129428) to 0.2 % / 0.8 % and the extraction's table for other tapers (tested).
//
// Length correction (eq. 3.9) in the plane of the bend: for a control amplitude a >= 0 the axis
// point at normalised x moves to (along, across) = (x - d/s, u/s) in units of the branch length, with
//   u = a (c2 x^2 + c4 x^4),  u' = a (2 c2 x + 4 c4 x^3),  s = sqrt(1 + u'^2),  d = u / g (s - 1),
// and g = sign(u') max(|u'|, eps) with sign(0) = +1. This is the guard the seed meant: its
// max(a, eps) + min(a, eps) equals a + eps for every a (errata 11), a bias with a 0/0 at a = -eps.
// (GLSL's sign(0) is 0, which would bring the 0/0 back; the shader uses the same +1 rule.)
// The tangent at x turns by theta with tan(theta) = u' (the seed evaluates u' at x, §4.4 note b).
//
// Bound. The correction over-compensates: with the seed's constants a branch is 0.8 % short at
// a = 0.25 and 8 % short at a = 1 (extraction §8.3). bend_amplitude_limit() finds, per shape, the
// amplitude A_max up to which the corrected branch keeps its length within a bound, and the
// animation saturates every amplitude smoothly below it (saturate_amplitude), so no wind, however
// strong, can stretch or shrink a branch beyond the bound. The seed itself observes that real
// branch amplitudes saturate in strong wind (§3.1.4).

#include <cmath>
#include <cstdint>

namespace sylva::vegetation {

struct BendConstants {
  float c2 = 0.374570f;
  float c4 = 0.129428f;
};

// The seed's constants (taper 0.2, §4.4).
inline constexpr BendConstants kSeedBendConstants{0.374570f, 0.129428f};

// Deflection shape of the ODE above for taper alpha (clamped to [0.02, 4]) at x in [0, 1], by
// numerical integration (double precision, 4000 steps). Exposed for tests.
double cantilever_shape(double alpha, double x);
// The closed form of eq. 3.7 with the prefactor dropped (as printed); singular at alpha = 1.
// Exposed only to test that the numerical shape is the seed's shape.
double cantilever_shape_closed_form(double alpha, double x);

// Least-squares fit of c2 x^2 + c4 x^4 to cantilever_shape(alpha, .) on 401 samples of [0, 1].
BendConstants fit_bend_constants(double alpha);
// The same, cached on alpha quantised to 1/1000 (what the generator and loader use). Thread-safe.
BendConstants bend_constants_for_taper(float alpha);

// Guarded derivative: sign(a) max(|a|, eps), sign(0) = +1.
inline float guard_derivative(float a, float eps) {
  const float m = std::fmax(std::fabs(a), eps);
  return a < 0.0f ? -m : m;
}

// One bent axis point in the bend plane, in units of the branch length.
struct BendPoint {
  float along = 0.0f;      // along the rest axis t
  float across = 0.0f;     // along the bend direction e
  float cos_theta = 1.0f;  // rotation of the frame at this point: tan(theta) = u'(x)
  float sin_theta = 0.0f;
};

// Eq. 3.8 + 3.9 for amplitude a >= 0 (already saturated) at x in [0, 1]. a = 0 returns exactly
// (x, 0, 1, 0): the rest pose is reproduced bit for bit.
inline BendPoint bend_profile(float x, float a, float c2, float c4, float eps) {
  const float x2 = x * x;
  const float u = a * (c2 * x2 + c4 * (x2 * x2));
  const float du = a * (2.0f * c2 * x + 4.0f * c4 * (x2 * x));
  const float g = guard_derivative(du, eps);
  const float s = std::sqrt(1.0f + du * du);
  const float d = u / g * (s - 1.0f);
  const float inv_s = 1.0f / s;
  return {x - d * inv_s, u * inv_s, inv_s, du * inv_s};
}

// Smooth saturation a / sqrt(1 + (a / limit)^2): ~a for a << limit, < limit always, monotonic,
// odd, finite for every a (+-inf give +-limit, NaN gives limit). limit > 0.
// Written in two branches so that q^2 never overflows: for |q| > 1 it is limit q / |q| / sqrt(1 + 1/q^2).
inline float saturate_amplitude(float a, float limit) {
  if (std::isnan(a)) return limit;  // never NaN
  const float q = a / limit;
  if (std::fabs(q) <= 1.0f) return a / std::sqrt(1.0f + q * q);
  const float iq = 1.0f / q;
  return std::copysign(limit, q) / std::sqrt(1.0f + iq * iq);
}

// Arc length (units of the branch length) of the corrected axis for amplitude a, from a polyline
// of `samples` segments (double arithmetic on the float formula).
double corrected_axis_length(float c2, float c4, float a, float eps = 1.0e-6f, int samples = 512);

// Largest amplitude A_max such that |corrected_axis_length(a) - 1| <= max_length_error for every
// a in [0, A_max] (scanned geometrically from 1e-3, refined by bisection to 1e-4 relative).
// Capped at 50 (uniform-ish branches barely change length). max_length_error in (0, 0.5].
float bend_amplitude_limit(float c2, float c4, float max_length_error);
// Cached on (alpha bucket of 1/1000, bound); constants from bend_constants_for_taper.
float bend_amplitude_limit_for_taper(float alpha, float max_length_error);

}  // namespace sylva::vegetation

#pragma once
// CPU reference of the blade physics (Jahrmann & Wimmer 2017 §4), mirrored bit-for-bit in
// structure by shaders/physics.comp (the GL test checks that they agree).
//
// Model (paper §4.1-4.3). The blade is a quadratic Bezier v0-v1-v2; only the tip v2 is
// simulated, v1 follows from it. The paper's model is overdamped: forces are tip velocities,
//     dv2/dt = s_eff (v0 + rest - v2) + F,        F = gravity + front gravity + wind,
// where s_eff = stiffness * max(1 - eta, 0.1) weakens recovery after collisions (eta in [0, 1]).
//
// Integration scheme, and why it is unconditionally stable:
//  1. Exponential (exact) integration of the linear recovery term with F frozen over the step:
//       v2 += (v0 + rest - v2) * a + F * phi,  a = 1 - exp(-s dt) in [0, 1), phi = a / s in [0, dt].
//     For any s >= 0 and dt >= 0 this moves v2 towards the equilibrium v0 + rest + F/s without
//     overshoot: the explicit Euler step of the paper (v2 += (r + F) dt) diverges once
//     s dt > 2, e.g. stiffness 200/s at 60 Hz, and this one cannot. s -> 0 gives phi -> dt
//     (pure drift), s dt -> inf gives the equilibrium. a and phi use expm1 so tiny s dt is exact.
//  2. Constraints by projection, not by forces (paper §4.3 "state validation"): collisions
//     push v2 (and the curve midpoint) out of spheres; v2 is lifted onto the ground plane through
//     v0; v1 is placed above v0 from v2's projected length; then the control polygon is scaled
//     about v0 by height / arclength, using the exact closed-form Bezier arc length instead of
//     the paper's approximation, so the length is preserved to float rounding (not 1 %).
//     Projections are idempotent and bounded, so no force or step size can make them grow.
//  3. Sub-stepping (dt split into at most max_substeps steps of at most max_substep) only
//     improves accuracy of the frozen-force assumption; it is capped, and stability never
//     depends on it, so a 1 s frame costs the same as a 1/15 s one.
//  4. Inputs are sanitised: NaN/Inf/negative dt counts as 0, NaN/Inf wind as no wind, wind is
//     clamped to 1000 m/s, stiffness to [0, 1e9], eta to [0, 1]. A blade whose state is not
//     finite (corrupted buffer) is reset to its rest pose.
//
// Units: positions in metres (BladeSet-local), dt in seconds, wind in m/s, stiffness in 1/s.

#include <sylva/grass/blade.hpp>
#include <sylva/grass/settings.hpp>

#include <glm/glm.hpp>

#include <functional>
#include <span>

namespace sylva::grass {

// A collider in the same frame as the blades (e.g. a foot, a ball, a wheel) [m].
struct CollisionSphere {
  glm::vec3 center{0.0f};
  float radius = 0.0f;
};

// Advances one blade by dt seconds with the wind velocity `wind` at its root [m/s].
void simulate_blade(Blade& blade, const glm::vec3& wind, float dt, const PhysicsSettings& settings,
                    std::span<const CollisionSphere> spheres = {});

// Wind velocity at a BladeSet-local position [m/s]; called once per blade per frame.
using WindSampler = std::function<glm::vec3(const glm::vec3& local_position)>;

// simulate_blade over a span, with the wind sampled at each root.
void simulate_blades(std::span<Blade> blades, const WindSampler& wind, float dt, const PhysicsSettings& settings,
                     std::span<const CollisionSphere> spheres = {});

// Paper §4.3 state validation (ground, v1 placement, exact length). Idempotent up to rounding.
void validate_blade(Blade& blade);

// Puts the blade into its rest pose: v2 = v0 + rest, then validated; eta = 0.
void reset_blade(Blade& blade);

// What the stability tests check (the invariants named in their test names).
struct BladeInvariants {
  bool finite = true;          // every component of v0, v1, v2 finite
  float tip_height = 0.0f;     // dot(up, v2 - v0) / height: >= 0 means the tip is above ground
  float control_height = 0.0f; // dot(up, v1 - v0) / height
  float length_error = 0.0f;   // |arclength - height| / height
};
BladeInvariants check_blade(const Blade& blade);

// The coefficients of step 1 above, exposed for tests: a = 1 - exp(-s dt), phi = a / s (-> dt).
void recovery_coefficients(float stiffness, float dt, float& a, float& phi);

}  // namespace sylva::grass

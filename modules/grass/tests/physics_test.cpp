// Blade physics behaviour: rest pose, recovery, gravity, wind, collisions, sub-step convergence.
#include <sylva/grass/physics.hpp>
#include <sylva/grass/seed001_wind.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace sylva::grass {
namespace {

// An upright blade at the origin: height 0.5 m, width along +x, front along +z... (orientation 0).
Blade make_test_blade(float stiffness = 50.0f, float lean = 0.0f) {
  Blade b{};
  const glm::vec3 up(0, 1, 0);
  b.v0 = glm::vec4(0, 0, 0, 0.0f);
  b.v1 = glm::vec4(0, 0.5f, 0, 0.5f);
  b.v2 = glm::vec4(glm::normalize(glm::vec3(0, 1, 0) + lean * blade_front_dir(up, 0.0f)) * 0.5f, 0.01f);
  b.up = glm::vec4(up, stiffness);
  b.attr = glm::vec4(0.5f);
  validate_blade(b);
  b.rest = glm::vec4(b.tip() - b.root(), 0.0f);
  return b;
}

PhysicsSettings no_gravity() {
  PhysicsSettings s;
  s.gravity = 0.0f;
  return s;
}

TEST(GrassPhysics, RecoveryCoefficientsAreExactAndBounded) {
  float a = 0, phi = 0;
  recovery_coefficients(0.0f, 0.5f, a, phi);
  EXPECT_EQ(a, 0.0f);
  EXPECT_FLOAT_EQ(phi, 0.5f);
  recovery_coefficients(10.0f, 0.1f, a, phi);
  EXPECT_NEAR(a, 1.0 - std::exp(-1.0), 1e-6);
  EXPECT_NEAR(phi, (1.0 - std::exp(-1.0)) / 10.0, 1e-7);
  recovery_coefficients(1.0e6f, 1.0f, a, phi);
  EXPECT_EQ(a, 1.0f);
  EXPECT_NEAR(phi, 1.0e-6f, 1e-12);
  recovery_coefficients(1.0e-3f, 1.0e-4f, a, phi);  // tiny s*dt: series branch
  EXPECT_NEAR(a, 1.0e-7, 1e-12);
  EXPECT_NEAR(phi, 1.0e-4, 1e-10);
}

TEST(GrassPhysics, RestPoseIsAFixedPoint) {
  const PhysicsSettings s = no_gravity();
  Blade b = make_test_blade(50.0f, 0.3f);
  const Blade before = b;
  for (int i = 0; i < 100; ++i) simulate_blade(b, glm::vec3(0.0f), 1.0f / 60.0f, s);
  EXPECT_LT(glm::length(b.tip() - before.tip()), 1e-5f);
  EXPECT_LT(glm::length(b.control() - before.control()), 1e-5f);
}

TEST(GrassPhysics, RecoversMonotonicallyFromABend) {
  const PhysicsSettings s = no_gravity();
  Blade b = make_test_blade(20.0f);
  b.v2 = glm::vec4(0.45f, 0.1f, 0.0f, b.v2.w);  // pushed over
  validate_blade(b);
  float prev = glm::length(b.tip() - (b.root() + glm::vec3(b.rest)));
  for (int i = 0; i < 120; ++i) {
    simulate_blade(b, glm::vec3(0.0f), 1.0f / 60.0f, s);
    const float d = glm::length(b.tip() - (b.root() + glm::vec3(b.rest)));
    EXPECT_LE(d, prev + 1e-6f) << "frame " << i;
    prev = d;
  }
  EXPECT_LT(prev, 1e-3f);
}

TEST(GrassPhysics, WindBendsDownwindAndMoreWithStrongerWind) {
  const PhysicsSettings s = no_gravity();
  float prev_lean = 0.0f;
  for (const float speed : {1.0f, 3.0f, 8.0f, 20.0f}) {
    Blade b = make_test_blade(50.0f);
    for (int i = 0; i < 240; ++i) simulate_blade(b, glm::vec3(speed, 0, 0), 1.0f / 60.0f, s);
    const float lean = b.tip().x - b.root().x;
    EXPECT_GT(lean, prev_lean) << "wind " << speed;
    EXPECT_LT(check_blade(b).length_error, 1e-4f);
    prev_lean = lean;
  }
}

TEST(GrassPhysics, GravityDroopsSoftBladesMore) {
  const PhysicsSettings s;
  float prev_tip = 1.0f;
  for (const float stiffness : {400.0f, 100.0f, 30.0f, 5.0f}) {
    Blade b = make_test_blade(stiffness);
    for (int i = 0; i < 600; ++i) simulate_blade(b, glm::vec3(0.0f), 1.0f / 60.0f, s);
    const float tip = check_blade(b).tip_height;
    EXPECT_LT(tip, prev_tip) << "stiffness " << stiffness;
    EXPECT_GE(tip, 0.0f);
    prev_tip = tip;
  }
}

TEST(GrassPhysics, CollisionPushesTheBladeOutAndWeakensRecovery) {
  const PhysicsSettings s = no_gravity();
  Blade b = make_test_blade(50.0f);
  // A ball resting on the blade from the side: centre at the blade's upper half.
  const CollisionSphere ball{{0.15f, 0.45f, 0.0f}, 0.2f};
  for (int i = 0; i < 60; ++i) simulate_blade(b, glm::vec3(0.0f), 1.0f / 60.0f, s, {&ball, 1});
  EXPECT_GT(b.collision(), 0.0f);
  EXPECT_LT(b.tip().x, 0.0f) << "pushed away from the ball";
  EXPECT_GT(glm::length(b.tip() - ball.center), ball.radius * 0.95f);
  EXPECT_LT(check_blade(b).length_error, 1e-4f);
  // Ball removed: the blade recovers and the collision strength decays.
  const float eta = b.collision();
  for (int i = 0; i < 600; ++i) simulate_blade(b, glm::vec3(0.0f), 1.0f / 60.0f, s);
  EXPECT_LT(b.collision(), 0.05f * eta + 1e-6f);
  EXPECT_LT(glm::length(b.tip() - (b.root() + glm::vec3(b.rest))), 0.01f);
}

TEST(GrassPhysics, SubstepsConvergeToTheFineSolution) {
  const PhysicsSettings coarse = [] { PhysicsSettings s; s.max_substeps = 1; s.max_substep = 1.0f; return s; }();
  const PhysicsSettings fine = [] { PhysicsSettings s; s.max_substeps = 64; s.max_substep = 1.0f / 960.0f; return s; }();
  const PhysicsSettings mid = [] { PhysicsSettings s; s.max_substeps = 4; s.max_substep = 1.0f / 60.0f; return s; }();
  Blade bc = make_test_blade(30.0f), bf = bc, bm = bc;
  const glm::vec3 wind(6.0f, 0.0f, 2.0f);
  for (int i = 0; i < 20; ++i) {
    simulate_blade(bc, wind, 1.0f / 15.0f, coarse);
    simulate_blade(bf, wind, 1.0f / 15.0f, fine);
    simulate_blade(bm, wind, 1.0f / 15.0f, mid);
  }
  const float err_coarse = glm::length(bc.tip() - bf.tip());
  const float err_mid = glm::length(bm.tip() - bf.tip());
  EXPECT_LE(err_mid, err_coarse + 1e-6f);
  EXPECT_LT(err_mid, 0.02f);
}

TEST(GrassPhysics, BezierLengthClosedForm) {
  // Straight, collinear-with-cusp and curved cases against fine polyline sums.
  const glm::vec3 cases[][3] = {{{0, 0, 0}, {0, 1, 0}, {0, 2, 0}},
                                {{0, 0, 0}, {0, 1, 0}, {0, 0.2f, 0}},
                                {{0, 0, 0}, {0, 0.5f, 0}, {0.4f, 0.3f, 0.1f}},
                                {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}},
                                {{0, 0, 0}, {0, 0.999f, 0}, {0.002f, 0.9999f, 0}},   // nearly straight, sharp top
                                {{0, 0, 0}, {0, 0.05f, 0}, {0.9f, 0.01f, 0.2f}}};    // lying flat
  for (const auto& c : cases) {
    double poly = 0.0;
    glm::dvec3 prev = glm::dvec3(c[0]);
    for (int i = 1; i <= 200000; ++i) {
      const double t = i / 200000.0;
      const glm::dvec3 p = (1 - t) * (1 - t) * glm::dvec3(c[0]) + 2 * t * (1 - t) * glm::dvec3(c[1]) + t * t * glm::dvec3(c[2]);
      poly += glm::length(p - prev);
      prev = p;
    }
    EXPECT_NEAR(bezier_length(c[0], c[1], c[2]), poly, 1e-5 + 1e-5 * poly);
  }
}

TEST(GrassPhysics, BatchSamplesWindAtEachRoot) {
  std::vector<Blade> blades = {make_test_blade(), make_test_blade()};
  blades[1].v0 = glm::vec4(10, 0, 0, 0);
  blades[1].v1 += glm::vec4(10, 0, 0, 0);
  blades[1].v2 += glm::vec4(10, 0, 0, 0);
  const WindSampler wind = [](const glm::vec3& p) { return p.x > 5.0f ? glm::vec3(10, 0, 0) : glm::vec3(0.0f); };
  for (int i = 0; i < 60; ++i) simulate_blades(blades, wind, 1.0f / 60.0f, no_gravity());
  EXPECT_LT(std::abs(blades[0].tip().x), 1e-4f);
  EXPECT_GT(blades[1].tip().x - 10.0f, 0.05f);
}

// Seed 001 eq. 2.7/4.2: bounded by strength (1 + 2 + 1) along x and (1 + 1 + 0.5) along z, finite
// on the lines where cos(k2 pi z) = 0 (eps 0.05), leaning towards +x/+z on average; time wraps.
TEST(GrassSeed001Wind, BoundedFiniteAndLeaningLikeTheThesis) {
  Seed001WindSettings s;
  s.strength = 2.0f;
  glm::dvec3 mean(0.0);
  int n = 0;
  for (float x = -20.0f; x <= 20.0f; x += 0.37f) {
    for (float z = -20.0f; z <= 20.0f; z += 0.25f) {  // z = k * 0.25: on the singular lines for k2 = 2
      for (const float t : {0.0f, 1.3f, 100.0f}) {
        const glm::vec3 w = seed001_wind({x, 0.1f, z}, t, s);
        ASSERT_TRUE(std::isfinite(w.x) && std::isfinite(w.z)) << x << " " << z;
        EXPECT_LE(std::abs(w.x), 2.0f * 4.0f + 1e-4f);
        EXPECT_LE(std::abs(w.z), 2.0f * 2.5f + 1e-4f);
        EXPECT_EQ(w.y, 0.0f);
        mean += glm::dvec3(w);
        ++n;
      }
    }
  }
  mean /= n;
  EXPECT_GT(mean.x, 1.0);  // long_x's +1 offset times strength 2
  EXPECT_GT(mean.z, 0.5);
  EXPECT_NEAR(seed001_wind_time(2.0 * 3.141592653589793 * 1000.0 + 1.0), 1.0f, 1e-4f);
  EXPECT_EQ(seed001_wind_time(std::nan("")), 0.0f);
  EXPECT_GE(seed001_wind_time(-5.0), 0.0f);
}

}  // namespace
}  // namespace sylva::grass

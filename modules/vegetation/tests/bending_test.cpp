// Bending model (seed 000 §3.1.1): the fitted constants, the guarded length correction and the
// amplitude limit that bounds the branch length change.
#include <sylva/vegetation/bending.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

namespace sylva::vegetation {
namespace {

TEST(Bending, NumericalShapeIsTheSeedsClosedForm) {
  for (double alpha : {0.1, 0.2, 0.5, 0.8}) {
    for (double x : {0.1, 0.37, 0.5, 0.9, 1.0}) {
      const double closed = cantilever_shape_closed_form(alpha, x);
      EXPECT_NEAR(cantilever_shape(alpha, x), closed, 1e-9 * std::max(1.0, std::fabs(closed)))
          << "alpha " << alpha << " x " << x;
    }
  }
  // The closed form is singular at alpha = 1; the ODE gives the uniform beam x^2 (6 - 4x + x^2) / 24
  // times 2 / pi * 2 (load normalisation of the seed's shape).
  for (double x : {0.25, 0.5, 1.0}) {
    const double uniform = (4.0 / 3.14159265358979) * x * x * (6.0 - 4.0 * x + x * x) / 24.0;
    EXPECT_NEAR(cantilever_shape(1.0, x), uniform, 1e-9);
  }
}

TEST(Bending, FitReproducesTheSeedsConstantsAndTheExtractionTable) {
  const BendConstants c = fit_bend_constants(0.2);
  EXPECT_NEAR(c.c2, 0.374570f, 0.002f * 0.374570f);  // seed §4.4, alpha = 0.2
  EXPECT_NEAR(c.c4, 0.129428f, 0.01f * 0.129428f);  // extraction: fits differ by 0.5-0.8 %
  struct Row { double alpha; float c2, c4; };
  // Extraction §2.1 [OUR CHECK] values for other tapers.
  for (const Row& r : {Row{0.1, 0.3326f, 0.3989f}, Row{0.3, 0.3644f, 0.0253f}, Row{0.5, 0.3237f, -0.0533f},
                       Row{0.8, 0.2691f, -0.0825f}, Row{0.99, 0.2421f, -0.0860f}}) {
    const BendConstants f = fit_bend_constants(r.alpha);
    EXPECT_NEAR(f.c2, r.c2, 2e-4f) << "alpha " << r.alpha;
    EXPECT_NEAR(f.c4, r.c4, 2e-4f) << "alpha " << r.alpha;
  }
  const BendConstants cached = bend_constants_for_taper(0.2f);
  EXPECT_EQ(cached.c2, c.c2);
  EXPECT_EQ(cached.c4, c.c4);
}

TEST(Bending, ZeroAmplitudeIsTheRestPoseExactly) {
  for (float x : {0.0f, 0.125f, 0.3f, 0.77f, 1.0f}) {
    const BendPoint p = bend_profile(x, 0.0f, 0.374570f, 0.129428f, 1e-6f);
    EXPECT_EQ(p.along, x);
    EXPECT_EQ(p.across, 0.0f);
    EXPECT_EQ(p.cos_theta, 1.0f);
    EXPECT_EQ(p.sin_theta, 0.0f);
  }
}

TEST(Bending, GuardKeepsTheSignAndNeverDividesByZero) {
  EXPECT_EQ(guard_derivative(0.0f, 1e-6f), 1e-6f);  // sign(0) = +1, unlike GLSL sign()
  EXPECT_EQ(guard_derivative(-0.0f, 1e-6f), 1e-6f);
  EXPECT_EQ(guard_derivative(-1e-9f, 1e-6f), -1e-6f);
  EXPECT_EQ(guard_derivative(-1e-6f, 1e-6f), -1e-6f);  // the seed's a + eps form gives 0 here
  EXPECT_EQ(guard_derivative(0.5f, 1e-6f), 0.5f);
  EXPECT_EQ(guard_derivative(-0.5f, 1e-6f), -0.5f);
  // x = 0 (u' = 0) and tiny amplitudes stay finite.
  for (float a : {1e-30f, 1e-8f, 1.0f, 1e6f}) {
    const BendPoint p = bend_profile(0.0f, a, 0.37f, 0.13f, 1e-6f);
    EXPECT_EQ(p.along, 0.0f);
    EXPECT_EQ(p.across, 0.0f);
    const BendPoint q = bend_profile(0.5f, a, 0.37f, 0.13f, 1e-6f);
    EXPECT_TRUE(std::isfinite(q.along) && std::isfinite(q.across) && std::isfinite(q.sin_theta));
  }
}

TEST(Bending, CorrectionMatchesTheExtractionsLengthTable) {
  // Extraction §8.3: corrected curve length for the seed's constants.
  struct Row { float a; double length; };
  for (const Row& r : {Row{0.25f, 0.992}, Row{0.5f, 0.972}, Row{1.0f, 0.922}, Row{2.0f, 0.851}}) {
    EXPECT_NEAR(corrected_axis_length(0.374570f, 0.129428f, r.a), r.length, 1.5e-3) << "a " << r.a;
  }
}

TEST(Bending, AmplitudeLimitBoundsTheLengthChange) {
  for (double alpha : {0.05, 0.1, 0.2, 0.35, 0.5, 0.8, 1.0, 1.5}) {
    const BendConstants c = fit_bend_constants(alpha);
    const float limit = bend_amplitude_limit(c.c2, c.c4, 0.009f);
    ASSERT_GT(limit, 0.05f) << "alpha " << alpha;
    double worst = 0.0;
    for (float a = 0.0f; a < 200.0f; a = a * 1.05f + 1e-3f) {
      const float s = saturate_amplitude(a, limit);
      ASSERT_LT(s, limit);
      worst = std::max(worst, std::fabs(corrected_axis_length(c.c2, c.c4, s) - 1.0));
    }
    EXPECT_LE(worst, 0.009 + 1e-6) << "alpha " << alpha;
    std::printf("taper %.2f: c2 %.4f c4 %.4f  A_max %.3f  worst |dL| %.4f %%\n", alpha, static_cast<double>(c.c2),
                static_cast<double>(c.c4), static_cast<double>(limit), 100.0 * worst);
  }
}

TEST(Bending, SaturationIsMonotonicAndFinite) {
  float prev = 0.0f;
  for (float a = 0.0f; a < 3e38f; a = a * 2.0f + 1e-4f) {
    const float s = saturate_amplitude(a, 0.3f);
    ASSERT_TRUE(std::isfinite(s));
    ASSERT_GE(s, prev);
    ASSERT_LE(s, 0.3f);
    prev = s;
  }
  EXPECT_EQ(saturate_amplitude(std::numeric_limits<float>::infinity(), 0.3f), 0.3f);
  EXPECT_NEAR(saturate_amplitude(0.01f, 0.3f), 0.01f, 1e-5f);
  EXPECT_LT(saturate_amplitude(-5.0f, 0.3f), 0.0f);
  EXPECT_EQ(saturate_amplitude(-std::numeric_limits<float>::infinity(), 0.3f), -0.3f);
  EXPECT_EQ(saturate_amplitude(std::nanf(""), 0.3f), 0.3f);
}

}  // namespace
}  // namespace sylva::vegetation

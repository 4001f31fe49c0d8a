// Cook-Torrance terms in their standard forms (seed 000 eqs. 3.22-3.25 with errata 3 and 4).
#include <sylva/vegetation/shading.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace sylva::vegetation {
namespace {

TEST(Shading, FresnelHasTheRightLimits) {
  for (float n : {1.33f, 1.45f, 1.6f}) {
    const float r0 = ((n - 1.0f) / (n + 1.0f)) * ((n - 1.0f) / (n + 1.0f));
    EXPECT_NEAR(fresnel_cook_torrance(1.0f, n), r0, 1e-6f);   // normal incidence
    EXPECT_NEAR(fresnel_cook_torrance(0.0f, n), 1.0f, 1e-6f);  // grazing
    float prev = 2.0f;
    for (float c = 0.0f; c <= 1.0f; c += 0.05f) {  // monotonic in the angle
      const float f = fresnel_cook_torrance(c, n);
      EXPECT_LE(f, prev + 1e-6f);
      prev = f;
    }
  }
  // The seed's printed form (ratio not squared) differs: at c = 0.5, n = 1.45 it is off.
  const float c = 0.5f, n = 1.45f;
  const float g = std::sqrt(n * n + c * c - 1.0f);
  const float a = (g - c) / (g + c);
  const float b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
  const float printed = 0.5f * a * a * (1.0f + b);
  EXPECT_GT(std::fabs(printed - fresnel_cook_torrance(c, n)), 1e-3f);
}

TEST(Shading, BeckmannIntegratesToPiOverTheHemisphere) {
  // int D(h) cos(theta_h) d omega = pi for D = exp(-tan^2 / s^2) / (s^2 cos^4) (no 1/pi factor).
  for (float sigma : {0.2f, 0.35f, 0.6f}) {
    double sum = 0.0;
    const int n = 4000;
    for (int i = 0; i < n; ++i) {
      const double theta = (i + 0.5) / n * (std::numbers::pi / 2.0);
      const double d = beckmann(static_cast<float>(std::cos(theta)), sigma);
      sum += d * std::cos(theta) * std::sin(theta) * (std::numbers::pi / 2.0 / n) * 2.0 * std::numbers::pi;
    }
    EXPECT_NEAR(sum, std::numbers::pi, 0.01 * std::numbers::pi) << "sigma " << sigma;
  }
  // The seed's printed exponent lost N.H: it would be constant over angles. Ours peaks at N.H = 1.
  EXPECT_GT(beckmann(1.0f, 0.3f), beckmann(0.9f, 0.3f));
}

TEST(Shading, SpecularIsReciprocalBoundedAndOneSided) {
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  for (float a = 0.1f; a < 1.5f; a += 0.2f) {
    for (float b = 0.1f; b < 1.5f; b += 0.3f) {
      const glm::vec3 l = glm::normalize(glm::vec3(std::sin(a), 0.2f, std::cos(a)));
      const glm::vec3 e = glm::normalize(glm::vec3(-std::sin(b), 0.1f, std::cos(b)));
      const float le = cook_torrance_specular(n, l, e, 0.35f, 1.45f) / glm::dot(n, l);  // BRDF(l, e)
      const float el = cook_torrance_specular(n, e, l, 0.35f, 1.45f) / glm::dot(n, e);  // BRDF(e, l)
      EXPECT_NEAR(le, el, 1e-4f * std::max(1.0f, le));
      EXPECT_GE(le, 0.0f);
      EXPECT_TRUE(std::isfinite(le));
    }
  }
  EXPECT_EQ(cook_torrance_specular(n, {0.0f, 0.0f, -1.0f}, {0.0f, 0.0f, 1.0f}, 0.35f, 1.45f), 0.0f);
  EXPECT_EQ(cook_torrance_specular(n, {0.0f, 0.0f, 1.0f}, {0.0f, 0.6f, -0.8f}, 0.35f, 1.45f), 0.0f);
  // G never exceeds 1.
  EXPECT_LE(geometric_attenuation(0.9f, 0.8f, 0.7f, 0.95f), 1.0f);
}

}  // namespace
}  // namespace sylva::vegetation

// core HeightField stability: non-finite input, degenerate sizes, far-from-origin queries.
#include <sylva/core/height_field.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using sylva::HeightField;
using sylva::Image;
using sylva::NonFinitePolicy;

// Invariant: NaN/Inf input is either rejected with count + first position, or repaired so that
// no sample is non-finite afterwards.
TEST(HeightFieldStability, NonFiniteSamplesRejectedOrRepairedNeverPropagated) {
  Image image(5, 5, 1);
  for (float& v : image.data()) v = 0.5f;
  image.at(3, 1) = std::numeric_limits<float>::quiet_NaN();
  image.at(4, 4) = -std::numeric_limits<float>::infinity();
  auto rejected = HeightField::from_image(image);
  ASSERT_FALSE(rejected.ok());
  EXPECT_NE(rejected.error().message.find("2 NaN/Inf"), std::string::npos) << rejected.error().message;
  EXPECT_NE(rejected.error().message.find("(3, 1)"), std::string::npos) << rejected.error().message;

  auto repaired = HeightField::from_image(image, {.height_scale = 10.0, .non_finite = NonFinitePolicy::kRepair});
  ASSERT_TRUE(repaired.ok());
  for (float h : repaired->samples()) ASSERT_TRUE(std::isfinite(h));
  EXPECT_FLOAT_EQ(repaired->sample(3, 1), 5.f);
  EXPECT_FLOAT_EQ(repaired->sample(4, 4), 5.f);
}

// Invariant: an all-NaN image repairs to a flat, finite field.
TEST(HeightFieldStability, AllNanRepairsToFlatZero) {
  Image image(3, 2, 1);
  for (float& v : image.data()) v = std::numeric_limits<float>::quiet_NaN();
  auto field = HeightField::from_image(image, {.non_finite = NonFinitePolicy::kRepair});
  ASSERT_TRUE(field.ok());
  for (float h : field->samples()) EXPECT_EQ(h, 0.f);
}

// Invariant: 1x1 and 1xN fields answer every query with finite heights and unit normals.
TEST(HeightFieldStability, DegenerateSizesGiveFiniteQueries) {
  for (auto [c, r] : {std::pair{1, 1}, std::pair{1, 7}, std::pair{7, 1}, std::pair{2, 2}}) {
    HeightField field(c, r, 1.0);
    field.sample(c - 1, r - 1) = 3.f;
    for (double x : {-1e9, -1.0, 0.0, 0.5, 3.0, 1e9}) {
      const float h = field.height(x, x);
      ASSERT_TRUE(std::isfinite(h)) << c << "x" << r << " at " << x;
      const glm::vec3 n = field.normal(x, x);
      ASSERT_NEAR(glm::length(n), 1.f, 1e-5f);
    }
  }
}

// Invariant: a field placed 1e6 m from the origin interpolates exactly as one at the origin.
TEST(HeightFieldStability, FarFromOriginKeepsPrecision) {
  HeightField near_field(4, 4, 0.25);
  HeightField far_field(4, 4, 0.25, {1.0e6, -1.0e6});
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) near_field.sample(i, j) = far_field.sample(i, j) = static_cast<float>(i * i + j);
  for (double t = 0.0; t <= 0.75; t += 0.01) {
    EXPECT_NEAR(near_field.height(t, 0.75 - t), far_field.height(1.0e6 + t, -1.0e6 + 0.75 - t), 1e-5f);
  }
  EXPECT_TRUE(std::isfinite(far_field.height(std::numeric_limits<double>::quiet_NaN(), 0.0)));
}

// core HeightField: sampling, normals, image import, non-finite handling.
#include <sylva/core/height_field.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using sylva::HeightField;
using sylva::Image;

TEST(HeightField, BilinearInterpolatesAndClampsAtBorders) {
  HeightField field(3, 2, 2.0, {10.0, -4.0});
  field.sample(0, 0) = 0.f;
  field.sample(1, 0) = 2.f;
  field.sample(2, 0) = 4.f;
  field.sample(0, 1) = 2.f;
  field.sample(1, 1) = 4.f;
  field.sample(2, 1) = 6.f;
  EXPECT_FLOAT_EQ(field.height(10.0, -4.0), 0.f);
  EXPECT_FLOAT_EQ(field.height(11.0, -4.0), 1.f);     // halfway between columns 0 and 1
  EXPECT_FLOAT_EQ(field.height(12.0, -3.0), 3.f);     // centre of a cell edge
  EXPECT_FLOAT_EQ(field.height(100.0, 100.0), 6.f);   // clamped to the far corner
  EXPECT_FLOAT_EQ(field.height(-100.0, -100.0), 0.f); // clamped to the origin corner
  EXPECT_EQ(field.extent(), glm::dvec2(4.0, 2.0));
}

TEST(HeightField, NormalOfAPlaneIsExact) {
  HeightField field(8, 8, 0.5);
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) field.sample(i, j) = 0.25f * static_cast<float>(i) * 0.5f;  // slope 0.25 in x
  const glm::vec3 expected = glm::normalize(glm::vec3(-0.25f, 1.f, 0.f));
  const glm::vec3 n = field.normal(1.7, 2.1);
  EXPECT_NEAR(n.x, expected.x, 1e-5f);
  EXPECT_NEAR(n.y, expected.y, 1e-5f);
  EXPECT_NEAR(n.z, 0.f, 1e-6f);
  const glm::vec3 s = field.sample_normal(0, 3);
  EXPECT_NEAR(s.x, expected.x, 1e-5f);
}

TEST(HeightField, FromImageAppliesScaleAndOffset) {
  Image image(4, 3, 2);
  image.at(2, 1, 1) = 0.5f;
  auto field = HeightField::from_image(image, {.spacing = 2.0, .height_scale = 100.0, .height_offset = -10.0,
                                               .channel = 1});
  ASSERT_TRUE(field.ok()) << field.error().message;
  EXPECT_EQ(field->columns(), 4);
  EXPECT_EQ(field->rows(), 3);
  EXPECT_FLOAT_EQ(field->sample(2, 1), 40.f);
  EXPECT_FLOAT_EQ(field->sample(0, 0), -10.f);
  EXPECT_FLOAT_EQ(field->min_height(), -10.f);
  EXPECT_FLOAT_EQ(field->max_height(), 40.f);
}

TEST(HeightField, FromImageRejectsBadOptionsNamingThem) {
  Image image(2, 2, 1);
  auto bad_channel = HeightField::from_image(image, {.channel = 3});
  ASSERT_FALSE(bad_channel.ok());
  EXPECT_NE(bad_channel.error().message.find("channel 3"), std::string::npos);
  auto bad_spacing = HeightField::from_image(image, {.spacing = 0.0});
  ASSERT_FALSE(bad_spacing.ok());
  EXPECT_NE(bad_spacing.error().message.find("spacing"), std::string::npos);
  EXPECT_FALSE(HeightField::from_image(Image()).ok());
}

// Found by the image_map fuzz target: a finite sample that overflows float once scaled became
// an infinite height that passed the NaN/Inf check.
TEST(HeightField, SamplesBeyondFloatRangeOnceScaledAreNonFinite) {
  Image image(3, 2, 1);
  image.at(1, 1) = 3e38f;
  auto rejected = HeightField::from_image(image, {.height_scale = 100.0});
  ASSERT_FALSE(rejected.ok());
  EXPECT_NE(rejected.error().message.find("1 NaN/Inf samples (or beyond float range once scaled), the first at (1, 1)"),
            std::string::npos) << rejected.error().message;
  auto repaired = HeightField::from_image(image, {.height_scale = 100.0, .non_finite = sylva::NonFinitePolicy::kRepair});
  ASSERT_TRUE(repaired.ok());
  for (float h : repaired->samples()) EXPECT_TRUE(std::isfinite(h));
  EXPECT_TRUE(HeightField::from_image(image, {.height_scale = 1.0}).ok());  // 3e38 m itself is a float
}

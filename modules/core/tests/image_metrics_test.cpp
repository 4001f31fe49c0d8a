// Image metrics against known answers: constant offsets (exact RMSE/PSNR and the closed-form
// SSIM of flat images), identical images, a direct (non-separable) SSIM reference, shifted masks
// with known coverage and IoU, thresholds, difference images and every error path.
#include <sylva/core/image_metrics.hpp>
#include <sylva/core/rng.hpp>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace sylva {
namespace {

Image filled(int w, int h, int ch, float v) {
  Image img(w, h, ch);
  for (float& x : img.data()) x = v;
  return img;
}

Image random_image(int w, int h, int ch, std::uint64_t seed) {
  Image img(w, h, ch);
  Pcg32 rng(seed);
  for (float& x : img.data()) x = rng.next_float();
  return img;
}

// A smooth test picture with structure at several scales (so SSIM has something to compare).
Image pattern(int w, int h, int ch) {
  Image img(w, h, ch);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < ch; ++c)
        img.at(x, y, c) = 0.5f + 0.3f * std::sin(0.31f * x + c) * std::cos(0.17f * y) + 0.1f * std::sin(1.3f * (x + y));
  return img;
}

TEST(ImageMetrics, ConstantOffsetGivesExactRmseAndPsnr) {
  // 0.375 - 0.25 = 0.125 exactly in float, so RMSE is exactly 0.125 and PSNR = 20 log10(8).
  const Image a = filled(37, 23, 3, 0.25f);
  const Image b = filled(37, 23, 3, 0.375f);
  EXPECT_DOUBLE_EQ(*rmse(a, b), 0.125);
  EXPECT_DOUBLE_EQ(*mse(a, b), 0.015625);
  EXPECT_NEAR(*psnr(a, b), 20.0 * std::log10(8.0), 1e-12);
  EXPECT_NEAR(*psnr(a, b, 255.0), 20.0 * std::log10(255.0 / 0.125), 1e-9);
  EXPECT_DOUBLE_EQ(*rmse(b, a), 0.125);
}

TEST(ImageMetrics, IdenticalImages) {
  const Image a = pattern(64, 48, 4);
  EXPECT_EQ(*rmse(a, a), 0.0);
  const double p = *psnr(a, a);
  EXPECT_TRUE(std::isinf(p) && p > 0) << p;
  for (SsimChannels ch : {SsimChannels::kLuminance, SsimChannels::kPerChannel}) {
    for (SsimBorder border : {SsimBorder::kValid, SsimBorder::kTruncated}) {
      const Result<SsimResult> s = ssim(a, a, {.channels = ch, .border = border});
      ASSERT_TRUE(s.ok()) << s.error().describe();
      EXPECT_EQ(s->mean, 1.0);
      for (float v : s->map.data()) ASSERT_EQ(v, 1.0f);
    }
  }
  EXPECT_EQ(*share_exceeding(a, a, 0.0f), 0.0);
}

TEST(ImageMetrics, SsimOfFlatImagesHasTheClosedForm) {
  // Flat images: sigma = 0, so SSIM = (2ab + C1) / (a^2 + b^2 + C1) everywhere.
  const double a = 0.25;
  const double b = 0.375;
  const double c1 = 0.01 * 0.01;
  const double expected = (2 * a * b + c1) / (a * a + b * b + c1);
  const Result<SsimResult> s = ssim(filled(30, 20, 1, 0.25f), filled(30, 20, 1, 0.375f));
  ASSERT_TRUE(s.ok());
  EXPECT_NEAR(s->mean, expected, 1e-6);
  EXPECT_EQ(s->map.width(), 20);
  EXPECT_EQ(s->map.height(), 10);
  EXPECT_EQ(s->map.channels(), 1);
}

// Direct SSIM at one window centre (11x11 double sums), independent of the separable code.
double direct_ssim_at(const Image& a, const Image& b, int cx, int cy) {
  double w[11][11];
  double wsum = 0.0;
  for (int j = 0; j < 11; ++j)
    for (int i = 0; i < 11; ++i) {
      w[j][i] = std::exp(-((i - 5) * (i - 5) + (j - 5) * (j - 5)) / (2.0 * 1.5 * 1.5));
      wsum += w[j][i];
    }
  double mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
  for (int j = 0; j < 11; ++j)
    for (int i = 0; i < 11; ++i) {
      const double k = w[j][i] / wsum;
      const double x = a.at(cx + i - 5, cy + j - 5);
      const double y = b.at(cx + i - 5, cy + j - 5);
      mx += k * x;
      my += k * y;
      xx += k * x * x;
      yy += k * y * y;
      xy += k * x * y;
    }
  const double c1 = 1e-4;
  const double c2 = 9e-4;
  return (2 * mx * my + c1) * (2 * (xy - mx * my) + c2) /
         ((mx * mx + my * my + c1) * (xx - mx * mx + yy - my * my + c2));
}

TEST(ImageMetrics, SsimMatchesADirectWindowComputation) {
  const Image a = random_image(29, 24, 1, 1);
  Image b = a;
  Pcg32 rng(2);
  for (float& v : b.data()) v = 0.7f * v + 0.3f * rng.next_float();
  const Result<SsimResult> s = ssim(a, b);
  ASSERT_TRUE(s.ok());
  ASSERT_EQ(s->map.width(), 19);
  ASSERT_EQ(s->map.height(), 14);
  double sum = 0.0;
  for (int y = 0; y < 14; ++y) {
    for (int x = 0; x < 19; ++x) {
      const double d = direct_ssim_at(a, b, x + 5, y + 5);
      EXPECT_NEAR(s->map.at(x, y), d, 2e-6) << "at map pixel " << x << ", " << y;
      sum += d;
    }
  }
  EXPECT_NEAR(s->mean, sum / (19 * 14), 1e-6);
  EXPECT_GT(s->mean, 0.2);
  EXPECT_LT(s->mean, 0.95);
}

TEST(ImageMetrics, SsimFallsWithNoiseIsSymmetricAndSeesInversion) {
  const Image a = pattern(96, 64, 3);
  double previous = 1.0;
  for (float amp : {0.02f, 0.05f, 0.1f, 0.2f}) {
    Image b = a;
    Pcg32 rng(static_cast<std::uint64_t>(amp * 1000));
    for (float& v : b.data()) v += amp * (rng.next_float() - 0.5f);
    const double s = ssim(a, b)->mean;
    EXPECT_LT(s, previous) << "amplitude " << amp;
    EXPECT_NEAR(s, ssim(b, a)->mean, 1e-12);
    previous = s;
  }
  Image inverted = a;
  for (float& v : inverted.data()) v = 1.0f - v;
  EXPECT_LT(ssim(a, inverted)->mean, 0.0) << "inverted contrast must correlate negatively";
}

TEST(ImageMetrics, SsimModesAndBorders) {
  const Image a = pattern(40, 30, 3);
  Image b = a;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) b.at(x, y, 2) = 0.5f * b.at(x, y, 2);  // only blue changes
  const Result<SsimResult> per = ssim(a, b, {.channels = SsimChannels::kPerChannel});
  ASSERT_TRUE(per.ok());
  ASSERT_EQ(per->per_channel.size(), 3u);
  EXPECT_EQ(per->per_channel[0], 1.0);
  EXPECT_EQ(per->per_channel[1], 1.0);
  EXPECT_LT(per->per_channel[2], 0.99);
  EXPECT_NEAR(per->mean, (2.0 + per->per_channel[2]) / 3.0, 1e-12);
  EXPECT_EQ(per->map.channels(), 3);
  // Luminance mode weighs blue by 0.0722 only.
  const Result<SsimResult> lum = ssim(a, b);
  ASSERT_TRUE(lum.ok());
  EXPECT_GT(lum->mean, per->per_channel[2]);
  EXPECT_LT(lum->mean, 1.0);
  // Truncated borders: full-size map; small images work there and are refused by kValid.
  const Result<SsimResult> trunc = ssim(a, b, {.border = SsimBorder::kTruncated});
  ASSERT_TRUE(trunc.ok());
  EXPECT_EQ(trunc->map.width(), 40);
  EXPECT_EQ(trunc->map.height(), 30);
  const Image small = pattern(8, 5, 1);
  const Result<SsimResult> refused = ssim(small, small);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("8x5x1"), std::string::npos) << refused.error().message;
  const Result<SsimResult> small_ok = ssim(small, small, {.border = SsimBorder::kTruncated});
  ASSERT_TRUE(small_ok.ok());
  EXPECT_EQ(small_ok->mean, 1.0);
}

TEST(ImageMetrics, ShareOfPixelsOverAThreshold) {
  Image a = filled(10, 10, 3, 0.5f);
  Image b = a;
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 5; ++x) b.at(x, y, 1) = 0.75f;  // 25 pixels off by 0.25 in one channel
  EXPECT_DOUBLE_EQ(*share_exceeding(a, b, 0.1f), 0.25);
  EXPECT_DOUBLE_EQ(*share_exceeding(a, b, 0.25f), 0.0) << "the comparison is strict";
  EXPECT_DOUBLE_EQ(*share_exceeding(a, b, 0.3f), 0.0);
  const DifferenceCount c = *count_exceeding(a, b, 0.0f);
  EXPECT_EQ(c.pixels, 25u);
  EXPECT_EQ(c.total, 100u);
  EXPECT_EQ(c.max_difference, 0.25f);
}

Image rect_mask(int w, int h, int x0, int y0, int rw, int rh, int channels = 1) {
  Image m(w, h, channels);
  for (int y = y0; y < y0 + rh; ++y)
    for (int x = x0; x < x0 + rw; ++x) m.at(x, y, channels - 1) = 1.0f;
  return m;
}

TEST(ImageMetrics, ShiftedMasksHaveKnownCoverageAndIoU) {
  // 20x10 rectangle and the same shifted right by 5: overlap 15x10 = 150, union 250.
  const Image ref = rect_mask(64, 32, 10, 10, 20, 10);
  const Image test = rect_mask(64, 32, 15, 10, 20, 10);
  const SilhouetteStats s = *silhouette_coverage(ref, test);
  EXPECT_EQ(s.reference_pixels, 200u);
  EXPECT_EQ(s.test_pixels, 200u);
  EXPECT_EQ(s.intersection, 150u);
  EXPECT_EQ(s.union_pixels, 250u);
  EXPECT_DOUBLE_EQ(s.coverage, 0.75);
  EXPECT_DOUBLE_EQ(s.iou, 0.6);
  // A test silhouette inside the reference covers part of it; IoU and coverage agree then.
  const SilhouetteStats inner = *silhouette_coverage(ref, rect_mask(64, 32, 10, 10, 10, 10));
  EXPECT_DOUBLE_EQ(inner.coverage, 0.5);
  EXPECT_DOUBLE_EQ(inner.iou, 0.5);
  // A bigger test silhouette covers everything but IoU drops.
  const SilhouetteStats outer = *silhouette_coverage(ref, rect_mask(64, 32, 0, 0, 40, 25));
  EXPECT_DOUBLE_EQ(outer.coverage, 1.0);
  EXPECT_DOUBLE_EQ(outer.iou, 200.0 / 1000.0);
  // RGBA: alpha is the mask by default.
  const SilhouetteStats rgba = *silhouette_coverage(rect_mask(64, 32, 10, 10, 20, 10, 4), rect_mask(64, 32, 15, 10, 20, 10, 4));
  EXPECT_DOUBLE_EQ(rgba.coverage, 0.75);
  // Empty masks.
  const Image empty(64, 32, 1);
  EXPECT_DOUBLE_EQ(silhouette_coverage(empty, ref)->coverage, 1.0);
  EXPECT_DOUBLE_EQ(silhouette_coverage(empty, empty)->iou, 1.0);
  EXPECT_DOUBLE_EQ(silhouette_coverage(ref, empty)->coverage, 0.0);
  // Threshold and channel choice.
  EXPECT_EQ(silhouette_coverage(ref, test, {.channel = 0, .threshold = 1.0f})->reference_pixels, 0u);
  const Result<SilhouetteStats> bad = silhouette_coverage(ref, test, {.channel = 3});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("channel 3"), std::string::npos) << bad.error().message;
}

TEST(ImageMetrics, MaskFromBackgroundColour) {
  Image img(16, 8, 4);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) {
      const bool fg = x >= 4 && x < 8;
      img.at(x, y, 0) = fg ? 0.2f : 1.0f;
      img.at(x, y, 1) = fg ? 0.6f : 0.0f;
      img.at(x, y, 2) = fg ? 0.1f : 1.0f;
      img.at(x, y, 3) = 1.0f;
    }
  img.at(0, 0, 1) = 0.01f;  // within tolerance: still background
  const Image mask = *mask_from_background(img, glm::vec4(1, 0, 1, 1), 0.02f);
  ASSERT_EQ(mask.channels(), 1);
  double sum = 0.0;
  for (float v : mask.data()) sum += v;
  EXPECT_EQ(sum, 4.0 * 8.0);
  EXPECT_EQ(mask.at(0, 0), 0.0f);
  EXPECT_EQ(mask.at(5, 3), 1.0f);
  EXPECT_FALSE(mask_from_background(img, glm::vec4(1, 0, 1, 1), -1.0f).ok());
}

TEST(ImageMetrics, DifferenceImages) {
  Image a = filled(8, 4, 2, 0.5f);
  Image b = a;
  b.at(3, 2, 1) = 0.25f;
  b.at(7, 3, 0) = 1.0f;
  const Image d = *difference_image(a, b, 2.0f);
  ASSERT_EQ(d.channels(), 2);
  EXPECT_EQ(d.at(3, 2, 1), 0.5f);
  EXPECT_EQ(d.at(7, 3, 0), 1.0f);
  EXPECT_EQ(d.at(0, 0, 0), 0.0f);
  const Image h = *difference_heatmap(a, b, 0.5f);
  ASSERT_EQ(h.channels(), 3);
  EXPECT_EQ(h.at(0, 0, 0), 0.0f);  // identical: black
  EXPECT_EQ(h.at(7, 3, 2), 1.0f);  // at max_error: white
  EXPECT_GT(h.at(3, 2, 0), 0.0f);  // half of max: red rising
  EXPECT_LT(h.at(3, 2, 2), 1.0f);
  EXPECT_FALSE(difference_heatmap(a, b, 0.0f).ok());
  EXPECT_FALSE(difference_image(a, b, std::numeric_limits<float>::quiet_NaN()).ok());
}

TEST(ImageMetrics, ErrorsNameBothSizes) {
  const Image a = filled(64, 32, 3, 0.5f);
  const Image taller = filled(64, 33, 3, 0.5f);
  const Image rgba = filled(64, 32, 4, 0.5f);
  for (const Image* other : {&taller, &rgba}) {
    const Result<double> r = rmse(a, *other);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, ErrorCode::kInvalidArgument);
    EXPECT_NE(r.error().message.find("64x32x3"), std::string::npos) << r.error().message;
    const std::string other_size = fmt::format("{}x{}x{}", other->width(), other->height(), other->channels());
    EXPECT_NE(r.error().message.find(other_size), std::string::npos) << r.error().message;
    EXPECT_FALSE(psnr(a, *other).ok());
    EXPECT_FALSE(ssim(a, *other).ok());
    EXPECT_FALSE(share_exceeding(a, *other, 0.1f).ok());
    EXPECT_FALSE(silhouette_coverage(a, *other).ok());
    EXPECT_FALSE(difference_image(a, *other).ok());
  }
  const Result<double> empty = rmse(Image(), a);
  ASSERT_FALSE(empty.ok());
  EXPECT_NE(empty.error().message.find("empty"), std::string::npos);

  Image nan_image = a;
  nan_image.at(5, 7, 1) = std::numeric_limits<float>::quiet_NaN();
  nan_image.at(9, 7, 0) = std::numeric_limits<float>::infinity();
  const Result<SsimResult> n = ssim(a, nan_image);
  ASSERT_FALSE(n.ok());
  EXPECT_NE(n.error().message.find("2 NaN/Inf"), std::string::npos) << n.error().message;
  EXPECT_NE(n.error().message.find("(5, 7)"), std::string::npos) << n.error().message;

  EXPECT_FALSE(psnr(a, a, 0.0).ok());
  EXPECT_FALSE(share_exceeding(a, a, -0.1f).ok());
  EXPECT_FALSE(ssim(a, a, {.dynamic_range = 0.0}).ok());
}

}  // namespace
}  // namespace sylva

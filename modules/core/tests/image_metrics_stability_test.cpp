// Image metrics on extreme inputs. Invariants checked:
//  - MetricsStayFiniteAndInRange: HDR values up to 1e30, negative values, denormals and all-zero
//    images give finite RMSE, PSNR (finite or +inf for identical), SSIM in [-1, 1].
//  - DegenerateSizesWork: 1x1, 1xN and Nx1 images work with truncated SSIM windows and are
//    refused (not crashed on) by valid-window SSIM.
#include <sylva/core/image_metrics.hpp>
#include <sylva/core/rng.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace sylva {
namespace {

void expect_sane(const Image& a, const Image& b, const char* what) {
  const Result<double> r = rmse(a, b);
  ASSERT_TRUE(r.ok()) << what;
  EXPECT_TRUE(std::isfinite(*r)) << what;
  const Result<double> p = psnr(a, b);
  ASSERT_TRUE(p.ok()) << what;
  EXPECT_FALSE(std::isnan(*p)) << what;
  for (SsimBorder border : {SsimBorder::kValid, SsimBorder::kTruncated}) {
    const Result<SsimResult> s = ssim(a, b, {.border = border});
    ASSERT_TRUE(s.ok()) << what;
    EXPECT_TRUE(std::isfinite(s->mean)) << what;
    EXPECT_GE(s->mean, -1.0) << what;
    EXPECT_LE(s->mean, 1.0) << what;
    for (float v : s->map.data()) {
      ASSERT_TRUE(std::isfinite(v) && v >= -1.0f && v <= 1.0f) << what << ": map value " << v;
    }
  }
}

TEST(ImageMetricsStability, MetricsStayFiniteAndInRange) {
  Pcg32 rng(3u);
  Image hdr_a(24, 20, 3);
  Image hdr_b(24, 20, 3);
  for (std::size_t i = 0; i < hdr_a.data().size(); ++i) {
    hdr_a.data()[i] = rng.uniform(-1e30f, 1e30f);
    hdr_b.data()[i] = rng.uniform(-1e30f, 1e30f);
  }
  expect_sane(hdr_a, hdr_b, "HDR 1e30");
  expect_sane(hdr_a, hdr_a, "HDR identical");

  Image zeros(16, 16, 1);
  expect_sane(zeros, zeros, "all zero");
  EXPECT_EQ(ssim(zeros, zeros)->mean, 1.0);

  Image denorm = zeros;
  for (float& v : denorm.data()) v = std::numeric_limits<float>::denorm_min();
  expect_sane(zeros, denorm, "denormals");

  Image neg(16, 16, 2);
  for (float& v : neg.data()) v = rng.uniform(-5.0f, -1.0f);
  Image pos = neg;
  for (float& v : pos.data()) v = -v;
  expect_sane(neg, pos, "negative vs positive");
}

TEST(ImageMetricsStability, DegenerateSizesWork) {
  for (auto [w, h] : {std::pair{1, 1}, std::pair{1, 57}, std::pair{57, 1}, std::pair{2, 2}}) {
    Image a(w, h, 3);
    Image b(w, h, 3);
    Pcg32 rng(static_cast<std::uint64_t>(w * 100 + h));
    for (float& v : a.data()) v = rng.next_float();
    for (float& v : b.data()) v = rng.next_float();
    const Result<SsimResult> t = ssim(a, b, {.border = SsimBorder::kTruncated});
    ASSERT_TRUE(t.ok()) << w << "x" << h;
    EXPECT_TRUE(std::isfinite(t->mean));
    EXPECT_EQ(t->map.width(), w);
    EXPECT_EQ(t->map.height(), h);
    EXPECT_EQ(ssim(a, a, {.border = SsimBorder::kTruncated})->mean, 1.0);
    EXPECT_FALSE(ssim(a, b).ok()) << "kValid must refuse " << w << "x" << h;
    EXPECT_TRUE(rmse(a, b).ok());
    EXPECT_TRUE(silhouette_coverage(a, b).ok());
  }
}

}  // namespace
}  // namespace sylva

#include <sylva/core/image_metrics.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace sylva {

namespace {

std::string describe_size(const Image& image) {
  return fmt::format("{}x{}x{}", image.width(), image.height(), image.channels());
}

Status check_one(const Image& image, const char* role) {
  if (image.empty()) return make_error(ErrorCode::kInvalidArgument, fmt::format("image metrics: the {} image is empty", role));
  const NonFiniteReport report = find_non_finite(image);
  if (report.count > 0) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("image metrics: the {} image ({}) holds {} NaN/Inf value(s), the first at pixel ({}, {})",
                                  role, describe_size(image), report.count, report.first_x, report.first_y));
  }
  return ok_status();
}

Status check_pair(const Image& a, const Image& b) {
  SYLVA_TRY(check_one(a, "first"));
  SYLVA_TRY(check_one(b, "second"));
  if (a.width() != b.width() || a.height() != b.height() || a.channels() != b.channels()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("image metrics: image sizes differ: {} vs {} (width x height x channels)",
                                  describe_size(a), describe_size(b)));
  }
  return ok_status();
}

// ---- SSIM ------------------------------------------------------------------------------------

constexpr int kWindow = 11;
constexpr int kRadius = kWindow / 2;
constexpr double kSigma = 1.5;
constexpr double kK1 = 0.01;
constexpr double kK2 = 0.03;

std::array<double, kWindow> gaussian_taps() {
  std::array<double, kWindow> w{};
  double sum = 0.0;
  for (int i = 0; i < kWindow; ++i) {
    const double x = i - kRadius;
    w[static_cast<std::size_t>(i)] = std::exp(-(x * x) / (2.0 * kSigma * kSigma));
    sum += w[static_cast<std::size_t>(i)];
  }
  std::array<double, kWindow> taps{};
  for (int i = 0; i < kWindow; ++i) taps[static_cast<std::size_t>(i)] = w[static_cast<std::size_t>(i)] / sum;
  return taps;
}

struct Plane {
  int width = 0;
  int height = 0;
  std::vector<float> v;
  float at(int x, int y) const { return v[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)]; }
};

// Extracts the planes SSIM compares.
std::vector<Plane> ssim_planes(const Image& image, SsimChannels mode) {
  const int w = image.width();
  const int h = image.height();
  const int ch = image.channels();
  std::vector<Plane> planes;
  auto make_plane = [&](auto value_of) {
    Plane p{w, h, std::vector<float>(static_cast<std::size_t>(w) * static_cast<std::size_t>(h))};
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) p.v[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] = value_of(x, y);
    planes.push_back(std::move(p));
  };
  if (mode == SsimChannels::kPerChannel) {
    for (int c = 0; c < ch; ++c) make_plane([&](int x, int y) { return image.at(x, y, c); });
  } else if (ch >= 3) {
    make_plane([&](int x, int y) {
      return 0.2126f * image.at(x, y, 0) + 0.7152f * image.at(x, y, 1) + 0.0722f * image.at(x, y, 2);
    });
  } else {
    make_plane([&](int x, int y) { return image.at(x, y, 0); });
  }
  return planes;
}

double plane_mean(const Plane& p) {
  double sum = 0.0;
  for (float v : p.v) sum += v;
  return sum / static_cast<double>(p.v.size());
}

// Separable Gaussian filtering of the five moments x, y, x^2, y^2, xy and the SSIM map of one
// plane pair, accumulated in double. The planes are shifted by their global means first so that
// the variance terms E[x^2] - E[x]^2 do not cancel catastrophically, and rounding-negative
// variances are clamped to 0 so HDR values stay finite.
std::vector<float> ssim_plane(const Plane& px, const Plane& py, SsimBorder border, double dynamic_range,
                              int out_w, int out_h) {
  static const std::array<double, kWindow> taps = gaussian_taps();
  const int w = px.width;
  const int h = px.height;
  const double ox = plane_mean(px);
  const double oy = plane_mean(py);
  const bool valid = border == SsimBorder::kValid;
  // Output pixel (u, v) is centred on input (u + shift, v + shift).
  const int shift = valid ? kRadius : 0;

  // Horizontal pass: 5 moments for out_w columns x h rows.
  const std::size_t hsize = static_cast<std::size_t>(out_w) * static_cast<std::size_t>(h);
  std::array<std::vector<double>, 5> hm;
  for (auto& m : hm) m.assign(hsize, 0.0);
  for (int y = 0; y < h; ++y) {
    for (int u = 0; u < out_w; ++u) {
      const int cx = u + shift;
      const int lo = std::max(-kRadius, -cx);
      const int hi = std::min(kRadius, w - 1 - cx);
      double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0, wsum = 0;
      for (int k = lo; k <= hi; ++k) {
        const double t = taps[static_cast<std::size_t>(k + kRadius)];
        const double a = static_cast<double>(px.at(cx + k, y)) - ox;
        const double b = static_cast<double>(py.at(cx + k, y)) - oy;
        sx += t * a;
        sy += t * b;
        sxx += t * a * a;
        syy += t * b * b;
        sxy += t * a * b;
        wsum += t;
      }
      const double inv = valid ? 1.0 : 1.0 / wsum;
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(out_w) + static_cast<std::size_t>(u);
      hm[0][i] = sx * inv;
      hm[1][i] = sy * inv;
      hm[2][i] = sxx * inv;
      hm[3][i] = syy * inv;
      hm[4][i] = sxy * inv;
    }
  }

  const double c1 = (kK1 * dynamic_range) * (kK1 * dynamic_range);
  const double c2 = (kK2 * dynamic_range) * (kK2 * dynamic_range);
  std::vector<float> map(static_cast<std::size_t>(out_w) * static_cast<std::size_t>(out_h));
  for (int v = 0; v < out_h; ++v) {
    const int cy = v + shift;
    const int lo = std::max(-kRadius, -cy);
    const int hi = std::min(kRadius, h - 1 - cy);
    for (int u = 0; u < out_w; ++u) {
      double m[5] = {0, 0, 0, 0, 0};
      double wsum = 0;
      for (int k = lo; k <= hi; ++k) {
        const double t = taps[static_cast<std::size_t>(k + kRadius)];
        const std::size_t i = static_cast<std::size_t>(cy + k) * static_cast<std::size_t>(out_w) + static_cast<std::size_t>(u);
        for (int q = 0; q < 5; ++q) m[q] += t * hm[static_cast<std::size_t>(q)][i];
        wsum += t;
      }
      if (!valid)
        for (double& q : m) q /= wsum;
      const double mx = m[0] + ox;
      const double my = m[1] + oy;
      const double vx = std::max(0.0, m[2] - m[0] * m[0]);
      const double vy = std::max(0.0, m[3] - m[1] * m[1]);
      const double cxy = m[4] - m[0] * m[1];
      const double num = (2.0 * mx * my + c1) * (2.0 * cxy + c2);
      const double den = (mx * mx + my * my + c1) * (vx + vy + c2);
      map[static_cast<std::size_t>(v) * static_cast<std::size_t>(out_w) + static_cast<std::size_t>(u)] =
          static_cast<float>(std::clamp(num / den, -1.0, 1.0));
    }
  }
  return map;
}

bool mask_at(const Image& image, int x, int y, int channel, float threshold) {
  return image.at(x, y, channel) > threshold;
}

}  // namespace

Result<double> mse(const Image& a, const Image& b) {
  SYLVA_TRY(check_pair(a, b));
  const auto da = a.data();
  const auto db = b.data();
  double sum = 0.0;
  for (std::size_t i = 0; i < da.size(); ++i) {
    const double d = static_cast<double>(da[i]) - static_cast<double>(db[i]);
    sum += d * d;
  }
  return sum / static_cast<double>(da.size());
}

Result<double> rmse(const Image& a, const Image& b) {
  Result<double> m = mse(a, b);
  if (!m) return m.error();
  return std::sqrt(*m);
}

Result<double> psnr(const Image& a, const Image& b, double peak) {
  if (!(peak > 0.0) || !std::isfinite(peak))
    return make_error(ErrorCode::kInvalidArgument, fmt::format("psnr: peak must be a finite value > 0, got {}", peak));
  Result<double> m = mse(a, b);
  if (!m) return m.error();
  if (*m == 0.0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(peak * peak / *m);
}

Result<SsimResult> ssim(const Image& a, const Image& b, const SsimOptions& options) {
  SYLVA_TRY(check_pair(a, b));
  if (!(options.dynamic_range > 0.0) || !std::isfinite(options.dynamic_range)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("ssim: dynamic_range must be a finite value > 0, got {}", options.dynamic_range));
  }
  const bool valid = options.border == SsimBorder::kValid;
  if (valid && (a.width() < kWindow || a.height() < kWindow)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("ssim: image {} is smaller than the 11x11 window; use SsimBorder::kTruncated for "
                                  "small images",
                                  describe_size(a)));
  }
  const int out_w = valid ? a.width() - 2 * kRadius : a.width();
  const int out_h = valid ? a.height() - 2 * kRadius : a.height();
  const std::vector<Plane> pa = ssim_planes(a, options.channels);
  const std::vector<Plane> pb = ssim_planes(b, options.channels);
  const int planes = static_cast<int>(pa.size());

  SsimResult result;
  result.map = Image(out_w, out_h, planes);
  double total = 0.0;
  for (int p = 0; p < planes; ++p) {
    const std::vector<float> map = ssim_plane(pa[static_cast<std::size_t>(p)], pb[static_cast<std::size_t>(p)],
                                              options.border, options.dynamic_range, out_w, out_h);
    double sum = 0.0;
    for (int y = 0; y < out_h; ++y) {
      for (int x = 0; x < out_w; ++x) {
        const float s = map[static_cast<std::size_t>(y) * static_cast<std::size_t>(out_w) + static_cast<std::size_t>(x)];
        result.map.at(x, y, p) = s;
        sum += s;
      }
    }
    const double mean = sum / (static_cast<double>(out_w) * static_cast<double>(out_h));
    result.per_channel.push_back(mean);
    total += mean;
  }
  result.mean = total / planes;
  return result;
}

Result<DifferenceCount> count_exceeding(const Image& a, const Image& b, float threshold) {
  if (!(threshold >= 0.0f) || !std::isfinite(threshold)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("count_exceeding: threshold must be a finite value >= 0, got {}", threshold));
  }
  SYLVA_TRY(check_pair(a, b));
  DifferenceCount out;
  out.total = a.pixel_count();
  const int ch = a.channels();
  const auto da = a.data();
  const auto db = b.data();
  for (std::size_t px = 0; px < out.total; ++px) {
    float worst = 0.0f;
    for (int c = 0; c < ch; ++c) {
      const std::size_t i = px * static_cast<std::size_t>(ch) + static_cast<std::size_t>(c);
      worst = std::max(worst, std::abs(da[i] - db[i]));
    }
    out.max_difference = std::max(out.max_difference, worst);
    if (worst > threshold) ++out.pixels;
  }
  out.share = static_cast<double>(out.pixels) / static_cast<double>(out.total);
  return out;
}

Result<double> share_exceeding(const Image& a, const Image& b, float threshold) {
  Result<DifferenceCount> c = count_exceeding(a, b, threshold);
  if (!c) return c.error();
  return c->share;
}

Result<SilhouetteStats> silhouette_coverage(const Image& reference, const Image& test, const MaskOptions& options) {
  SYLVA_TRY(check_pair(reference, test));
  const int ch = reference.channels();
  int channel = options.channel;
  if (channel < 0) channel = (ch == 2 || ch == 4) ? ch - 1 : 0;
  if (channel >= ch) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("silhouette_coverage: mask channel {} does not exist in {} images", channel,
                                  describe_size(reference)));
  }
  if (!std::isfinite(options.threshold)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("silhouette_coverage: threshold must be finite, got {}", options.threshold));
  }
  SilhouetteStats s;
  for (int y = 0; y < reference.height(); ++y) {
    for (int x = 0; x < reference.width(); ++x) {
      const bool r = mask_at(reference, x, y, channel, options.threshold);
      const bool t = mask_at(test, x, y, channel, options.threshold);
      s.reference_pixels += r ? 1u : 0u;
      s.test_pixels += t ? 1u : 0u;
      s.intersection += (r && t) ? 1u : 0u;
      s.union_pixels += (r || t) ? 1u : 0u;
    }
  }
  s.coverage = s.reference_pixels == 0 ? 1.0 : static_cast<double>(s.intersection) / static_cast<double>(s.reference_pixels);
  s.iou = s.union_pixels == 0 ? 1.0 : static_cast<double>(s.intersection) / static_cast<double>(s.union_pixels);
  return s;
}

Result<Image> mask_from_background(const Image& image, glm::vec4 background, float tolerance) {
  if (!(tolerance >= 0.0f) || !std::isfinite(tolerance)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("mask_from_background: tolerance must be a finite value >= 0, got {}", tolerance));
  }
  SYLVA_TRY(check_one(image, "input"));
  const int compared = std::min(image.channels(), 4);
  Image mask(image.width(), image.height(), 1);
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      bool differs = false;
      for (int c = 0; c < compared; ++c) differs = differs || std::abs(image.at(x, y, c) - background[c]) > tolerance;
      mask.at(x, y) = differs ? 1.0f : 0.0f;
    }
  }
  return mask;
}

Result<Image> difference_image(const Image& a, const Image& b, float gain) {
  if (!(gain >= 0.0f) || !std::isfinite(gain)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("difference_image: gain must be a finite value >= 0, got {}", gain));
  }
  SYLVA_TRY(check_pair(a, b));
  Image out(a.width(), a.height(), a.channels());
  const auto da = a.data();
  const auto db = b.data();
  auto dst = out.data();
  for (std::size_t i = 0; i < da.size(); ++i) dst[i] = std::abs(da[i] - db[i]) * gain;
  return out;
}

Result<Image> difference_heatmap(const Image& a, const Image& b, float max_error) {
  if (!(max_error > 0.0f) || !std::isfinite(max_error)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("difference_heatmap: max_error must be a finite value > 0, got {}", max_error));
  }
  SYLVA_TRY(check_pair(a, b));
  Image out(a.width(), a.height(), 3);
  const int ch = a.channels();
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      float worst = 0.0f;
      for (int c = 0; c < ch; ++c) worst = std::max(worst, std::abs(a.at(x, y, c) - b.at(x, y, c)));
      const float t = std::min(worst / max_error, 1.0f);
      out.at(x, y, 0) = std::clamp(3.0f * t, 0.0f, 1.0f);
      out.at(x, y, 1) = std::clamp(3.0f * t - 1.0f, 0.0f, 1.0f);
      out.at(x, y, 2) = std::clamp(3.0f * t - 2.0f, 0.0f, 1.0f);
    }
  }
  return out;
}

}  // namespace sylva

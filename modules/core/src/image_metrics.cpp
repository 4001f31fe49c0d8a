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
};

// Extracts the planes SSIM compares.
std::vector<Plane> ssim_planes(const Image& image, SsimChannels mode) {
  const std::size_t pixels = image.pixel_count();
  const auto ch = static_cast<std::size_t>(image.channels());
  const std::span<const float> src = image.data();
  std::vector<Plane> planes;
  auto make_plane = [&](auto value_of) {
    Plane p{image.width(), image.height(), std::vector<float>(pixels)};
    for (std::size_t i = 0; i < pixels; ++i) p.v[i] = value_of(src.data() + i * ch);
    planes.push_back(std::move(p));
  };
  if (mode == SsimChannels::kPerChannel) {
    for (std::size_t c = 0; c < ch; ++c) make_plane([c](const float* px) { return px[c]; });
  } else if (ch >= 3) {
    make_plane([](const float* px) { return 0.2126f * px[0] + 0.7152f * px[1] + 0.0722f * px[2]; });
  } else {
    make_plane([](const float* px) { return px[0]; });
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

  // Horizontal pass: 5 moments for out_w columns x h rows. Each row of moments is written into
  // zero-padded buffers (kRadius zeros on both sides) so the filter is a plain contiguous
  // convolution; in kTruncated mode the zeros drop out of the sum and hnorm renormalises.
  const auto width = static_cast<std::size_t>(out_w);
  const auto in_w = static_cast<std::size_t>(w);
  std::vector<double> hnorm(width, 1.0);
  if (!valid) {
    for (std::size_t u = 0; u < width; ++u) {
      double wsum = 0.0;
      for (int k = -kRadius; k <= kRadius; ++k) {
        const long x = static_cast<long>(u) + k;
        if (x >= 0 && x < static_cast<long>(in_w)) wsum += taps[static_cast<std::size_t>(k + kRadius)];
      }
      hnorm[u] = 1.0 / wsum;
    }
  }
  std::array<std::vector<double>, 5> padded;
  for (auto& row : padded) row.assign(in_w + 2 * kRadius, 0.0);
  // Horizontal rows live in a ring of kWindow rows (all the vertical window needs), so the
  // working set stays in cache instead of streaming five full-image planes.
  std::array<std::vector<double>, 5> ring;
  for (auto& m : ring) m.assign(width * kWindow, 0.0);
  const auto start = static_cast<std::size_t>(shift);  // padded index of the first window
  auto horizontal_row = [&](int y) {
    const float* ra = px.v.data() + static_cast<std::size_t>(y) * in_w;
    const float* rb = py.v.data() + static_cast<std::size_t>(y) * in_w;
    for (std::size_t x = 0; x < in_w; ++x) {
      const double a = static_cast<double>(ra[x]) - ox;
      const double b = static_cast<double>(rb[x]) - oy;
      const std::size_t i = x + kRadius;
      padded[0][i] = a;
      padded[1][i] = b;
      padded[2][i] = a * a;
      padded[3][i] = b * b;
      padded[4][i] = a * b;
    }
    const std::size_t slot = static_cast<std::size_t>(y % kWindow) * width;
    for (std::size_t q = 0; q < 5; ++q) {
      double* dst = ring[q].data() + slot;
      std::fill(dst, dst + width, 0.0);
      const double* src = padded[q].data() + start;
      for (int k = 0; k < kWindow; ++k) {
        const double t = taps[static_cast<std::size_t>(k)];
        const double* sk = src + k;
        for (std::size_t u = 0; u < width; ++u) dst[u] += t * sk[u];
      }
      if (!valid)
        for (std::size_t u = 0; u < width; ++u) dst[u] *= hnorm[u];
    }
  };
  int rows_done = 0;

  const double c1 = (kK1 * dynamic_range) * (kK1 * dynamic_range);
  const double c2 = (kK2 * dynamic_range) * (kK2 * dynamic_range);
  std::vector<float> map(static_cast<std::size_t>(out_w) * static_cast<std::size_t>(out_h));
  // Vertical pass row by row (contiguous, vectorisable): acc[q][u] = sum_k tap_k * ring[q][row + k].
  std::array<std::vector<double>, 5> acc;
  for (auto& a : acc) a.resize(width);
  for (int v = 0; v < out_h; ++v) {
    const int cy = v + shift;
    const int lo = std::max(-kRadius, -cy);
    const int hi = std::min(kRadius, h - 1 - cy);
    while (rows_done <= cy + hi) horizontal_row(rows_done++);
    for (auto& a : acc) std::fill(a.begin(), a.end(), 0.0);
    double wsum = 0.0;
    for (int k = lo; k <= hi; ++k) {
      const double t = taps[static_cast<std::size_t>(k + kRadius)];
      const std::size_t row = static_cast<std::size_t>((cy + k) % kWindow) * width;
      for (std::size_t q = 0; q < 5; ++q) {
        const double* src = ring[q].data() + row;
        double* dst = acc[q].data();
        for (std::size_t u = 0; u < width; ++u) dst[u] += t * src[u];
      }
      wsum += t;
    }
    const double inv = valid ? 1.0 : 1.0 / wsum;
    float* out = map.data() + static_cast<std::size_t>(v) * width;
    for (std::size_t u = 0; u < width; ++u) {
      const double m0 = acc[0][u] * inv;
      const double m1 = acc[1][u] * inv;
      const double mx = m0 + ox;
      const double my = m1 + oy;
      const double vx = std::max(0.0, acc[2][u] * inv - m0 * m0);
      const double vy = std::max(0.0, acc[3][u] * inv - m1 * m1);
      const double cxy = acc[4][u] * inv - m0 * m1;
      const double num = (2.0 * mx * my + c1) * (2.0 * cxy + c2);
      const double den = (mx * mx + my * my + c1) * (vx + vy + c2);
      out[u] = static_cast<float>(std::clamp(num / den, -1.0, 1.0));
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

#include <sylva/vegetation/bending.hpp>

#include <sylva/core/assert.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <utility>
#include <vector>

namespace sylva::vegetation {
namespace {

constexpr int kOdeSteps = 4000;
constexpr int kFitSamples = 401;  // the ODE grid holds every 10th step as a fit sample

double clamp_alpha(double alpha) {
  if (!std::isfinite(alpha)) return 1.0;
  return std::clamp(alpha, 0.02, 4.0);
}

// u'' of the tapered cantilever under a uniform load (see bending.hpp).
double curvature(double alpha, double t) {
  const double y = 1.0 + (alpha - 1.0) * t;
  const double y2 = y * y;
  return (2.0 / std::numbers::pi) * (1.0 - t) * (1.0 - t) / (y2 * y2);
}

// Integrates u'' twice from 0 to x_end with kOdeSteps Simpson steps; calls out(i, u) after step i.
template <class Out>
void integrate_shape(double alpha, double x_end, Out&& out) {
  const double h = x_end / kOdeSteps;
  double du = 0.0;
  double u = 0.0;
  for (int i = 0; i < kOdeSteps; ++i) {
    const double t = i * h;
    const double f0 = curvature(alpha, t);
    const double fm = curvature(alpha, t + 0.5 * h);
    const double f1 = curvature(alpha, t + h);
    const double du_new = du + h * (f0 + 4.0 * fm + f1) / 6.0;
    const double du_mid = du + h * (5.0 * f0 + 8.0 * fm - f1) / 24.0;
    u += h * (du + 4.0 * du_mid + du_new) / 6.0;
    du = du_new;
    out(i + 1, u);
  }
}

}  // namespace

double cantilever_shape(double alpha, double x) {
  alpha = clamp_alpha(alpha);
  x = std::clamp(std::isfinite(x) ? x : 0.0, 0.0, 1.0);
  if (x == 0.0) return 0.0;
  double result = 0.0;
  integrate_shape(alpha, x, [&](int, double u) { result = u; });
  return result;
}

double cantilever_shape_closed_form(double alpha, double x) {
  const double a = alpha - 1.0;
  const double y = 1.0 + x * a;
  const double bracket =
      x * a * (6.0 + x * a * (2.0 * x * a * (3.0 + (alpha - 3.0) * alpha) + 3.0 * (4.0 + (alpha - 2.0) * alpha))) -
      6.0 * y * y * std::log(y);
  return bracket / (3.0 * std::numbers::pi * y * y * a * a * a * a);
}

BendConstants fit_bend_constants(double alpha) {
  alpha = clamp_alpha(alpha);
  std::vector<double> samples(kFitSamples, 0.0);
  constexpr int kStride = kOdeSteps / (kFitSamples - 1);
  static_assert(kStride * (kFitSamples - 1) == kOdeSteps);
  integrate_shape(alpha, 1.0, [&](int i, double u) {
    if (i % kStride == 0) samples[static_cast<std::size_t>(i / kStride)] = u;
  });
  // Normal equations of min sum (c2 x^2 + c4 x^4 - u)^2.
  double s22 = 0.0, s24 = 0.0, s44 = 0.0, b2 = 0.0, b4 = 0.0;
  for (int i = 0; i < kFitSamples; ++i) {
    const double x = static_cast<double>(i) / (kFitSamples - 1);
    const double p2 = x * x;
    const double p4 = p2 * p2;
    const double u = samples[static_cast<std::size_t>(i)];
    s22 += p2 * p2;
    s24 += p2 * p4;
    s44 += p4 * p4;
    b2 += p2 * u;
    b4 += p4 * u;
  }
  const double det = s22 * s44 - s24 * s24;
  return {static_cast<float>((b2 * s44 - b4 * s24) / det), static_cast<float>((s22 * b4 - s24 * b2) / det)};
}

namespace {

int taper_bucket(float alpha) {
  const double a = clamp_alpha(static_cast<double>(alpha));
  return static_cast<int>(std::lround(a * 1000.0));
}

std::mutex& cache_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace

BendConstants bend_constants_for_taper(float alpha) {
  static std::map<int, BendConstants> cache;
  const int bucket = taper_bucket(alpha);
  {
    std::lock_guard lock(cache_mutex());
    if (auto it = cache.find(bucket); it != cache.end()) return it->second;
  }
  const BendConstants c = fit_bend_constants(bucket / 1000.0);
  std::lock_guard lock(cache_mutex());
  cache.emplace(bucket, c);
  return c;
}

double corrected_axis_length(float c2, float c4, float a, float eps, int samples) {
  SYLVA_ASSERT(samples >= 1, "samples={}", samples);
  double length = 0.0;
  BendPoint prev = bend_profile(0.0f, a, c2, c4, eps);
  for (int i = 1; i <= samples; ++i) {
    const float x = static_cast<float>(i) / static_cast<float>(samples);
    const BendPoint p = bend_profile(x, a, c2, c4, eps);
    length += std::hypot(static_cast<double>(p.along) - prev.along, static_cast<double>(p.across) - prev.across);
    prev = p;
  }
  return length;
}

float bend_amplitude_limit(float c2, float c4, float max_length_error) {
  SYLVA_ASSERT(max_length_error > 0.0f && max_length_error <= 0.5f, "max_length_error={}", max_length_error);
  constexpr float kCap = 50.0f;
  const auto within = [&](float a) {
    const double len = corrected_axis_length(c2, c4, a);
    return std::isfinite(len) && std::fabs(len - 1.0) <= max_length_error;
  };
  float good = 0.0f;
  float bad = -1.0f;
  for (float a = 1.0e-3f; a <= kCap; a *= 1.1f) {
    if (!within(a)) {
      bad = a;
      break;
    }
    good = a;
  }
  if (bad < 0.0f) return kCap;
  while (bad - good > 1.0e-4f * bad) {
    const float mid = 0.5f * (good + bad);
    (within(mid) ? good : bad) = mid;
  }
  return std::max(good, 1.0e-4f);
}

float bend_amplitude_limit_for_taper(float alpha, float max_length_error) {
  static std::map<std::pair<int, float>, float> cache;
  const std::pair<int, float> key{taper_bucket(alpha), max_length_error};
  {
    std::lock_guard lock(cache_mutex());
    if (auto it = cache.find(key); it != cache.end()) return it->second;
  }
  const BendConstants c = bend_constants_for_taper(alpha);
  const float limit = bend_amplitude_limit(c.c2, c.c4, max_length_error);
  std::lock_guard lock(cache_mutex());
  cache.emplace(key, limit);
  return limit;
}

}  // namespace sylva::vegetation

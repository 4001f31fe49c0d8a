// Stability cases of core (wind, noise, metrics, parameters), built from its public API.
#include "ground_target.hpp"
#include "stability.hpp"

#include <sylva/core/image_metrics.hpp>
#include <sylva/core/noise.hpp>
#include <sylva/core/params.hpp>
#include <sylva/core/wind.hpp>

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace sylva::bench {
namespace {

std::uint64_t count_non_finite(const glm::vec3& v) {
  return static_cast<std::uint64_t>(!std::isfinite(v.x)) + !std::isfinite(v.y) + !std::isfinite(v.z);
}

StabilityOutcome wind_hurricane() {
  WindSettings s;
  s.strength = 100.0f;
  s.gust_amplitude = 100.0f;
  s.turbulence_amplitude = 100.0f;
  s.turbulence_scale = 0.05f;
  s.gust_period = 0.1f;
  const WindField wind(s);
  const float bound = wind.max_speed();
  StabilityOutcome o;
  float worst = 0.0f;
  for (double t : {0.0, 1e-3, 1.0, 1e4, 1e7, 1e9}) {
    for (double x : {0.0, 1.0, 1e4, 1e6, 1e9}) {
      const glm::vec3 v = wind.evaluate(glm::dvec3(x, 10.0, -x), t);
      o.nan_count += count_non_finite(v);
      if (std::isfinite(glm::length(v))) worst = std::max(worst, glm::length(v));
    }
  }
  o.passed = worst <= bound * 1.0001f;
  o.detail = fmt::format("max |v| {:.2f} m/s, bound {:.2f} m/s over t up to 1e9 s and |x| up to 1e9 m", worst, bound);
  return o;
}

StabilityOutcome wind_continuity_late() {
  const WindField wind(WindSettings{});
  StabilityOutcome o;
  float worst = 0.0f;
  for (double t0 : {1e6, 1e7}) {
    for (int k = 0; k < 100; ++k) {
      const double t = t0 + k * 0.37;
      const glm::vec3 a = wind.evaluate(glm::dvec3(12.0, 3.0, -7.0), t);
      const glm::vec3 b = wind.evaluate(glm::dvec3(12.0, 3.0, -7.0), t + 1.0 / 120.0);
      o.nan_count += count_non_finite(a) + count_non_finite(b);
      worst = std::max(worst, glm::length(a - b));
    }
  }
  const float bound = 0.05f * wind.max_speed();
  o.passed = worst <= bound;
  o.detail = fmt::format("largest change over 1/120 s at t ~ 1e7 s: {:.4f} m/s (allowed {:.3f})", worst, bound);
  return o;
}

StabilityOutcome noise_far() {
  StabilityOutcome o;
  FbmSettings fbm;
  float lo = 1.0f, hi = -1.0f;
  for (double x : {0.0, 1e5, 1e8, 1e12, -1e12}) {
    for (double z : {0.5, 1e7, -3e9}) {
      const float f = fbm2(glm::dvec2(x, z), fbm);
      const float r = ridged2(glm::dvec2(x, z), fbm);
      o.nan_count += !std::isfinite(f) + !std::isfinite(r);
      lo = std::min({lo, f, r});
      hi = std::max({hi, f, r});
    }
  }
  o.passed = lo >= -1.0f && hi <= 1.0f;
  o.detail = fmt::format("fBm and ridged at |p| up to 1e12: values in [{:.3f}, {:.3f}]", lo, hi);
  return o;
}

StabilityOutcome metrics_reject_nan() {
  Image a(16, 16, 3), b(16, 16, 3);
  b.at(3, 4, 1) = std::numeric_limits<float>::quiet_NaN();
  StabilityOutcome o;
  auto p = psnr(a, b);
  auto s = ssim(a, b);
  o.passed = !p.ok() && !s.ok();
  o.detail = p.ok() ? fmt::format("psnr returned {} instead of an error", *p) : "error: " + p.error().message;
  return o;
}

StabilityOutcome params_reject_non_finite() {
  GroundTargetSettings s;
  const float before = s.ground.height;
  StabilityOutcome o;
  const Status nan = set_param(s, "ground.height", "nan");
  const Status inf = set_param(s, "ground.height", "inf");
  const Status huge = set_param(s, "ground.height", "1e300");
  o.passed = !nan.ok() && !inf.ok() && !huge.ok() && s.ground.height == before;
  o.detail = nan.ok() ? "nan was accepted" : "rejected: " + nan.error().message;
  return o;
}

}  // namespace

void add_core_stability_cases(std::vector<StabilityCase>& cases) {
  cases.push_back({"core", "wind_hurricane_far", "no NaN; |wind| <= WindField::max_speed() for 100 m/s wind, t to 1e9 s, "
                   "|x| to 1e9 m", false, wind_hurricane});
  cases.push_back({"core", "wind_continuous_late", "wind changes by < 5 % of its bound over 1/120 s at t ~ 1e7 s "
                   "(no precision collapse late in a run)", false, wind_continuity_late});
  cases.push_back({"core", "noise_far_coordinates", "fBm and ridged noise stay finite and in [-1, 1] at |p| up to 1e12",
                   false, noise_far});
  cases.push_back({"core", "metrics_reject_nan", "PSNR/SSIM on an image holding NaN return an error, never a number",
                   false, metrics_reject_nan});
  cases.push_back({"core", "params_reject_non_finite", "nan, inf and out-of-range text are rejected and leave the value "
                   "unchanged", false, params_reject_non_finite});
}

}  // namespace sylva::bench

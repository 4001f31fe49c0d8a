#include <sylva/scene/camera_path.hpp>

#include <sylva/core/assert.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace sylva::scene {

float unwrap_degrees(float angle, float reference) {
  const double turns = std::round((static_cast<double>(angle) - reference) / 360.0);
  return static_cast<float>(angle - turns * 360.0);
}

double CameraPath::start_time() const { return keys.empty() ? 0.0 : keys.front().time_s; }
double CameraPath::end_time() const { return keys.empty() ? 0.0 : keys.back().time_s; }

namespace {

// The channels that are interpolated, with yaw already unwrapped.
struct Sample {
  glm::dvec3 position;
  double yaw, pitch, fov;
};

Sample operator+(const Sample& a, const Sample& b) {
  return {a.position + b.position, a.yaw + b.yaw, a.pitch + b.pitch, a.fov + b.fov};
}
Sample operator-(const Sample& a, const Sample& b) {
  return {a.position - b.position, a.yaw - b.yaw, a.pitch - b.pitch, a.fov - b.fov};
}
Sample operator*(const Sample& a, double s) { return {a.position * s, a.yaw * s, a.pitch * s, a.fov * s}; }

// Key i of a path extended periodically (loop) or by the end keys; time shifted by whole periods.
struct Extended {
  const CameraPath& path;
  std::vector<Sample> samples;  // yaw unwrapped along the keys
  bool loop;

  int size() const { return static_cast<int>(samples.size()); }
  double period() const { return path.duration(); }

  // Loop indices wrap over keys 0..n-2 (the last key closes the loop onto the first).
  double time(int i) const {
    const int n = size();
    if (!loop) return path.keys[static_cast<std::size_t>(std::clamp(i, 0, n - 1))].time_s;
    const int m = n - 1;
    const int k = ((i % m) + m) % m;
    const int wraps = (i - k) / m;
    return path.keys[static_cast<std::size_t>(k)].time_s + wraps * period();
  }
  Sample sample(int i) const {
    const int n = size();
    if (!loop) return samples[static_cast<std::size_t>(std::clamp(i, 0, n - 1))];
    const int m = n - 1;
    const int k = ((i % m) + m) % m;
    const int wraps = (i - k) / m;
    Sample s = samples[static_cast<std::size_t>(k)];
    // Keep yaw continuous across the wrap: add the net yaw change of one period per wrap.
    s.yaw += wraps * (samples.back().yaw - samples.front().yaw);
    return s;
  }
  // Finite-difference tangent (per second) at extended key i.
  Sample tangent(int i) const {
    const int n = size();
    if (!loop && i <= 0) return (sample(1) - sample(0)) * (1.0 / (time(1) - time(0)));
    if (!loop && i >= n - 1) return (sample(n - 1) - sample(n - 2)) * (1.0 / (time(n - 1) - time(n - 2)));
    return (sample(i + 1) - sample(i - 1)) * (1.0 / (time(i + 1) - time(i - 1)));
  }
};

}  // namespace

CameraView CameraPath::evaluate(double t) const {
  SYLVA_ASSERT(!keys.empty(), "evaluate() on a camera path without keys");
  CameraView out = keys.front().view;
  if (keys.size() == 1) return out;

  Extended ext{*this, {}, settings.loop && keys.size() >= 3};
  ext.samples.reserve(keys.size());
  double previous_yaw = keys.front().view.yaw_deg;
  for (const CameraKey& k : keys) {
    const double yaw = unwrap_degrees(k.view.yaw_deg, static_cast<float>(previous_yaw));
    ext.samples.push_back({k.view.position, yaw, k.view.pitch_deg, k.view.fov_deg});
    previous_yaw = yaw;
  }

  if (!std::isfinite(t)) t = start_time();
  if (ext.loop) {
    const double d = duration();
    t = start_time() + std::fmod(t - start_time(), d);
    if (t < start_time()) t += d;
  }
  t = std::clamp(t, start_time(), end_time());

  // Segment i: keys[i].time_s <= t <= keys[i + 1].time_s.
  const auto upper = std::upper_bound(keys.begin(), keys.end(), t,
                                      [](double value, const CameraKey& k) { return value < k.time_s; });
  int i = static_cast<int>(upper - keys.begin()) - 1;
  i = std::clamp(i, 0, static_cast<int>(keys.size()) - 2);
  const double t0 = keys[static_cast<std::size_t>(i)].time_s;
  const double t1 = keys[static_cast<std::size_t>(i) + 1].time_s;
  const double h = t1 - t0;
  const double s = std::clamp((t - t0) / h, 0.0, 1.0);
  const Sample& p0 = ext.samples[static_cast<std::size_t>(i)];
  const Sample& p1 = ext.samples[static_cast<std::size_t>(i) + 1];

  Sample r;
  if (settings.interpolation == PathInterpolation::kLinear) {
    r = p0 + (p1 - p0) * s;
  } else {
    const Sample m0 = ext.tangent(i) * h;
    const Sample m1 = ext.tangent(i + 1) * h;
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    r = p0 * h00 + m0 * h10 + p1 * h01 + m1 * h11;
  }
  out = keys[static_cast<std::size_t>(i)].view;
  out.position = r.position;
  out.yaw_deg = unwrap_degrees(static_cast<float>(r.yaw), 0.0f);
  out.pitch_deg = static_cast<float>(std::clamp(r.pitch, -89.9, 89.9));
  out.fov_deg = static_cast<float>(std::clamp(r.fov, 1.0, 170.0));
  return out;
}

Status CameraPath::validate(std::string_view json_path) const {
  if (keys.empty()) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}.keys: a camera path needs at least one key", json_path));
  }
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const std::string key_path = fmt::format("{}.keys[{}]", json_path, i);
    SYLVA_TRY(validate_params(keys[i], key_path));
    if (i > 0 && !(keys[i].time_s > keys[i - 1].time_s)) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}.time_s: {} is not after the previous key's time {} (times must increase)",
                                    key_path, keys[i].time_s, keys[i - 1].time_s));
    }
    if (keys[i].view.height_mode != keys.front().view.height_mode) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}.height_mode: every key of a path must use the same height mode", key_path));
    }
  }
  return {};
}

}  // namespace sylva::scene

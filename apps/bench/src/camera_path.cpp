#include "camera_path.hpp"

#include <sylva/core/assert.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::bench {

CameraPose CameraPath::at(double u) const {
  SYLVA_ASSERT(!keys.empty(), "camera path {} has no keys", name);
  if (keys.size() == 1) return keys.front();
  u = std::clamp(std::isnan(u) ? 0.0 : u, 0.0, 1.0);
  const double s = u * static_cast<double>(keys.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(s), keys.size() - 2);
  const double t = s - static_cast<double>(i);
  const CameraPose& p1 = keys[i];
  const CameraPose& p2 = keys[i + 1];
  const CameraPose& p0 = i > 0 ? keys[i - 1] : p1;
  const CameraPose& p3 = i + 2 < keys.size() ? keys[i + 2] : p2;
  const double t2 = t * t, t3 = t2 * t;
  CameraPose out;
  out.position = 0.5 * ((2.0 * p1.position) + (-p0.position + p2.position) * t +
                        (2.0 * p0.position - 5.0 * p1.position + 4.0 * p2.position - p3.position) * t2 +
                        (-p0.position + 3.0 * p1.position - 3.0 * p2.position + p3.position) * t3);
  const float tf = static_cast<float>(t);
  out.yaw_deg = p1.yaw_deg + (p2.yaw_deg - p1.yaw_deg) * tf;
  out.pitch_deg = p1.pitch_deg + (p2.pitch_deg - p1.pitch_deg) * tf;
  out.fov_deg = p1.fov_deg + (p2.fov_deg - p1.fov_deg) * tf;
  return out;
}

CameraPose CameraPath::frame(int i, int n) const {
  SYLVA_ASSERT(n >= 1 && i >= 0 && i < n, "frame {} of {}", i, n);
  return at(n == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(n - 1));
}

}  // namespace sylva::bench

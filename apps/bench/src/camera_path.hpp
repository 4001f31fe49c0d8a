#pragma once
// Scripted camera paths (GL-free): keyframes interpolated over a normalised parameter
// u in [0, 1], so a path gives the same poses for any frame count and every run sees exactly
// the same frames (frame i of N samples u = i / (N - 1); one frame samples u = 0).
//
// Positions follow a centripetal-free uniform Catmull-Rom spline through the keyframes
// (end keys duplicated), which passes through every key and has no kinks; yaw, pitch and field
// of view are interpolated linearly (yaw along the shorter arc is NOT applied: keys are taken as
// written, so a path may turn more than half a circle on purpose). Keys are evenly spaced in u.

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace sylva::bench {

struct CameraPose {
  glm::dvec3 position{0.0};  // world metres
  float yaw_deg = 0.0f;      // 0 looks along -z, positive turns left (render::Camera convention)
  float pitch_deg = 0.0f;    // positive looks up
  float fov_deg = 60.0f;     // vertical field of view
};

// What a target tells about one of its paths before it is built.
struct CameraPathInfo {
  std::string name;
  std::string description;
};

struct CameraPath {
  std::string name;
  std::string description;   // what the path shows
  std::vector<CameraPose> keys;  // at least one

  // Pose at u (clamped to [0, 1]).
  CameraPose at(double u) const;
  // Pose of frame i of n (n >= 1).
  CameraPose frame(int i, int n) const;
};

}  // namespace sylva::bench

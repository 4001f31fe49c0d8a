#pragma once
// Camera bookmarks and named, keyframed camera paths of a scene (GL-free).
//
// A CameraView is a pose: world position in metres (double, so a scene far from the origin
// keeps its precision), yaw/pitch in degrees with render::Camera's conventions (yaw 0 looks
// along -z, positive yaw turns left, positive pitch looks up) and a vertical field of view.
// With height_mode = above_ground, position.y is the height above the scene's ground at (x, z);
// Scene::resolve() turns it into an absolute height (a bookmark then stays on the ground when
// the terrain is edited).
//
// A CameraPath is a list of keys with strictly increasing times. evaluate(t) interpolates:
//  - linear: piecewise linear in every channel;
//  - catmull_rom: cubic Hermite per segment with tangents from the neighbouring keys divided by
//    their time span (a Catmull-Rom spline for non-uniform key times), one-sided at the ends.
//    The curve passes through every key and is C1 in time, so the camera speed never jumps.
// Yaw is unwrapped key to key (each key's yaw is moved by whole turns to within 180 degrees of
// the previous one), so a path from 170 to -170 degrees turns 20 degrees, not 340.
// Times before the first key give the first pose, after the last the last pose; a looping path
// wraps t into [first, last) and uses the wrapped neighbours for the end tangents (give the
// last key the first key's pose for a closed loop). Pitch is clamped to +-89.9 degrees and the
// field of view to [1, 170] degrees after interpolation (a spline may overshoot).

#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>

#include <glm/glm.hpp>

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::scene {

enum class HeightMode { kAbsolute, kAboveGround };
constexpr std::array<EnumName<HeightMode>, 2> enum_names(HeightMode) {
  return {{{HeightMode::kAbsolute, "absolute"}, {HeightMode::kAboveGround, "above_ground"}}};
}

struct CameraView {
  glm::dvec3 position{0.0, 2.0, 0.0};  // world metres (y: see height_mode)
  float yaw_deg = 0.0f;                // heading; 0 looks along -z, positive turns left
  float pitch_deg = 0.0f;              // elevation of the view; positive looks up
  float fov_deg = 60.0f;               // vertical field of view
  HeightMode height_mode = HeightMode::kAbsolute;

  template <class V>
  void visit(V& v) {
    v(position, "position", {.min = -1.0e9, .max = 1.0e9, .unit = "m", .help = "Camera position in world metres"});
    v(yaw_deg, "yaw_deg", {.min = -720.0, .max = 720.0, .unit = "deg", .help = "Heading, 0 looks along -z"});
    v(pitch_deg, "pitch_deg", {.min = -89.9, .max = 89.9, .unit = "deg", .help = "Elevation of the view"});
    v(fov_deg, "fov_deg", {.min = 1.0, .max = 170.0, .unit = "deg", .help = "Vertical field of view"});
    v(height_mode, "height_mode", {.help = "absolute: position.y is world height; above_ground: height above the ground"});
  }
};

struct CameraKey {
  double time_s = 0.0;  // seconds from the start of the path's clock
  CameraView view;

  template <class V>
  void visit(V& v) {
    v(time_s, "time_s", {.min = -1.0e7, .max = 1.0e7, .unit = "s", .help = "Time of this key"});
    view.visit(v);  // flat in JSON: {"time_s": 0, "position": [...], "yaw_deg": ...}
  }
};

enum class PathInterpolation { kLinear, kCatmullRom };
constexpr std::array<EnumName<PathInterpolation>, 2> enum_names(PathInterpolation) {
  return {{{PathInterpolation::kLinear, "linear"}, {PathInterpolation::kCatmullRom, "catmull_rom"}}};
}

// The scalar settings of a path (its keys are a list, handled by the scene file).
struct CameraPathSettings {
  PathInterpolation interpolation = PathInterpolation::kCatmullRom;
  bool loop = false;

  template <class V>
  void visit(V& v) {
    v(interpolation, "interpolation", {.help = "linear or catmull_rom"});
    v(loop, "loop", {.help = "Wrap time around the path"});
  }
};

struct CameraPath {
  CameraPathSettings settings;
  std::vector<CameraKey> keys;

  // first and last key time [s]; 0 for an empty path.
  double start_time() const;
  double end_time() const;
  double duration() const { return end_time() - start_time(); }

  // The pose at time t (see the header comment). Asserts the path is valid (validate()).
  // height_mode of the result: that of the segment's first key (keys of one path should agree;
  // validate() rejects mixed modes).
  CameraView evaluate(double t) const;

  // At least one key, strictly increasing finite times, one height mode, every key in range.
  // Messages start with `json_path` (e.g. "camera_paths.flyover.keys[2].time_s").
  Status validate(std::string_view json_path) const;
};

// Angle in degrees moved by whole turns to within 180 degrees of `reference`.
float unwrap_degrees(float angle, float reference);

}  // namespace sylva::scene

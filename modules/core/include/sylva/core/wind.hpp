#pragma once
// The wind field every module reads (DESIGN.md §2 "shared world services"): trees, grass and
// leaves sample one model so they move together. Velocities are in m/s, positions in metres
// (y up), time in seconds.
//
// Model (seed 000 §2.4: wind = directional (laminar) part + turbulent part; "if the signals
// change smoothly, the animation is smooth"):
//
//   v(p, t) = d * (strength + gust_amplitude * g(p, t)) + turbulence(p, t)
//
//  * d = (cos a, 0, sin a), a = direction_deg: the mean wind is horizontal.
//  * Gusts g in [0, 1] are slow 1D gradient noise along the wind, g = 0.5 + 0.5 n(s) with
//    s = (t - dot(p, d) / c) / gust_period, c = max(strength, 1 m/s): a gust front travels
//    downwind, so a row of trees bends one after the other instead of all at once (the seed's
//    grass wind was a global sine; seed 001 §7 notes its regular waves look artificial).
//  * Turbulence is 3D fBm (lacunarity 2, persistence 0.5, turbulence_octaves) advected with the
//    mean wind (Taylor's frozen turbulence, seed 000 §2.4 "shifted by -W t") plus a vertical drift
//    of turbulence_evolution m/s, so calm air still changes over time:
//      q = (p - d * strength * t - (0, turbulence_evolution * t, 0)) / turbulence_scale
//      turbulence = turbulence_amplitude * (f_x(q), turbulence_vertical * f_y(q), f_z(q))
//    with three independently seeded fields f in [-1, 1]. It replaces the seed's three
//    unnormalised 2D texture lookups (eq. 3.18), which also divide by |W| and break in calm air.
//
// Bounds: |v - d*strength| <= gust_amplitude + turbulence_amplitude * sqrt(2 + turbulence_vertical^2),
// and every component is finite for all inputs (tested).
//
// Precision (why WindFrame exists). t reaches 1e7 s and positions 1e6 m; W*t/scale is then far
// beyond float precision. All time- and origin-dependent terms are evaluated once per frame in
// double and split into an integer noise cell (wrapped by the noise period, which is exact
// because the noise is periodic) plus a small float offset: WindField::frame(t, origin). The
// per-sample part (WindField::evaluate(frame, local)) is float arithmetic on the position relative
// to `origin` and is exactly what render/lib/wind.glsl computes from the same WindGpuParams,
// so the CPU and the GPU agree to float rounding (measured on llvmpipe: <= 1e-7 of max_speed).
// At the origin the gust phase resolves 2^-24 gust periods and the turbulence 2^-24 cells at any
// t; a local offset adds float rounding of |local| / (c * gust_period) periods and of
// |local| / turbulence_scale cells, so keep local positions camera-relative.
// Time is continuous: the split moves whole cells into the integer part without changing the sum.
//
// Failure: settings outside the documented ranges are clamped into them by WindField (hurricane
// tests rely on it never producing NaN); validate() reports them as an error naming the field.
// Non-finite t or positions are treated as 0.

#include <sylva/core/result.hpp>

#include <glm/glm.hpp>

#include <cstdint>

namespace sylva {

struct WindSettings {
  float direction_deg = 0.0f;         // azimuth the wind blows towards: 0 = +x, 90 = +z
  float strength = 3.0f;              // mean (lull) speed along the direction [m/s]
  float gust_amplitude = 2.0f;        // extra speed at a gust's peak [m/s]
  float gust_period = 8.0f;           // time scale of gusts (one noise cell) [s]
  float turbulence_amplitude = 1.0f;  // peak turbulent speed per horizontal axis [m/s]
  float turbulence_scale = 6.0f;      // size of the largest eddies [m]
  float turbulence_evolution = 0.5f;  // vertical drift through the turbulence field [m/s]
  float turbulence_vertical = 0.3f;   // vertical turbulence relative to horizontal [0, 1]
  int turbulence_octaves = 2;         // fBm octaves of the turbulence [1, 4]
  std::uint32_t seed = 1;

  template <class V>
  void visit(V& v) {
    v(direction_deg, "direction_deg", {.min = -360.0, .max = 360.0, .unit = "deg",
      .help = "Direction the wind blows towards (0 = +x, 90 = +z)"});
    v(strength, "strength", {.min = 0.0, .max = 100.0, .unit = "m/s", .help = "Mean wind speed between gusts"});
    v(gust_amplitude, "gust_amplitude", {.min = 0.0, .max = 100.0, .unit = "m/s",
      .help = "Extra speed at the peak of a gust"});
    v(gust_period, "gust_period", {.min = 0.1, .max = 3600.0, .unit = "s",
      .help = "Time scale of gusts (slow variation)", .log_scale = true});
    v(turbulence_amplitude, "turbulence_amplitude", {.min = 0.0, .max = 100.0, .unit = "m/s",
      .help = "Peak speed of turbulent eddies per horizontal axis"});
    v(turbulence_scale, "turbulence_scale", {.min = 0.05, .max = 10000.0, .unit = "m",
      .help = "Size of the largest turbulent eddies", .log_scale = true});
    v(turbulence_evolution, "turbulence_evolution", {.min = 0.0, .max = 100.0, .unit = "m/s",
      .help = "Vertical drift through the turbulence so calm air still moves"});
    v(turbulence_vertical, "turbulence_vertical", {.min = 0.0, .max = 1.0,
      .help = "Vertical turbulence relative to horizontal"});
    v(turbulence_octaves, "turbulence_octaves", {.min = 1, .max = 4, .help = "Detail layers of turbulence"});
    v(seed, "seed", {.min = 0.0, .max = 4294967295.0, .help = "Random seed of gusts and turbulence"});
  }
};

// Per-frame wind state, laid out for a std140 uniform block or std430 buffer: vec4/ivec4/uvec4
// members only (render/lib/wind.glsl declares the matching `SylvaWind` struct). Built by
// WindField::frame(); 112 bytes.
struct WindGpuParams {
  float direction_strength[4];  // xyz unit direction d, w strength [m/s]
  float gust[4];                // x gust_amplitude [m/s], y gust phase offset (cells, in [0,1]), zw 0
  float gust_spatial[4];        // xyz d / (c * gust_period) [cells/m], w 0
  float turbulence[4];          // x amplitude [m/s], y vertical ratio, z 1/scale [cells/m], w octaves
  float turbulence_offset[4];   // xyz offset of the origin in cells (in [0,1]), w 0
  std::int32_t cells[4];        // xyz turbulence cell of the origin, w gust cell
  std::uint32_t seeds[4];       // x gust seed, yzw turbulence seeds of the x, y, z components
};
static_assert(sizeof(WindGpuParams) == 112, "WindGpuParams must match the std140 layout of SylvaWind");

// A frame's precomputed wind: origin (double, world) and the GPU parameters for time t.
struct WindFrame {
  glm::dvec3 origin{0.0};
  double time = 0.0;
  WindGpuParams gpu{};
};

class WindField {
 public:
  WindField() : WindField(WindSettings{}) {}
  explicit WindField(const WindSettings& settings);

  // The settings as used (clamped into the documented ranges).
  const WindSettings& settings() const { return settings_; }
  // Errors (kInvalidArgument) for fields outside their ranges or non-finite, naming the field.
  static Status validate(const WindSettings& settings);

  // Wind velocity in m/s at world position `pos` and time t.
  glm::vec3 evaluate(glm::vec3 pos, double t) const;
  // The same with a double world position (full precision far from the origin).
  glm::vec3 evaluate(glm::dvec3 pos, double t) const;

  // Per-frame split (see the header comment). `origin` is the world point that local positions
  // are relative to, normally the camera position of camera-relative rendering.
  WindFrame frame(double t, glm::dvec3 origin = glm::dvec3(0.0)) const;
  // Wind at world position frame.origin + local: the float code path render/lib/wind.glsl mirrors.
  static glm::vec3 evaluate(const WindFrame& frame, glm::vec3 local);

  // Unit mean direction d.
  glm::vec3 direction() const { return direction_; }
  // Upper bound of |v(p, t)| over all p and t (see Bounds above).
  float max_speed() const;

 private:
  WindSettings settings_;
  glm::vec3 direction_{1.0f, 0.0f, 0.0f};
};

}  // namespace sylva

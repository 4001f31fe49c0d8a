#pragma once
// Brush maths for painting scene maps (GL-free, unit-tested in tests/brush_test.cpp).
//
// A stroke is a polyline of world x/z points resampled into dabs every `spacing * radius`
// metres. A dab changes the texels whose centres lie strictly inside `radius` of its centre,
// each by an amount scaled by the falloff weight w(d / radius) in [0, 1]:
//
//   raise    v += strength * w            (height maps: metres per dab; unit maps: share)
//   lower    v -= strength * w
//   paint    v += (target - v) * a,   a = clamp(strength * w, 0, 1)   (unit maps; target in [0, 1])
//   erase    v += (0 - v) * a
//   flatten  v += (target - v) * a        (target: the height under the stroke's first dab
//                                          unless set explicitly)
//   smooth   v += (m - v) * a,  m = mean of the 3x3 neighbourhood read from the values before
//                                   the dab (so the result does not depend on texel order)
//   noise    v += strength * w * fbm(p / noise_scale)   (core fBm, deterministic in seed)
//
// No overshoot: paint, erase, flatten and smooth move each texel by a share a <= 1 of the way to
// a value inside the range of the values involved, so repeated dabs converge monotonically and
// never leave [min, max] of (old values, target). Unit maps are clamped to [0, 1] afterwards.

#include <sylva/core/params.hpp>
#include <sylva/scene/map_grid.hpp>

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace sylva::editor {

enum class BrushOp { kRaise, kLower, kPaint, kErase, kFlatten, kSmooth, kNoise };
constexpr std::array<EnumName<BrushOp>, 7> enum_names(BrushOp) {
  return {{{BrushOp::kRaise, "raise"},
           {BrushOp::kLower, "lower"},
           {BrushOp::kPaint, "paint"},
           {BrushOp::kErase, "erase"},
           {BrushOp::kFlatten, "flatten"},
           {BrushOp::kSmooth, "smooth"},
           {BrushOp::kNoise, "noise"}}};
}

enum class Falloff { kConstant, kLinear, kSmooth, kGaussian };
constexpr std::array<EnumName<Falloff>, 4> enum_names(Falloff) {
  return {{{Falloff::kConstant, "constant"}, {Falloff::kLinear, "linear"}, {Falloff::kSmooth, "smooth"}, {Falloff::kGaussian, "gaussian"}}};
}

struct BrushSettings {
  BrushOp op = BrushOp::kRaise;
  float radius = 8.0f;      // metres
  float strength = 0.5f;    // per dab: metres (raise/lower/noise on height maps) or share (others)
  Falloff falloff = Falloff::kSmooth;
  bool use_target = false;  // flatten/paint: use `target` instead of the first dab's value
                            // (paint without it paints 1)
  float target = 1.0f;      // paint value or flatten height
  float spacing = 0.25f;    // dab spacing as a share of the radius
  float noise_scale = 6.0f; // metres per noise cell
  std::uint32_t seed = 1;
  glm::vec3 color{1.0f};    // colour maps: the paint colour, linear RGB [0, 1] (see color_channel_brush)

  template <class V>
  void visit(V& v) {
    v(op, "op", {.help = "raise, lower, paint, erase, flatten, smooth or noise"});
    v(radius, "radius", {.min = 0.01, .max = 1.0e5, .unit = "m", .help = "Brush radius", .log_scale = true});
    v(strength, "strength", {.min = 0.0, .max = 1.0e4, .help = "Change per dab (metres on height maps for raise/lower/noise, else a share)"});
    v(falloff, "falloff", {.help = "constant, linear, smooth or gaussian"});
    v(use_target, "use_target", {.help = "Paint/flatten toward `target` instead of the value under the first dab"});
    v(target, "target", {.min = -1.0e6, .max = 1.0e6, .help = "Paint value or flatten height"});
    v(spacing, "spacing", {.min = 0.01, .max = 4.0, .help = "Dab spacing as a share of the radius"});
    v(noise_scale, "noise_scale", {.min = 0.01, .max = 1.0e5, .unit = "m", .help = "Noise feature size", .log_scale = true});
    v(seed, "seed", {.min = 0.0, .max = 4294967295.0, .help = "Noise seed"});
    v(color, "color", {.min = 0.0, .max = 1.0, .help = "Paint colour of colour maps (grass.tint), linear RGB"});
  }
};

// Falloff weight for a normalised distance t = d / radius: 1 at the centre, 0 for t >= 1
// (constant: 1 for t < 1).
float falloff_weight(Falloff falloff, double t);

// Texels whose centres are strictly within `radius` of `center` (clipped to the grid; empty
// when none).
scene::TexelRect dab_rect(const scene::MapGrid& grid, glm::dvec2 center, double radius);

// Resamples a polyline into dab centres `spacing` metres apart (the first point is always a dab;
// a single point gives one dab). spacing > 0.
std::vector<glm::dvec2> stroke_dabs(std::span<const glm::dvec2> points, double spacing);

// Bilinear value of the grid at a world point (clamped to the edge).
float sample_grid(const scene::MapGrid& grid, glm::dvec2 world);

// One dab. `target` is the resolved paint/flatten value (see resolve_target). Returns the texels
// it changed (a subset of dab_rect). Unit maps are clamped to [0, 1].
scene::TexelRect apply_dab(scene::MapGrid& grid, scene::MapKind kind, const BrushSettings& brush, glm::dvec2 center,
                           float target);

// The paint/flatten target of a stroke starting at `first_dab`.
float resolve_target(const scene::MapGrid& grid, const BrushSettings& brush, glm::dvec2 first_dab);

// Colour maps (issue 16: the grass tint is three unit maps, tint_r, tint_g, tint_b). A stroke on
// the colour map "grass.tint" paints its three channel maps with the same dabs, one undo entry.
// The ids of the channel maps of colour map `color_map_id` ("grass.tint" -> "grass.tint_r", ...).
std::array<std::string, 3> color_channel_ids(const std::string& color_map_id);
// The brush channel `channel` (0..2) of a colour stroke gets: paint goes towards color[channel]
// and erase towards 1 (white: no tint), both as paint with use_target; the other ops act on each
// channel as on any unit map.
BrushSettings color_channel_brush(const BrushSettings& brush, int channel);

}  // namespace sylva::editor

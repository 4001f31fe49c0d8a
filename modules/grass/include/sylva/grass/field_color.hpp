#pragma once
// The colour of a grass field at a world point, shared by its three levels of detail (blades,
// clumps, ground layer; seed 003 §2.3 asks that the far representations reproduce the near
// field's look): a multiplier of the blades' base/tip colours that varies in
//  - patches: low-frequency fBm over `patch_size` metres moving the colour between lush (deeper,
//    bluer green) and dry (yellower, lighter), so a field reads as grown grass, not a flat fill;
//  - clumps: one hue/brightness offset per cell of `clump_size` metres (a tussock's blades share
//    their genes and their light), so neighbouring blades agree and the field shows tufts.
// The multiplier averages to about (1, 1, 1) over a field (zero-mean noise, linear in it), so the
// mean colour of a field does not depend on the variation settings.
//
// Dry tips: a share of the blades turn towards straw at the tip (grass/color.glsl, per blade);
// kMeanTipDryness is the field's mean, used by the far representations.

#include <sylva/grass/settings.hpp>

#include <glm/glm.hpp>

#include <cstdint>

namespace sylva::grass {

// Mean over blades of the per-blade tip dryness of grass/color.glsl's grass_blade_dryness()
// (0.8 * smoothstep(0.55, 1, r) over r uniform in [0, 1): 0.8 * 0.45 / 2).
inline constexpr float kMeanTipDryness = 0.18f;

// Colour multiplier (linear RGB, each channel in [0.3, 1.7]) of the field at world (x, z) [m].
// Deterministic in (x, z, seed); finite for finite input (non-finite input gives (1, 1, 1)).
glm::vec3 field_color(double x, double z, const BladeSettings& blade, std::uint32_t seed);

// Seed 003 §3.4 motion by colour, the uniform of color.glsl grass_color_pulse(): x amplitude
// (ShadingSettings::color_motion), y = 2 pi hz t reduced to [0, 2 pi) in double precision, so the
// pulse stays smooth after days of simulation time. Non-finite time gives phase 0.
glm::vec2 color_motion_uniform(float amplitude, float hz, double time);

}  // namespace sylva::grass

#pragma once
// Settings of the image-based levels (seed 000 §2.6-2.11, §2.13, §3.3): bake resolution and cache,
// LOD thresholds and transitions. Listed once through visit() as `forest.lod.*` (DESIGN.md §2), so
// scenes, the editor and sylva-bench set them by path (e.g. `vegetation.forest.lod.v1=40`).

#include <sylva/core/params.hpp>

#include <array>
#include <string>

namespace sylva::vegetation {

// How the per-instance LOD metric is measured (seed §2.8: 3D or horizontal distance; beyond the
// seed a screen-size criterion, independent of resolution and field of view changes).
enum class LodCriterion { kDistance = 0, kHorizontalDistance = 1, kScreenSize = 2 };
constexpr std::array<EnumName<LodCriterion>, 3> enum_names(LodCriterion) {
  return {{{LodCriterion::kDistance, "distance"},
           {LodCriterion::kHorizontalDistance, "horizontal_distance"},
           {LodCriterion::kScreenSize, "screen_size"}}};
}

// How the two levels of an instance in transition are blended (seed 000 §2.9, eq. 3.41-3.43; the
// thesis's Fig. 3.25 compares all four). For an instance at LOD coordinate l = k + f (f in (0, 1) the
// transition phase), A = level k (the level being left) and B = level k + 1 (the level entered);
// each weight is the fade its level is drawn with (dithered coverage, 1 = opaque, 0 = not drawn):
//   fade_in_background (eq. 3.42, the default):  A = min(1, 2(1 - f)),  B = min(1, 2f)
//     one level is opaque at every f, so the tree is never see-through;
//   cross_fade (eq. 3.41):  A = 1 - f,  B = f
//     the print writes R = f A + (1 - f) B, with A and B swapped against eq. 3.42/3.43 (seed errata
//     item 9); in this convention it is (1 - f) A + f B. Both levels are semi-transparent inside
//     the band (0.5 / 0.5 at f = 0.5): the see-through defect the thesis describes;
//   soft (eq. 3.43 with s = 0):  A = (1 + cos(f pi)) / 2,  B = 1 - A
//     a cosine cross-fade: still see-through in the middle;
//   shifted_soft (eq. 3.43, s = transition_shift):
//     A = (smooth((f - s) / (1 - s) pi) + 1) / 2,  B = 1 - (smooth(f / (1 - s) pi) + 1) / 2,
//     smooth(x) = 1 for x <= 0, cos(x) on (0, pi), -1 for x >= pi.
//     A is opaque for f <= s, B for f >= 1 - s; s = 0.5: one layer always opaque (fade in
//     background with cosine ramps), s > 0.5: the opaque ranges overlap.
enum class LodTransition { kFadeInBackground = 0, kCrossFade = 1, kSoft = 2, kShiftedSoft = 3 };
constexpr std::array<EnumName<LodTransition>, 4> enum_names(LodTransition) {
  return {{{LodTransition::kFadeInBackground, "fade_in_background"},
           {LodTransition::kCrossFade, "cross_fade"},
           {LodTransition::kSoft, "soft"},
           {LodTransition::kShiftedSoft, "shifted_soft"}}};
}

struct LodSettings {
  bool enabled = true;            // false: every tree is drawn at LOD0 (Trees I behaviour)
  int slice_resolution = 128;     // texels per slice side (baked LOD1 and LOD2 slices)
  std::string cache_directory = "auto";  // bake cache folder; "auto" = <temp>/sylva-lod-cache, "" = off
  LodCriterion criterion = LodCriterion::kDistance;
  float v1 = 45.0f;               // LOD0 -> LOD1 distance [m] (seed's v1)
  float v2 = 110.0f;              // LOD1 -> LOD2 distance [m] (seed's v2), >= v1 (clamped up)
  float s1 = 70.0f;               // screen_size: LOD1 below this projected tree height [px]
  float s2 = 28.0f;               // screen_size: LOD2 below this projected height [px]
  float band = 0.15f;             // transition width relative to the threshold distance
  LodTransition transition = LodTransition::kFadeInBackground;  // blend of the two levels (above)
  float transition_shift = 0.5f;  // shifted_soft: the seed's s in [0, 0.95] (s < 1; no value in the seed)
  float hysteresis = 0.05f;       // backlash on the distance (relative) against threshold jitter
  float slice_margin = 0.12f;     // quads grow by this share of the tree height for swaying content
  float leaf_displacement = 0.002f;  // scrolling leaf displacement [m per m/s of wind] (seed eq. 3.40)
  float leaf_displacement_scale = 0.6f;  // feature size of the leaf displacement field [m]
  // Colour noise in slices (seed 000 §3.3.1): each leaf's normal tilts by up to this angle per
  // m/s of wind (capped at 0.5 rad), coherently for the whole leaf, so distant crowns twinkle as
  // leaves turn instead of shading like rigid cards. 0 = off.
  float color_noise = 0.03f;             // [rad per m/s of wind]
  bool shadow_depth_offset = true;       // slices write their baked depth offset into shadow maps (§4.7)
  bool sort_front_to_back = true;        // order each LOD queue near to far (early depth rejection)
  // Draw switches per level at unchanged thresholds (seed 000 Tab 5.4 measures each level's share
  // of the frame by leaving it out): a level switched off is selected and counted as usual but
  // neither drawn nor cast into shadow maps.
  bool draw_lod0 = true;
  bool draw_lod1 = true;
  bool draw_lod2 = true;
  bool draws_level(int level) const { return level == 0 ? draw_lod0 : level == 1 ? draw_lod1 : draw_lod2; }

  template <class V>
  void visit(V& v) {
    v(enabled, "enabled", {.help = "Image-based LOD1/LOD2 for distant trees", .rebuild = Rebuild::kOffline});
    v(slice_resolution, "slice_resolution", {.min = 16, .max = 1024, .unit = "px", .help = "Texels per baked slice side", .rebuild = Rebuild::kOffline});
    v(cache_directory, "cache_directory", {.min = 0, .max = 4096, .help = "Bake cache folder (auto = temp folder, empty = no cache)"});
    v(criterion, "criterion", {.help = "LOD metric: distance, horizontal distance or projected size"});
    v(v1, "v1", {.min = 0.0, .max = 1.0e7, .unit = "m", .help = "Distance where LOD0 turns into LOD1"});
    v(v2, "v2", {.min = 0.0, .max = 1.0e7, .unit = "m", .help = "Distance where LOD1 turns into LOD2"});
    v(s1, "s1", {.min = 0.0, .max = 1.0e5, .unit = "px", .help = "screen_size: projected height below which LOD1 is used"});
    v(s2, "s2", {.min = 0.0, .max = 1.0e5, .unit = "px", .help = "screen_size: projected height below which LOD2 is used"});
    v(band, "band", {.min = 0.0, .max = 4.0, .help = "Transition width relative to the threshold"});
    v(transition, "transition", {.help = "Blend of the two levels in a transition: fade_in_background (eq. 3.42, never see-through), cross_fade (eq. 3.41), soft (eq. 3.43, s = 0) or shifted_soft (eq. 3.43, s = transition_shift)"});
    v(transition_shift, "transition_shift", {.min = 0.0, .max = 0.95, .help = "shifted_soft: mutual shift s of the two cosine ramps (0 = soft, 0.5 = one level always opaque)"});
    v(hysteresis, "hysteresis", {.min = 0.0, .max = 1.0, .help = "Relative distance change needed before the LOD follows"});
    v(slice_margin, "slice_margin", {.min = 0.0, .max = 1.0, .help = "Slice quad growth for swaying content (share of height)"});
    v(leaf_displacement, "leaf_displacement", {.min = 0.0, .max = 1.0, .unit = "m/(m/s)", .help = "Scrolling leaf displacement in slices"});
    v(leaf_displacement_scale, "leaf_displacement_scale", {.min = 0.01, .max = 100.0, .unit = "m", .help = "Feature size of the leaf displacement"});
    v(color_noise, "color_noise", {.min = 0.0, .max = 1.0, .unit = "rad/(m/s)", .help = "Per-leaf normal tilt in slices per m/s of wind (colour noise)"});
    v(shadow_depth_offset, "shadow_depth_offset", {.help = "Slices write their baked depth into shadow maps"});
    v(sort_front_to_back, "sort_front_to_back", {.help = "Order LOD queues near to far"});
    v(draw_lod0, "draw_lod0", {.help = "Draw the trees selected for LOD0 (off: left out, thresholds unchanged)"});
    v(draw_lod1, "draw_lod1", {.help = "Draw the trees selected for LOD1 (off: left out, thresholds unchanged)"});
    v(draw_lod2, "draw_lod2", {.help = "Draw the trees selected for LOD2 (off: left out, thresholds unchanged)"});
  }
};

}  // namespace sylva::vegetation

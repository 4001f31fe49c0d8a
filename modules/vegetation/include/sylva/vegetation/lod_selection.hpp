#pragma once
// Per-instance LOD selection and transitions (seed 000 §2.8, §2.9, §2.11). GL-free, so the CPU
// cost can be measured and tested on its own (100,000 instances, bench_vegetation_cpu).
//
// LOD coordinate. Every instance has a continuous coordinate l in [0, 2]: 0 = LOD0, 1 = LOD1,
// 2 = LOD2, fractional = in transition between floor(l) and floor(l) + 1. The target l*(d) of a
// distance d rises linearly from k to k + 1 over [v_k, v_k (1 + band)] (the seed gives no band,
// §2.8 [INFERRED] a linear ramp); with v1 = v2 both ramps run at once and l* still is continuous.
// Hysteresis is backlash (play) on the distance: each instance keeps an effective distance e that
// follows its true distance d only when d leaves [e / (1 + h), e (1 + h)]:
//   e <- clamp(e, d / (1 + h), d (1 + h)),   l = l*(e).
// Continuous in d, so nothing pops; a camera jittering by less than the share h leaves l (and the
// picture) unchanged; and l still settles on exact levels between the ramps. The screen-size criterion converts its pixel
// thresholds s1 > s2 to per-instance distances v_k = K h_tree / s_k (K = viewport height /
// (2 tan(fov_y / 2))), so the same ramps apply.
//
// Transition (seed eq. 3.42, "fade in background", the default): for l = k + f, level k is drawn
// with fade min(1, 2 (1 - f)) and level k + 1 with min(1, 2 f). At every f one of the two is fully
// opaque, so the union covers at least the opaque level's pixels: the tree is never see-through.
// LodSettings::transition selects the seed's other blends for comparison (cross-fade eq. 3.41,
// soft and shifted soft eq. 3.43; formulas in lod_settings.hpp); a level whose weight is 0 is not
// queued, one with weight 1 draws opaque. The fades act as dithered coverage (alpha-to-coverage
// sample masks or a hashed alpha test keyed on rest positions), the same in colour and shadow
// passes (the seed's dithered shadows, §2.13), and need no back-to-front sorting: each queue is
// ordered near to far instead (the seed's future work), a linear-time counting sort on quantised
// distance. Depth and draw order: every fragment (sample) that survives the dither is opaque and
// writes depth, so the seed's two draw orders with depth writes off for the fading level (§4.2
// makeTransition) are not needed and every blend stays correct in any order. Each fragment
// dithers on its own hash (rest position; slices: slice point and layer), so with two
// semi-transparent levels (cross-fade, soft) a pixel behind n LOD0 fragments and m slice layers
// shows the background with probability (1 - a)^n (1 - b)^m: the see-through of the seed's
// cross-fade, strongest where the tree is thin (lod_transition_gl_test).

#include <sylva/render/frustum.hpp>
#include <sylva/vegetation/lod_settings.hpp>

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace sylva::vegetation {

inline constexpr int kLodLevels = 3;

// Resolved thresholds of one instance: ramp k runs over [start[k], start[k] + width[k]] metres.
struct LodRamps {
  std::array<double, 2> start{0.0, 0.0};
  std::array<double, 2> width{0.0, 0.0};
};

// `tree_height` [m] and `pixels_per_radian` (K above) are used by the screen-size criterion only.
// Invalid settings are made usable: v2 < v1 is raised to v1, s2 > s1 lowered to s1, non-finite
// values count as 0; the widths never drop below 1 mm so a zero band is a (continuous) step.
LodRamps lod_ramps(const LodSettings& settings, double tree_height, double pixels_per_radian);
// Target coordinate l*(d) in [0, 2] (NaN distance counts as infinitely far).
float lod_target(const LodRamps& ramps, double distance);
// Backlash update of an effective distance: clamp(current, d / (1 + h), d (1 + h)); a NaN current
// (a new instance) starts at d; h is clamped to [0, 1] (non-finite: 0).
double lod_follow(double current, double distance, float hysteresis);

// The level(s) one coordinate draws, with their fades (1 = opaque).
struct LodDraw {
  int level = 0;
  float fade = 1.0f;
};
struct LodDraws {
  std::array<LodDraw, 2> draw{};
  int count = 0;
};
// Fade-in-background draws (eq. 3.42), bit-identical to lod_draws(coordinate, kFadeInBackground, ..).
LodDraws lod_draws(float coordinate);
// Draws of one coordinate with the chosen blend. At an integer coordinate one opaque level; inside
// a transition the levels with a weight above 0, level k first (count 1 or 2). `shift` is the
// seed's s for kShiftedSoft, clamped to [0, 0.95] (non-finite: 0); the other blends ignore it.
LodDraws lod_draws(float coordinate, LodTransition transition, float shift);

// Weights of the two levels at phase f in [0, 1] (clamped; NaN counts as 0): a for level k (the
// seed's A, the level being left), b for level k + 1 (B, the level entered), each in [0, 1], per
// the equations in lod_settings.hpp. a = 1, b = 0 at f = 0 and a = 0, b = 1 at f = 1 for every
// blend; a + b >= 1 always (= 1 for cross_fade and soft).
struct LodWeights {
  float a = 1.0f;
  float b = 0.0f;
};
LodWeights lod_transition_weights(LodTransition transition, float phase, float shift);

// One queued draw: instance index and fade; queues are ordered near to far when sorting is on.
struct LodQueueEntry {
  std::uint32_t instance = 0;
  float fade = 1.0f;
};

struct LodQueues {
  std::array<std::vector<LodQueueEntry>, kLodLevels> level;
  std::size_t considered = 0;   // instances in the input
  std::size_t visible = 0;      // instances drawn (at one level or two)
  std::size_t transitions = 0;  // of those, instances drawn at two levels
  // scratch of the sort (kept to avoid reallocation)
  std::array<std::vector<float>, kLodLevels> distance;
  std::vector<LodQueueEntry> sort_tmp;
  std::vector<std::uint32_t> sort_count;
};

struct LodView {
  glm::dvec3 camera{0.0};
  const render::Frustum* frustum = nullptr;  // null: no frustum culling
  double pixels_per_radian = 1.0;            // viewport height / (2 tan(fov_y / 2))
  double max_distance = 1.0e30;              // farther bounding spheres are dropped [m]
};

// Per-instance state of the selection: the effective distance (hysteresis) and the coordinate.
struct LodState {
  std::vector<double> distance;  // effective distance [m], NaN before the first selection
  std::vector<float> level;      // LOD coordinate in [0, 2], NaN before the first selection
};

// Selects the LOD of every instance (bounding spheres in world space, tree heights in metres),
// updates `state` (resized and reset when its size differs from the instance count) and fills
// `out`. The coordinate of every instance within max_distance is updated, culled or not, so a
// shadow pass can reuse it. With settings.enabled false every instance is LOD0. A camera within
// 1.5 bounding-sphere radii of an instance's centre (inside or next to its slice cluster) always
// gets LOD0 for it, whatever the thresholds: slices are pictures for a distant viewer.
void select_lods(const LodSettings& settings, const LodView& view, std::span<const render::Sphere> spheres,
                 std::span<const float> heights, LodState& state, LodQueues& out);

}  // namespace sylva::vegetation

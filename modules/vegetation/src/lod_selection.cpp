#include <sylva/vegetation/lod_selection.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva::vegetation {
namespace {

constexpr double kMinWidth = 1.0e-3;  // [m] a zero band is a continuous step over 1 mm
// A camera closer than this many bounding-sphere radii to a tree's centre is inside or right
// next to its slice cluster: slices seen from there are not a picture of the tree (each layer is a
// flat projection for a distant viewer; from inside they fan over the whole screen, the editor's
// "dark triangle and green shards"), so such a tree is LOD0 whatever the thresholds say.
constexpr double kLod0Radii = 1.5;

double finite_or_zero(double v) { return std::isfinite(v) ? std::max(v, 0.0) : 0.0; }

// Counting sort of one queue by quantised distance (256 buckets over the queue's range): linear
// time, stable, near to far.
void sort_queue(std::vector<LodQueueEntry>& q, const std::vector<float>& dist, std::vector<LodQueueEntry>& tmp,
                std::vector<std::uint32_t>& count) {
  if (q.size() < 2) return;
  float lo = std::numeric_limits<float>::max();
  float hi = 0.0f;
  for (float d : dist) {
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  constexpr std::uint32_t kBuckets = 256;
  const float scale = hi > lo ? static_cast<float>(kBuckets - 1) / (hi - lo) : 0.0f;
  count.assign(kBuckets + 1, 0u);
  for (float d : dist) ++count[static_cast<std::uint32_t>((d - lo) * scale) + 1];
  for (std::uint32_t b = 1; b <= kBuckets; ++b) count[b] += count[b - 1];
  tmp.resize(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) tmp[count[static_cast<std::uint32_t>((dist[i] - lo) * scale)]++] = q[i];
  q.swap(tmp);
}

}  // namespace

LodRamps lod_ramps(const LodSettings& s, double tree_height, double pixels_per_radian) {
  LodRamps r;
  double v1 = 0.0;
  double v2 = 0.0;
  if (s.criterion == LodCriterion::kScreenSize) {
    // Projected height h K / d falls below s_k at d = K h / s_k; s = 0 never switches.
    const double k = finite_or_zero(pixels_per_radian) * finite_or_zero(tree_height);
    const double s1 = finite_or_zero(s.s1);
    const double s2 = std::min(finite_or_zero(s.s2), s1);
    v1 = s1 > 0.0 ? k / s1 : std::numeric_limits<double>::infinity();
    v2 = s2 > 0.0 ? k / s2 : std::numeric_limits<double>::infinity();
  } else {
    v1 = finite_or_zero(s.v1);
    v2 = std::max(finite_or_zero(s.v2), v1);
  }
  const double band = finite_or_zero(s.band);
  r.start = {v1, v2};
  r.width = {std::max(v1 * band, kMinWidth), std::max(v2 * band, kMinWidth)};
  return r;
}

float lod_target(const LodRamps& r, double d) {
  if (std::isnan(d)) return 2.0f;
  double l = 0.0;
  for (int k = 0; k < 2; ++k) {
    if (!std::isfinite(r.start[static_cast<std::size_t>(k)])) continue;  // never switches
    l += std::clamp((d - r.start[static_cast<std::size_t>(k)]) / r.width[static_cast<std::size_t>(k)], 0.0, 1.0);
  }
  return static_cast<float>(l);
}

double lod_follow(double current, double distance, float hysteresis) {
  const double h = std::isfinite(hysteresis) ? std::clamp(static_cast<double>(hysteresis), 0.0, 1.0) : 0.0;
  if (std::isnan(current) || std::isnan(distance)) return distance;
  return std::clamp(current, distance / (1.0 + h), distance * (1.0 + h));
}

LodWeights lod_transition_weights(LodTransition t, float phase, float shift) {
  const float f = std::isnan(phase) ? 0.0f : std::clamp(phase, 0.0f, 1.0f);
  LodWeights w;
  switch (t) {
    case LodTransition::kCrossFade:  // eq. 3.41 with A and B in eq. 3.42's roles (errata 9)
      w = {1.0f - f, f};
      break;
    case LodTransition::kSoft:
    case LodTransition::kShiftedSoft: {  // eq. 3.43 (soft: s = 0)
      double s = 0.0;
      if (t == LodTransition::kShiftedSoft && std::isfinite(shift)) s = std::clamp(static_cast<double>(shift), 0.0, 0.95);
      constexpr double kPi = 3.14159265358979323846;
      // smooth(x): 1 for x <= 0, cos x on (0, pi), -1 for x >= pi.
      const auto smooth = [](double x) { return x <= 0.0 ? 1.0 : x >= kPi ? -1.0 : std::cos(x); };
      const double fd = static_cast<double>(f);
      const double a = 0.5 * (smooth((fd - s) / (1.0 - s) * kPi) + 1.0);
      const double b = 1.0 - 0.5 * (smooth(fd / (1.0 - s) * kPi) + 1.0);
      w = {static_cast<float>(std::clamp(a, 0.0, 1.0)), static_cast<float>(std::clamp(b, 0.0, 1.0))};
      break;
    }
    case LodTransition::kFadeInBackground:
    default:  // eq. 3.42: one level is opaque at every phase.
      w = {std::min(1.0f, 2.0f * (1.0f - f)), std::min(1.0f, 2.0f * f)};
      break;
  }
  return w;
}

LodDraws lod_draws(float l) { return lod_draws(l, LodTransition::kFadeInBackground, 0.5f); }

LodDraws lod_draws(float l, LodTransition transition, float shift) {
  LodDraws out;
  if (!(l > 0.0f)) {
    out.draw[0] = {0, 1.0f};
    out.count = 1;
    return out;
  }
  if (l >= 2.0f) {
    out.draw[0] = {2, 1.0f};
    out.count = 1;
    return out;
  }
  const int k = static_cast<int>(std::floor(l));
  const float f = l - static_cast<float>(k);
  if (f == 0.0f) {
    out.draw[0] = {k, 1.0f};
    out.count = 1;
    return out;
  }
  // A level of weight 0 (the far end of a cosine ramp, or of a shifted one) is not drawn; the
  // weights never are both 0 (a + b >= 1).
  const LodWeights w = lod_transition_weights(transition, f, shift);
  if (w.a > 0.0f) out.draw[static_cast<std::size_t>(out.count++)] = {k, w.a};
  if (w.b > 0.0f) out.draw[static_cast<std::size_t>(out.count++)] = {k + 1, w.b};
  return out;
}

void select_lods(const LodSettings& s, const LodView& view, std::span<const render::Sphere> spheres,
                 std::span<const float> heights, LodState& state, LodQueues& out) {
  for (int k = 0; k < kLodLevels; ++k) {
    out.level[static_cast<std::size_t>(k)].clear();
    out.distance[static_cast<std::size_t>(k)].clear();
  }
  out.considered = spheres.size();
  out.visible = 0;
  out.transitions = 0;
  if (state.distance.size() != spheres.size() || state.level.size() != spheres.size()) {
    state.distance.assign(spheres.size(), std::numeric_limits<double>::quiet_NaN());
    state.level.assign(spheres.size(), std::numeric_limits<float>::quiet_NaN());
  }
  const double max_d = std::isnan(view.max_distance) ? 0.0 : view.max_distance;
  // Thresholds are per instance only for the screen-size criterion; resolve once otherwise.
  const bool per_instance = s.criterion == LodCriterion::kScreenSize;
  const LodRamps shared = lod_ramps(s, 1.0, view.pixels_per_radian);
  const bool horizontal = s.criterion == LodCriterion::kHorizontalDistance;
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const render::Sphere& sp = spheres[i];
    const glm::dvec3 d = sp.center - view.camera;
    const double dist3 = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    if (dist3 - sp.radius > max_d) continue;
    float l = 0.0f;
    if (s.enabled) {
      const double metric = horizontal ? std::sqrt(d.x * d.x + d.z * d.z) : dist3;
      const LodRamps r = per_instance ? lod_ramps(s, static_cast<double>(heights[i]), view.pixels_per_radian) : shared;
      const double e = lod_follow(state.distance[i], metric, s.hysteresis);
      state.distance[i] = e;
      l = dist3 < kLod0Radii * sp.radius ? 0.0f : lod_target(r, e);
      state.level[i] = l;
    }
    if (view.frustum != nullptr && !view.frustum->intersects(sp)) continue;
    const LodDraws draws = lod_draws(l, s.transition, s.transition_shift);
    for (int k = 0; k < draws.count; ++k) {
      const auto level = static_cast<std::size_t>(draws.draw[static_cast<std::size_t>(k)].level);
      out.level[level].push_back({static_cast<std::uint32_t>(i), draws.draw[static_cast<std::size_t>(k)].fade});
      out.distance[level].push_back(static_cast<float>(dist3));
    }
    ++out.visible;
    if (draws.count == 2) ++out.transitions;
  }
  if (s.sort_front_to_back)
    for (int k = 0; k < kLodLevels; ++k)
      sort_queue(out.level[static_cast<std::size_t>(k)], out.distance[static_cast<std::size_t>(k)], out.sort_tmp, out.sort_count);
}

}  // namespace sylva::vegetation

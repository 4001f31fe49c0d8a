#include <sylva/vegetation/placement.hpp>

#include <sylva/core/rng.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva::vegetation {
namespace {

Status check_settings(const PlacementSettings& s) {
  SYLVA_TRY(validate_params(s, "placement"));
  if (s.scale_min > s.scale_max)
    return make_error(ErrorCode::kInvalidArgument, fmt::format("placement.scale_min: {} is above placement.scale_max = {}",
                                                               s.scale_min, s.scale_max));
  return ok_status();
}

Status check_ground(const HeightField& g) {
  if (g.columns() < 1 || g.rows() < 1)
    return make_error(ErrorCode::kInvalidArgument, "placement: the height field is empty");
  return ok_status();
}

bool slope_ok(const HeightField& g, double x, double z, float max_slope_deg) {
  const glm::vec3 n = g.normal(x, z);
  const float cos_max = std::cos(max_slope_deg * std::numbers::pi_v<float> / 180.0f);
  return n.y >= cos_max - 1e-6f;
}

TreeInstance make_instance(const HeightField& g, double x, double z, const PlacementSettings& s, Pcg32& rng) {
  TreeInstance t;
  t.position = glm::dvec3(x, static_cast<double>(g.height(x, z)) - s.sink, z);
  t.yaw = rng.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
  t.scale = s.scale_min + (s.scale_max - s.scale_min) * rng.next_float();
  t.time_offset = s.time_offset_range * rng.next_float();
  t.season_offset = -s.season_spread * rng.next_float();
  const glm::vec3 v(rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f));
  t.color_variation = s.color_variation * v * glm::vec3(0.8f, 0.6f, 0.3f);
  t.number = rng.next_float();
  return t;
}

Error too_many(const PlacementSettings& s) {
  return make_error(ErrorCode::kLimit, fmt::format("placement: more than placement.max_instances = {} trees; raise it or "
                                                   "lower the density", s.max_instances));
}

}  // namespace

float density_at(const HeightField& g, const Image& map, double x, double z) {
  const glm::dvec2 e = g.extent();
  const double u = e.x > 0.0 ? (x - g.origin().x) / e.x : 0.5;
  const double v = e.y > 0.0 ? (z - g.origin().y) / e.y : 0.5;
  const double fx = u * map.width() - 0.5;
  const double fy = (1.0 - v) * map.height() - 0.5;  // image row 0 at the field's max z
  const double x0 = std::floor(fx);
  const double y0 = std::floor(fy);
  const auto tx = static_cast<float>(fx - x0);
  const auto ty = static_cast<float>(fy - y0);
  const int ix = static_cast<int>(x0);
  const int iy = static_cast<int>(y0);
  const float a = map.at_clamped(ix, iy, 0);
  const float b = map.at_clamped(ix + 1, iy, 0);
  const float c = map.at_clamped(ix, iy + 1, 0);
  const float d = map.at_clamped(ix + 1, iy + 1, 0);
  return std::clamp((a * (1.0f - tx) + b * tx) * (1.0f - ty) + (c * (1.0f - tx) + d * tx) * ty, 0.0f, 1.0f);
}

Result<std::vector<TreeInstance>> place_poisson_disk(const HeightField& g, const PlacementSettings& s, const Image* map) {
  SYLVA_TRY(check_settings(s));
  SYLVA_TRY(check_ground(g));
  if (map != nullptr && map->empty()) return make_error(ErrorCode::kInvalidArgument, "placement: the density map is empty");
  const glm::dvec2 origin = g.origin();
  const glm::dvec2 extent = g.extent();
  const double r = s.min_distance;
  // Bridson's background grid: cells of r / sqrt(2) hold at most one sample.
  const double cell = r / std::sqrt(2.0);
  const auto gw = static_cast<std::int64_t>(std::floor(extent.x / cell)) + 1;
  const auto gh = static_cast<std::int64_t>(std::floor(extent.y / cell)) + 1;
  if (gw * gh > static_cast<std::int64_t>(s.max_instances) * 8 + 64) return too_many(s);
  std::vector<int> grid(static_cast<std::size_t>(gw * gh), -1);
  std::vector<glm::dvec2> samples;
  std::vector<int> active;
  Pcg32 rng(s.seed, 0x706f6973u);
  const auto grid_index = [&](const glm::dvec2& p) {
    const auto gx = std::clamp<std::int64_t>(static_cast<std::int64_t>((p.x - origin.x) / cell), 0, gw - 1);
    const auto gy = std::clamp<std::int64_t>(static_cast<std::int64_t>((p.y - origin.y) / cell), 0, gh - 1);
    return std::pair{gx, gy};
  };
  const auto fits = [&](const glm::dvec2& p) {
    if (p.x < origin.x || p.y < origin.y || p.x > origin.x + extent.x || p.y > origin.y + extent.y) return false;
    const auto [gx, gy] = grid_index(p);
    for (std::int64_t y = std::max<std::int64_t>(0, gy - 2); y <= std::min(gh - 1, gy + 2); ++y)
      for (std::int64_t x = std::max<std::int64_t>(0, gx - 2); x <= std::min(gw - 1, gx + 2); ++x) {
        const int k = grid[static_cast<std::size_t>(y * gw + x)];
        if (k >= 0 && glm::length(samples[static_cast<std::size_t>(k)] - p) < r) return false;
      }
    return true;
  };
  const auto add = [&](const glm::dvec2& p) {
    const auto [gx, gy] = grid_index(p);
    grid[static_cast<std::size_t>(gy * gw + gx)] = static_cast<int>(samples.size());
    active.push_back(static_cast<int>(samples.size()));
    samples.push_back(p);
  };
  add(origin + glm::dvec2(rng.next_double() * extent.x, rng.next_double() * extent.y));
  constexpr int kCandidates = 30;
  while (!active.empty()) {
    const std::size_t pick = rng.next_below(static_cast<std::uint32_t>(active.size()));
    const glm::dvec2 base = samples[static_cast<std::size_t>(active[pick])];
    bool found = false;
    for (int c = 0; c < kCandidates; ++c) {
      const double angle = rng.next_double() * 2.0 * std::numbers::pi;
      const double dist = r * (1.0 + rng.next_double());
      const glm::dvec2 p = base + dist * glm::dvec2(std::cos(angle), std::sin(angle));
      if (fits(p)) {
        add(p);
        found = true;
        break;
      }
    }
    if (!found) {
      active[pick] = active.back();
      active.pop_back();
    }
  }
  std::vector<TreeInstance> out;
  Pcg32 attrs(s.seed, 0x61747472u);
  for (const glm::dvec2& p : samples) {
    const float keep = attrs.next_float();  // drawn for every sample so the thinning is stable
    Pcg32 tree_rng(hash_u32(static_cast<std::uint32_t>(out.size()), s.seed), attrs.next_u32());
    if (map != nullptr && keep >= density_at(g, *map, p.x, p.y)) continue;
    if (!slope_ok(g, p.x, p.y, s.max_slope_deg)) continue;
    if (out.size() >= s.max_instances) return too_many(s);
    out.push_back(make_instance(g, p.x, p.y, s, tree_rng));
  }
  return out;
}

Result<std::vector<TreeInstance>> place_by_density(const HeightField& g, const Image& map, const PlacementSettings& s) {
  SYLVA_TRY(check_settings(s));
  SYLVA_TRY(check_ground(g));
  if (map.empty()) return make_error(ErrorCode::kInvalidArgument, "placement: the density map is empty");
  const double cell = 1.0 / std::sqrt(static_cast<double>(s.density));
  const glm::dvec2 lo = g.origin();
  const glm::dvec2 hi = g.origin() + g.extent();
  const auto i0 = static_cast<std::int64_t>(std::floor(lo.x / cell));
  const auto i1 = static_cast<std::int64_t>(std::floor(hi.x / cell));
  const auto j0 = static_cast<std::int64_t>(std::floor(lo.y / cell));
  const auto j1 = static_cast<std::int64_t>(std::floor(hi.y / cell));
  if ((i1 - i0 + 1) * (j1 - j0 + 1) > static_cast<std::int64_t>(s.max_instances) * 64 + 64) return too_many(s);
  std::vector<TreeInstance> out;
  for (std::int64_t j = j0; j <= j1; ++j) {
    for (std::int64_t i = i0; i <= i1; ++i) {
      const std::uint32_t h = hash_i32(static_cast<std::int32_t>(i), static_cast<std::int32_t>(j), s.seed);
      const double x = (static_cast<double>(i) + hash_to_unit_float(hash_u32(h, 1u))) * cell;
      const double z = (static_cast<double>(j) + hash_to_unit_float(hash_u32(h, 2u))) * cell;
      if (x < lo.x || z < lo.y || x > hi.x || z > hi.y) continue;
      if (hash_to_unit_float(h) >= density_at(g, map, x, z)) continue;
      if (!slope_ok(g, x, z, s.max_slope_deg)) continue;
      if (out.size() >= s.max_instances) return too_many(s);
      Pcg32 rng(hash_u32(h, 3u), hash_u32(h, 4u));
      out.push_back(make_instance(g, x, z, s, rng));
    }
  }
  return out;
}

}  // namespace sylva::vegetation

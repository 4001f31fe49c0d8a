#include <sylva/grass/far_field.hpp>

#include "shadow_binding.hpp"
#include "tile_merge.hpp"

#include <sylva/core/log.hpp>
#include <sylva/core/params.hpp>
#include <sylva/core/rng.hpp>
#include <sylva/grass/culling.hpp>
#include <sylva/grass/field_color.hpp>
#include <sylva/render/frame_context.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <numbers>

namespace sylva::render::embedded {
void register_grass_shaders();
}  // namespace sylva::render::embedded

namespace sylva::grass {

namespace {

constexpr GLuint kClumpsBinding = 5;
constexpr GLuint kWindUboBinding = 1;
constexpr float kPi = std::numbers::pi_v<float>;
constexpr int kAtlasSize = 256;  // the clump atlas, 2 x 2 cells
constexpr std::size_t kGroundFloats = kGroundVertexFloats;  // ground layer vertex: position, normal, field colour

float ramp(float d, float a, float b) {
  if (!(b > a)) return d >= b ? 1.0f : 0.0f;
  return std::clamp((d - a) / (b - a), 0.0f, 1.0f);
}

float unit(std::uint32_t h, std::uint32_t salt) { return hash_to_unit_float(hash_u32(salt, h)); }

// Periodic value noise on a period x period lattice, smooth (quintic) interpolation.
float periodic_noise(float x, float y, int period, std::uint32_t seed) {
  const int xi = static_cast<int>(std::floor(x)), yi = static_cast<int>(std::floor(y));
  const float fx = x - static_cast<float>(xi), fy = y - static_cast<float>(yi);
  auto v = [&](int i, int j) {
    const auto wi = static_cast<std::uint32_t>(((i % period) + period) % period);
    const auto wj = static_cast<std::uint32_t>(((j % period) + period) % period);
    return hash_to_unit_float(hash_u32(wi, wj, seed));
  };
  auto q = [](float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); };
  const float sx = q(fx), sy = q(fy);
  const float a = v(xi, yi) + (v(xi + 1, yi) - v(xi, yi)) * sx;
  const float b = v(xi, yi + 1) + (v(xi + 1, yi + 1) - v(xi, yi + 1)) * sx;
  return a + (b - a) * sy;
}

bool box_visible(const CullView& view, const glm::vec3& lo, const glm::vec3& hi) {
  for (const glm::vec4& p : view.planes) {
    const glm::vec3 n(p);
    const glm::vec3 far_corner(n.x >= 0 ? hi.x : lo.x, n.y >= 0 ? hi.y : lo.y, n.z >= 0 ? hi.z : lo.z);
    if (glm::dot(n, far_corner) + p.w < 0.0f) return false;
  }
  return true;
}

// Nearest and farthest distance from p to a box.
void box_distances(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi, float& nearest, float& farthest) {
  nearest = glm::length(glm::clamp(p, lo, hi) - p);
  const glm::vec3 far_corner(std::abs(p.x - lo.x) > std::abs(p.x - hi.x) ? lo.x : hi.x,
                             std::abs(p.y - lo.y) > std::abs(p.y - hi.y) ? lo.y : hi.y,
                             std::abs(p.z - lo.z) > std::abs(p.z - hi.z) ? lo.z : hi.z);
  farthest = glm::length(far_corner - p);
}

}  // namespace

namespace {

// The sample point of texel (i, j) of extended images over `out` of w x h texels: its centre,
// clamped a hair inside the original rectangle, where every map is defined.
glm::dvec2 extended_sample_point(const Rect& in, const Rect& out, int w, int h, int i, int j) {
  const glm::dvec2 lo = in.min + 1e-6 * in.size(), hi = in.max - 1e-6 * in.size();
  return glm::clamp(out.min + (glm::dvec2(i, j) + 0.5) * out.size() / glm::dvec2(w, h), lo, hi);
}

void resample_extended_texel(ExtendedMapImages& e, const GrassMaps& maps, int i, int j) {
  const glm::dvec2 p = extended_sample_point(maps.rect(), e.rect, e.density.width(), e.density.height(), i, j);
  e.density.at(i, j, 0) = maps.density(p.x, p.y);
  e.height.at(i, j, 0) = maps.height_scale(p.x, p.y);
  const glm::vec3 t = maps.tint(p.x, p.y);
  for (int c = 0; c < 3; ++c) e.tint.at(i, j, c) = t[c];
}

}  // namespace

ExtendedMapImages extend_map_images(const GrassMaps& maps, double margin) {
  ExtendedMapImages e;
  const Rect in = maps.rect();
  if (!(margin > 0.0) || in.empty()) return e;
  e.rect = {in.min - margin, in.max + margin};
  const glm::dvec2 texel = glm::max(maps.density_texel(), e.rect.size() / 2048.0);
  const int w = std::max(1, static_cast<int>(std::ceil(e.rect.size().x / texel.x)));
  const int h = std::max(1, static_cast<int>(std::ceil(e.rect.size().y / texel.y)));
  e.density = Image(w, h, 1);
  e.height = Image(w, h, 1);
  e.tint = Image(w, h, 3);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) resample_extended_texel(e, maps, i, j);
  return e;
}

Rect refresh_extended_map_images(ExtendedMapImages& e, const GrassMaps& maps, const Rect& changed) {
  if (e.rect.empty() || changed.empty()) return {};
  const int w = e.density.width(), h = e.density.height();
  const glm::dvec2 texel = e.rect.size() / glm::dvec2(w, h);
  // A texel's sample point is its centre clamped into maps.rect(): texels beyond an edge the edit
  // touches sample the edit too, so the candidates run out to the margin there.
  const Rect in = maps.rect();
  auto first = [&](double lo, double in_lo, double out_lo, double t) {
    return lo <= in_lo ? 0 : static_cast<int>(std::floor((lo - out_lo) / t - 0.5)) - 1;
  };
  auto last = [&](double hi, double in_hi, double out_lo, double t, int n) {
    return hi >= in_hi ? n : static_cast<int>(std::ceil((hi - out_lo) / t - 0.5)) + 2;
  };
  const int i0 = std::clamp(first(changed.min.x, in.min.x + 1e-6 * in.size().x, e.rect.min.x, texel.x), 0, w);
  const int i1 = std::clamp(last(changed.max.x, in.max.x - 1e-6 * in.size().x, e.rect.min.x, texel.x, w), 0, w);
  const int j0 = std::clamp(first(changed.min.y, in.min.y + 1e-6 * in.size().y, e.rect.min.y, texel.y), 0, h);
  const int j1 = std::clamp(last(changed.max.y, in.max.y - 1e-6 * in.size().y, e.rect.min.y, texel.y, h), 0, h);
  int ri0 = w, ri1 = -1, rj0 = h, rj1 = -1;
  for (int j = j0; j < j1; ++j) {
    for (int i = i0; i < i1; ++i) {
      const glm::dvec2 p = extended_sample_point(in, e.rect, w, h, i, j);
      if (p.x < changed.min.x || p.x > changed.max.x || p.y < changed.min.y || p.y > changed.max.y) continue;
      resample_extended_texel(e, maps, i, j);
      ri0 = std::min(ri0, i);
      ri1 = std::max(ri1, i);
      rj0 = std::min(rj0, j);
      rj1 = std::max(rj1, j);
    }
  }
  if (ri1 < 0) return {};
  // The bilinear interpolant (and a cell's exact integral) reads a texel within one texel of its
  // centre; one more texel and a hair of margin against rounding.
  return {e.rect.min + (glm::dvec2(ri0, rj0) - 1.01) * texel, e.rect.min + (glm::dvec2(ri1, rj1) + 2.01) * texel};
}

Result<GrassMaps> extend_maps(const GrassMaps& maps, double margin) {
  const ExtendedMapImages e = extend_map_images(maps, margin);
  if (e.rect.empty()) return maps;
  return e.maps();
}

float slope_keep(float normal_y, float max_slope_deg) {
  if (max_slope_deg >= 90.0f) return 1.0f;
  const float slope = std::acos(std::clamp(normal_y, -1.0f, 1.0f)) * (180.0f / kPi);
  return 1.0f - ramp(slope, max_slope_deg - 8.0f, max_slope_deg);
}

float clump_fade(float d, float near_distance, const FarFieldSettings& s) {
  const float in = ramp(d, near_distance - s.clump_fade_in, near_distance);
  const float out = 1.0f - ramp(d, s.mid_distance - s.mid_fade, s.mid_distance);
  const float wide = s.wide_billboards ? ramp(d, s.wide_distance - s.wide_fade, s.wide_distance) : 0.0f;
  return in * out * (1.0f - wide);
}

float wide_fade_at(float d, float near_distance, const FarFieldSettings& s) {
  if (!s.wide_billboards) return 0.0f;
  const float in = ramp(d, near_distance - s.clump_fade_in, near_distance);
  const float out = 1.0f - ramp(d, s.mid_distance - s.mid_fade, s.mid_distance);
  return in * out * ramp(d, s.wide_distance - s.wide_fade, s.wide_distance);
}

float ground_fade(float d, const FarFieldSettings& s) {
  return ramp(d, s.mid_distance - s.mid_fade, s.mid_distance) * (1.0f - ramp(d, s.far_distance - s.far_fade, s.far_distance));
}

float ground_coverage(float sin_elevation, float tau_side, float tau_top, float gain) {
  const float s = std::clamp(sin_elevation, 0.05f, 1.0f);
  const float cot = std::sqrt(std::max(1.0f - s * s, 0.0f)) / s;
  return 1.0f - std::exp(-gain * (tau_top + tau_side * cot));
}

namespace {

// Clumps of `width` at per_m2 times the density map on a world grid of tile_size (the blades'
// tile sampler), one GrassTile per grid cell that holds any; shared by the small clumps and the
// wide billboards (seed 003 §2.4.1 and §2.4.3 differ only in grid, count and width). `wide`:
// each cell is a group clipped to the map, with far.wide_per_group billboards per clipped group at
// density 1, as wide as its longer side, their strand keep in size.z (far_field.hpp).
Result<ClumpSet> place_clumps(const GrassFieldSettings& field, const BladeSettings& blade, const GrassMaps& maps,
                              const HeightField& ground, const glm::dvec3& origin, const FarFieldSettings& far,
                              double t, double per_m2, float width, std::uint32_t seed, const char* what, bool wide,
                              const Rect* within) {
  SYLVA_TRY(check_settings(field, blade));
  SYLVA_TRY(validate_params(far, "grass.far"));
  if (ground.samples().empty()) return make_error(ErrorCode::kInvalidArgument, "grass far field: the ground height field is empty");
  ClumpSet set;
  set.origin = origin;
  const Rect area = maps.rect();
  if (area.empty()) return set;
  const Result<TileRange> range = tiles_overlapping(area, t);
  if (!range.ok()) return range.error();
  const auto [x0, x1, z0, z1] = within ? clump_tile_range(area, *within, t) : *range;
  const double expected = maps.density_integral(area) * per_m2;
  if (expected > static_cast<double>(kMaxBlades)) {
    return make_error(ErrorCode::kLimit, fmt::format("{}: {:.0f} clumps is above the limit {}", what, expected, kMaxBlades));
  }
  const float mean_height = 0.5f * (blade.height_min + blade.height_max);
  const bool dense = !wide && far.dense_extra_billboards;
  // The atlas FarField::create draws the clumps with (same size and seed): its coverage curve.
  const std::vector<float> curve = dense ? clump_coverage_curve(make_clump_atlas(kAtlasSize, field.seed)) : std::vector<float>{};
  for (std::int64_t z = z0; z < z1; ++z) {
    for (std::int64_t x = x0; x < x1; ++x) {
      GrassTile tile;
      tile.key = {static_cast<std::int32_t>(x), 0, static_cast<std::int32_t>(z)};
      tile.first = static_cast<std::uint32_t>(set.clumps.size());
      const Rect cell{{x * t, z * t}, {(x + 1) * t, (z + 1) * t}};
      double cell_per_m2 = per_m2;
      float cell_width = width, keep = 0.0f;
      std::size_t extras = 0;
      if (wide) {
        const Rect clipped = cell.intersect(area);
        if (clipped.empty()) continue;
        const double a = clipped.size().x * clipped.size().y;
        cell_per_m2 = far.wide_per_group / a;
        cell_width = static_cast<float>(std::max(clipped.size().x, clipped.size().y));
        keep = wide_keep(far, a, cell_width);
      }
      auto points = sample_tile_points(maps, tile.key, t, cell_per_m2, seed);
      const double integral = maps.density_integral(cell);
      if (dense) {
        // Seed 003 §2.4.2 overcrowding guard (far_field.hpp): above 50 % of the maximum density the
        // tile gets dense_extra_per_tile clumps more, following the map, and a shifted threshold.
        const Rect clipped = cell.intersect(area);
        const double inside = clipped.empty() ? 0.0 : clipped.size().x * clipped.size().y;
        keep = 1.0f;
        // "Above 50 %" with a relative tolerance, so a map value of exactly 0.5 is not above it by
        // the rounding of the integral.
        if (inside > 0.0 && integral > 0.5 * inside * (1.0 + 1e-5)) {
          const int extra = far.dense_extra_per_tile;
          const auto more = sample_tile_points(maps, tile.key, t, extra / integral, seed ^ 0x0de45e7u);
          points.insert(points.end(), more.begin(), more.end());
          extras = more.size();
          keep = dense_keep(integral * cell_per_m2, extra, curve);
        }
      }
      glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
      for (const TilePoint& p : points) {
        const double wx = p.position.x, wz = p.position.y;
        if (!(unit(p.hash, 27u) < slope_keep(ground.normal(wx, wz).y, far.max_slope_deg))) continue;
        const glm::vec3 root(static_cast<float>(wx - origin.x), static_cast<float>(ground.height(wx, wz) - origin.y),
                             static_cast<float>(wz - origin.z));
        const float h = std::max(mean_height * (0.8f + 0.4f * unit(p.hash, 21u)) * maps.height_scale(wx, wz), blade.min_height);
        const glm::vec3 tint = maps.tint(wx, wz) * field_color(wx, wz, blade, field.seed) *
                               (1.0f + blade.color_variation * (2.0f * unit(p.hash, 22u) - 1.0f));
        Clump c;
        c.root = glm::vec4(root, unit(p.hash, 23u) * kPi);
        const float w = cell_width * (wide ? 1.0f : 0.8f + 0.4f * unit(p.hash, 24u));
        c.size = glm::vec4(w, h, wide || dense ? keep : p.rank, std::floor(unit(p.hash, 25u) * 4.0f));
        c.color = glm::vec4(tint, unit(p.hash, 26u));
        set.clumps.push_back(c);
        lo = glm::min(lo, root - glm::vec3(w + h));
        hi = glm::max(hi, root + glm::vec3(w + h));
      }
      tile.count = static_cast<std::uint32_t>(set.clumps.size()) - tile.first;
      if (tile.count == 0) continue;
      tile.bounds_min = lo;
      tile.bounds_max = hi;
      tile.expected = integral * cell_per_m2 + static_cast<double>(extras);
      set.tiles.push_back(tile);
    }
  }
  return set;
}

}  // namespace

TileRange clump_tile_range(const Rect& area, const Rect& within, double tile) {
  const Rect r = area.intersect(within);
  if (r.empty()) return {};
  const Result<TileRange> range = tiles_overlapping(r, tile);
  return range.ok() ? *range : TileRange{};
}

Result<ClumpSet> generate_clumps(const GrassFieldSettings& field, const BladeSettings& blade, const GrassMaps& maps,
                                 const HeightField& ground, const glm::dvec3& origin, const FarFieldSettings& far,
                                 const Rect* within) {
  // A different seed than the blades so clumps do not sit on the first blades.
  return place_clumps(field, blade, maps, ground, origin, far, field.tile_size, far.clumps_per_m2, far.clump_width,
                      field.seed ^ 0xc1a3a5u, "grass.far.clumps_per_m2", false, within);
}

namespace {
double wide_group_size(const GrassFieldSettings& field, const FarFieldSettings& far) {
  return static_cast<double>(field.tile_size) * far.wide_group;
}
}  // namespace

Result<ClumpSet> generate_wide_billboards(const GrassFieldSettings& field, const BladeSettings& blade, const GrassMaps& maps,
                                          const HeightField& ground, const glm::dvec3& origin, const FarFieldSettings& far,
                                          const Rect* within) {
  // Seed 003 §2.4.3 / Tab. 4.2: wide_per_group billboards per (clipped) group at density 1.
  const double group = wide_group_size(field, far);
  return place_clumps(field, blade, maps, ground, origin, far, group, far.wide_per_group / (group * group),
                      static_cast<float>(group), field.seed ^ 0x3f1de5u, "grass.far.wide_per_group", true, within);
}

std::vector<float> clump_coverage_curve(const Image& atlas) {
  std::vector<float> curve;
  curve.reserve(atlas.pixel_count());
  for (int y = 0; y < atlas.height(); ++y)
    for (int x = 0; x < atlas.width(); ++x) curve.push_back(atlas.at(x, y, atlas.channels() - 1));
  std::sort(curve.begin(), curve.end());
  return curve;
}

double clump_coverage(const std::vector<float>& curve, float threshold) {
  if (curve.empty()) return 0.0;
  const auto below = std::lower_bound(curve.begin(), curve.end(), threshold) - curve.begin();
  return static_cast<double>(below) / static_cast<double>(curve.size());
}

float dense_keep(double plain_count, int extra, const std::vector<float>& curve) {
  // Seed 003 §2.4.2 "shifted threshold" (far_field.hpp): (n + extra) c(k) = n c(1).
  if (extra <= 0 || curve.empty() || !(plain_count > 0.0)) return 1.0f;
  const double target = plain_count / (plain_count + extra) * clump_coverage(curve, 1.0f) * static_cast<double>(curve.size());
  float best = 1.0f;
  double best_error = std::abs(clump_coverage(curve, 1.0f) * static_cast<double>(curve.size()) - target);
  // Candidates: halfway between consecutive distinct strand thresholds (texels below: i).
  for (std::size_t i = 1; i < curve.size() && curve[i] < 1.0f; ++i) {
    if (curve[i] == curve[i - 1]) continue;
    const double error = std::abs(static_cast<double>(i) - target);
    if (error < best_error) {
      best_error = error;
      best = 0.5f * (curve[i - 1] + curve[i]);
    }
  }
  return best;
}

NoiseSubregion noise_subregion(std::int32_t tx, std::int32_t tz, std::uint32_t seed) {
  // shaders/far.glsl grass_noise_subregion() is the twin: same bits, same scales.
  const std::uint32_t h = hash_i32(tx, tz, seed);
  NoiseSubregion r;
  r.offset = glm::vec2(static_cast<float>(h & 0xffffu) / 65536.0f, static_cast<float>((h >> 16u) & 0xfffu) / 4096.0f);
  r.quarter_turns = static_cast<int>(h >> 30u);
  return r;
}

float wide_keep(const FarFieldSettings& s, double group_area, float width) {
  // Strand length per m^2 at density 1: count per m^2 x billboard width (both levels cross two quads).
  const double small = static_cast<double>(s.clumps_per_m2) * s.clump_width;
  const double wide = s.wide_per_group / std::max(group_area, 1e-6) * width;
  return static_cast<float>(std::clamp(small / wide, 1e-3, 1.0));
}

Image make_clump_atlas(int size, std::uint32_t seed) {
  Image img(size, size, 4, PixelFormat::kU8);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) img.at(x, y, 3) = 1.0f;
  const int cs = size / 2;
  constexpr int kStrands = 56;
  for (int cell = 0; cell < 4; ++cell) {
    const int ox = (cell % 2) * cs, oy = (cell / 2) * cs;
    // A random permutation of the graded thresholds, so neighbouring strands appear at
    // unrelated densities.
    int order[kStrands];
    for (int k = 0; k < kStrands; ++k) order[k] = k;
    Pcg32 rng(hash_u32(static_cast<std::uint32_t>(cell), seed), 7u);
    for (int k = kStrands - 1; k > 0; --k) std::swap(order[k], order[rng.next_below(static_cast<std::uint32_t>(k + 1))]);
    for (int k = 0; k < kStrands; ++k) {
      const float threshold = (static_cast<float>(order[k]) + 0.5f) / kStrands;
      const float x0 = (0.06f + 0.88f * rng.next_float()) * static_cast<float>(cs);
      const float height = (0.55f + 0.45f * rng.next_float()) * static_cast<float>(cs - 2);
      const float lean = (rng.next_float() - 0.5f) * 0.5f * static_cast<float>(cs);
      const float half_w = 0.6f + 1.2f * rng.next_float() * static_cast<float>(cs) / 64.0f;
      const float shade = 0.75f + 0.5f * rng.next_float();
      for (int row = 0; row < static_cast<int>(height); ++row) {
        const float v = static_cast<float>(row) / height;  // 0 root, 1 tip
        const float cx = x0 + lean * v * v;
        const float hw = half_w * (1.0f - v) + 0.35f;
        const int y = oy + (cs - 1 - row);  // image row 0 is the top: roots at the bottom
        for (int x = static_cast<int>(std::floor(cx - hw)); x <= static_cast<int>(std::ceil(cx + hw)); ++x) {
          if (x < 0 || x >= cs || std::abs(static_cast<float>(x) + 0.5f - cx) > hw) continue;
          const int px = ox + x;
          if (threshold < img.at(px, y, 3)) {
            img.at(px, y, 3) = threshold;
            // Luminance ramp root -> tip; the hue comes from the field's colours in the shader.
            const float l = std::clamp((0.25f + 0.75f * v) * shade, 0.0f, 1.0f);
            img.at(px, y, 0) = l;
            img.at(px, y, 1) = l;
            img.at(px, y, 2) = l;
          }
        }
      }
    }
  }
  return img;
}

Image make_ground_texture(int size, std::uint32_t seed) {
  Image img(size, size, 4, PixelFormat::kU8);
  std::vector<float> coverage(static_cast<std::size_t>(size) * static_cast<std::size_t>(size));
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float u = static_cast<float>(x) / static_cast<float>(size), v = static_cast<float>(y) / static_cast<float>(size);
      // Coverage noise: fine blades-from-above speckle over a tuft-scale pattern.
      float n = 0.0f, amp = 1.0f, norm = 0.0f;
      for (int o = 0; o < 4; ++o) {
        const int period = 8 << o;
        n += amp * periodic_noise(u * static_cast<float>(period), v * static_cast<float>(period), period, seed + static_cast<std::uint32_t>(o));
        norm += amp;
        amp *= 0.7f;
      }
      coverage[static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x)] = n / norm;
      const float c = periodic_noise(u * 16.0f, v * 16.0f, 16, seed ^ 0xabcdu);
      const float l = 0.55f + 0.45f * periodic_noise(u * 64.0f, v * 64.0f, 64, seed ^ 0x1234u);
      img.at(x, y, 0) = std::clamp(l * (0.8f + 0.4f * c), 0.0f, 1.0f);
      img.at(x, y, 1) = std::clamp(l, 0.0f, 1.0f);
      img.at(x, y, 2) = std::clamp(l * (1.1f - 0.3f * c), 0.0f, 1.0f);
    }
  }
  // Histogram equalisation: alpha = rank / count, so "alpha < density" covers exactly a share
  // `density` of the texels.
  std::vector<std::uint32_t> order(coverage.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return coverage[a] < coverage[b]; });
  for (std::size_t r = 0; r < order.size(); ++r) {
    const std::uint32_t i = order[r];
    img.at(static_cast<int>(i % static_cast<std::uint32_t>(size)), static_cast<int>(i / static_cast<std::uint32_t>(size)), 3) =
        (static_cast<float>(r) + 0.5f) / static_cast<float>(order.size());
  }
  return img;
}

std::vector<Image> coverage_preserving_mips(const Image& level0) {
  std::vector<Image> levels{level0};
  const int channels = level0.channels();
  // The level-0 alpha distribution, sorted, is the target of every level.
  std::vector<float> target(level0.pixel_count());
  for (int y = 0, i = 0; y < level0.height(); ++y)
    for (int x = 0; x < level0.width(); ++x) target[static_cast<std::size_t>(i++)] = level0.at(x, y, channels - 1);
  std::sort(target.begin(), target.end());
  while (levels.back().width() > 1 || levels.back().height() > 1) {
    const Image& prev = levels.back();
    const int w = std::max(prev.width() / 2, 1), h = std::max(prev.height() / 2, 1);
    Image next(w, h, channels, prev.format());
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < channels; ++c)
          next.at(x, y, c) = 0.25f * (prev.at_clamped(2 * x, 2 * y, c) + prev.at_clamped(2 * x + 1, 2 * y, c) +
                                      prev.at_clamped(2 * x, 2 * y + 1, c) + prev.at_clamped(2 * x + 1, 2 * y + 1, c));
    // Histogram matching of alpha: the k-th smallest texel gets the level-0 quantile (k + 0.5) / n.
    std::vector<std::uint32_t> order(next.pixel_count());
    for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      return next.at(static_cast<int>(a % static_cast<std::uint32_t>(w)), static_cast<int>(a / static_cast<std::uint32_t>(w)), channels - 1) <
             next.at(static_cast<int>(b % static_cast<std::uint32_t>(w)), static_cast<int>(b / static_cast<std::uint32_t>(w)), channels - 1);
    });
    for (std::size_t k = 0; k < order.size(); ++k) {
      const double q = (static_cast<double>(k) + 0.5) / static_cast<double>(order.size());
      const auto src = static_cast<std::size_t>(std::min(q * static_cast<double>(target.size()), static_cast<double>(target.size() - 1)));
      next.at(static_cast<int>(order[k] % static_cast<std::uint32_t>(w)), static_cast<int>(order[k] / static_cast<std::uint32_t>(w)), channels - 1) =
          target[src];
    }
    levels.push_back(std::move(next));
  }
  return levels;
}

namespace {

// The ground layer's vertex on height-field sample `sample` (9 floats: position lifted along the
// normal by ground_offset, normal, field colour) written to `out`; returns the position.
glm::vec3 ground_layer_vertex(const GrassFieldSettings& field, const BladeSettings& blade, const HeightField& ground,
                              const glm::dvec3& origin, const FarFieldSettings& far, glm::ivec2 sample, float* out) {
  const double sp = ground.spacing();
  const double wx = ground.origin().x + sample.x * sp, wz = ground.origin().y + sample.y * sp;
  const glm::vec3 n = ground.sample_normal(sample.x, sample.y);
  const glm::vec3 p(static_cast<float>(wx - origin.x), static_cast<float>(static_cast<double>(ground.sample(sample.x, sample.y)) - origin.y),
                    static_cast<float>(wz - origin.z));
  const glm::vec3 q = p + n * far.ground_offset;
  const glm::vec3 col = field_color(wx, wz, blade, field.seed);
  const float v[kGroundVertexFloats] = {q.x, q.y, q.z, n.x, n.y, n.z, col.r, col.g, col.b};
  std::copy(std::begin(v), std::end(v), out);
  return q;
}

}  // namespace

Result<GroundLayerMesh> build_ground_layer(const GrassFieldSettings& field, const BladeSettings& blade, const GrassMaps& maps,
                                           const HeightField& ground, const glm::dvec3& origin, const FarFieldSettings& far) {
  SYLVA_TRY(validate_params(far, "grass.far"));
  if (ground.samples().empty()) return make_error(ErrorCode::kInvalidArgument, "grass far field: the ground height field is empty");
  // Ground layer: chunks of 16 x 16 quads over the map rectangle and its margin, with the field's
  // colour per vertex (its patches are metres wide). Vertices sit on the height field's own samples
  // (every k-th, k = ground_spacing / spacing rounded, at least 1) and quads are split along the
  // same diagonal as the scene's ground mesh: with k = 1 the layer is that mesh lifted by
  // ground_offset exactly. A layer through bilinear heights at other points left the ground mesh
  // of a 6.25 m hilly height field up to decimetres above it (the layer vanished in patches).
  GroundLayerMesh mesh;
  const Rect area{maps.rect().min - static_cast<double>(far.ground_margin), maps.rect().max + static_cast<double>(far.ground_margin)};
  const double sp = ground.spacing();
  const int k = std::max(1, static_cast<int>(std::lround(far.ground_spacing / sp)));
  auto grid = [&](double w, int count, bool up) {
    const double g = w / sp;
    return std::clamp(static_cast<int>(up ? std::ceil(g) : std::floor(g)), 0, count - 1);
  };
  const int gi0 = grid(area.min.x - ground.origin().x, ground.columns(), false);
  const int gi1 = grid(area.max.x - ground.origin().x, ground.columns(), true);
  const int gj0 = grid(area.min.y - ground.origin().y, ground.rows(), false);
  const int gj1 = grid(area.max.y - ground.origin().y, ground.rows(), true);
  std::vector<float>& vertices = mesh.vertices;  // xyz local position, xyz normal, rgb field colour
  std::vector<std::uint32_t>& indices = mesh.indices;
  constexpr int kQuads = 16;
  const int cx = (gi1 - gi0 + k * kQuads - 1) / (k * kQuads);
  const int cz = (gj1 - gj0 + k * kQuads - 1) / (k * kQuads);
  if (static_cast<double>(cx) * cz * (kQuads + 1) * (kQuads + 1) > 2.0e7) {
    return make_error(ErrorCode::kLimit, fmt::format("grass.far.ground_spacing: {} m gives more than 20 million ground vertices", far.ground_spacing));
  }
  // Appends the vertex on height-field sample (global fine-grid index gi, gj) and returns its index.
  auto vertex = [&](int gi, int gj, glm::vec3& lo, glm::vec3& hi) {
    const glm::ivec2 sample(std::min(gi0 + gi * k, gi1), std::min(gj0 + gj * k, gj1));
    const auto id = static_cast<std::uint32_t>(vertices.size() / kGroundVertexFloats);
    vertices.resize(vertices.size() + kGroundVertexFloats);
    mesh.samples.push_back(sample);
    const glm::vec3 q = ground_layer_vertex(field, blade, ground, origin, far, sample, &vertices[id * kGroundVertexFloats]);
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
    return id;
  };
  auto finish = [&](GroundChunk& gc, const glm::vec3& lo, const glm::vec3& hi) {
    gc.index_count = static_cast<std::uint32_t>(indices.size()) - gc.first_index;
    gc.bounds_min = lo - glm::vec3(0.1f);
    gc.bounds_max = hi + glm::vec3(0.1f);
  };
  auto vertex_count = [&] { return static_cast<std::uint32_t>(vertices.size() / kGroundVertexFloats); };
  // A grid of (kQuads + 1)^2 vertices every `step` fine quads from fine index (gi, gj); quads
  // [q0, q1)^2 of it are indexed. Split along the (i + 1, j) - (i, j + 1) diagonal, like the scene's
  // ground mesh.
  auto patch = [&](int gi, int gj, int step, int q0, int q1, glm::vec3& lo, glm::vec3& hi) {
    const auto base = static_cast<std::uint32_t>(vertices.size() / kGroundVertexFloats);
    for (int b = 0; b <= kQuads; ++b)
      for (int a = 0; a <= kQuads; ++a) vertex(gi + a * step, gj + b * step, lo, hi);
    for (int b = q0; b < q1; ++b) {
      for (int a = q0; a < q1; ++a) {
        const std::uint32_t v00 = base + static_cast<std::uint32_t>(b * (kQuads + 1) + a);
        const std::uint32_t v10 = v00 + 1, v01 = v00 + kQuads + 1, v11 = v01 + 1;
        indices.insert(indices.end(), {v00, v01, v10, v10, v01, v11});
      }
    }
    return base;
  };
  const glm::vec3 kLo(std::numeric_limits<float>::max()), kHi(std::numeric_limits<float>::lowest());
  for (int j = 0; j < cz; ++j) {
    for (int i = 0; i < cx; ++i) {
      GroundChunk gc;
      gc.first_index = static_cast<std::uint32_t>(indices.size());
      gc.first_vertex = vertex_count();
      glm::vec3 lo = kLo, hi = kHi;
      patch(i * kQuads, j * kQuads, 1, 0, kQuads, lo, hi);
      finish(gc, lo, hi);
      gc.vertex_count = vertex_count() - gc.first_vertex;
      mesh.chunks.push_back(gc);
    }
  }
  if (!far.coarse_ground) return mesh;

  // Coarse sub-level (seed 003 §4.3; far_field.hpp): chunk (I, J) covers the ordinary chunks
  // [I f, I f + f) x [J f, J f + f) with 16 x 16 quads of f fine quads each.
  const int f = far.coarse_spacing_factor;
  const int ccx = (cx + f - 1) / f, ccz = (cz + f - 1) / f;
  for (int J = 0; J < ccz; ++J) {
    for (int I = 0; I < ccx; ++I) {
      CoarseGroundChunk cc;
      glm::vec3 lo = kLo, hi = kHi;
      const int gi = I * f * kQuads, gj = J * f * kQuads;
      cc.interior.first_index = static_cast<std::uint32_t>(indices.size());
      cc.interior.first_vertex = vertex_count();
      const std::uint32_t base = patch(gi, gj, f, 1, kQuads - 1, lo, hi);
      cc.interior.index_count = static_cast<std::uint32_t>(indices.size()) - cc.interior.first_index;
      auto coarse_id = [&](int a, int b) { return base + static_cast<std::uint32_t>(b * (kQuads + 1) + a); };
      for (int side = 0; side < 4; ++side) {
        // Outer polyline along the side (coarse units 0..kQuads) and the inner ring's (1..kQuads-1).
        auto at = [&](double u, double w) {  // (along, across) in coarse units -> (a, b)
          switch (side) {
            case 0: return glm::dvec2(w, u);
            case 1: return glm::dvec2(kQuads - w, u);
            case 2: return glm::dvec2(u, w);
            default: return glm::dvec2(u, kQuads - w);
          }
        };
        std::vector<std::uint32_t> inner;
        std::vector<double> inner_u;
        for (int u = 1; u <= kQuads - 1; ++u) {
          const glm::dvec2 ab = at(u, 1);
          inner.push_back(coarse_id(static_cast<int>(ab.x), static_cast<int>(ab.y)));
          inner_u.push_back(u);
        }
        for (int variant = 0; variant < 2; ++variant) {
          std::vector<std::uint32_t> outer;
          std::vector<double> outer_u;
          const int m = variant == 0 ? kQuads : kQuads * f;
          for (int e = 0; e <= m; ++e) {
            const double u = static_cast<double>(e) * kQuads / m;
            const glm::dvec2 ab = at(u, 0);
            if (variant == 0) {
              outer.push_back(coarse_id(static_cast<int>(ab.x), static_cast<int>(ab.y)));
            } else {
              // Stitched: the ordinary chunks' own edge vertices (same samples, same floats).
              outer.push_back(vertex(gi + static_cast<int>(std::lround(ab.x * f)), gj + static_cast<int>(std::lround(ab.y * f)), lo, hi));
            }
            outer_u.push_back(u);
          }
          GroundChunk& sc = cc.sides[side][variant];
          sc.first_index = static_cast<std::uint32_t>(indices.size());
          // Zipper between the two polylines, by position along the side; the winding of every
          // triangle is made that of the quads' (v00, v01, v10).
          auto emit = [&](std::uint32_t v0, std::uint32_t v1, std::uint32_t v2) {
            auto xz = [&](std::uint32_t v) { return glm::vec2(vertices[v * kGroundVertexFloats], vertices[v * kGroundVertexFloats + 2]); };
            const glm::vec2 e1 = xz(v1) - xz(v0), e2 = xz(v2) - xz(v0);
            if (e1.x * e2.y - e1.y * e2.x > 0.0f) std::swap(v1, v2);
            indices.insert(indices.end(), {v0, v1, v2});
          };
          std::size_t o = 0, n = 0;
          while (o + 1 < outer.size() || n + 1 < inner.size()) {
            if (n + 1 >= inner.size() || (o + 1 < outer.size() && outer_u[o + 1] <= inner_u[n + 1])) {
              emit(outer[o], outer[o + 1], inner[n]);
              ++o;
            } else {
              emit(outer[o], inner[n + 1], inner[n]);
              ++n;
            }
          }
          sc.index_count = static_cast<std::uint32_t>(indices.size()) - sc.first_index;
        }
      }
      cc.interior.bounds_min = lo - glm::vec3(0.1f);
      cc.interior.bounds_max = hi + glm::vec3(0.1f);
      cc.interior.vertex_count = vertex_count() - cc.interior.first_vertex;
      for (auto& side : cc.sides)
        for (GroundChunk& v : side) {
          v.bounds_min = cc.interior.bounds_min;
          v.bounds_max = cc.interior.bounds_max;
        }
      for (int j = J * f; j < std::min((J + 1) * f, cz); ++j)
        for (int i = I * f; i < std::min((I + 1) * f, cx); ++i) cc.fine.push_back(static_cast<std::uint32_t>(j * cx + i));
      cc.neighbour[0] = I > 0 ? J * ccx + I - 1 : -1;
      cc.neighbour[1] = I + 1 < ccx ? J * ccx + I + 1 : -1;
      cc.neighbour[2] = J > 0 ? (J - 1) * ccx + I : -1;
      cc.neighbour[3] = J + 1 < ccz ? (J + 1) * ccx + I : -1;
      mesh.coarse.push_back(std::move(cc));
    }
  }
  return mesh;
}

namespace {

// RGBA8 texture from an explicit mip chain (rows flipped to GL's bottom-up order).
render::Texture texture_from_mips(const std::vector<Image>& mips, GLenum min_filter, GLenum wrap, int max_level) {
  render::Texture tex = render::Texture::create_2d(mips[0].width(), mips[0].height(), GL_RGBA8, static_cast<int>(mips.size()));
  for (std::size_t level = 0; level < mips.size(); ++level) {
    const Image& im = mips[level];
    std::vector<float> rows(im.pixel_count() * 4);
    for (int y = 0; y < im.height(); ++y)
      for (int x = 0; x < im.width(); ++x)
        for (int c = 0; c < 4; ++c)
          rows[(static_cast<std::size_t>(im.height() - 1 - y) * static_cast<std::size_t>(im.width()) + static_cast<std::size_t>(x)) * 4 +
               static_cast<std::size_t>(c)] = c < im.channels() ? im.at(x, y, c) : 1.0f;
    glTextureSubImage2D(tex.id(), static_cast<GLint>(level), 0, 0, im.width(), im.height(), GL_RGBA, GL_FLOAT, rows.data());
  }
  tex.set_filter(min_filter, GL_NEAREST);
  tex.set_wrap(wrap);
  // Coarser levels have too few texels for a threshold to express a coverage share.
  glTextureParameteri(tex.id(), GL_TEXTURE_MAX_LEVEL, std::min(max_level, static_cast<int>(mips.size()) - 1));
  return tex;
}

}  // namespace

Result<FarField> FarField::create(const GrassFieldSettings& field, const BladeSettings& blade, const GrassMaps& maps,
                                  const HeightField& ground, const glm::dvec3& origin, const FarFieldSettings& far) {
  render::embedded::register_render_shaders();
  render::embedded::register_grass_shaders();
  SYLVA_TRY(validate_params(far, "grass.far"));
  FarField f;
  f.clump_map_images_ = extend_map_images(maps, far.clump_margin);
  Result<GrassMaps> clump_maps = f.clump_map_images_.rect.empty() ? Result<GrassMaps>(maps) : f.clump_map_images_.maps();
  if (!clump_maps) return clump_maps.error();
  auto clumps = generate_clumps(field, blade, *clump_maps, ground, origin, far);
  if (!clumps) return clumps.error();

  f.settings_ = far;
  f.built_ = far;
  f.origin_ = origin;
  f.map_rect_ = maps.rect();
  f.clump_tiles_ = std::move(clumps->tiles);
  f.clump_count_ = clumps->clumps.size();
  f.dense_keeps_ = far.dense_extra_billboards;
  if (far.wide_billboards) {
    auto wide = generate_wide_billboards(field, blade, *clump_maps, ground, origin, far);
    if (!wide) return wide.error();
    // One clump buffer: the wide billboards follow the small clumps.
    for (GrassTile& t : wide->tiles) t.first += static_cast<std::uint32_t>(f.clump_count_);
    f.wide_tiles_ = std::move(wide->tiles);
    f.wide_count_ = wide->clumps.size();
    clumps->clumps.insert(clumps->clumps.end(), wide->clumps.begin(), wide->clumps.end());
  }
  const float side_area = field.density * 0.5f * (blade.width_min + blade.width_max) * 0.5f * (blade.height_min + blade.height_max);
  f.tau_side_ = side_area * 2.0f / kPi;
  f.tau_top_ = 0.2f * side_area;

  auto cp = render::Program::create({"grass/clump.vert", "grass/clump.frag"});
  if (!cp) return cp.error();
  auto gp = render::Program::create({"grass/ground.vert", "grass/ground.frag"});
  if (!gp) return gp.error();
  f.clump_program_ = std::move(*cp);
  f.ground_program_ = std::move(*gp);

  f.clump_records_ = std::move(clumps->clumps);
  f.upload_clumps(0);
  f.wind_ = render::Buffer::immutable(sizeof(WindGpuParams), nullptr, true);
  f.clump_vao_ = render::VertexArray::create();

  auto layer = build_ground_layer(field, blade, maps, ground, origin, far);
  if (!layer) return layer.error();
  f.layer_rect_ = {maps.rect().min - static_cast<double>(far.ground_margin), maps.rect().max + static_cast<double>(far.ground_margin)};
  f.chunks_ = std::move(layer->chunks);
  f.coarse_chunks_ = std::move(layer->coarse);
  f.noise_seed_ = field.seed ^ 0x7e11eu;
  std::vector<float>& vertices = layer->vertices;
  std::vector<std::uint32_t>& indices = layer->indices;
  if (vertices.empty()) vertices.assign(kGroundFloats, 0.0f);
  if (indices.empty()) indices.assign(3, 0u);
  f.ground_vertices_ = render::Buffer::immutable(std::span<const float>(vertices), true);  // update_region
  f.ground_vertex_data_ = std::move(vertices);
  f.ground_samples_ = std::move(layer->samples);
  f.ground_indices_ = render::Buffer::immutable(std::span<const std::uint32_t>(indices));
  f.ground_vao_ = render::VertexArray::create();
  f.ground_vao_.attribute(0, 0, 3, GL_FLOAT, 0);
  f.ground_vao_.attribute(1, 0, 3, GL_FLOAT, 3 * sizeof(float));
  f.ground_vao_.attribute(2, 0, 3, GL_FLOAT, 6 * sizeof(float));
  f.ground_vao_.vertex_buffer(0, f.ground_vertices_, kGroundFloats * sizeof(float));
  f.ground_vao_.index_buffer(f.ground_indices_);

  // Textures: alpha holds thresholds, so the mip chains are coverage-preserving (see
  // coverage_preserving_mips) and sampled without blending between texels or levels.
  f.atlas_ = texture_from_mips(coverage_preserving_mips(make_clump_atlas(kAtlasSize, field.seed)), GL_NEAREST_MIPMAP_NEAREST,
                               GL_CLAMP_TO_EDGE, 3);  // cells of 128 -> 16 texels
  f.ground_texture_ = texture_from_mips(coverage_preserving_mips(make_ground_texture(256, field.seed ^ 0x5eedu)),
                                        GL_NEAREST_MIPMAP_NEAREST, GL_REPEAT, 4);  // 256 -> 16 texels
  render::TextureOptions linear;
  linear.mipmaps = false;
  linear.min_filter = GL_LINEAR;
  linear.wrap = GL_CLAMP_TO_EDGE;
  linear.encoding = render::TextureEncoding::kFloat32;
  f.density_image_ = maps.density_image();
  auto dens = render::Texture::from_image(f.density_image_, linear);
  if (!dens) return dens.error();
  f.density_ = std::move(*dens);
  // The tint map (maps.hpp) colours the ground layer as it colours blades and clumps.
  f.tinted_ = maps.has_tint_map();
  f.tint_image_ = maps.tint_image();
  auto tint = render::Texture::from_image(f.tint_image_, linear);
  if (!tint) return tint.error();
  f.tint_ = std::move(*tint);
  return f;
}

void FarField::upload_clumps(std::size_t first_changed) {
  const std::size_t n = clump_records_.size();
  if (n > clump_capacity_ || !clumps_) {
    // Room for edits that add clumps (an eighth more), so a dab re-uploads only its changed range.
    clump_capacity_ = std::max<std::size_t>(n + n / 8, 1);
    clumps_ = render::Buffer::immutable(clump_capacity_ * sizeof(Clump), nullptr, true);
    first_changed = 0;
  }
  if (first_changed < n) {
    clumps_.update(first_changed * sizeof(Clump), (n - first_changed) * sizeof(Clump), clump_records_.data() + first_changed);
  }
}

namespace {

// Rewrites texels [x0, x1) x [y0, y1) (image rows, row 0 = rect min) of `tex` from `im`; the
// texture holds the rows flipped (render::Texture::upload).
void upload_texels(const render::Texture& tex, const Image& im, int x0, int y0, int x1, int y1) {
  const int c = im.channels();
  std::vector<float> rows(static_cast<std::size_t>(x1 - x0) * static_cast<std::size_t>(y1 - y0) * static_cast<std::size_t>(c));
  std::size_t k = 0;
  for (int y = y1 - 1; y >= y0; --y)
    for (int x = x0; x < x1; ++x)
      for (int ch = 0; ch < c; ++ch) rows[k++] = im.at(x, y, ch);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTextureSubImage2D(tex.id(), 0, x0, im.height() - y1, x1 - x0, y1 - y0, c == 1 ? GL_RED : GL_RGB, GL_FLOAT, rows.data());
}

// Copies into `held` (and its texture) the bounding box of the texels where `now` differs from it.
void refresh_texels(Image& held, const render::Texture& tex, const Image& now) {
  int x0 = held.width(), x1 = -1, y0 = held.height(), y1 = -1;
  for (int y = 0; y < held.height(); ++y)
    for (int x = 0; x < held.width(); ++x)
      for (int c = 0; c < held.channels(); ++c) {
        if (std::bit_cast<std::uint32_t>(held.at(x, y, c)) == std::bit_cast<std::uint32_t>(now.at(x, y, c))) continue;
        x0 = std::min(x0, x);
        x1 = std::max(x1, x);
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
      }
  if (x1 < 0) return;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x)
      for (int c = 0; c < held.channels(); ++c) held.at(x, y, c) = now.at(x, y, c);
  upload_texels(tex, held, x0, y0, x1 + 1, y1 + 1);
}

Rect bounding(const Rect& a, const Rect& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  return {glm::min(a.min, b.min), glm::max(a.max, b.max)};
}

}  // namespace

Status FarField::update_region(const GrassFieldSettings& field, const BladeSettings& blade, const GrassMaps& maps,
                               const HeightField& ground, std::span<const Rect> areas, bool ground_changed) {
  const FarFieldSettings& far = built_;
  const Image density = maps.density_image(), tint = maps.tint_image();
  auto same_size = [](const Image& a, const Image& b) {
    return a.width() == b.width() && a.height() == b.height() && a.channels() == b.channels();
  };
  if (maps.rect().min != map_rect_.min || maps.rect().max != map_rect_.max || !same_size(density, density_image_) ||
      !same_size(tint, tint_image_) || maps.has_tint_map() != tinted_) {
    return make_error(ErrorCode::kInvalidArgument,
                      "grass far field: the maps' rectangle, size or tint changed since it was built; it needs a full rebuild");
  }
  // Where the clumps' inputs changed: the maps' edits, grown for a ground edit by the two samples
  // that HeightField::normal's central differences reach (slope_keep reads it).
  std::vector<Rect> changed;
  for (Rect a : areas) {
    if (ground_changed) a = {a.min - 2.0 * ground.spacing(), a.max + 2.0 * ground.spacing()};
    if (!a.empty()) changed.push_back(a);
  }
  // The clumps' maps (extended by clump_margin): resample the edited texels; each edit then reaches
  // where the extended interpolant changed (and the ground edit's own area).
  Result<GrassMaps> clump_maps = maps;
  if (!clump_map_images_.rect.empty()) {
    for (Rect& a : changed) {
      const Rect reach = refresh_extended_map_images(clump_map_images_, maps, a);
      a = ground_changed ? bounding(reach, a) : reach;
    }
    clump_maps = clump_map_images_.maps();
    if (!clump_maps) return clump_maps.error();
  }
  // Splice the fresh tiles of each edit into the small clumps, then the wide billboards' groups.
  std::vector<Clump> small(clump_records_.begin(), clump_records_.begin() + static_cast<std::ptrdiff_t>(clump_count_));
  std::vector<Clump> wide(clump_records_.begin() + static_cast<std::ptrdiff_t>(clump_count_), clump_records_.end());
  std::vector<GrassTile> small_tiles = clump_tiles_, wide_tiles = wide_tiles_;
  for (GrassTile& t : wide_tiles) t.first -= static_cast<std::uint32_t>(clump_count_);
  const bool with_wide = far.wide_billboards;
  for (const Rect& a : changed) {
    auto fresh = generate_clumps(field, blade, *clump_maps, ground, origin_, far, &a);
    if (!fresh) return fresh.error();
    auto merged = detail::merge_tiles<Clump>(small, small_tiles, fresh->clumps, fresh->tiles,
                                             clump_tile_range(clump_maps->rect(), a, field.tile_size));
    small = std::move(merged.items);
    small_tiles = std::move(merged.tiles);
    if (!with_wide) continue;
    auto fresh_wide = generate_wide_billboards(field, blade, *clump_maps, ground, origin_, far, &a);
    if (!fresh_wide) return fresh_wide.error();
    auto merged_wide = detail::merge_tiles<Clump>(wide, wide_tiles, fresh_wide->clumps, fresh_wide->tiles,
                                                  clump_tile_range(clump_maps->rect(), a, wide_group_size(field, far)));
    wide = std::move(merged_wide.items);
    wide_tiles = std::move(merged_wide.tiles);
  }
  if (static_cast<double>(small.size() + wide.size()) > static_cast<double>(kMaxBlades)) {
    return make_error(ErrorCode::kLimit, fmt::format("grass.far.clumps_per_m2: {} clumps is above the limit {}",
                                                     small.size() + wide.size(), kMaxBlades));
  }
  std::vector<Clump> records = std::move(small);
  const std::size_t small_count = records.size();
  records.insert(records.end(), wide.begin(), wide.end());
  for (GrassTile& t : wide_tiles) t.first += static_cast<std::uint32_t>(small_count);
  // Re-upload from the first record that differs (the records after an edit that changed the
  // count all move).
  const auto same = [](const Clump& x, const Clump& y) { return std::memcmp(&x, &y, sizeof(Clump)) == 0; };
  const std::size_t common = std::min(records.size(), clump_records_.size());
  const auto first = static_cast<std::size_t>(
      std::mismatch(records.begin(), records.begin() + static_cast<std::ptrdiff_t>(common), clump_records_.begin(), same).first -
      records.begin());
  clump_records_ = std::move(records);
  clump_count_ = small_count;
  wide_count_ = clump_records_.size() - small_count;
  clump_tiles_ = std::move(small_tiles);
  wide_tiles_ = std::move(wide_tiles);
  upload_clumps(first);

  // The ground layer's density and tint textures: their changed texels.
  refresh_texels(density_image_, density_, density);
  refresh_texels(tint_image_, tint_, tint);

  if (ground_changed) update_ground_layer(field, blade, ground, areas);
  return {};
}

void FarField::update_ground_layer(const GrassFieldSettings& field, const BladeSettings& blade, const HeightField& ground,
                                   std::span<const Rect> areas) {
  // The layer's vertices stand on the ground's samples: those within two samples of an edit (their
  // normals are central differences) are remade, the changed range is uploaded and the chunks
  // holding changed vertices get their bounds again (min/max over the same vertices: exact).
  std::vector<glm::ivec4> boxes;  // sample ranges [x0, x1] x [z0, z1]
  const double sp = ground.spacing();
  for (const Rect& a : areas) {
    if (a.empty()) continue;
    boxes.emplace_back(static_cast<int>(std::floor((a.min.x - ground.origin().x) / sp)) - 2,
                       static_cast<int>(std::ceil((a.max.x - ground.origin().x) / sp)) + 2,
                       static_cast<int>(std::floor((a.min.y - ground.origin().y) / sp)) - 2,
                       static_cast<int>(std::ceil((a.max.y - ground.origin().y) / sp)) + 2);
  }
  std::size_t first = ground_samples_.size(), last = 0;
  float v[kGroundVertexFloats];
  for (std::size_t i = 0; i < ground_samples_.size(); ++i) {
    const glm::ivec2 s = ground_samples_[i];
    const bool reached = std::any_of(boxes.begin(), boxes.end(), [s](const glm::ivec4& b) {
      return s.x >= b.x && s.x <= b.y && s.y >= b.z && s.y <= b.w;
    });
    if (!reached) continue;
    ground_layer_vertex(field, blade, ground, origin_, built_, s, v);
    float* held = &ground_vertex_data_[i * kGroundVertexFloats];
    if (std::memcmp(v, held, sizeof(v)) == 0) continue;
    std::copy(std::begin(v), std::end(v), held);
    first = std::min(first, i);
    last = i;
  }
  if (first > last) return;
  ground_vertices_.update(first * kGroundVertexFloats * sizeof(float), (last + 1 - first) * kGroundVertexFloats * sizeof(float),
                          &ground_vertex_data_[first * kGroundVertexFloats]);
  auto refresh_bounds = [&](GroundChunk& c) {
    if (c.first_vertex > last || c.first_vertex + c.vertex_count <= first) return false;
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (std::uint32_t i = c.first_vertex; i < c.first_vertex + c.vertex_count; ++i) {
      const glm::vec3 q(ground_vertex_data_[i * kGroundVertexFloats], ground_vertex_data_[i * kGroundVertexFloats + 1],
                        ground_vertex_data_[i * kGroundVertexFloats + 2]);
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
    c.bounds_min = lo - glm::vec3(0.1f);
    c.bounds_max = hi + glm::vec3(0.1f);
    return true;
  };
  for (GroundChunk& c : chunks_) refresh_bounds(c);
  for (CoarseGroundChunk& cc : coarse_chunks_) {
    if (!refresh_bounds(cc.interior)) continue;
    for (auto& side : cc.sides)
      for (GroundChunk& c : side) {
        c.bounds_min = cc.interior.bounds_min;
        c.bounds_max = cc.interior.bounds_max;
      }
  }
}

std::vector<Clump> FarField::read_clump_buffer() const {
  std::vector<Clump> out(clump_records_.size());
  if (!out.empty()) clumps_.read(0, out.size() * sizeof(Clump), out.data());
  return out;
}

std::vector<float> FarField::read_ground_vertex_buffer() const {
  std::vector<float> out(ground_vertex_data_.size());
  if (!out.empty()) ground_vertices_.read(0, out.size() * sizeof(float), out.data());
  return out;
}

namespace {
// A texture's level 0 as an image in the input's row order (row 0 = rect min).
Image read_texture(const render::Texture& tex, const Image& like) {
  const int w = like.width(), h = like.height(), c = like.channels();
  std::vector<float> rows(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * static_cast<std::size_t>(c));
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(tex.id(), 0, c == 1 ? GL_RED : GL_RGB, GL_FLOAT, static_cast<GLsizei>(rows.size() * sizeof(float)), rows.data());
  Image out(w, h, c);
  std::size_t k = 0;
  for (int y = h - 1; y >= 0; --y)
    for (int x = 0; x < w; ++x)
      for (int ch = 0; ch < c; ++ch) out.at(x, y, ch) = rows[k++];
  return out;
}
}  // namespace

Image FarField::read_density_texture() const { return read_texture(density_, density_image_); }
Image FarField::read_tint_texture() const { return read_texture(tint_, tint_image_); }

void FarField::set_near(float near_distance, float wind_response, float mean_stiffness, const glm::vec3& base_color,
                        const glm::vec3& tip_color, float ambient, float translucency) {
  near_distance_ = near_distance;
  ambient_ = ambient;
  translucency_ = translucency;
  wind_response_ = wind_response;
  mean_stiffness_ = mean_stiffness;
  base_color_ = base_color;
  tip_color_ = tip_color;
}

void FarField::update(const render::FrameContext& frame) { update(frame.camera, frame.viewport); }

void FarField::update(const render::Camera& camera, glm::ivec2 viewport) {
  const glm::mat4 vp_local = camera.view_projection() * camera.relative_model(origin_);
  camera_local_ = glm::vec3(camera.position() - origin_);
  const CullView view = make_cull_view(vp_local, camera_local_, camera.forward(), static_cast<float>(std::max(viewport.y, 1)),
                                       camera.perspective().fov_y);
  const FarFieldSettings& s = settings_;
  visible_clump_tiles_.clear();
  visible_wide_tiles_.clear();
  ground_draws_.clear();
  float nearest = 0.0f, farthest = 0.0f;
  if (s.clumps) {
    // With wide billboards on, small clumps end at wide_distance and the wide ones start
    // wide_fade before it (clump_fade / wide_fade_at).
    const bool wide = s.wide_billboards && !wide_tiles_.empty();
    const float small_end = wide ? std::min(s.mid_distance, s.wide_distance) : s.mid_distance;
    for (std::uint32_t i = 0; i < clump_tiles_.size(); ++i) {
      const GrassTile& t = clump_tiles_[i];
      box_distances(camera_local_, t.bounds_min, t.bounds_max, nearest, farthest);
      if (nearest >= small_end || farthest <= near_distance_ - s.clump_fade_in) continue;
      if (!box_visible(view, t.bounds_min, t.bounds_max)) continue;
      visible_clump_tiles_.push_back(i);
    }
    const float wide_start = std::max(s.wide_distance - s.wide_fade, near_distance_ - s.clump_fade_in);
    for (std::uint32_t i = 0; wide && i < wide_tiles_.size(); ++i) {
      const GrassTile& t = wide_tiles_[i];
      box_distances(camera_local_, t.bounds_min, t.bounds_max, nearest, farthest);
      if (nearest >= s.mid_distance || farthest < wide_start) continue;
      if (!box_visible(view, t.bounds_min, t.bounds_max)) continue;
      visible_wide_tiles_.push_back(i);
    }
  }
  coarse_drawn_ = 0;
  ground_chunks_ = 0;
  if (s.ground) {
    const float starts = s.under_layer ? 0.0f : s.mid_distance - s.mid_fade;
    auto add = [&](const GroundChunk& c) {
      box_distances(camera_local_, c.bounds_min, c.bounds_max, nearest, farthest);
      if (nearest >= s.far_distance || farthest <= starts) return false;
      if (!box_visible(view, c.bounds_min, c.bounds_max)) return false;
      ground_draws_.push_back(c);
      ++ground_chunks_;
      return true;
    };
    if (s.coarse_ground && !coarse_chunks_.empty()) {
      // Seed 003 §4.3 coarse sub-level (far_field.hpp): a coarse chunk wholly beyond
      // coarse_distance replaces its ordinary chunks; each side of its outer ring is stitched to
      // the ordinary chunks' edge where the neighbour is not drawn coarse.
      coarse_selected_.assign(coarse_chunks_.size(), 0);
      for (std::size_t i = 0; i < coarse_chunks_.size(); ++i) {
        const GroundChunk& c = coarse_chunks_[i].interior;
        box_distances(camera_local_, c.bounds_min, c.bounds_max, nearest, farthest);
        coarse_selected_[i] = nearest >= s.coarse_distance ? 1 : 0;
      }
      for (std::size_t i = 0; i < coarse_chunks_.size(); ++i) {
        const CoarseGroundChunk& cc = coarse_chunks_[i];
        if (!coarse_selected_[i]) {
          for (const std::uint32_t fi : cc.fine) add(chunks_[fi]);
          continue;
        }
        if (!add(cc.interior)) continue;
        ++coarse_drawn_;
        for (int side = 0; side < 4; ++side) {
          const std::int32_t nb = cc.neighbour[side];
          ground_draws_.push_back(cc.sides[side][nb >= 0 && !coarse_selected_[static_cast<std::size_t>(nb)] ? 1 : 0]);
        }
      }
    } else {
      for (const GroundChunk& c : chunks_) add(c);
    }
  }
}

void FarField::draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) {
  if (pass != render::Pass::kOpaque) return;
  draw_far(frame.camera, frame.wind, frame.time, &stats);
}

void FarField::draw_far(const render::Camera& camera, const WindField& wind, double time, render::PassStats* stats) {
  clumps_drawn_ = 0;
  wide_drawn_ = 0;
  ground_drawn_ = 0;
  const glm::vec3 origin_rel(origin_ - camera.position());
  const FarFieldSettings& s = settings_;
  const glm::vec4 fades(near_distance_, s.clump_fade_in, s.mid_distance, s.mid_fade);
  const glm::vec2 far_fades(s.far_distance, s.far_fade);
  const bool receive = s.receive_shadows && detail::shadow_block_bound();
  const glm::vec2 color_motion = color_motion_uniform(color_motion_, color_motion_hz_, time);
  if (!visible_clump_tiles_.empty() || !visible_wide_tiles_.empty()) {
    const WindFrame wf = wind.frame(std::isfinite(time) ? time : 0.0, origin_);
    wind_.update(0, sizeof(WindGpuParams), &wf.gpu);
    wind_.bind_base(GL_UNIFORM_BUFFER, kWindUboBinding);
    clumps_.bind_base(GL_SHADER_STORAGE_BUFFER, kClumpsBinding);
    const render::Program& p = clump_program_;
    p.set("u_view_proj", camera.view_projection());
    p.set("u_origin_rel", origin_rel);
    p.set("u_camera", camera_local_);
    p.set("u_fades", fades);
    p.set("u_sway", s.sway * wind_response_ / std::max(mean_stiffness_, 1.0f));
    p.set("u_base_color", base_color_);
    p.set("u_tip_color", tip_color_);
    p.set("u_receive_shadows", receive ? 1 : 0);
    p.set("u_shading", glm::vec3(s.clump_brightness, ambient_, translucency_));
    p.set("u_color_motion", color_motion);
    atlas_.bind(0);
    clump_vao_.bind();
    p.use();
    // u_wide: x wide_distance, y wide_fade, z level (0 small clumps without wide billboards,
    // 1 small clumps giving way to wide ones, 2 wide billboards; their strand keep is in size.z).
    const bool wide_on = s.wide_billboards && !wide_tiles_.empty();
    // u_wide.w: the small clumps' strand keep of the overcrowding guard is in size.z (dense_keep).
    // (As built: a keep in size.z exists only when the clumps were generated with the option.)
    const float dense_on = dense_keeps_ ? 1.0f : 0.0f;
    p.set("u_wide", glm::vec4(s.wide_distance, s.wide_fade, wide_on ? 1.0f : 0.0f, dense_on));
    p.set("u_cell_width", s.clump_width);
    for (const std::uint32_t ti : visible_clump_tiles_) {
      const GrassTile& t = clump_tiles_[ti];
      p.set("u_first", static_cast<int>(t.first));
      glDrawArraysInstanced(GL_TRIANGLES, 0, 12, static_cast<GLsizei>(t.count));
      clumps_drawn_ += t.count;
    }
    if (!visible_wide_tiles_.empty()) p.set("u_wide", glm::vec4(s.wide_distance, s.wide_fade, 2.0f, dense_on));
    for (const std::uint32_t ti : visible_wide_tiles_) {
      const GrassTile& t = wide_tiles_[ti];
      p.set("u_first", static_cast<int>(t.first));
      glDrawArraysInstanced(GL_TRIANGLES, 0, 12, static_cast<GLsizei>(t.count));
      wide_drawn_ += t.count;
    }
    if (stats) {
      stats->draw_calls += visible_clump_tiles_.size() + visible_wide_tiles_.size();
      stats->instances += clumps_drawn_ + wide_drawn_;
      stats->triangles += 4 * (clumps_drawn_ + wide_drawn_);
    }
  }
  if (!ground_draws_.empty()) {
    const render::Program& p = ground_program_;
    p.set("u_view_proj", camera.view_projection());
    p.set("u_origin_rel", origin_rel);
    p.set("u_origin_xz", glm::vec2(static_cast<float>(std::fmod(origin_.x, static_cast<double>(s.texture_scale))),
                                   static_cast<float>(std::fmod(origin_.z, static_cast<double>(s.texture_scale)))));
    p.set("u_fades", glm::vec4(s.mid_distance, s.mid_fade, far_fades.x, far_fades.y));
    p.set("u_texture_scale", s.texture_scale);
    p.set("u_coverage", glm::vec3(tau_side_, tau_top_, s.coverage_gain));
    p.set("u_map_min", glm::vec2(glm::dvec2(map_rect_.min) - glm::dvec2(origin_.x, origin_.z)));
    p.set("u_map_size", glm::vec2(map_rect_.size()));
    p.set("u_layer_rect", glm::vec4(glm::dvec2(layer_rect_.min) - glm::dvec2(origin_.x, origin_.z),
                                    glm::dvec2(layer_rect_.max) - glm::dvec2(origin_.x, origin_.z)));
    p.set("u_base_color", base_color_);
    p.set("u_tip_color", tip_color_);
    p.set("u_receive_shadows", receive ? 1 : 0);
    p.set("u_shading", glm::vec4(s.ground_brightness, ambient_, s.under_layer ? 1.0f : 0.0f, s.under_shade));
    p.set("u_lift_per_m", s.lift_per_m);
    p.set("u_max_slope_deg", s.max_slope_deg);
    p.set("u_translucency", translucency_);
    p.set("u_color_motion", color_motion);
    // Seed 003 §2.5 noise sub-regions: the far tile grid is world-anchored; the origin's tile and
    // its offset inside it are split off in double so far-away fields keep float precision.
    p.set("u_noise_sub", s.noise_subregions ? 1 : 0);
    if (s.noise_subregions) {
      const double tile = s.noise_tile;
      const glm::dvec2 base(std::floor(origin_.x / tile), std::floor(origin_.z / tile));
      p.set("u_noise_tile", s.noise_tile);
      p.set("u_noise_base", glm::ivec2(base));
      p.set("u_noise_frac", glm::vec2(glm::dvec2(origin_.x, origin_.z) - base * tile));
      p.set("u_noise_seed", noise_seed_);
    }
    ground_texture_.bind(0);
    density_.bind(1);
    tint_.bind(2);
    p.set("u_tinted", tinted_ ? 1 : 0);
    ground_vao_.bind();
    p.use();
    std::uint64_t tris = 0;
    for (const GroundChunk& c : ground_draws_) {
      glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(c.index_count), GL_UNSIGNED_INT,
                     reinterpret_cast<const void*>(static_cast<std::uintptr_t>(c.first_index) * sizeof(std::uint32_t)));
      tris += c.index_count / 3;
    }
    ground_drawn_ = ground_chunks_;
    if (stats) {
      stats->draw_calls += ground_draws_.size();
      stats->triangles += tris;
    }
  }
  glBindVertexArray(0);
}

}  // namespace sylva::grass

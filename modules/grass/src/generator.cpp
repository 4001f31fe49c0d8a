#include <sylva/grass/generator.hpp>

#include "tile_merge.hpp"

#include <sylva/core/params.hpp>
#include <sylva/core/rng.hpp>
#include <sylva/grass/field_color.hpp>
#include <sylva/grass/physics.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>

namespace sylva::grass {

namespace {

// Salts that separate the independent randoms of one blade.
enum Salt : std::uint32_t {
  kSaltTile = 0x7431u,
  kSaltRound = 0x52d1u,
  kSaltOrient = 1u,
  kSaltHeight = 2u,
  kSaltWidth = 3u,
  kSaltBend = 4u,
  kSaltBendDir = 5u,
  kSaltStiff = 6u,
  kSaltColorR = 7u,
  kSaltColorG = 8u,
  kSaltColorB = 9u,
  kSaltShade = 10u,
  kSaltShape = 11u,
  kSaltRank = 12u,
  kSaltUvKeep = 13u,
};

float unit(std::uint32_t blade_hash, std::uint32_t salt) { return hash_to_unit_float(hash_u32(salt, blade_hash)); }

std::uint32_t tile_hash(TileKey key, std::uint32_t seed) {
  return hash_u32(static_cast<std::uint32_t>(key.x), static_cast<std::uint32_t>(key.z),
                  static_cast<std::uint32_t>(key.y) ^ kSaltTile, seed);
}

// The R2 sequence (Roberts 2018, generalised golden ratio): evenly spread for every prefix.
glm::dvec2 r2_point(std::uint32_t index, std::uint32_t tile) {
  constexpr double kA1 = 0.7548776662466927;  // 1 / plastic number
  constexpr double kA2 = 0.5698402909980532;  // 1 / plastic number^2
  const glm::dvec2 offset(hash_to_unit_float(hash_u32(0x0ff5e7u, tile)), hash_to_unit_float(hash_u32(0x0ff5e8u, tile)));
  const double n = static_cast<double>(index) + 1.0;
  glm::dvec2 p = offset + n * glm::dvec2(kA1, kA2);
  return p - glm::floor(p);
}

Rect tile_rect(const GrassFieldSettings& field, TileKey key) {
  const double t = field.tile_size;
  return {{key.x * t, key.z * t}, {(key.x + 1) * t, (key.z + 1) * t}};
}

// The randoms that make a blade unique, turned into a blade at `root` (BladeSet-local).
Blade make_blade(const BladeSettings& settings, std::uint32_t blade_hash, const glm::vec3& root, const glm::vec3& up,
                 float height_scale, const glm::vec3& tint, float rank) {
  const float r_orient = unit(blade_hash, kSaltOrient);
  const float r_height = unit(blade_hash, kSaltHeight);
  const float r_width = glm::mix(unit(blade_hash, kSaltWidth), r_height, settings.height_width_correlation);
  const float r_bend = unit(blade_hash, kSaltBend);
  const float r_bend_dir = unit(blade_hash, kSaltBendDir);
  const float r_stiff = unit(blade_hash, kSaltStiff);

  const float scale = std::clamp(height_scale, 0.0f, 1.0f);
  const float height = std::max(glm::mix(settings.height_min, settings.height_max, r_height) * scale, settings.min_height);
  // Width follows the height map like seed 001's Algorithm 2, but never below a quarter.
  const float width = glm::mix(settings.width_min, settings.width_max, r_width) * std::max(scale, 0.25f);
  const float orientation = r_orient * 2.0f * std::numbers::pi_v<float>;

  // Rest lean (seed 001 eq. 2.2's bend factor b): over the blade's face, within +-0.5 rad.
  glm::vec3 t1, t2;
  tangent_frame(up, t1, t2);
  const glm::vec3 width_dir = std::cos(orientation) * t1 + std::sin(orientation) * t2;
  const glm::vec3 front = glm::normalize(glm::cross(width_dir, up));
  const float dir_angle = (r_bend_dir - 0.5f);
  const glm::vec3 lean_dir = std::cos(dir_angle) * front + std::sin(dir_angle) * width_dir;
  const float lean = settings.bend * (0.3f + 0.7f * r_bend);

  glm::vec3 mult;
  const std::uint32_t salts[3] = {kSaltColorR, kSaltColorG, kSaltColorB};
  for (int c = 0; c < 3; ++c) {
    const float r = unit(blade_hash, salts[c]);
    mult[c] = std::clamp(tint[c] * (1.0f + settings.color_variation * (2.0f * r - 1.0f)), 0.0f, 2.0f);
  }

  Blade b;
  b.v0 = glm::vec4(root, orientation);
  b.v1 = glm::vec4(root + up * height, height);
  b.v2 = glm::vec4(root + height * glm::normalize(up + lean * lean_dir), width);
  b.up = glm::vec4(up, glm::mix(settings.stiffness_min, settings.stiffness_max, r_stiff));
  b.rest = glm::vec4(0.0f);
  // attr.w: the shape random s, as 1 + s when the control point is jittered (seed 001 eq. 2.4,
  // blade.hpp drawn_control: r3 and r4 come from s).
  const float shape = unit(blade_hash, kSaltShape);
  b.attr = glm::vec4(rank, unit(blade_hash, kSaltShade), pack_color(mult * 0.5f), settings.control_jitter ? 1.0f + shape : shape);
  // The rest pose is the validated pose, so it is a fixed point of the physics without forces.
  validate_blade(b);
  b.rest = glm::vec4(b.tip() - b.root(), 0.0f);
  return b;
}

void finish_tile_bounds(GrassTile& tile, std::span<const Blade> blades) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (std::uint32_t i = tile.first; i < tile.first + tile.count; ++i) {
    const Blade& b = blades[i];
    // Any pose keeps the tip within one blade height of the root (arc length = height); a
    // jittered control point (seed 001 eq. 2.4) reaches up to 1.3 heights (blade.hpp).
    lo = glm::min(lo, b.root() - glm::vec3(b.height() * drawn_reach(b)));
    hi = glm::max(hi, b.root() + glm::vec3(b.height() * drawn_reach(b)));
  }
  if (tile.count == 0) lo = hi = glm::vec3(0.0f);
  tile.bounds_min = lo;
  tile.bounds_max = hi;
}

}  // namespace

double BladeSet::expected_total() const {
  double sum = 0.0;
  for (const GrassTile& t : tiles) sum += t.expected;
  return sum;
}

Result<TileRange> tiles_overlapping(const Rect& area, double tile_size) {
  TileRange r;
  r.x0 = static_cast<std::int64_t>(std::floor(area.min.x / tile_size));
  r.x1 = static_cast<std::int64_t>(std::ceil(area.max.x / tile_size));
  r.z0 = static_cast<std::int64_t>(std::floor(area.min.y / tile_size));
  r.z1 = static_cast<std::int64_t>(std::ceil(area.max.y / tile_size));
  const std::int64_t nx = r.x1 - r.x0, nz = r.z1 - r.z0;
  if (nx > 1000000 || nz > 1000000 || nx * nz > 4000000) {
    return make_error(ErrorCode::kLimit, fmt::format("grass.field.tile_size: {} m makes {} x {} tiles, more than 4 million",
                                                     tile_size, nx, nz));
  }
  return r;
}

double tile_expected_blades(const GrassFieldSettings& field, const GrassMaps& maps, TileKey key) {
  return maps.density_integral(tile_rect(field, key)) * static_cast<double>(field.density);
}

std::uint32_t tile_blade_count(const GrassFieldSettings& field, const GrassMaps& maps, TileKey key) {
  const double expected = tile_expected_blades(field, maps, key);  // same rounding as sample_tile_points
  const double xi = hash_to_unit_float(hash_u32(kSaltRound, tile_hash(key, field.seed)));
  const double n = std::floor(expected + xi);
  return static_cast<std::uint32_t>(std::clamp(n, 0.0, static_cast<double>(kMaxBlades)));
}

std::vector<TilePoint> sample_tile_points(const GrassMaps& maps, TileKey key, double tile_size, double per_m2,
                                         std::uint32_t seed) {
  std::vector<TilePoint> out;
  const Rect rect{{key.x * tile_size, key.z * tile_size}, {(key.x + 1) * tile_size, (key.z + 1) * tile_size}};
  const double expected = maps.density_integral(rect) * per_m2;
  const std::uint32_t th = tile_hash(key, seed);
  const double xi = hash_to_unit_float(hash_u32(kSaltRound, th));
  const auto count = static_cast<std::uint32_t>(std::clamp(std::floor(expected + xi), 0.0, static_cast<double>(kMaxBlades)));
  if (count == 0) return out;

  // Density CDF over K x K cells (rows along z, columns along x), from exact cell integrals.
  // Four cells per map pixel (at most 32 x 32 per tile): points are uniform inside a cell, so
  // cells must be small against the map's features (an empty strip stays empty). Without a
  // map the density is 1 inside the rectangle: one cell, unless the tile straddles its border.
  const glm::dvec2 texel = maps.density_texel();
  const double per_side = std::ceil(4.0 * tile_size / std::max(std::min(texel.x, texel.y), 1e-9));
  const bool whole = rect.intersect(maps.rect()).size() == rect.size();
  const int k = maps.has_density_map() ? static_cast<int>(std::clamp(per_side, 1.0, 32.0)) : (whole ? 1 : 32);
  const double cell = tile_size / k;
  std::vector<double> mass(static_cast<std::size_t>(k * k));
  std::vector<double> row_cum(static_cast<std::size_t>(k + 1), 0.0);
  for (int r = 0; r < k; ++r) {
    double row = 0.0;
    for (int c = 0; c < k; ++c) {
      const Rect cr{{rect.min.x + c * cell, rect.min.y + r * cell}, {rect.min.x + (c + 1) * cell, rect.min.y + (r + 1) * cell}};
      const double m = std::max(maps.density_integral(cr), 0.0);
      mass[static_cast<std::size_t>(r * k + c)] = m;
      row += m;
    }
    row_cum[static_cast<std::size_t>(r + 1)] = row_cum[static_cast<std::size_t>(r)] + row;
  }
  const double total = row_cum[static_cast<std::size_t>(k)];
  if (!(total > 0.0)) return out;

  out.reserve(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    const glm::dvec2 u = r2_point(i, th);
    // Row by the marginal CDF, then column by the row's conditional CDF; linear inside a cell.
    const double tz = u.y * total;
    int r = static_cast<int>(std::upper_bound(row_cum.begin() + 1, row_cum.end(), tz) - (row_cum.begin() + 1));
    r = std::clamp(r, 0, k - 1);
    while (r < k - 1 && row_cum[static_cast<std::size_t>(r + 1)] - row_cum[static_cast<std::size_t>(r)] <= 0.0) ++r;
    const double row_mass = row_cum[static_cast<std::size_t>(r + 1)] - row_cum[static_cast<std::size_t>(r)];
    const double fz = row_mass > 0.0 ? std::clamp((tz - row_cum[static_cast<std::size_t>(r)]) / row_mass, 0.0, 1.0) : 0.5;
    double tx = u.x * row_mass;
    int c = 0;
    for (; c < k - 1; ++c) {
      const double m = mass[static_cast<std::size_t>(r * k + c)];
      if (tx < m) break;
      tx -= m;
    }
    const double m = mass[static_cast<std::size_t>(r * k + c)];
    const double fx = m > 0.0 ? std::clamp(tx / m, 0.0, 1.0) : 0.5;
    TilePoint p;
    p.position = {rect.min.x + (c + fx) * cell, rect.min.y + (r + fz) * cell};
    p.hash = hash_u32(i, th);
    p.rank = (static_cast<float>(i) + 0.5f) / static_cast<float>(count);
    out.push_back(p);
  }
  return out;
}

void generate_tile(const GrassFieldSettings& field, const BladeSettings& blade, const GrassMaps& maps,
                   const HeightField& ground, TileKey key, const glm::dvec3& origin, std::vector<Blade>& out) {
  const std::vector<TilePoint> points = sample_tile_points(maps, key, field.tile_size, field.density, field.seed);
  out.reserve(out.size() + points.size());
  for (const TilePoint& p : points) {
    const double x = p.position.x, z = p.position.y;
    // Seed 001 Algorithm 2: a blade is kept only where the height map exceeds the threshold.
    if (field.height_threshold > 0.0f && !(maps.height_scale(x, z) > field.height_threshold)) continue;
    const double y = ground.height(x, z);
    glm::vec3 up(0.0f, 1.0f, 0.0f);
    if (field.up_normal_blend > 0.0f) up = glm::normalize(glm::mix(up, ground.normal(x, z), field.up_normal_blend));
    const glm::vec3 root(static_cast<float>(x - origin.x), static_cast<float>(y - origin.y), static_cast<float>(z - origin.z));
    out.push_back(make_blade(blade, p.hash, root, up, maps.height_scale(x, z), maps.tint(x, z) * field_color(x, z, blade, field.seed), p.rank));
  }
}

Status check_settings(const GrassFieldSettings& field, const BladeSettings& blade) {
  SYLVA_TRY(validate_params(field, "grass.field"));
  SYLVA_TRY(validate_params(blade, "grass.blade"));
  auto ordered = [](float lo, float hi, const char* lo_name, const char* hi_name) -> Status {
    if (lo > hi) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("grass.blade.{}: {} is above grass.blade.{} = {}", lo_name, lo, hi_name, hi));
    }
    return {};
  };
  SYLVA_TRY(ordered(blade.height_min, blade.height_max, "height_min", "height_max"));
  SYLVA_TRY(ordered(blade.width_min, blade.width_max, "width_min", "width_max"));
  SYLVA_TRY(ordered(blade.stiffness_min, blade.stiffness_max, "stiffness_min", "stiffness_max"));
  return {};
}

namespace {

// Appends the tiles of `range` in generate_blades' order (z, then x), skipping tiles that have
// neither blades nor an expected count.
void append_tiles(const GrassFieldSettings& field, const BladeSettings& blade, const GrassMaps& maps,
                  const HeightField& ground, const TileRange& range, BladeSet& set) {
  for (std::int64_t z = range.z0; z < range.z1; ++z) {
    for (std::int64_t x = range.x0; x < range.x1; ++x) {
      GrassTile tile;
      tile.key = {static_cast<std::int32_t>(x), 0, static_cast<std::int32_t>(z)};
      tile.first = static_cast<std::uint32_t>(set.blades.size());
      tile.expected = tile_expected_blades(field, maps, tile.key);
      generate_tile(field, blade, maps, ground, tile.key, set.origin, set.blades);
      tile.count = static_cast<std::uint32_t>(set.blades.size()) - tile.first;
      if (tile.count == 0 && tile.expected <= 0.0) continue;
      finish_tile_bounds(tile, set.blades);
      set.tiles.push_back(tile);
    }
  }
}

}  // namespace

Result<BladeSet> generate_blades(const GrassFieldSettings& field, const BladeSettings& blade, const GrassMaps& maps,
                                 const HeightField& ground, const glm::dvec3& origin) {
  SYLVA_TRY(check_settings(field, blade));
  if (ground.samples().empty()) return make_error(ErrorCode::kInvalidArgument, "grass: the ground height field is empty");
  const Rect area = maps.rect();
  BladeSet set;
  set.origin = origin;
  if (area.empty()) return set;
  const Result<TileRange> range = tiles_overlapping(area, field.tile_size);
  if (!range.ok()) return range.error();
  const auto [x0, x1, z0, z1] = *range;
  // Count first so a typo in density fails fast instead of allocating gigabytes.
  double expected = 0.0;
  for (std::int64_t z = z0; z < z1; ++z) {
    for (std::int64_t x = x0; x < x1; ++x) {
      expected += tile_expected_blades(field, maps, {static_cast<std::int32_t>(x), 0, static_cast<std::int32_t>(z)});
    }
  }
  if (expected > static_cast<double>(kMaxBlades)) {
    return make_error(ErrorCode::kLimit, fmt::format("grass.field.density: {} blades/m^2 over this map gives {:.0f} "
                                                     "blades, above the limit of {}",
                                                     field.density, expected, kMaxBlades));
  }
  set.blades.reserve(static_cast<std::size_t>(expected * 1.01) + 16);
  append_tiles(field, blade, maps, ground, *range, set);
  for (const Blade& b : set.blades) set.max_height = std::max(set.max_height, b.height());
  return set;
}

Result<std::uint32_t> regenerate_tiles(BladeSet& set, const GrassFieldSettings& field, const BladeSettings& blade,
                                       const GrassMaps& maps, const HeightField& ground, const Rect& area) {
  SYLVA_TRY(check_settings(field, blade));
  if (ground.samples().empty()) return make_error(ErrorCode::kInvalidArgument, "grass: the ground height field is empty");
  const Rect clipped = area.intersect(maps.rect());
  const auto unchanged = static_cast<std::uint32_t>(set.blades.size());
  if (clipped.empty()) return unchanged;
  const Result<TileRange> range = tiles_overlapping(clipped, field.tile_size);
  if (!range.ok()) return range.error();
  // The tiles of the area, made exactly as generate_blades makes them (first = into `fresh`).
  BladeSet fresh;
  fresh.origin = set.origin;
  append_tiles(field, blade, maps, ground, *range, fresh);
  // Merge in generate_blades' order (z, then x): old tiles outside the area, fresh ones inside.
  auto merged = detail::merge_tiles<Blade>(set.blades, set.tiles, fresh.blades, fresh.tiles, *range);
  BladeSet out;
  out.origin = set.origin;
  out.blades = std::move(merged.items);
  out.tiles = std::move(merged.tiles);
  std::uint32_t first_changed = merged.first_changed;
  if (out.blades.size() > kMaxBlades) {
    return make_error(ErrorCode::kLimit, fmt::format("grass.field.density: {} blades/m^2 over this map gives {} "
                                                     "blades, above the limit of {}",
                                                     field.density, out.blades.size(), kMaxBlades));
  }
  for (const Blade& b : out.blades) out.max_height = std::max(out.max_height, b.height());
  if (first_changed == unchanged) first_changed = static_cast<std::uint32_t>(out.blades.size());
  set = std::move(out);
  return first_changed;
}

Result<BladeSet> generate_blades_on_mesh(const GrassFieldSettings& field, const BladeSettings& blade,
                                         const GroundMesh& mesh, const glm::dvec3& origin, const MeshUvDensity* uv) {
  SYLVA_TRY(check_settings(field, blade));
  if (mesh.indices.size() % 3 != 0) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("grass mesh: {} indices is not a multiple of 3", mesh.indices.size()));
  }
  const std::size_t nv = mesh.positions.size();
  if (!mesh.normals.empty() && mesh.normals.size() != nv) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("grass mesh: {} normals for {} positions", mesh.normals.size(), nv));
  }
  if (!mesh.density.empty() && mesh.density.size() != nv) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("grass mesh: {} density values for {} positions", mesh.density.size(), nv));
  }
  for (std::size_t i = 0; i < nv; ++i) {
    const glm::vec3& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      return make_error(ErrorCode::kInvalidArgument, fmt::format("grass mesh: position {} is not finite", i));
    }
  }
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
    if (mesh.indices[i] >= nv) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("grass mesh: index {} (= {}) is out of range for {} vertices", i, mesh.indices[i], nv));
    }
  }
  if (uv != nullptr && uv->corner_uvs.size() != mesh.indices.size()) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("grass mesh: {} corner UVs for {} indices",
                                                               uv->corner_uvs.size(), mesh.indices.size()));
  }
  auto vertex_density = [&](std::uint32_t v) {
    if (mesh.density.empty() || uv != nullptr) return 1.0f;
    const float d = mesh.density[v];
    return std::isfinite(d) ? std::clamp(d, 0.0f, 1.0f) : 0.0f;
  };

  // Expected counts first (limit check), then the blades.
  const std::size_t triangles = mesh.indices.size() / 3;
  std::vector<double> expected(triangles);
  double total = 0.0;
  for (std::size_t t = 0; t < triangles; ++t) {
    const std::uint32_t a = mesh.indices[3 * t], b = mesh.indices[3 * t + 1], c = mesh.indices[3 * t + 2];
    const double area = 0.5 * glm::length(glm::cross(glm::dvec3(mesh.positions[b] - mesh.positions[a]),
                                                      glm::dvec3(mesh.positions[c] - mesh.positions[a])));
    const double dens = (vertex_density(a) + vertex_density(b) + vertex_density(c)) / 3.0;
    expected[t] = area * dens * field.density;
    total += expected[t];
  }
  if (total > static_cast<double>(kMaxBlades)) {
    return make_error(ErrorCode::kLimit, fmt::format("grass.field.density: {} blades/m^2 on this mesh gives {:.0f} "
                                                     "blades, above the limit of {}",
                                                     field.density, total, kMaxBlades));
  }

  struct Keyed {
    TileKey key;
    std::uint32_t order;
    double expected_share;
  };
  std::vector<Blade> blades;
  std::vector<Keyed> keys;
  blades.reserve(static_cast<std::size_t>(total * 1.01) + 16);
  const double ts = field.tile_size;
  for (std::size_t t = 0; t < triangles; ++t) {
    const std::uint32_t ia = mesh.indices[3 * t], ib = mesh.indices[3 * t + 1], ic = mesh.indices[3 * t + 2];
    const glm::vec3 pa = mesh.positions[ia], pb = mesh.positions[ib], pc = mesh.positions[ic];
    // Anchor the randoms on the geometry, not on the index order.
    std::uint32_t th = field.seed ^ 0x6d657368u;
    for (const glm::vec3& p : {pa, pb, pc}) {
      th = hash_u32(std::bit_cast<std::uint32_t>(p.x), std::bit_cast<std::uint32_t>(p.y), std::bit_cast<std::uint32_t>(p.z), th);
    }
    const double xi = hash_to_unit_float(hash_u32(kSaltRound, th));
    const auto count = static_cast<std::uint32_t>(std::max(std::floor(expected[t] + xi), 0.0));
    if (count == 0) continue;
    const glm::vec3 face = glm::cross(pb - pa, pc - pa);
    const float face_len = glm::length(face);
    if (!(face_len > 0.0f)) continue;  // degenerate triangles have no area and got no blades
    const glm::vec3 face_n = face / face_len;
    const std::size_t first_kept = keys.size();
    double uv_expected = 0.0;  // with uv: the candidates' summed density
    for (std::uint32_t i = 0; i < count; ++i) {
      glm::dvec2 u = r2_point(i, th);
      if (u.x + u.y > 1.0) u = glm::dvec2(1.0) - u;
      const float fu = static_cast<float>(u.x), fv = static_cast<float>(u.y);
      if (uv != nullptr) {
        const glm::vec2* c = &uv->corner_uvs[3 * t];
        const float d = uv->map.sample((1.0f - fu - fv) * c[0] + fu * c[1] + fv * c[2]);
        uv_expected += d;
        if (!(d > unit(hash_u32(i, th), kSaltUvKeep))) continue;
      }
      const glm::vec3 root = pa + fu * (pb - pa) + fv * (pc - pa);
      glm::vec3 up = face_n;
      if (!mesh.normals.empty()) {
        const glm::vec3 n = (1.0f - fu - fv) * mesh.normals[ia] + fu * mesh.normals[ib] + fv * mesh.normals[ic];
        const float len = glm::length(n);
        if (len > 1e-6f && std::isfinite(len)) up = n / len;
      }
      const std::uint32_t bh = hash_u32(i, th);
      const glm::dvec3 world = origin + glm::dvec3(root);
      Blade b = make_blade(blade, bh, root, up, 1.0f, field_color(world.x, world.z, blade, field.seed), unit(bh, kSaltRank));
      keys.push_back({{static_cast<std::int32_t>(std::floor(world.x / ts)), static_cast<std::int32_t>(std::floor(world.y / ts)),
                       static_cast<std::int32_t>(std::floor(world.z / ts))},
                      static_cast<std::uint32_t>(blades.size()), expected[t] / count});
      blades.push_back(b);
    }
    if (uv != nullptr && keys.size() > first_kept) {
      // The triangle's ideal count spread over the blades it kept.
      const double share = uv_expected * expected[t] / count / static_cast<double>(keys.size() - first_kept);
      for (std::size_t k = first_kept; k < keys.size(); ++k) keys[k].expected_share = share;
    }
  }

  // Group by tile (stable, so the order inside a tile follows the mesh).
  std::stable_sort(keys.begin(), keys.end(), [](const Keyed& a, const Keyed& b) {
    return std::tie(a.key.x, a.key.y, a.key.z) < std::tie(b.key.x, b.key.y, b.key.z);
  });
  BladeSet set;
  set.origin = origin;
  set.blades.reserve(blades.size());
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (set.tiles.empty() || !(set.tiles.back().key == keys[i].key)) {
      GrassTile tile;
      tile.key = keys[i].key;
      tile.first = static_cast<std::uint32_t>(set.blades.size());
      set.tiles.push_back(tile);
    }
    set.tiles.back().count++;
    set.tiles.back().expected += keys[i].expected_share;
    set.blades.push_back(blades[keys[i].order]);
  }
  for (GrassTile& tile : set.tiles) finish_tile_bounds(tile, set.blades);
  for (const Blade& b : set.blades) set.max_height = std::max(set.max_height, b.height());
  return set;
}

}  // namespace sylva::grass

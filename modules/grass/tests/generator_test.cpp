// Blade placement: density fidelity (count per tile = density-map integral within +-1 %),
// determinism, world anchoring, per-blade ranges, seed 001's control-point jitter, meshes and bad
// input.
#include <sylva/grass/generator.hpp>
#include <sylva/grass/physics.hpp>

#include "support/fields.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <map>
#include <numbers>
#include <tuple>

namespace sylva::grass {
namespace {

struct Fixture {
  GrassFieldSettings field;
  BladeSettings blade;
  Image density = testing::make_density_image(48, 40);
  HeightField ground = testing::make_ground(-40.0, 120.0);
  Rect rect{{-3.0, 2.0}, {93.0, 82.0}};
  GrassMaps maps() const { return GrassMaps::from_images(rect, &density, nullptr, nullptr).value(); }
};

TEST(GrassGenerator, DensityFidelityPerTileAndTotal) {
  Fixture f;
  f.field.density = 60.0f;
  f.field.tile_size = 4.0f;
  const GrassMaps maps = f.maps();
  auto set = generate_blades(f.field, f.blade, maps, f.ground, {0, 0, 0});
  ASSERT_TRUE(set.ok()) << set.error().message;
  int big_tiles = 0;
  for (const GrassTile& t : set->tiles) {
    // Every tile: within one blade of its density-map integral (stochastic rounding).
    EXPECT_LT(std::abs(static_cast<double>(t.count) - t.expected), 1.0) << t.key.x << "," << t.key.z;
    EXPECT_NEAR(t.expected, tile_expected_blades(f.field, maps, t.key), 1e-9);
    if (t.expected >= 100.0) {
      ++big_tiles;
      EXPECT_LE(std::abs(t.count - t.expected), 0.01 * t.expected);
    }
  }
  EXPECT_GT(big_tiles, 100);
  const double expected = maps.density_integral(maps.rect()) * f.field.density;
  EXPECT_NEAR(set->expected_total(), expected, 1e-6 * expected);
  EXPECT_NEAR(static_cast<double>(set->blades.size()), expected, 0.01 * expected);
  // The empty strip of the map (z in 0.8..0.9 of the rectangle, minus the bilinear ramp) is bare.
  for (const Blade& b : set->blades) {
    const double z = b.root().z;
    EXPECT_FALSE(z > f.rect.min.y + 0.82 * 80.0 && z < f.rect.min.y + 0.88 * 80.0) << z;
  }
}

TEST(GrassGenerator, BladesFollowTheDensityInsideTiles) {
  // One 16 m tile over a 16-pixel map whose density is a sharp left/right split: the sub-tile
  // CDF must put the blades where the map says, not uniformly over the tile.
  GrassFieldSettings field;
  field.tile_size = 16.0f;
  field.density = 200.0f;
  Image img(16, 16, 1);
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) img.at(i, j) = i < 4 ? 1.0f : 0.1f;
  const GrassMaps maps = GrassMaps::from_images({{0, 0}, {16, 16}}, &img, nullptr, nullptr).value();
  const HeightField ground(17, 17, 1.0);
  std::vector<Blade> blades;
  generate_tile(field, BladeSettings{}, maps, ground, {0, 0, 0}, {0, 0, 0}, blades);
  // Compare counts in 4 x 4 cells with the exact cell integrals.
  for (int cz = 0; cz < 4; ++cz) {
    for (int cx = 0; cx < 4; ++cx) {
      const Rect cell{{cx * 4.0, cz * 4.0}, {cx * 4.0 + 4.0, cz * 4.0 + 4.0}};
      const double expected = maps.density_integral(cell) * field.density;
      int count = 0;
      for (const Blade& b : blades) {
        const glm::vec3 p = b.root();
        if (p.x >= cell.min.x && p.x < cell.max.x && p.z >= cell.min.y && p.z < cell.max.y) ++count;
      }
      EXPECT_NEAR(count, expected, 0.03 * expected + 2.0) << "cell " << cx << "," << cz;
    }
  }
}

TEST(GrassGenerator, DeterministicBitForBit) {
  Fixture f;
  f.field.density = 20.0f;
  const GrassMaps maps = f.maps();
  auto a = generate_blades(f.field, f.blade, maps, f.ground, {1.0, 2.0, 3.0});
  auto b = generate_blades(f.field, f.blade, maps, f.ground, {1.0, 2.0, 3.0});
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_EQ(a->blades.size(), b->blades.size());
  EXPECT_EQ(std::memcmp(a->blades.data(), b->blades.data(), a->blades.size() * sizeof(Blade)), 0);
  f.field.seed = 2;
  auto c = generate_blades(f.field, f.blade, maps, f.ground, {1.0, 2.0, 3.0});
  ASSERT_TRUE(c.ok());
  int same = 0;
  const std::size_t n = std::min(a->blades.size(), c->blades.size());
  for (std::size_t i = 0; i < n; ++i) same += a->blades[i].v0 == c->blades[i].v0;
  EXPECT_LT(same, static_cast<int>(n / 100)) << "a new seed must move the blades";
}

TEST(GrassGenerator, WorldAnchoredAcrossExtentsAndOrigins) {
  // Field A covers [0, 32]^2, field B [-16, 48]^2 with the same (uniform) density and a different
  // origin: every tile inside both must hold the same blades at the same world positions.
  GrassFieldSettings field;
  field.density = 30.0f;
  const BladeSettings blade;
  const HeightField ground = testing::make_ground(-40.0, 80.0);
  const GrassMaps ma = GrassMaps::uniform({{0, 0}, {32, 32}});
  const GrassMaps mb = GrassMaps::uniform({{-16, -16}, {48, 48}});
  const glm::dvec3 oa(0, 0, 0), ob(1.0e5, -20.0, -3.0e4);
  auto a = generate_blades(field, blade, ma, ground, oa);
  auto b = generate_blades(field, blade, mb, ground, ob);
  ASSERT_TRUE(a.ok() && b.ok());
  std::map<std::tuple<int, int>, const GrassTile*> tiles_b;
  for (const GrassTile& t : b->tiles) tiles_b[{t.key.x, t.key.z}] = &t;
  int compared = 0;
  for (const GrassTile& ta : a->tiles) {
    const GrassTile* tb = tiles_b.at({ta.key.x, ta.key.z});
    ASSERT_EQ(ta.count, tb->count);
    for (std::uint32_t i = 0; i < ta.count; ++i) {
      const Blade& ba = a->blades[ta.first + i];
      const Blade& bb = b->blades[tb->first + i];
      const glm::dvec3 wa = oa + glm::dvec3(ba.root());
      const glm::dvec3 wb = ob + glm::dvec3(bb.root());
      ASSERT_LT(glm::length(wa - wb), 0.02) << "tile " << ta.key.x << "," << ta.key.z << " blade " << i;
      EXPECT_EQ(ba.orientation(), bb.orientation());
      EXPECT_EQ(ba.height(), bb.height());
      EXPECT_EQ(ba.width(), bb.width());
      EXPECT_EQ(ba.stiffness(), bb.stiffness());
      EXPECT_EQ(ba.attr, bb.attr);
      ++compared;
    }
  }
  EXPECT_GT(compared, 20000);
}

TEST(GrassGenerator, PerBladeRangesAndRestPose) {
  Fixture f;
  f.field.density = 15.0f;
  Image height(4, 4, 1);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) height.at(i, j) = 0.5f;
  const GrassMaps maps = GrassMaps::from_images(f.rect, &f.density, &height, nullptr).value();
  auto set = generate_blades(f.field, f.blade, maps, f.ground, {0, 0, 0});
  ASSERT_TRUE(set.ok());
  ASSERT_GT(set->blades.size(), 10000u);
  double mean_orient = 0.0;
  for (const Blade& b : set->blades) {
    EXPECT_GE(b.orientation(), 0.0f);
    EXPECT_LT(b.orientation(), 2.0f * std::numbers::pi_v<float>);
    EXPECT_GE(b.height(), 0.5f * f.blade.height_min - 1e-6f);
    EXPECT_LE(b.height(), 0.5f * f.blade.height_max + 1e-6f);
    EXPECT_GE(b.width(), 0.5f * f.blade.width_min - 1e-7f);
    EXPECT_LE(b.width(), 0.5f * f.blade.width_max + 1e-7f);
    EXPECT_GE(b.stiffness(), f.blade.stiffness_min);
    EXPECT_LE(b.stiffness(), f.blade.stiffness_max);
    EXPECT_GE(b.rank(), 0.0f);
    EXPECT_LT(b.rank(), 1.0f);
    // Root on the ground, rest pose valid and equal to the current pose.
    EXPECT_NEAR(b.root().y, f.ground.height(b.root().x, b.root().z), 1e-4);
    const BladeInvariants inv = check_blade(b);
    EXPECT_TRUE(inv.finite);
    EXPECT_LT(inv.length_error, 1e-4f);
    EXPECT_GT(inv.tip_height, 0.5f);
    EXPECT_LT(glm::length(b.tip() - b.root() - glm::vec3(b.rest)), 1e-6f);
    mean_orient += b.orientation();
  }
  mean_orient /= static_cast<double>(set->blades.size());
  EXPECT_NEAR(mean_orient, std::numbers::pi, 0.05);
}

// Seed 001 eq. 2.4 (grass.blade.control_jitter): the drawn control point of each blade gets its
// own r3 in [-0.25, 0.25] (share of the tip's sideways offset, x/z) and r4 in [0.75, 1.25]
// (height factor, y); the record is otherwise the unjittered one, and off draws v1 bit for bit.
TEST(GrassGenerator, ControlJitterIsSeed001Equation24) {
  Fixture f;
  f.field.density = 15.0f;
  const GrassMaps maps = f.maps();
  const BladeSet off = generate_blades(f.field, f.blade, maps, f.ground, {0, 0, 0}).value();
  f.blade.control_jitter = true;
  const BladeSet on = generate_blades(f.field, f.blade, maps, f.ground, {0, 0, 0}).value();
  ASSERT_EQ(on.blades.size(), off.blades.size());
  ASSERT_GT(on.blades.size(), 10000u);
  double r3_min = 1.0, r3_max = -1.0, r4_min = 2.0, r4_max = 0.0, r3_sum = 0.0, r4_sum = 0.0, r34_sum = 0.0;
  double ratio_sum = 0.0, ratio_sq = 0.0;
  int sideways = 0;
  for (std::size_t i = 0; i < on.blades.size(); ++i) {
    const Blade& a = off.blades[i];
    const Blade& b = on.blades[i];
    // Only attr.w (the shape random s, stored as 1 + s) tells the records apart.
    ASSERT_EQ(std::memcmp(&a, &b, offsetof(Blade, attr) + 3 * sizeof(float)), 0) << i;
    ASSERT_EQ(b.attr.w, 1.0f + a.attr.w) << i;
    ASSERT_FALSE(has_control_jitter(a));
    ASSERT_TRUE(has_control_jitter(b));
    const glm::vec3 c0 = drawn_control(a);
    ASSERT_EQ(std::memcmp(&c0, &a.v1, sizeof(c0)), 0) << "off must draw the physics' control point bit for bit";
    // Recover r4 (height factor of the control point) and r3 (share of the tip's side offset).
    const glm::vec3 up = b.up_dir(), c = drawn_control(b);
    const double r4 = glm::dot(c - b.root(), up) / glm::dot(b.control() - b.root(), up);
    const glm::vec3 d = b.tip() - b.root(), side = d - up * glm::dot(d, up);
    const glm::vec3 moved = (c - b.control()) - up * glm::dot(c - b.control(), up);
    EXPECT_GE(r4, 0.75 - 1e-4);
    EXPECT_LE(r4, 1.25 + 1e-4);
    r4_min = std::min(r4_min, r4);
    r4_max = std::max(r4_max, r4);
    r4_sum += r4;
    if (glm::length(side) > 0.02f) {
      const double r3 = glm::dot(moved, side) / glm::dot(side, side);
      EXPECT_NEAR(glm::length(moved), std::abs(r3) * glm::length(side), 1e-5);  // along the side offset only
      EXPECT_GE(r3, -0.25 - 1e-4);
      EXPECT_LE(r3, 0.25 + 1e-4);
      r3_min = std::min(r3_min, r3);
      r3_max = std::max(r3_max, r3);
      r3_sum += r3;
      r34_sum += r3 * (r4 - 1.0);
      ++sideways;
    }
    // The drawn blade's mid-point height against the unjittered one.
    const float h0 = glm::dot(bezier_point(a.root(), a.control(), a.tip(), 0.5f) - a.root(), up);
    const float h1 = glm::dot(bezier_point(b.root(), c, b.tip(), 0.5f) - b.root(), up);
    const double ratio = h1 / h0;
    ratio_sum += ratio;
    ratio_sq += ratio * ratio;
  }
  const double n = static_cast<double>(on.blades.size());
  const double ratio_mean = ratio_sum / n, ratio_sd = std::sqrt(std::max(ratio_sq / n - ratio_mean * ratio_mean, 0.0));
  std::printf("r3 [%.4f, %.4f] mean %.4f over %d leaning blades; r4 [%.4f, %.4f] mean %.4f; cov(r3, r4) %.5f; "
              "mid-point height ratio mean %.4f sd %.4f\n",
              r3_min, r3_max, r3_sum / sideways, sideways, r4_min, r4_max, r4_sum / n, r34_sum / sideways, ratio_mean, ratio_sd);
  ASSERT_GT(sideways, static_cast<int>(n / 2));
  // The whole ranges are used, evenly and independently.
  EXPECT_LT(r3_min, -0.24);
  EXPECT_GT(r3_max, 0.24);
  EXPECT_LT(r4_min, 0.76);
  EXPECT_GT(r4_max, 1.24);
  EXPECT_NEAR(r3_sum / sideways, 0.0, 0.01);
  EXPECT_NEAR(r4_sum / n, 1.0, 0.01);
  EXPECT_LT(std::abs(r34_sum / sideways), 0.002);  // |cov|; uniform r3, r4 alone: var 0.0208 each
  // Blade shapes differ blade to blade: the mid-point height spreads by several per cent.
  EXPECT_NEAR(ratio_mean, 1.0, 0.01);
  EXPECT_GT(ratio_sd, 0.05);

  // Every drawn curve stays in its root +- drawn_reach * height box (which the tile bounds are
  // made of), and the wider reach is needed: some leave the unjittered root +- height box.
  int outside_height_box = 0, outside_reach = 0;
  for (const GrassTile& t : on.tiles) {
    for (std::uint32_t i = t.first; i < t.first + t.count; ++i) {
      const Blade& b = on.blades[i];
      for (int k = 0; k <= 16; ++k) {
        const glm::vec3 p = bezier_point(b.root(), drawn_control(b), b.tip(), k / 16.0f);
        ASSERT_TRUE(glm::all(glm::greaterThanEqual(p, t.bounds_min)) && glm::all(glm::lessThanEqual(p, t.bounds_max))) << i;
        const glm::vec3 offset = glm::abs(p - b.root());
        outside_height_box += glm::any(glm::greaterThan(offset, glm::vec3(b.height())));
        outside_reach += glm::any(glm::greaterThan(offset, glm::vec3(b.height() * drawn_reach(b))));
      }
    }
  }
  std::printf("drawn curve points outside the root +- height box: %d, outside the drawn reach: %d\n", outside_height_box,
              outside_reach);
  EXPECT_GT(outside_height_box, 0);
  EXPECT_EQ(outside_reach, 0);
}

TEST(GrassGenerator, GrassOnASphereMesh) {
  const testing::SphereMesh sphere = testing::make_sphere(5.0f, 24, 48);
  GrassFieldSettings field;
  field.density = 80.0f;
  auto set = generate_blades_on_mesh(field, BladeSettings{}, sphere.view(), {100.0, 0.0, 0.0});
  ASSERT_TRUE(set.ok()) << set.error().message;
  const double expected = sphere.area() * field.density;
  EXPECT_NEAR(set->expected_total(), expected, 1e-6 * expected);
  EXPECT_NEAR(static_cast<double>(set->blades.size()), expected, 0.01 * expected);
  std::uint32_t in_tiles = 0;
  for (const GrassTile& t : set->tiles) in_tiles += t.count;
  EXPECT_EQ(in_tiles, set->blades.size());
  for (const Blade& b : set->blades) {
    const glm::vec3 p = b.root();
    EXPECT_NEAR(glm::length(p), 5.0f, 0.06f);               // on the (faceted) surface
    EXPECT_GT(glm::dot(b.up_dir(), glm::normalize(p)), 0.99f);  // growing outwards
    EXPECT_GT(check_blade(b).tip_height, 0.5f);
  }
  // Anchored on geometry: re-indexing the triangles (reversed order) keeps the same blade multiset.
  testing::SphereMesh shuffled = sphere;
  std::vector<std::uint32_t> rev;
  for (std::size_t t = shuffled.indices.size(); t >= 3; t -= 3)
    rev.insert(rev.end(), {shuffled.indices[t - 3], shuffled.indices[t - 2], shuffled.indices[t - 1]});
  shuffled.indices = rev;
  auto set2 = generate_blades_on_mesh(field, BladeSettings{}, shuffled.view(), {100.0, 0.0, 0.0});
  ASSERT_TRUE(set2.ok());
  ASSERT_EQ(set2->blades.size(), set->blades.size());
  double sum_a = 0.0, sum_b = 0.0;
  for (std::size_t i = 0; i < set->blades.size(); ++i) {
    sum_a += set->blades[i].orientation() + set->blades[i].root().x;
    sum_b += set2->blades[i].orientation() + set2->blades[i].root().x;
  }
  EXPECT_NEAR(sum_a, sum_b, 1e-6 * std::abs(sum_a) + 1e-3);
}

TEST(GrassGenerator, BadInputGivesClearErrors) {
  Fixture f;
  const GrassMaps maps = f.maps();
  BladeSettings bad = f.blade;
  bad.height_min = 2.0f;
  bad.height_max = 1.0f;
  auto a = generate_blades(f.field, bad, maps, f.ground, {0, 0, 0});
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.error().message.find("grass.blade.height_min"), std::string::npos) << a.error().message;

  GrassFieldSettings dense = f.field;
  dense.density = 5000.0f;
  const GrassMaps huge = GrassMaps::uniform({{0, 0}, {1000, 1000}});
  auto b = generate_blades(dense, f.blade, huge, f.ground, {0, 0, 0});
  ASSERT_FALSE(b.ok());
  EXPECT_EQ(b.error().code, ErrorCode::kLimit);
  EXPECT_NE(b.error().message.find("grass.field.density"), std::string::npos);

  GrassFieldSettings neg = f.field;
  neg.density = -1.0f;
  auto c = generate_blades(neg, f.blade, maps, f.ground, {0, 0, 0});
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error().message.find("grass.field.density"), std::string::npos) << c.error().message;

  const std::vector<glm::vec3> pos = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}};
  const std::vector<std::uint32_t> idx = {0, 1, 3};
  auto d = generate_blades_on_mesh(f.field, f.blade, {pos, {}, idx, {}}, {0, 0, 0});
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.error().message.find("out of range"), std::string::npos);
  const std::vector<std::uint32_t> idx2 = {0, 1};
  EXPECT_FALSE(generate_blades_on_mesh(f.field, f.blade, {pos, {}, idx2, {}}, {0, 0, 0}).ok());
  const std::vector<glm::vec3> nan_pos = {{0, 0, 0}, {NAN, 0, 0}, {0, 0, 1}};
  const std::vector<std::uint32_t> idx_ok = {0, 1, 2};
  auto e = generate_blades_on_mesh(f.field, f.blade, {nan_pos, {}, idx_ok, {}}, {0, 0, 0});
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().message.find("not finite"), std::string::npos);
}

TEST(GrassGenerator, TilesOverlappingCoverTheAreaAndCapTheCount) {
  // Tiles of 2 m over [-3, 5) x [0.5, 4]: x tiles -2..2, z tiles 0..1 (half-open ranges).
  const TileRange r = tiles_overlapping({{-3.0, 0.5}, {5.0, 4.0}}, 2.0).value();
  EXPECT_EQ(r.x0, -2);
  EXPECT_EQ(r.x1, 3);
  EXPECT_EQ(r.z0, 0);
  EXPECT_EQ(r.z1, 2);
  // 4 million tiles is the cap; one side alone may not pass a million (the product would
  // overflow long before the area does).
  EXPECT_TRUE(tiles_overlapping({{0.0, 0.0}, {2000.0, 2000.0}}, 1.0).ok());
  const auto too_many = tiles_overlapping({{0.0, 0.0}, {2001.0, 2000.0}}, 1.0);
  ASSERT_FALSE(too_many.ok());
  EXPECT_EQ(too_many.error().code, ErrorCode::kLimit);
  EXPECT_NE(too_many.error().message.find("grass.field.tile_size"), std::string::npos) << too_many.error().message;
  EXPECT_FALSE(tiles_overlapping({{0.0, 0.0}, {1.0e7, 0.5}}, 1.0).ok());
}

}  // namespace
}  // namespace sylva::grass

namespace sylva::grass {
namespace {

bool same_sets(const BladeSet& a, const BladeSet& b) {
  if (a.blades.size() != b.blades.size() || a.tiles.size() != b.tiles.size() || a.max_height != b.max_height) return false;
  if (std::memcmp(a.blades.data(), b.blades.data(), a.blades.size() * sizeof(Blade)) != 0) return false;
  for (std::size_t i = 0; i < a.tiles.size(); ++i) {
    const GrassTile &s = a.tiles[i], &t = b.tiles[i];
    if (!(s.key == t.key) || s.first != t.first || s.count != t.count || s.bounds_min != t.bounds_min ||
        s.bounds_max != t.bounds_max || s.expected != t.expected)
      return false;
  }
  return true;
}

}  // namespace

// Tile-local regeneration (issue 16): a dab on the density, height and tint maps regenerates
// only the tiles it reaches, and the set equals a full regeneration of the same maps bit for bit
// (blades, tiles with bounds and expected counts, tallest blade), dab after dab, also at the
// map's edge; the blades before the returned index are untouched. Regenerating a smaller area
// than the dab's gives a different set (the comparison can fail).
TEST(GrassGenerator, RegeneratingTheTilesOfADabEqualsAFullRegeneration) {
  Fixture f;
  f.field.density = 30.0f;
  Image height(48, 40, 1), tint(48, 40, 3);
  for (float& v : height.data()) v = 0.8f;
  for (float& v : tint.data()) v = 1.0f;
  auto maps = [&] { return GrassMaps::from_images(f.rect, &f.density, &height, &tint).value(); };
  const glm::dvec3 origin(45.0, 0.0, 42.0);
  auto set = generate_blades(f.field, f.blade, maps(), f.ground, origin);
  ASSERT_TRUE(set.ok());
  const glm::dvec2 texel = f.rect.size() / glm::dvec2(48.0, 40.0);
  // Texel rectangles [i0, i1) x [j0, j1): inside, at the map's corner, then one again.
  const int dabs[][4] = {{10, 8, 15, 13}, {0, 0, 3, 4}, {30, 20, 33, 22}};
  int k = 0;
  for (const auto& d : dabs) {
    SCOPED_TRACE(k);
    for (int j = d[1]; j < d[3]; ++j)
      for (int i = d[0]; i < d[2]; ++i) {
        f.density.at(i, j) = (i + j + k) % 3 == 0 ? 0.0f : 1.0f;
        height.at(i, j) = 0.3f + 0.1f * static_cast<float>((i + k) % 5);
        tint.at(i, j, 1) = 0.25f;
      }
    ++k;
    // The world area the edit shows in: the texels grown by one (bilinear interpolation).
    const Rect area{f.rect.min + glm::dvec2(d[0] - 1, d[1] - 1) * texel, f.rect.min + glm::dvec2(d[2] + 1, d[3] + 1) * texel};
    const BladeSet old = *set;
    auto first = regenerate_tiles(*set, f.field, f.blade, maps(), f.ground, area);
    ASSERT_TRUE(first.ok()) << first.error().message;
    auto full = generate_blades(f.field, f.blade, maps(), f.ground, origin);
    ASSERT_TRUE(full.ok());
    EXPECT_FALSE(same_sets(old, *full)) << "the dab changes the field";
    EXPECT_TRUE(same_sets(*set, *full)) << "per-tile update == full regeneration";
    ASSERT_LE(*first, old.blades.size());
    EXPECT_EQ(std::memcmp(old.blades.data(), set->blades.data(), *first * sizeof(Blade)), 0);
    std::printf("dab %d: %zu -> %zu blades, first changed %u\n", k, old.blades.size(), set->blades.size(), *first);
  }
  // Too small an area leaves tiles the edit reached as they were: no longer a full regeneration.
  for (int j = 20; j < 30; ++j)
    for (int i = 20; i < 30; ++i) f.density.at(i, j) = 0.0f;
  BladeSet partial = *set;
  const Rect corner{f.rect.min + glm::dvec2(20, 20) * texel, f.rect.min + glm::dvec2(21, 21) * texel};
  ASSERT_TRUE(regenerate_tiles(partial, f.field, f.blade, maps(), f.ground, corner).ok());
  EXPECT_FALSE(same_sets(partial, generate_blades(f.field, f.blade, maps(), f.ground, origin).value()));
}

}  // namespace sylva::grass

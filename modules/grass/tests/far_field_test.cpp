// Far field CPU parts: fades partition the distance axis, clumps follow the density map and are
// world-anchored, procedural textures have the threshold distributions the shaders rely on.
#include <sylva/grass/far_field.hpp>

#include "support/fields.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <set>
#include <tuple>

namespace sylva::grass {
namespace {

TEST(GrassFarField, FadesAreContinuousAndHandOver) {
  FarFieldSettings s;
  s.clump_fade_in = 10.0f;
  s.mid_distance = 120.0f;
  s.mid_fade = 30.0f;
  s.far_distance = 1000.0f;
  s.far_fade = 100.0f;
  const float near = 50.0f;
  float prev_c = clump_fade(0.0f, near, s), prev_g = ground_fade(0.0f, s);
  for (float d = 0.0f; d < 1200.0f; d += 0.25f) {
    const float c = clump_fade(d, near, s), g = ground_fade(d, s);
    EXPECT_GE(c, 0.0f);
    EXPECT_LE(c, 1.0f);
    EXPECT_LE(std::abs(c - prev_c), 0.25f / 10.0f + 1e-5f) << d;  // Lipschitz: no jumps
    EXPECT_LE(std::abs(g - prev_g), 0.25f / 30.0f + 1e-5f) << d;
    // Clumps hand over to the ground layer: their weights sum to 1 across the mid band.
    if (d >= near && d <= s.mid_distance) {
      EXPECT_NEAR(c + g, 1.0f, 1e-5f) << d;
    }
    prev_c = c;
    prev_g = g;
  }
  EXPECT_EQ(clump_fade(near - 10.0f, near, s), 0.0f);
  EXPECT_EQ(clump_fade(near, near, s), 1.0f);
  EXPECT_EQ(ground_fade(s.mid_distance, s), 1.0f);
  EXPECT_EQ(ground_fade(s.far_distance, s), 0.0f);
}

TEST(GrassFarField, ClumpsFollowTheMapAndAreWorldAnchored) {
  GrassFieldSettings field;
  BladeSettings blade;
  FarFieldSettings far;
  far.clumps_per_m2 = 2.0f;
  const Image density = testing::make_density_image(32, 32);
  const HeightField ground = testing::make_ground(-10.0, 110.0);
  const GrassMaps maps = GrassMaps::from_images({{0, 0}, {100, 100}}, &density, nullptr, nullptr).value();
  auto a = generate_clumps(field, blade, maps, ground, {50, 0, 50}, far);
  ASSERT_TRUE(a.ok()) << a.error().message;
  const double expected = maps.density_integral(maps.rect()) * far.clumps_per_m2;
  EXPECT_NEAR(static_cast<double>(a->clumps.size()), expected, 0.01 * expected);
  for (const GrassTile& t : a->tiles) EXPECT_LT(std::abs(t.count - t.expected), 1.0);
  auto b = generate_clumps(field, blade, maps, ground, {50, 0, 50}, far);
  ASSERT_EQ(a->clumps.size(), b->clumps.size());
  EXPECT_EQ(std::memcmp(a->clumps.data(), b->clumps.data(), a->clumps.size() * sizeof(Clump)), 0);
  for (const Clump& c : a->clumps) {
    EXPECT_NEAR(c.root.y + 0.0f, ground.height(c.root.x + 50.0, c.root.z + 50.0), 1e-3);
    EXPECT_GT(c.size.y, 0.0f);
    EXPECT_GE(c.size.w, 0.0f);
    EXPECT_LE(c.size.w, 3.0f);
  }
  FarFieldSettings bad = far;
  bad.clumps_per_m2 = -1.0f;
  auto e = generate_clumps(field, blade, maps, ground, {0, 0, 0}, bad);
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().message.find("grass.far.clumps_per_m2"), std::string::npos);
}

// Seed 003 Tab. 4.2: 20 wide billboards per 5 x 5-tile group at the densest, 20 ceil(N/5)^2 for
// an N x N map of 1 m tiles (groups clipped to the map), each no wider than its group.
TEST(GrassFarField, WideBillboardsAreTwentyPerGroupOfFiveByFiveTiles) {
  GrassFieldSettings field;
  field.tile_size = 1.0f;
  BladeSettings blade;
  FarFieldSettings far;
  far.wide_billboards = true;
  const HeightField ground = testing::make_ground(-10.0, 110.0);
  for (const int n : {1, 4, 8, 32, 64}) {
    Image ones(8, 8, 1);
    for (float& v : ones.data()) v = 1.0f;
    const GrassMaps maps = GrassMaps::from_images({{0, 0}, {n, n}}, &ones, nullptr, nullptr).value();
    auto w = generate_wide_billboards(field, blade, maps, ground, {0, 0, 0}, far);
    ASSERT_TRUE(w.ok()) << w.error().message;
    const int groups = (n + 4) / 5;
    EXPECT_EQ(static_cast<int>(w->tiles.size()), groups * groups) << n;
    EXPECT_NEAR(static_cast<double>(w->clumps.size()), 20.0 * groups * groups, 0.5 * groups) << n;  // thesis: 20, 20, 80, 980, 3380
    for (const Clump& c : w->clumps) {
      EXPECT_LE(c.size.x, std::min(5.0f, static_cast<float>(n)) + 1e-4f);
      EXPECT_GT(c.size.z, 0.0f);  // the group's strand keep
      EXPECT_LE(c.size.z, 1.0f);
    }
  }
  // The wide level takes over from the small clumps: their fades add up to one clump's fade.
  far.wide_distance = 80.0f;
  far.wide_fade = 20.0f;
  for (float d = 0.0f; d < 300.0f; d += 2.5f) {
    FarFieldSettings off = far;
    off.wide_billboards = false;
    EXPECT_NEAR(clump_fade(d, 50.0f, far) + wide_fade_at(d, 50.0f, far), clump_fade(d, 50.0f, off), 1e-6f) << d;
  }
  EXPECT_EQ(wide_fade_at(55.0f, 50.0f, far), 0.0f);
  EXPECT_EQ(clump_fade(100.0f, 50.0f, far), 0.0f);
  // Threshold shift: a full 5 m group of 20 billboards has 4 m of strands per m^2 against the small
  // clumps' 0.81, so each wide strand is kept with 0.2025.
  EXPECT_NEAR(wide_keep(far, 25.0, 5.0f), 0.81f / 4.0f, 1e-6f);
}

// Seed 003 §2.4.2 overcrowding guard, Tab. 4.5's step between density index 5 and 6: with
// grass.far.dense_extra_billboards every tile above 50 % density gets dense_extra_per_tile clumps
// more (none at or below), and its strands are kept below dense_keep k, where (n + extra) c(k) =
// n c(1) (c: one clump's cover at a threshold): the cover per tile stays the plain rule's.
TEST(GrassFarField, DenseExtraBillboardsStepAboveHalfDensity) {
  GrassFieldSettings field;  // 4 m tiles: 10 x 10 tiles over 40 x 40 m
  BladeSettings blade;
  FarFieldSettings off;
  FarFieldSettings on = off;
  on.dense_extra_billboards = true;
  on.dense_extra_per_tile = 4;
  const HeightField ground = testing::make_ground(-10.0, 50.0);
  const int tiles = 100;
  const std::vector<float> curve = clump_coverage_curve(make_clump_atlas(256, field.seed));
  const double c1 = clump_coverage(curve, 1.0f);
  for (int step = 1; step <= 10; ++step) {
    const float d = 0.1f * static_cast<float>(step);
    Image img(8, 8, 1);
    for (float& v : img.data()) v = d;
    const GrassMaps maps = GrassMaps::from_images({{0, 0}, {40, 40}}, &img, nullptr, nullptr).value();
    auto a = generate_clumps(field, blade, maps, ground, {0, 0, 0}, off);
    auto b = generate_clumps(field, blade, maps, ground, {0, 0, 0}, on);
    ASSERT_TRUE(a.ok() && b.ok());
    const auto extra = static_cast<long>(b->clumps.size()) - static_cast<long>(a->clumps.size());
    EXPECT_EQ(extra, step <= 5 ? 0 : on.dense_extra_per_tile * tiles) << "density " << d;
    double cover_on = 0.0;  // clumps' worth of cover: sum of c(keep) / c(1)
    for (const Clump& c : b->clumps) cover_on += clump_coverage(curve, c.size.z) / c1;
    EXPECT_NEAR(cover_on, static_cast<double>(a->clumps.size()), 0.01 * static_cast<double>(a->clumps.size())) << d;
    for (const Clump& c : b->clumps) {
      if (step <= 5) {
        EXPECT_EQ(c.size.z, 1.0f) << d;
      } else {
        EXPECT_LT(c.size.z, 1.0f) << d;
      }
    }
  }
  // A strand step is 1/56 of a cell's thresholds: k lands within a step of the exact cover.
  const double c_keep = clump_coverage(curve, dense_keep(12.0, 4, curve));
  EXPECT_NEAR(16.0 * c_keep, 12.0 * c1, 16.0 * c1 / 56.0);
  EXPECT_EQ(dense_keep(12.0, 0, curve), 1.0f);
}

// Seed 003 §2.5 / Fig. 3.15: every far tile gets its own deterministic sub-region of the noise
// texture; neighbours differ, all four quarter turns occur, offsets cover the texture evenly.
TEST(GrassFarField, NoiseSubregionsAreRandomPerTileAndDeterministic) {
  int turns[4] = {0, 0, 0, 0};
  double mean_u = 0.0, mean_v = 0.0;
  int same_as_right = 0;
  for (int z = -32; z < 32; ++z) {
    for (int x = -32; x < 32; ++x) {
      const NoiseSubregion r = noise_subregion(x, z, 7u);
      const NoiseSubregion again = noise_subregion(x, z, 7u);
      EXPECT_EQ(r.offset, again.offset);
      ASSERT_GE(r.quarter_turns, 0);
      ASSERT_LE(r.quarter_turns, 3);
      EXPECT_GE(r.offset.x, 0.0f);
      EXPECT_LT(r.offset.x, 1.0f);
      EXPECT_GE(r.offset.y, 0.0f);
      EXPECT_LT(r.offset.y, 1.0f);
      ++turns[r.quarter_turns];
      mean_u += r.offset.x;
      mean_v += r.offset.y;
      const NoiseSubregion right = noise_subregion(x + 1, z, 7u);
      same_as_right += glm::length(right.offset - r.offset) < 1e-3f && right.quarter_turns == r.quarter_turns;
    }
  }
  EXPECT_EQ(same_as_right, 0);
  for (const int t : turns) EXPECT_NEAR(t / 4096.0, 0.25, 0.03);
  EXPECT_NEAR(mean_u / 4096.0, 0.5, 0.02);
  EXPECT_NEAR(mean_v / 4096.0, 0.5, 0.02);
  EXPECT_NE(noise_subregion(0, 0, 7u).offset, noise_subregion(0, 0, 8u).offset);  // the seed matters
}

namespace {

using Edge = std::tuple<float, float, float, float, float, float>;

// Edges used by exactly one triangle of the index ranges (by vertex position, not index: the
// coarse chunks have their own copies of the ordinary chunks' edge vertices).
std::set<Edge> boundary_edges(const GroundLayerMesh& m, const std::vector<GroundChunk>& ranges) {
  std::map<Edge, int> uses;
  auto pos = [&](std::uint32_t v) {
    const float* p = &m.vertices[v * kGroundVertexFloats];
    return std::make_tuple(p[0], p[1], p[2]);
  };
  for (const GroundChunk& r : ranges) {
    for (std::uint32_t t = r.first_index; t < r.first_index + r.index_count; t += 3) {
      for (int e = 0; e < 3; ++e) {
        auto a = pos(m.indices[t + e]), b = pos(m.indices[t + (e + 1) % 3]);
        if (b < a) std::swap(a, b);
        ++uses[std::tuple_cat(a, b)];
      }
    }
  }
  std::set<Edge> out;
  for (const auto& [e, n] : uses)
    if (n == 1) out.insert(e);
  return out;
}

std::uint64_t triangles(const std::vector<GroundChunk>& ranges) {
  std::uint64_t n = 0;
  for (const GroundChunk& r : ranges) n += r.index_count / 3;
  return n;
}

}  // namespace

// Seed 003 §4.3's "another far sub-level with much larger polygons": with
// grass.far.coarse_ground a coarse chunk over f x f ordinary chunks (f = coarse_spacing_factor)
// has f^2 times fewer triangles; the ordinary chunks are as without the option; a coarse chunk
// stitched on all sides has exactly the outline of its ordinary chunks (watertight against
// them), with coarse sides its outline is the coarse grid's.
TEST(GrassFarField, CoarseGroundHasFactorSquaredFewerTrianglesAndStitchesWatertight) {
  GrassFieldSettings field;
  BladeSettings blade;
  FarFieldSettings far;
  far.ground_spacing = 1.0f;
  const HeightField ground = testing::make_ground(0.0, 256.0);  // 257 x 257 samples, 1 m
  const GrassMaps maps = GrassMaps::uniform({{0.0, 0.0}, {256.0, 256.0}});
  auto plain = build_ground_layer(field, blade, maps, ground, {128, 0, 128}, far);
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  EXPECT_TRUE(plain->coarse.empty());
  far.coarse_ground = true;
  for (const int f : {2, 4}) {
    far.coarse_spacing_factor = f;
    auto m = build_ground_layer(field, blade, maps, ground, {128, 0, 128}, far);
    ASSERT_TRUE(m.ok()) << m.error().message;
    // The ordinary chunks (16 x 16 of 16 x 16 quads) are unchanged.
    ASSERT_EQ(m->chunks.size(), 256u);
    ASSERT_EQ(m->chunks.size(), plain->chunks.size());
    EXPECT_EQ(std::memcmp(m->vertices.data(), plain->vertices.data(), plain->vertices.size() * sizeof(float)), 0);
    EXPECT_EQ(m->chunks.back().first_index + m->chunks.back().index_count, plain->indices.size());
    ASSERT_EQ(m->coarse.size(), static_cast<std::size_t>(16 / f * 16 / f));
    std::uint64_t fine_tris = 0, coarse_tris = 0;
    for (const CoarseGroundChunk& cc : m->coarse) {
      std::vector<GroundChunk> fine, coarse{cc.interior}, stitched{cc.interior};
      for (const std::uint32_t i : cc.fine) fine.push_back(m->chunks[i]);
      for (const auto& side : cc.sides) {
        coarse.push_back(side[0]);
        stitched.push_back(side[1]);
      }
      ASSERT_EQ(fine.size(), static_cast<std::size_t>(f * f));
      fine_tris += triangles(fine);
      coarse_tris += triangles(coarse);
      EXPECT_EQ(triangles(coarse), 512u);  // 16 x 16 quads, like an ordinary chunk
      const std::set<Edge> outline = boundary_edges(*m, fine);
      EXPECT_EQ(outline.size(), static_cast<std::size_t>(4 * 16 * f));
      EXPECT_EQ(boundary_edges(*m, stitched), outline);
      EXPECT_EQ(boundary_edges(*m, coarse).size(), 64u);
    }
    EXPECT_EQ(fine_tris, static_cast<std::uint64_t>(f * f) * coarse_tris) << f;
    std::printf("coarse_spacing_factor %d: ordinary %llu triangles, coarse %llu (1/%.1f)\n", f,
                static_cast<unsigned long long>(fine_tris), static_cast<unsigned long long>(coarse_tris),
                static_cast<double>(fine_tris) / static_cast<double>(coarse_tris));
  }
}

TEST(GrassFarField, GroundTextureAlphaIsUniformAndTiles) {
  const Image tex = make_ground_texture(64, 3);
  // Equalised: the share of texels below t is t.
  for (const float t : {0.1f, 0.25f, 0.5f, 0.9f}) {
    int below = 0;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) below += tex.at(x, y, 3) < t;
    EXPECT_NEAR(below / 4096.0, t, 0.01);
  }
  // Tileable: the wrap-around step is no larger than an interior step (colour channel).
  double edge = 0.0, inner = 0.0;
  for (int y = 0; y < 64; ++y) {
    edge += std::abs(tex.at(63, y, 1) - tex.at(0, y, 1));
    inner += std::abs(tex.at(31, y, 1) - tex.at(32, y, 1));
  }
  EXPECT_LT(edge, 2.0 * inner + 0.5);
}

TEST(GrassFarField, ClumpAtlasThresholdsAreGraded) {
  const Image atlas = make_clump_atlas(128, 9);
  // Covered share grows steadily with the threshold (strands appear one by one).
  double prev = 0.0;
  for (int k = 1; k <= 10; ++k) {
    int covered = 0;
    for (int y = 0; y < 128; ++y)
      for (int x = 0; x < 128; ++x) covered += atlas.at(x, y, 3) < k / 10.0f;
    const double share = covered / (128.0 * 128.0);
    EXPECT_GT(share, prev) << k;
    prev = share;
  }
  EXPECT_GT(prev, 0.15);  // a full clump covers a good part of its quad
  EXPECT_LT(prev, 0.9);
}

}  // namespace
}  // namespace sylva::grass

// The far field's tile-local update after edits (issue 16, FarField::update_region): density,
// height and tint dabs (one at the map's edge, which the clump margin extends outwards) and a
// ground dab, applied one by one to a far field with every generated level on (clump margin,
// wide billboards, the overcrowding guard's extra clumps, the coarse ground sub-level), leave it
// equal bit for bit to a far field created from the final maps and ground: clump records, tiles,
// wide groups, the density and tint images and the ground layer's vertices and chunk bounds on the
// CPU, and the
// clump buffer, the ground vertex buffer and the density/tint textures read back from the GPU.
#include <sylva/core/height_field.hpp>
#include <sylva/grass/far_field.hpp>
#include <sylva/render/testing.hpp>

#include "support/fields.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

namespace sylva::grass {
namespace {

using GrassFarFieldEditGl = render::GlTest;

const Rect kRect{{-20.0, -24.0}, {20.0, 24.0}};
constexpr int kW = 40, kH = 48;  // map texels: 1 m

struct Stage {
  GrassFieldSettings field;
  BladeSettings blade;
  FarFieldSettings far;
  HeightField ground{65, 65, 2.0, {-64.0, -64.0}};
  Image density = testing::make_density_image(kW, kH);
  Image height{kW, kH, 1};
  Image tint{kW, kH, 3};
  Stage() {
    field.tile_size = 1.0f;
    far.clump_margin = 6.0f;
    far.ground_margin = 10.0f;
    far.wide_billboards = true;
    far.dense_extra_billboards = true;
    far.coarse_ground = true;
    for (int j = 0; j < ground.rows(); ++j)
      for (int i = 0; i < ground.columns(); ++i) ground.sample(i, j) = static_cast<float>(2.0 * std::sin(0.11 * i) * std::cos(0.07 * j));
    ground.update_range();
    for (int j = 0; j < kH; ++j)
      for (int i = 0; i < kW; ++i) {
        height.at(i, j, 0) = 0.5f + 0.5f * static_cast<float>(std::sin(0.3 * i + 0.2 * j));
        for (int c = 0; c < 3; ++c) tint.at(i, j, c) = 0.8f + 0.1f * static_cast<float>(c) * static_cast<float>((i + j) % 3);
      }
  }
  GrassMaps maps() const { return GrassMaps::from_images(kRect, &density, &height, &tint).value(); }
  Result<FarField> create() const { return FarField::create(field, blade, maps(), ground, {0.0, 0.0, 0.0}, far); }
};

// Sets map texels within `r` texels of (ci, cj) with value(i, j, c) and returns the world area whose
// interpolant changed: the texels' cells grown by one texel (the scene's changed_world_area).
template <class F>
Rect dab(Image& im, int ci, int cj, int r, F value) {
  const int i0 = std::max(ci - r, 0), i1 = std::min(ci + r + 1, im.width()), j0 = std::max(cj - r, 0), j1 = std::min(cj + r + 1, im.height());
  for (int j = j0; j < j1; ++j)
    for (int i = i0; i < i1; ++i)
      for (int c = 0; c < im.channels(); ++c) im.at(i, j, c) = value(i, j, c);
  const glm::dvec2 texel = kRect.size() / glm::dvec2(im.width(), im.height());
  return {kRect.min + (glm::dvec2(i0, j0) - 1.0) * texel, kRect.min + (glm::dvec2(i1, j1) + 1.0) * texel};
}

template <class T>
std::size_t differing(const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) n += std::memcmp(&a[i], &b[i], sizeof(T)) != 0 ? 1 : 0;
  return n;
}

std::size_t differing(const Image& a, const Image& b) {
  const auto x = a.data(), y = b.data();
  return differing(std::vector<float>(x.begin(), x.end()), std::vector<float>(y.begin(), y.end()));
}

std::size_t differing_tiles(const std::vector<GrassTile>& a, const std::vector<GrassTile>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const GrassTile &x = a[i], &y = b[i];
    const bool same = x.key.x == y.key.x && x.key.z == y.key.z && x.first == y.first && x.count == y.count &&
                      x.bounds_min == y.bounds_min && x.bounds_max == y.bounds_max && x.expected == y.expected;
    n += same ? 0 : 1;
  }
  return n;
}

// Ground chunks whose index range or bounds differ (coarse chunks: interior and sides).
std::size_t differing_chunks(const FarField& a, const FarField& b) {
  auto same = [](const GroundChunk& x, const GroundChunk& y) {
    return x.first_index == y.first_index && x.index_count == y.index_count && x.bounds_min == y.bounds_min &&
           x.bounds_max == y.bounds_max && x.first_vertex == y.first_vertex && x.vertex_count == y.vertex_count;
  };
  const auto &ca = a.ground_chunks(), &cb = b.ground_chunks();
  const auto &ka = a.coarse_ground_chunks(), &kb = b.coarse_ground_chunks();
  if (ca.size() != cb.size() || ka.size() != kb.size()) return std::max(ca.size(), cb.size()) + std::max(ka.size(), kb.size());
  std::size_t n = 0;
  for (std::size_t i = 0; i < ca.size(); ++i) n += same(ca[i], cb[i]) ? 0 : 1;
  for (std::size_t i = 0; i < ka.size(); ++i) {
    bool all = same(ka[i].interior, kb[i].interior);
    for (int s = 0; s < 4; ++s)
      for (int v = 0; v < 2; ++v) all = all && same(ka[i].sides[s][v], kb[i].sides[s][v]);
    n += all ? 0 : 1;
  }
  return n;
}

}  // namespace

TEST_F(GrassFarFieldEditGl, UpdatesAfterDabsEqualACreateFromTheFinalMaps) {
  Stage s;
  auto far = s.create();
  ASSERT_TRUE(far.ok()) << far.error().message;
  const std::vector<Clump> before = far->clump_records();
  const std::vector<float> ground_before = far->ground_vertices();

  // Density to 0 over a disc, then the height and tint maps at the map's -x edge (the clump
  // margin continues that edge outwards), then the ground.
  const Rect a = dab(s.density, 12, 30, 3, [](int, int, int) { return 0.0f; });
  ASSERT_TRUE(far->update_region(s.field, s.blade, s.maps(), s.ground, {&a, 1}, false).ok());
  const Rect b = dab(s.height, 0, 10, 2, [](int, int, int) { return 0.2f; });
  const Rect c = dab(s.tint, 1, 14, 2, [](int i, int, int ch) { return ch == 0 ? 0.3f + 0.1f * static_cast<float>(i) : 1.2f; });
  const Rect bc[2] = {b, c};
  ASSERT_TRUE(far->update_region(s.field, s.blade, s.maps(), s.ground, bc, false).ok());
  // Ground samples around (10, -15) (sample spacing 2 m) up by 6 m (steep enough for slope_keep); the area their bilinear
  // surface changes in.
  const int gi = (10 + 64) / 2, gj = (-15 + 64) / 2;
  for (int j = gj - 1; j <= gj + 1; ++j)
    for (int i = gi - 1; i <= gi + 1; ++i) s.ground.sample(i, j) += 6.0f;
  s.ground.update_range();
  const Rect g{{-64.0 + 2.0 * (gi - 2), -64.0 + 2.0 * (gj - 2)}, {-64.0 + 2.0 * (gi + 2), -64.0 + 2.0 * (gj + 2)}};
  ASSERT_TRUE(far->update_region(s.field, s.blade, s.maps(), s.ground, {&g, 1}, true).ok());

  auto fresh = s.create();
  ASSERT_TRUE(fresh.ok()) << fresh.error().message;
  std::printf("%zu clumps (%zu wide) before the dabs, %zu after; %zu of them moved or changed; %zu ground floats changed\n",
              before.size(), far->wide_billboard_count(), far->clump_records().size(), differing(before, far->clump_records()),
              differing(ground_before, far->ground_vertices()));
  EXPECT_GT(differing(before, far->clump_records()), 0u) << "the dabs changed clumps";
  EXPECT_GT(differing(ground_before, far->ground_vertices()), 0u) << "the ground dab moved the ground layer";
  EXPECT_GT(far->wide_billboard_count(), 0u);
  // CPU data.
  EXPECT_EQ(far->clump_count(), fresh->clump_count());
  EXPECT_EQ(far->wide_billboard_count(), fresh->wide_billboard_count());
  EXPECT_EQ(differing(far->clump_records(), fresh->clump_records()), 0u);
  EXPECT_EQ(differing_tiles(far->clump_tiles(), fresh->clump_tiles()), 0u);
  EXPECT_EQ(differing_tiles(far->wide_tiles(), fresh->wide_tiles()), 0u);
  EXPECT_EQ(differing(far->density_image(), fresh->density_image()), 0u);
  EXPECT_EQ(differing(far->tint_image(), fresh->tint_image()), 0u);
  EXPECT_EQ(differing(far->ground_vertices(), fresh->ground_vertices()), 0u);
  EXPECT_EQ(differing_chunks(*far, *fresh), 0u) << "ground chunks' bounds follow the ground";
  // GPU data.
  EXPECT_EQ(differing(far->read_clump_buffer(), fresh->read_clump_buffer()), 0u);
  EXPECT_EQ(differing(far->read_clump_buffer(), far->clump_records()), 0u);
  EXPECT_EQ(differing(far->read_ground_vertex_buffer(), fresh->read_ground_vertex_buffer()), 0u);
  EXPECT_EQ(differing(far->read_density_texture(), fresh->read_density_texture()), 0u);
  EXPECT_EQ(differing(far->read_tint_texture(), fresh->read_tint_texture()), 0u);
  EXPECT_EQ(differing(far->read_density_texture(), fresh->density_image()), 0u);
}

TEST_F(GrassFarFieldEditGl, AnEditThatAddsATintMapAsksForARebuild) {
  Stage s;
  auto far = FarField::create(s.field, s.blade, GrassMaps::from_images(kRect, &s.density, &s.height, nullptr).value(), s.ground,
                              {0.0, 0.0, 0.0}, s.far);
  ASSERT_TRUE(far.ok()) << far.error().message;
  const Rect a = dab(s.tint, 5, 5, 1, [](int, int, int) { return 0.5f; });
  const Status st = far->update_region(s.field, s.blade, s.maps(), s.ground, {&a, 1}, false);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().message.find("full rebuild"), std::string::npos) << st.error().message;
}

}  // namespace sylva::grass

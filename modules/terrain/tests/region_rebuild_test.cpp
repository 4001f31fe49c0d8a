// ChunkTree::rebuild_region (issue 9, live height painting): after an edit, the partially rebuilt
// tree equals a full rebuild of the edited field chunk for chunk, and only the chunks whose
// square grown by half a chunk meets the edit are re-triangulated.
#include <sylva/terrain/chunk_tree.hpp>

#include "support/terrain_test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace sylva::terrain {
namespace {

using testing::fbm_field;

ChunkTree build_or_die(const HeightField& f, const ChunkTreeSettings& s) {
  auto r = ChunkTree::build(f, s);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().describe());
  return std::move(r).value();
}

// A smooth bump of `amount` metres centred on sample (cx, cz) with radius r, applied to the
// samples in [x0, x1) x [z0, z1) only, as a brush stroke's dirty rectangle.
void paint(HeightField& f, int cx, int cz, int r, float amount, int& x0, int& z0, int& x1, int& z1) {
  x0 = std::max(cx - r, 0);
  z0 = std::max(cz - r, 0);
  x1 = std::min(cx + r + 1, f.columns());
  z1 = std::min(cz + r + 1, f.rows());
  for (int z = z0; z < z1; ++z) {
    for (int x = x0; x < x1; ++x) {
      const double d = std::hypot(x - cx, z - cz) / (r + 1);
      if (d < 1.0) f.sample(x, z) += amount * static_cast<float>(1.0 - d * d);
    }
  }
  f.update_range();
}

// Invariant: partial == full, for every field of every chunk the renderer and selection read.
void expect_same_tree(const ChunkTree& a, const ChunkTree& b) {
  ASSERT_EQ(a.chunk_count(), b.chunk_count());
  for (std::uint32_t i = 0; i < a.chunk_count(); ++i) {
    const Chunk& p = a.chunk(i);
    const Chunk& q = b.chunk(i);
    ASSERT_EQ(p.present, q.present) << i;
    EXPECT_EQ(p.error, q.error) << "chunk " << i;
    EXPECT_EQ(p.error_bound, q.error_bound) << "chunk " << i;
    EXPECT_EQ(p.min_y, q.min_y) << "chunk " << i;
    EXPECT_EQ(p.max_y, q.max_y) << "chunk " << i;
    EXPECT_EQ(p.triangle_count, q.triangle_count) << "chunk " << i;
    ASSERT_EQ(p.mesh.vertices.size(), q.mesh.vertices.size()) << "chunk " << i;
    EXPECT_EQ(p.mesh.indices, q.mesh.indices) << "chunk " << i;
    for (int e = 0; e < 4; ++e) EXPECT_EQ(p.mesh.edges[e], q.mesh.edges[e]) << "chunk " << i;
    for (std::size_t v = 0; v < p.mesh.vertices.size(); ++v) {
      const ChunkVertex& x = p.mesh.vertices[v];
      const ChunkVertex& y = q.mesh.vertices[v];
      ASSERT_TRUE(x.gx == y.gx && x.gz == y.gz && x.height == y.height && x.morph_target == y.morph_target &&
                  x.morph_error == y.morph_error && x.intro_level == y.intro_level && x.outside == y.outside)
          << "chunk " << i << " vertex " << v << " (" << x.gx << ", " << x.gz << ")";
    }
    const ChunkNode& n = a.nodes()[i];
    const ChunkNode& m = b.nodes()[i];
    EXPECT_TRUE(n.lo == m.lo && n.hi == m.hi && n.error_bound == m.error_bound && n.parent_bound == m.parent_bound)
        << "node " << i;
  }
  EXPECT_EQ(a.report().triangles(), b.report().triangles());
}

// The expected rebuilt set: present chunks whose square grown by half a chunk meets the edit
// (inclusive grid points; x1/z1 exclusive samples).
std::vector<std::uint32_t> expected_rebuilt(const ChunkTree& t, int x0, int z0, int x1, int z1) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t i = 0; i < t.chunk_count(); ++i) {
    const Chunk& c = t.chunk(i);
    if (!c.present) continue;
    const std::int64_t size = t.chunk_size(c.key.level);
    const std::int64_t lo_x = c.key.x * size - size / 2, hi_x = (c.key.x + 1) * size + size / 2;
    const std::int64_t lo_z = c.key.z * size - size / 2, hi_z = (c.key.z + 1) * size + size / 2;
    if (lo_x <= x1 - 1 && x0 <= hi_x && lo_z <= z1 - 1 && z0 <= hi_z) out.push_back(i);
  }
  return out;
}

ChunkTreeSettings small_settings() {
  ChunkTreeSettings s;
  s.leaf_dimension = 17;
  s.flat_tolerance = 0.02f;
  return s;
}

TEST(RegionRebuild, EqualsFullRebuildAndRebuildsOnlyTheNearChunks) {
  HeightField f = fbm_field(257, 257, 1.0, 30.0f, 11);
  const ChunkTreeSettings s = small_settings();
  ChunkTree partial = build_or_die(f, s);
  int x0, z0, x1, z1;
  paint(f, 150, 90, 6, 4.0f, x0, z0, x1, z1);
  auto r = partial.rebuild_region(f, x0, z0, x1, z1);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  const ChunkTree full = build_or_die(f, s);
  expect_same_tree(partial, full);
  EXPECT_EQ(r->rebuilt, expected_rebuilt(full, x0, z0, x1, z1));
  // 256 intervals, leaf 16: levels 0..4 with 1 + 4 + 16 + 64 + 256 = 341 chunks; a 13-sample
  // stroke re-triangulates a handful per level, far fewer than the tree.
  EXPECT_EQ(partial.chunk_count(), 341u);
  EXPECT_LE(r->rebuilt.size(), 30u);
  EXPECT_GE(r->rebuilt.size(), 5u);  // at least one per level
  for (std::uint32_t i : r->updated) EXPECT_FALSE(std::binary_search(r->rebuilt.begin(), r->rebuilt.end(), i));

  // A second edit on the already edited tree, and an edit on the field's far corner (padding).
  paint(f, 40, 200, 3, -2.5f, x0, z0, x1, z1);
  ASSERT_TRUE(partial.rebuild_region(f, x0, z0, x1, z1).ok());
  paint(f, 256, 256, 4, 3.0f, x0, z0, x1, z1);
  ASSERT_TRUE(partial.rebuild_region(f, x0, z0, x1, z1).ok());
  expect_same_tree(partial, build_or_die(f, s));
}

// A point's intro level (the coarsest level holding it) follows its RTIN error, which a stroke
// far beyond the point's own chunk can change (the error of a coarse point gathers a large
// triangle): on a nearly flat field, tall strokes make far vertices of chunks that are not
// rebuilt enter coarser levels, so their intro level and morph target must be taken again.
TEST(RegionRebuild, StrokesOnANearlyFlatFieldKeepEveryIntroLevelExact) {
  HeightField f = fbm_field(257, 201, 2.0, 0.05f, 61);  // padded, non-square, 5 cm of relief
  ChunkTreeSettings s;
  s.leaf_dimension = 17;
  ChunkTree partial = build_or_die(f, s);
  int x0, z0, x1, z1;
  const int strokes[][2] = {{60, 70}, {200, 40}, {128, 100}, {20, 180}, {240, 190}, {130, 20}};
  for (const auto& at : strokes) {
    paint(f, at[0], at[1], 14, 300.0f, x0, z0, x1, z1);
    ASSERT_TRUE(partial.rebuild_region(f, x0, z0, x1, z1).ok());
  }
  expect_same_tree(partial, build_or_die(f, s));
}

TEST(RegionRebuild, EditAtAChunkCornerRebuildsEveryChunkSharingIt) {
  // A non-square field with padding: 200 x 150 samples in a 256-interval root grid.
  HeightField f = fbm_field(200, 150, 1.0, 20.0f, 5);
  const ChunkTreeSettings s = small_settings();
  ChunkTree partial = build_or_die(f, s);
  // The single sample (64, 64) is a corner of four leaf chunks (size 16), of four level-3 chunks
  // (size 32) and of four level-2 chunks (size 64).
  f.sample(64, 64) += 5.0f;
  f.update_range();
  auto r = partial.rebuild_region(f, 64, 64, 65, 65);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  expect_same_tree(partial, build_or_die(f, s));
  for (int level = 2; level < partial.levels(); ++level) {
    const std::uint32_t c = 64 / partial.chunk_size(level);
    for (std::uint32_t dz = 0; dz < 2; ++dz) {
      for (std::uint32_t dx = 0; dx < 2; ++dx) {
        const std::uint32_t idx = partial.index(level, c - 1 + dx, c - 1 + dz);
        EXPECT_TRUE(std::binary_search(r->rebuilt.begin(), r->rebuilt.end(), idx))
            << "level " << level << " chunk (" << c - 1 + dx << ", " << c - 1 + dz << ")";
      }
    }
  }
  // Leaf chunks further than half a chunk from the corner keep their meshes.
  EXPECT_FALSE(std::binary_search(r->rebuilt.begin(), r->rebuilt.end(), partial.index(4, 6, 6)));
  EXPECT_EQ(r->rebuilt, expected_rebuilt(partial, 64, 64, 65, 65));
}

TEST(RegionRebuild, RejectsAnotherFieldAndKeepsTheTree) {
  const HeightField f = fbm_field(65, 65, 1.0, 10.0f, 3);
  ChunkTreeSettings s;
  s.leaf_dimension = 17;
  ChunkTree t = build_or_die(f, s);
  const HeightField g = fbm_field(33, 33, 1.0, 10.0f, 3);
  auto r = t.rebuild_region(g, 0, 0, 4, 4);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("65x65"), std::string::npos) << r.error().message;
  auto empty = t.rebuild_region(f, 10, 10, 10, 20);
  ASSERT_TRUE(empty.ok());
  EXPECT_TRUE(empty->rebuilt.empty());
  ChunkTreeSettings no_mesh = s;
  no_mesh.keep_meshes = false;
  ChunkTree bare = build_or_die(f, no_mesh);
  EXPECT_FALSE(bare.rebuild_region(f, 0, 0, 4, 4).ok());
}

}  // namespace
}  // namespace sylva::terrain

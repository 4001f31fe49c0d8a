// Chunk tree build: grid and level layout, measured error against a brute-force evaluation,
// monotone bounds, conforming meshes, shared edges, nesting, morph targets, vertex-cache order.
#include <sylva/core/timer.hpp>
#include <sylva/terrain/chunk_tree.hpp>

#include "support/terrain_test_support.hpp"

#include <gtest/gtest.h>
#include <meshoptimizer.h>

#include <cmath>
#include <map>
#include <set>

namespace sylva::terrain {
namespace {

using testing::fbm_field;
using testing::make_field;
using testing::same_bytes;

ChunkTree build_or_die(const HeightField& f, ChunkTreeSettings s = {}) {
  auto r = ChunkTree::build(f, s);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().describe());
  return std::move(r).value();
}

// Height of a chunk's mesh at grid point (x, z) by scanning its triangles (brute force).
bool mesh_height_at(const ChunkMesh& m, double x, double z, double& out) {
  for (std::size_t i = 0; i < m.indices.size(); i += 3) {
    const ChunkVertex& a = m.vertices[m.indices[i]];
    const ChunkVertex& b = m.vertices[m.indices[i + 1]];
    const ChunkVertex& c = m.vertices[m.indices[i + 2]];
    const double ax = a.gx, az = a.gz, bx = b.gx, bz = b.gz, cx = c.gx, cz = c.gz;
    const double det = (bz - az) * (cx - ax) - (bx - ax) * (cz - az);
    const double w0 = ((bz - z) * (cx - x) - (bx - x) * (cz - z)) / det;
    const double w1 = ((z - az) * (cx - ax) - (x - ax) * (cz - az)) / det;
    const double w2 = 1.0 - w0 - w1;
    if (w0 < -1e-12 || w1 < -1e-12 || w2 < -1e-12) continue;
    out = w0 * a.height + w1 * b.height + w2 * c.height;
    return true;
  }
  return false;
}

TEST(ChunkTree, LevelLayoutCoversTheField) {
  const HeightField f = fbm_field(129, 129, 1.0, 50.0f, 1);
  ChunkTreeSettings s;
  s.leaf_dimension = 17;
  const Stopwatch wall;
  const ChunkTree t = build_or_die(f, s);
  const double wall_ms = wall.elapsed_ms();
  EXPECT_EQ(t.leaf_intervals(), 16u);
  EXPECT_EQ(t.levels(), 4);  // 16 * 2^3 = 128
  EXPECT_EQ(t.root_intervals(), 128u);
  EXPECT_EQ(t.chunk_count(), 1u + 4u + 16u + 64u);
  for (int l = 0; l < t.levels(); ++l) EXPECT_EQ(t.chunk_size(l) / t.step(l), 16u) << "level " << l;
  const BuildReport& r = t.report();
  ASSERT_EQ(r.levels.size(), 4u);
  std::uint64_t sum = 0;
  for (std::size_t i = 0; i < t.chunk_count(); ++i) sum += t.chunk(static_cast<std::uint32_t>(i)).triangle_count;
  EXPECT_EQ(r.triangles(), sum);
  EXPECT_EQ(r.levels[3].chunks, 64u);
  // The build's own time lies within the wall time around it (no bound on either).
  EXPECT_GT(r.total_ms, 0.0);
  EXPECT_LE(r.total_ms, wall_ms);
  // The rough field keeps most of the leaf grid.
  EXPECT_GT(r.levels[3].triangles, r.levels[3].grid_triangles / 2);
  EXPECT_GE(r.threads, 1);
  const std::string text = r.describe();
  EXPECT_NE(text.find("level 3: 64 chunks, " + std::to_string(r.levels[3].triangles) + " triangles"), std::string::npos) << text;
}

TEST(ChunkTree, MeasuredErrorEqualsBruteForceMaximum) {
  const HeightField f = fbm_field(65, 65, 2.0, 40.0f, 7);
  ChunkTreeSettings s;
  s.leaf_dimension = 9;
  s.flat_tolerance = 0.05f;
  const ChunkTree t = build_or_die(f, s);
  for (std::uint32_t i = 0; i < t.chunk_count(); ++i) {
    const Chunk& c = t.chunk(i);
    ASSERT_TRUE(c.present);
    const std::uint32_t size = t.chunk_size(c.key.level);
    double worst = 0.0;
    for (std::uint32_t z = c.key.z * size; z <= (c.key.z + 1) * size; ++z) {
      for (std::uint32_t x = c.key.x * size; x <= (c.key.x + 1) * size; ++x) {
        double h = 0.0;
        ASSERT_TRUE(mesh_height_at(c.mesh, x, z, h)) << "sample outside every triangle";
        worst = std::max(worst, std::fabs(h - f.sample(static_cast<int>(x), static_cast<int>(z))));
      }
    }
    EXPECT_GE(static_cast<double>(c.error), worst - 1e-9) << "level " << c.key.level;
    EXPECT_LE(static_cast<double>(c.error), worst + 1e-4) << "level " << c.key.level;
  }
  // Leaves with a small tolerance are nearly exact; the root is not.
  EXPECT_GT(t.chunk(0).error, 1.0f);
}

TEST(ChunkTree, ErrorBoundsAreMonotone) {
  const HeightField f = fbm_field(257, 257, 1.0, 80.0f, 3);
  ChunkTreeSettings s;
  s.leaf_dimension = 17;
  const ChunkTree t = build_or_die(f, s);
  const double growth = 1.0 / (1.0 - s.max_morph_fraction);
  for (std::uint32_t i = 0; i < t.chunk_count(); ++i) {
    const Chunk& c = t.chunk(i);
    EXPECT_GE(c.error_bound, c.error);
    if (c.key.level + 1 < t.levels()) {
      for (std::uint32_t ci : t.child_indices(i)) {
        EXPECT_GE(static_cast<double>(c.error_bound), growth * t.chunk(ci).error_bound * (1.0 - 1e-6));
        EXPECT_GE(c.error_bound, t.chunk(ci).error);
      }
    }
  }
}

TEST(ChunkTree, ChunkMeshesAreConformingAndUpFacing) {
  const HeightField f = fbm_field(129, 129, 1.0, 60.0f, 11);
  ChunkTreeSettings s;
  s.leaf_dimension = 17;
  s.flat_tolerance = 0.2f;
  const ChunkTree t = build_or_die(f, s);
  for (std::uint32_t i = 0; i < t.chunk_count(); ++i) {
    const Chunk& c = t.chunk(i);
    const std::uint32_t size = t.chunk_size(c.key.level);
    const std::uint32_t x0 = c.key.x * size, z0 = c.key.z * size;
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> net;
    for (std::size_t k = 0; k < c.mesh.indices.size(); k += 3) {
      const std::uint32_t v[3] = {c.mesh.indices[k], c.mesh.indices[k + 1], c.mesh.indices[k + 2]};
      const ChunkVertex &a = c.mesh.vertices[v[0]], &b = c.mesh.vertices[v[1]], &d = c.mesh.vertices[v[2]];
      const std::int64_t area = (static_cast<std::int64_t>(b.gz) - a.gz) * (static_cast<std::int64_t>(d.gx) - a.gx) -
                                (static_cast<std::int64_t>(b.gx) - a.gx) * (static_cast<std::int64_t>(d.gz) - a.gz);
      ASSERT_GT(area, 0) << "degenerate or down-facing triangle";
      for (int e = 0; e < 3; ++e) {
        const std::uint32_t p = v[e], q = v[(e + 1) % 3];
        if (p < q) net[{p, q}] += 1; else net[{q, p}] -= 1;
      }
    }
    for (const auto& [edge, n] : net) {
      if (n == 0) continue;
      const ChunkVertex &a = c.mesh.vertices[edge.first], &b = c.mesh.vertices[edge.second];
      const bool on_side = (a.gx == b.gx && (a.gx == x0 || a.gx == x0 + size)) ||
                           (a.gz == b.gz && (a.gz == z0 || a.gz == z0 + size));
      EXPECT_TRUE(on_side) << "T-junction inside chunk level " << c.key.level << " at (" << a.gx << "," << a.gz
                           << ")-(" << b.gx << "," << b.gz << ")";
    }
    // The edge lists hold exactly the vertices on each side.
    EXPECT_EQ(c.mesh.vertices[c.mesh.edges[kWest].front()].gz, z0);
    EXPECT_EQ(c.mesh.vertices[c.mesh.edges[kWest].back()].gz, z0 + size);
  }
}

TEST(ChunkTree, SameLevelNeighboursShareIdenticalEdgeVertices) {
  const HeightField f = fbm_field(257, 257, 1.0, 60.0f, 5);
  ChunkTreeSettings s;
  s.leaf_dimension = 17;
  s.flat_tolerance = 0.1f;
  const ChunkTree t = build_or_die(f, s);
  std::size_t pairs = 0;
  for (std::uint32_t i = 0; i < t.chunk_count(); ++i) {
    const Chunk& c = t.chunk(i);
    const Chunk* east = t.find(c.key.level, c.key.x + 1, c.key.z);
    const Chunk* north = t.find(c.key.level, c.key.x, c.key.z + 1);
    auto compare = [&](const Chunk* o, Edge mine, Edge theirs) {
      if (o == nullptr) return;
      ++pairs;
      const auto& a = c.mesh.edges[mine];
      const auto& b = o->mesh.edges[theirs];
      ASSERT_EQ(a.size(), b.size());
      for (std::size_t k = 0; k < a.size(); ++k) {
        const ChunkVertex &va = c.mesh.vertices[a[k]], &vb = o->mesh.vertices[b[k]];
        EXPECT_EQ(va.gx, vb.gx);
        EXPECT_EQ(va.gz, vb.gz);
        EXPECT_EQ(std::memcmp(&va.height, &vb.height, 4), 0);
        EXPECT_EQ(std::memcmp(&va.morph_target, &vb.morph_target, 4), 0);
        EXPECT_EQ(std::memcmp(&va.morph_error, &vb.morph_error, 4), 0);
        EXPECT_EQ(va.intro_level, vb.intro_level);
      }
    };
    compare(east, kEast, kWest);
    compare(north, kNorth, kSouth);
  }
  EXPECT_GT(pairs, 100u);
}

TEST(ChunkTree, FinerLevelsContainTheCoarserVerticesAndMorphTargetsLieOnTheParent) {
  const HeightField f = fbm_field(129, 129, 1.0, 60.0f, 9);
  ChunkTreeSettings s;
  s.leaf_dimension = 17;
  s.flat_tolerance = 0.1f;
  const ChunkTree t = build_or_die(f, s);
  for (std::uint32_t i = 1; i < t.chunk_count(); ++i) {
    const Chunk& c = t.chunk(i);
    const Chunk& p = t.chunk(t.parent_index(i));
    const std::uint32_t size = t.chunk_size(c.key.level);
    const std::uint32_t x0 = c.key.x * size, z0 = c.key.z * size;
    std::set<std::pair<std::uint32_t, std::uint32_t>> mine;
    for (const ChunkVertex& v : c.mesh.vertices) mine.insert({v.gx, v.gz});
    for (const ChunkVertex& v : p.mesh.vertices) {
      if (v.gx < x0 || v.gx > x0 + size || v.gz < z0 || v.gz > z0 + size) continue;
      EXPECT_TRUE(mine.count({v.gx, v.gz})) << "parent vertex missing in child";
    }
    for (const ChunkVertex& v : c.mesh.vertices) {
      if (v.intro_level != c.key.level) continue;
      double h = 0.0;
      ASSERT_TRUE(mesh_height_at(p.mesh, v.gx, v.gz, h));
      EXPECT_NEAR(v.morph_target, h, 1e-3) << "morph target off the parent surface";
      EXPECT_GT(v.morph_error, 0.0f);
    }
  }
}

TEST(ChunkTree, FlatAndPlanarFieldsReduceToTheMinimum) {
  for (int planar = 0; planar < 2; ++planar) {
    const HeightField f = make_field(129, 129, 1.0, [&](int i, int j) {
      return planar ? 3.0f + 0.25f * static_cast<float>(i) - 0.125f * static_cast<float>(j) : 7.0f;
    });
    ChunkTreeSettings s;
    s.leaf_dimension = 33;
    const ChunkTree t = build_or_die(f, s);
    for (std::uint32_t i = 0; i < t.chunk_count(); ++i) {
      EXPECT_EQ(t.chunk(i).triangle_count, 8u);  // split down to the four quadrants only
      EXPECT_LE(t.chunk(i).error, 1e-4f);
    }
  }
}

TEST(ChunkTree, VertexCacheOrderImprovesAcmr) {
  const HeightField f = fbm_field(129, 129, 1.0, 60.0f, 2);
  ChunkTreeSettings s;
  s.leaf_dimension = 65;
  s.flat_tolerance = 0.0f;
  const ChunkTree opt = build_or_die(f, s);
  s.optimize_vertex_cache = false;
  const ChunkTree raw = build_or_die(f, s);
  const Chunk& a = opt.chunk(opt.index(1, 0, 0));
  const Chunk& b = raw.chunk(raw.index(1, 0, 0));
  ASSERT_EQ(a.triangle_count, b.triangle_count);
  const auto sa = meshopt_analyzeVertexCache(a.mesh.indices.data(), a.mesh.indices.size(), a.vertex_count, 16, 0, 0);
  const auto sb = meshopt_analyzeVertexCache(b.mesh.indices.data(), b.mesh.indices.size(), b.vertex_count, 16, 0, 0);
  EXPECT_LT(sa.acmr, sb.acmr);
  EXPECT_LT(sa.acmr, 0.8f);
}

TEST(ChunkTree, ThreadCountAndMeshRetentionDoNotChangeTheResult) {
  const HeightField f = fbm_field(200, 150, 1.5, 60.0f, 4);
  ChunkTreeSettings s;
  s.leaf_dimension = 17;
  s.threads = 1;
  const ChunkTree one = build_or_die(f, s);
  s.threads = 2;
  const ChunkTree two = build_or_die(f, s);
  s.keep_meshes = false;
  const ChunkTree meta = build_or_die(f, s);
  ASSERT_EQ(one.chunk_count(), two.chunk_count());
  for (std::uint32_t i = 0; i < one.chunk_count(); ++i) {
    const Chunk &a = one.chunk(i), &b = two.chunk(i), &m = meta.chunk(i);
    ASSERT_EQ(a.present, b.present);
    EXPECT_EQ(a.error, b.error);
    EXPECT_EQ(a.error_bound, m.error_bound);
    EXPECT_EQ(a.triangle_count, m.triangle_count);
    ASSERT_EQ(a.mesh.vertices.size(), b.mesh.vertices.size());
    EXPECT_TRUE(same_bytes(a.mesh.vertices, b.mesh.vertices));
    EXPECT_EQ(a.mesh.indices, b.mesh.indices);
    EXPECT_TRUE(m.mesh.vertices.empty());
  }
}

TEST(ChunkTree, InvalidSettingsNameTheParameter) {
  const HeightField f = fbm_field(33, 33, 1.0, 10.0f, 1);
  ChunkTreeSettings s;
  s.leaf_dimension = 20;
  auto r = ChunkTree::build(f, s);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("leaf_dimension"), std::string::npos) << r.error().message;
  s.leaf_dimension = 1000;
  r = ChunkTree::build(f, s);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("leaf_dimension"), std::string::npos) << r.error().message;
  r = ChunkTree::build(HeightField{}, ChunkTreeSettings{});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("empty"), std::string::npos);
  s = ChunkTreeSettings{};
  s.max_build_bytes = 1e6;
  r = ChunkTree::build(make_field(1025, 1025, 1.0, [](int, int) { return 0.0f; }), s);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kLimit);
}

TEST(ChunkTree, CancelStopsTheBuild) {
  const HeightField f = fbm_field(257, 257, 1.0, 10.0f, 1);
  std::atomic<bool> cancel{true};
  BuildControl control;
  control.cancel = &cancel;
  auto r = ChunkTree::build(f, ChunkTreeSettings{}, control);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kCancelled);
  cancel = false;
  float last = 0.0f;
  control.progress = [&](float p) { EXPECT_GE(p, last); last = p; };
  r = ChunkTree::build(f, ChunkTreeSettings{}, control);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(last, 1.0f);
}

}  // namespace
}  // namespace sylva::terrain

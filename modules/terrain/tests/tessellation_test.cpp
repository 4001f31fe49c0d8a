// The seed's tessellation modes hq 0/1/2 beside RTIN (seed 002 §3.3, Tab. 3.2/3.5) and the
// brute-force criterion (Tab. 3.1 "unoptimised"): triangle and vertex counts per chunk, up-facing
// triangles, hq1's diagonal rule, the measured error and the morph targets against a brute-force
// evaluation of the meshes, watertight frames with seams, and brute force drawing every leaf.
#include <sylva/terrain/chunk_file.hpp>
#include <sylva/terrain/chunk_tree.hpp>
#include <sylva/terrain/frame_mesh.hpp>
#include <sylva/terrain/selection.hpp>

#include "support/terrain_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace sylva::terrain {
namespace {

using testing::fbm_field;

constexpr Tessellation kGrids[] = {Tessellation::kHq0, Tessellation::kHq1, Tessellation::kHq2};

ChunkTree build_or_die(const HeightField& f, Tessellation t, int leaf_dimension = 17) {
  ChunkTreeSettings s;
  s.leaf_dimension = leaf_dimension;
  s.tessellation = t;
  auto r = ChunkTree::build(f, s);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().describe());
  return std::move(r).value();
}

glm::dvec2 xz(const ChunkVertex& v) { return glm::dvec2(v.gx, v.gz) + 0.5 * static_cast<double>(v.centre); }

// Height of a chunk mesh at (x, z) by scanning its triangles; false when no triangle holds it.
bool mesh_height_at(const ChunkMesh& m, glm::dvec2 p, double& out) {
  for (std::size_t i = 0; i < m.indices.size(); i += 3) {
    const ChunkVertex& a = m.vertices[m.indices[i]];
    const ChunkVertex& b = m.vertices[m.indices[i + 1]];
    const ChunkVertex& c = m.vertices[m.indices[i + 2]];
    const glm::dvec2 pa = xz(a), pb = xz(b), pc = xz(c);
    const double det = (pb.y - pa.y) * (pc.x - pa.x) - (pb.x - pa.x) * (pc.y - pa.y);
    const double w0 = ((pb.y - p.y) * (pc.x - p.x) - (pb.x - p.x) * (pc.y - p.y)) / det;
    const double w1 = ((p.y - pa.y) * (pc.x - pa.x) - (p.x - pa.x) * (pc.y - pa.y)) / det;
    const double w2 = 1.0 - w0 - w1;
    if (w0 < -1e-12 || w1 < -1e-12 || w2 < -1e-12) continue;
    out = w0 * a.height + w1 * b.height + w2 * c.height;
    return true;
  }
  return false;
}

TEST(Tessellation, CountsPerChunkFollowTheSeedsMethods) {
  // A tilted plane with one hill: RTIN keeps the hill's vertices only, the grids keep all.
  const HeightField f = testing::make_field(129, 129, 1.0, [](int x, int z) {
    const double r2 = (x - 40.0) * (x - 40.0) + (z - 70.0) * (z - 70.0);
    return static_cast<float>(0.25 * x + 20.0 * std::exp(-r2 / 200.0));
  });
  const ChunkTree rtin = build_or_die(f, Tessellation::kRtin);
  std::uint64_t totals[4] = {rtin.report().triangles(), 0, 0, 0};
  for (Tessellation t : kGrids) {
    const ChunkTree tree = build_or_die(f, t);
    const std::uint32_t n = tree.leaf_intervals();
    const bool four = t == Tessellation::kHq2;
    for (std::uint32_t i = 0; i < tree.chunk_count(); ++i) {
      const Chunk& c = tree.chunk(i);
      ASSERT_TRUE(c.present);
      // Methods A/B: 2 triangles per square; C: 4 around a centre vertex.
      EXPECT_EQ(c.triangle_count, (four ? 4u : 2u) * n * n) << "chunk " << i;
      EXPECT_EQ(c.vertex_count, (n + 1) * (n + 1) + (four ? n * n : 0u)) << "chunk " << i;
      for (std::size_t k = 0; k < c.mesh.indices.size(); k += 3) {
        const glm::dvec2 a = xz(c.mesh.vertices[c.mesh.indices[k]]), b = xz(c.mesh.vertices[c.mesh.indices[k + 1]]),
                         d = xz(c.mesh.vertices[c.mesh.indices[k + 2]]);
        ASSERT_GT((b.y - a.y) * (d.x - a.x) - (b.x - a.x) * (d.y - a.y), 0.0) << "up-facing, chunk " << i;
      }
    }
    totals[static_cast<int>(t)] = tree.report().triangles();
    for (const LevelReport& l : tree.report().levels) EXPECT_EQ(l.triangles, l.grid_triangles) << "the full grid";
  }
  EXPECT_EQ(totals[1], totals[2]);
  EXPECT_EQ(totals[3], 2 * totals[1]);
  EXPECT_LT(totals[0], totals[1]) << "RTIN drops flat vertices above the leaves";
}

TEST(Tessellation, Hq1SplitsAlongTheDiagonalWhoseEndsDifferLess) {
  const HeightField f = fbm_field(65, 65, 1.0, 40.0f, 5);
  const ChunkTree tree = build_or_die(f, Tessellation::kHq1);
  int main = 0, anti = 0;
  for (std::uint32_t i = 0; i < tree.chunk_count(); ++i) {
    const ChunkMesh& m = tree.chunk(i).mesh;
    const double s = tree.step(tree.chunk(i).key.level);
    for (std::size_t k = 0; k < m.indices.size(); k += 3) {
      for (int e = 0; e < 3; ++e) {
        const ChunkVertex& a = m.vertices[m.indices[k + e]];
        const ChunkVertex& b = m.vertices[m.indices[k + (e + 1) % 3]];
        if (a.gx == b.gx || a.gz == b.gz) continue;  // the diagonal has both coordinates different
        const std::uint32_t x0 = std::min(a.gx, b.gx), z0 = std::min(a.gz, b.gz);
        const auto h = [&](double x, double z) { return static_cast<double>(f.sample(static_cast<int>(x), static_cast<int>(z))); };
        const double d_main = std::fabs(h(x0, z0) - h(x0 + s, z0 + s));
        const double d_anti = std::fabs(h(x0 + s, z0) - h(x0, z0 + s));
        const bool is_main = (a.gx < b.gx) == (a.gz < b.gz);
        EXPECT_EQ(is_main, d_main <= d_anti) << "square (" << x0 << ", " << z0 << ") step " << s;
        (is_main ? main : anti) += 1;
      }
    }
  }
  EXPECT_GT(main, 0);
  EXPECT_GT(anti, 0) << "an fBm field needs both diagonals";
}

TEST(Tessellation, MeasuredErrorsAndMorphTargetsAreThoseOfTheMeshes) {
  const HeightField f = fbm_field(65, 49, 1.0, 40.0f, 7);  // non-square: padding too
  for (Tessellation t : kGrids) {
    const ChunkTree tree = build_or_die(f, t, 9);
    ASSERT_EQ(tree.levels(), 4);
    for (std::uint32_t i = 0; i < tree.chunk_count(); ++i) {
      const Chunk& c = tree.chunk(i);
      if (!c.present) continue;
      const std::uint32_t size = tree.chunk_size(c.key.level);
      double worst = 0.0;
      for (std::uint32_t z = c.key.z * size; z <= (c.key.z + 1) * size && z < 49; ++z) {
        for (std::uint32_t x = c.key.x * size; x <= (c.key.x + 1) * size && x < 65; ++x) {
          double h = 0.0;
          ASSERT_TRUE(mesh_height_at(c.mesh, glm::dvec2(x, z), h));
          worst = std::max(worst, std::fabs(h - f.sample(static_cast<int>(x), static_cast<int>(z))));
        }
      }
      EXPECT_NEAR(c.error, worst, 1e-4) << "tessellation " << static_cast<int>(t) << " chunk " << i;
      EXPECT_GE(c.error, worst - 1e-5);
      if (c.key.level + 1 == tree.levels()) {
        EXPECT_EQ(c.error, 0.0f) << "leaves pass through every sample";
      }
      if (c.key.level == 0) continue;
      // Morph target: the coarser level's mesh at the vertex.
      const ChunkMesh& parent = tree.chunk(tree.parent_index(i)).mesh;
      for (const ChunkVertex& v : c.mesh.vertices) {
        if (v.intro_level != c.key.level) continue;  // introduced by this level
        double g = 0.0;
        ASSERT_TRUE(mesh_height_at(parent, xz(v), g));
        EXPECT_NEAR(v.morph_target, g, 1e-3) << "tessellation " << static_cast<int>(t) << " chunk " << i;
      }
    }
  }
}

TEST(Tessellation, FramesWithSeamsAreWatertight) {
  const HeightField f = fbm_field(129, 129, 1.0, 60.0f, 11);
  for (Tessellation t : kGrids) {
    const ChunkTree tree = build_or_die(f, t, 9);
    LodSelector selector(tree);
    SeamCache seams;
    std::mt19937 rng(17);
    int seamed = 0;
    for (int pose = 0; pose < 24; ++pose) {
      const LodView view = testing::random_view(rng, tree, f, {});
      LodSettings ls;
      ls.max_pixel_error = pose % 2 ? 1.0f : 4.0f;
      const Selection& sel = selector.select(view, ls);
      const FrameMesh mesh = assemble_frame(tree, sel, make_vertex_frame(tree, view, ls), CrackFix::kSeams, seams);
      seamed += sel.stats.max_level_difference > 0;
      const auto r = testing::check_watertight(tree, selector, make_vertex_frame(tree, view, ls), mesh);
      ASSERT_EQ(r.crack_edges, 0u) << "tessellation " << static_cast<int>(t) << " pose " << pose << "\n" << r.report;
    }
    EXPECT_GT(seamed, 0) << "some frames must mix levels";
  }
}

TEST(Tessellation, ChunkFilesRefuseTheSeedsGrids) {
  const HeightField f = fbm_field(33, 33, 1.0, 10.0f, 2);
  const std::filesystem::path path = testing::unique_temp("hq.sylvaterrain");
  const Status saved = save_chunk_file(path, build_or_die(f, Tessellation::kHq1));
  ASSERT_FALSE(saved.ok());
  EXPECT_NE(saved.error().message.find("tessellation"), std::string::npos) << saved.error().message;
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(BruteForce, DrawsEveryLeafAtFullResolution) {
  const HeightField f = fbm_field(129, 129, 1.0, 40.0f, 13);
  const LodView view = testing::look_at_view({-50.0, 80.0, -50.0}, {64.0, 0.0, 64.0}, 60.0);
  for (Tessellation t : {Tessellation::kRtin, Tessellation::kHq0, Tessellation::kHq2}) {
    const ChunkTree tree = build_or_die(f, t);
    LodSelector selector(tree);
    LodSettings ls;
    ls.criterion = LodCriterion::kBruteForce;
    ls.frustum_cull = false;
    const Selection& sel = selector.select(view, ls);
    const int leaf = tree.levels() - 1;
    EXPECT_EQ(sel.stats.chunks, 64u);
    EXPECT_EQ(sel.stats.chunks_per_level[static_cast<std::size_t>(leaf)], 64u);
    EXPECT_EQ(sel.stats.triangles, tree.report().levels[static_cast<std::size_t>(leaf)].triangles);
    EXPECT_FALSE(sel.morph);
    EXPECT_TRUE(sel.bound_certified);
    if (t == Tessellation::kHq0) {
      EXPECT_EQ(sel.stats.triangles, 2u * 128u * 128u) << "the full-resolution grid";
    }
    // The default criterion draws far fewer from the same camera.
    LodSettings lod;
    EXPECT_LT(selector.select(view, lod).stats.triangles, sel.stats.triangles / 2);
  }
}

}  // namespace
}  // namespace sylva::terrain

// The exhaustive CPU edge test: over many random camera poses, tau values, with and without
// culling and morphing, every edge between two drawn chunks is used by both sides with
// bit-identical end points (the drawn surface has no boundary inside the drawn region).
#include <sylva/terrain/frame_mesh.hpp>

#include "support/terrain_test_support.hpp"

#include <gtest/gtest.h>

#include <random>

namespace sylva::terrain {
namespace {

using testing::check_watertight;
using testing::cliff_field;
using testing::fbm_field;
using testing::PoseOptions;
using testing::random_view;

struct Case {
  const char* name;
  HeightField field;
  int leaf_dimension;
  float flat_tolerance;
};

void run_edge_test(const Case& c, int poses, std::uint32_t seed, std::size_t& coarse_seams) {
  ChunkTreeSettings s;
  s.leaf_dimension = c.leaf_dimension;
  s.flat_tolerance = c.flat_tolerance;
  auto built = ChunkTree::build(c.field, s);
  ASSERT_TRUE(built.ok()) << built.error().describe();
  const ChunkTree& tree = built.value();
  LodSelector selector(tree);
  SeamCache seams;
  std::mt19937 rng(seed);
  const float taus[] = {0.25f, 0.5f, 1.0f, 2.0f, 4.0f, 16.0f};
  int nonempty_frames = 0;
  for (int pose = 0; pose < poses; ++pose) {
    PoseOptions po;
    po.min_fov_deg = 10.0;
    po.max_fov_deg = 120.0;
    const LodView view = random_view(rng, tree, c.field, po);
    LodSettings ls;
    ls.max_pixel_error = taus[pose % 6];
    ls.frustum_cull = (pose % 3) != 0;
    ls.morph_fraction = (pose % 4 == 0) ? 0.0f : 0.25f + 0.5f * static_cast<float>(pose % 2);
    const Selection& sel = selector.select(view, ls);
    const VertexFrame frame = make_vertex_frame(tree, view, ls);
    const FrameMesh mesh = assemble_frame(tree, sel, frame, CrackFix::kSeams, seams);
    for (const SelectedChunk& sc : sel.chunks)
      for (std::uint32_t n : sc.coarser_neighbour) coarse_seams += n != kNoChunk;
    const auto r = check_watertight(tree, selector, frame, mesh);
    ASSERT_EQ(r.crack_edges, 0u) << c.name << " pose " << pose << " tau " << ls.max_pixel_error << "\n" << r.report;
    nonempty_frames += r.edges > 0;
  }
  EXPECT_GT(nonempty_frames, poses / 2) << "most poses must see terrain";
}

TEST(Seams, EveryEdgeBetweenDrawnChunksIsSharedBitIdenticallyOnFbm) {
  std::size_t seams = 0;
  run_edge_test({"fbm", fbm_field(257, 257, 2.0, 150.0f, 31), 17, 0.05f}, 120, 7, seams);
  EXPECT_GT(seams, 200u) << "the poses must produce LOD differences";
}

TEST(Seams, EveryEdgeBetweenDrawnChunksIsSharedBitIdenticallyOnCliffs) {
  std::size_t seams = 0;
  run_edge_test({"cliff", cliff_field(257, 257, 1.0, 60.0f, 32), 9, 0.02f}, 120, 8, seams);
  EXPECT_GT(seams, 200u);
}

TEST(Seams, NonSquarePaddedFieldWithLargeLodDifferences) {
  std::size_t seams = 0;
  // 5-vertex chunks and 7 levels: LOD differences beyond log2(dimension - 1) occur, where the
  // seed's inset strip would need interpolated vertices.
  run_edge_test({"padded", fbm_field(300, 170, 1.0, 80.0f, 33), 5, 0.0f}, 80, 9, seams);
  EXPECT_GT(seams, 100u);
}

TEST(Seams, WithoutSeamsTheSameTestFindsCracks) {
  const HeightField field = fbm_field(129, 129, 2.0, 150.0f, 34);
  ChunkTreeSettings s;
  s.leaf_dimension = 9;
  const ChunkTree tree = std::move(ChunkTree::build(field, s)).value();
  LodSelector selector(tree);
  SeamCache seams;
  std::mt19937 rng(10);
  std::size_t cracks = 0;
  for (int pose = 0; pose < 20; ++pose) {
    const LodView view = random_view(rng, tree, field, PoseOptions{});
    LodSettings ls;
    ls.frustum_cull = false;
    const Selection& sel = selector.select(view, ls);
    const VertexFrame frame = make_vertex_frame(tree, view, ls);
    cracks += check_watertight(tree, selector, frame, assemble_frame(tree, sel, frame, CrackFix::kNone, seams)).crack_edges;
  }
  EXPECT_GT(cracks, 0u) << "the check must be able to fail";
}

TEST(Seams, CacheReusesSeamsUntilTheNeighbourChanges) {
  const HeightField field = fbm_field(129, 129, 2.0, 150.0f, 35);
  ChunkTreeSettings s;
  s.leaf_dimension = 9;
  const ChunkTree tree = std::move(ChunkTree::build(field, s)).value();
  LodSelector selector(tree);
  SeamCache cache;
  const LodView view = testing::look_at_view({10, 200, 10}, {200, 0, 200}, 60.0);
  LodSettings ls;
  const Selection& sel = selector.select(view, ls);
  const VertexFrame frame = make_vertex_frame(tree, view, ls);
  (void)assemble_frame(tree, sel, frame, CrackFix::kSeams, cache);
  const auto builds = cache.builds();
  EXPECT_GT(builds, 0u);
  (void)assemble_frame(tree, sel, frame, CrackFix::kSeams, cache);
  EXPECT_EQ(cache.builds(), builds);
  EXPECT_GE(cache.hits(), builds);
  // The same seam built directly matches the cached one.
  for (const SelectedChunk& c : sel.chunks) {
    for (int e = 0; e < 4; ++e) {
      if (c.coarser_neighbour[static_cast<std::size_t>(e)] == kNoChunk) continue;
      const Seam direct = build_seam(tree, c.index, static_cast<Edge>(e), c.coarser_neighbour[static_cast<std::size_t>(e)]);
      EXPECT_EQ(direct.indices, cache.get(tree, c.index, static_cast<Edge>(e), c.coarser_neighbour[static_cast<std::size_t>(e)]).indices);
    }
  }
}

}  // namespace
}  // namespace sylva::terrain

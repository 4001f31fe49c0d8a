// LOD selection: tiling, the screen-space error rule and its minimality, frustum culling, the
// seed's distance criterion, neighbour detection and timing.
#include <sylva/core/timer.hpp>
#include <sylva/terrain/selection.hpp>

#include "support/terrain_test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace sylva::terrain {
namespace {

using testing::fbm_field;
using testing::PoseOptions;
using testing::random_view;

struct Fixture {
  HeightField field = fbm_field(257, 257, 2.0, 120.0f, 21);
  ChunkTree tree = [&] {
    ChunkTreeSettings s;
    s.leaf_dimension = 17;
    return std::move(ChunkTree::build(field, s)).value();
  }();
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

TEST(Selection, WithoutCullingTheDrawnChunksTileTheFieldExactlyOnce) {
  Fixture& fx = fixture();
  LodSelector sel(fx.tree);
  std::mt19937 rng(1);
  LodSettings ls;
  ls.frustum_cull = false;
  for (int pose = 0; pose < 40; ++pose) {
    const LodView v = random_view(rng, fx.tree, fx.field, PoseOptions{});
    const Selection& s = sel.select(v, ls);
    const std::uint32_t n = fx.tree.root_intervals();
    std::vector<int> cover(static_cast<std::size_t>(n) * n, 0);
    for (const SelectedChunk& c : s.chunks) {
      const ChunkKey& k = fx.tree.chunk(c.index).key;
      const std::uint32_t size = fx.tree.chunk_size(k.level);
      for (std::uint32_t z = k.z * size; z < (k.z + 1) * size; ++z)
        for (std::uint32_t x = k.x * size; x < (k.x + 1) * size; ++x) ++cover[z * n + x];
    }
    for (int c : cover) ASSERT_EQ(c, 1);
    EXPECT_EQ(s.stats.culled, 0u);
  }
}

TEST(Selection, DrawnChunksMeetTauAndTheirParentsDoNot) {
  Fixture& fx = fixture();
  LodSelector sel(fx.tree);
  std::mt19937 rng(2);
  for (float tau : {0.5f, 1.0f, 2.0f, 4.0f}) {
    LodSettings ls;
    ls.max_pixel_error = tau;
    for (int pose = 0; pose < 20; ++pose) {
      const LodView v = random_view(rng, fx.tree, fx.field, PoseOptions{});
      const Stopwatch wall;
      const Selection& s = sel.select(v, ls);
      const double wall_ms = wall.elapsed_ms();
      for (const SelectedChunk& c : s.chunks) {
        const Chunk& ch = fx.tree.chunk(c.index);
        glm::dvec3 lo, hi;
        fx.tree.chunk_bounds(c.index, lo, hi);
        const double d = v.distance_to_box(lo, hi) - ch.error_bound;
        if (ch.key.level + 1 < fx.tree.levels()) {
          EXPECT_GT(d, 0.0);
          EXPECT_LE(v.k * ch.error_bound, tau * d * (1 + 1e-12));
        }
        if (ch.key.level > 0) {
          const std::uint32_t p = fx.tree.parent_index(c.index);
          fx.tree.chunk_bounds(p, lo, hi);
          const double pe = fx.tree.chunk(p).error_bound;
          const double pd = v.distance_to_box(lo, hi) - pe;
          EXPECT_TRUE(pd <= 0.0 || v.k * pe > tau * pd) << "parent was good enough";
        }
      }
      // This selection's time, not a sum over frames: within the wall time around the call.
      EXPECT_GE(s.stats.cpu_ms, 0.0);
      EXPECT_LE(s.stats.cpu_ms, wall_ms);
      EXPECT_EQ(s.stats.chunks, s.chunks.size());
    }
  }
}

TEST(Selection, FrustumCullingKeepsEveryVisibleSampleCovered) {
  Fixture& fx = fixture();
  LodSelector sel(fx.tree);
  std::mt19937 rng(3);
  LodSettings ls;
  std::size_t culled_total = 0;
  for (int pose = 0; pose < 30; ++pose) {
    const LodView v = random_view(rng, fx.tree, fx.field, PoseOptions{});
    const Selection& s = sel.select(v, ls);
    culled_total += s.stats.culled;
    for (int j = 0; j < fx.field.rows() - 1; j += 3) {
      for (int i = 0; i < fx.field.columns() - 1; i += 3) {
        const glm::dvec3 p(fx.field.origin().x + i * fx.field.spacing(), fx.field.sample(i, j),
                           fx.field.origin().y + j * fx.field.spacing());
        bool inside = true;
        for (const glm::dvec4& pl : v.planes) inside = inside && glm::dot(glm::dvec3(pl), p) + pl.w >= 0.0;
        if (inside) {
          ASSERT_NE(sel.drawn_chunk_at_cell(i, j), kNoChunk) << "visible sample not drawn";
        }
      }
    }
    for (const SelectedChunk& c : s.chunks) {
      glm::dvec3 lo, hi;
      fx.tree.chunk_bounds(c.index, lo, hi);
      EXPECT_TRUE(v.box_visible(lo, hi));
    }
  }
  EXPECT_GT(culled_total, 0u);
}

TEST(Selection, SeedDistanceCriterionFollowsTheSeedFormula) {
  Fixture& fx = fixture();
  LodSelector sel(fx.tree);
  std::mt19937 rng(4);
  LodSettings ls;
  ls.criterion = LodCriterion::kSeedDistance;
  ls.lod_distance = 40.0f;
  for (int pose = 0; pose < 20; ++pose) {
    const LodView v = random_view(rng, fx.tree, fx.field, PoseOptions{});
    const Selection& s = sel.select(v, ls);
    EXPECT_FALSE(s.morph);
    EXPECT_FALSE(s.bound_certified);
    for (const SelectedChunk& c : s.chunks) {
      const Chunk& ch = fx.tree.chunk(c.index);
      glm::dvec3 lo, hi;
      fx.tree.chunk_bounds(c.index, lo, hi);
      const double spacing = fx.tree.step(ch.key.level) * fx.tree.spacing();
      const double d = glm::length(v.position - 0.5 * (lo + hi));
      if (ch.key.level + 1 < fx.tree.levels()) {
        EXPECT_LE(spacing * ls.lod_distance / d, 1.0 + 1e-12);
      }
    }
  }
}

TEST(Selection, CoarserNeighboursMatchABruteForceSearch) {
  Fixture& fx = fixture();
  LodSelector sel(fx.tree);
  std::mt19937 rng(5);
  LodSettings ls;
  ls.frustum_cull = false;
  ls.max_pixel_error = 0.5f;
  int coarse_edges = 0;
  for (int pose = 0; pose < 20; ++pose) {
    const LodView v = random_view(rng, fx.tree, fx.field, PoseOptions{});
    const Selection& s = sel.select(v, ls);
    int largest_difference = 0;  // brute force twin of s.stats.max_level_difference
    for (const SelectedChunk& c : s.chunks) {
      const ChunkKey& k = fx.tree.chunk(c.index).key;
      const std::int64_t size = fx.tree.chunk_size(k.level);
      for (int e = 0; e < 4; ++e) {
        // Every cell along the edge: the drawn chunk across must be one coarser chunk, or
        // chunks no coarser than this one.
        std::uint32_t coarser = kNoChunk;
        for (std::int64_t t = 0; t < size; ++t) {
          std::int64_t cx = 0, cz = 0;
          if (e == kWest) { cx = k.x * size - 1; cz = k.z * size + t; }
          if (e == kEast) { cx = (k.x + 1) * size; cz = k.z * size + t; }
          if (e == kSouth) { cx = k.x * size + t; cz = k.z * size - 1; }
          if (e == kNorth) { cx = k.x * size + t; cz = (k.z + 1) * size; }
          const std::uint32_t o = sel.drawn_chunk_at_cell(cx, cz);
          if (o != kNoChunk && fx.tree.chunk(o).key.level < k.level) {
            if (coarser != kNoChunk) {
              EXPECT_EQ(coarser, o);
            }
            coarser = o;
          }
        }
        EXPECT_EQ(c.coarser_neighbour[static_cast<std::size_t>(e)], coarser);
        coarse_edges += coarser != kNoChunk;
        if (coarser != kNoChunk) {
          largest_difference = std::max(largest_difference, k.level - fx.tree.chunk(coarser).key.level);
        }
      }
    }
    EXPECT_EQ(s.stats.max_level_difference, largest_difference) << "pose " << pose;
  }
  EXPECT_GT(coarse_edges, 10);
}


// Front to back (issue 18): a software rasteriser's early depth test only saves shading when the
// near ground is drawn first. Of any two drawn chunks, the one listed first lies in the child of
// their lowest common ancestor whose box centre is nearer the eye (horizontally).
TEST(Selection, ChunksComeOutNearestFirst) {
  Fixture& fx = fixture();
  LodSettings unculled;
  unculled.frustum_cull = false;  // every chunk of the field is ordered, seen or not
  LodSelector sel(fx.tree);
  std::mt19937 rng(7);
  auto ancestor = [&](const ChunkKey& k, int level) {
    const int up = k.level - level;
    const std::uint32_t x = k.x >> up, z = k.z >> up;
    return fx.tree.nodes()[fx.tree.level_offset(level) + z * (1u << level) + x];
  };
  int compared = 0;
  for (int pose = 0; pose < 30; ++pose) {
    const LodView v = random_view(rng, fx.tree, fx.field, PoseOptions{});
    const Selection& s = sel.select(v, unculled);
    auto distance2 = [&](const ChunkNode& n) {
      const double dx = 0.5 * (n.lo.x + n.hi.x) - v.position.x, dz = 0.5 * (n.lo.z + n.hi.z) - v.position.z;
      return dx * dx + dz * dz;
    };
    for (std::size_t i = 0; i < s.chunks.size(); ++i)
      for (std::size_t j = i + 1; j < s.chunks.size(); ++j) {
        const ChunkKey& a = fx.tree.chunk(s.chunks[i].index).key;
        const ChunkKey& b = fx.tree.chunk(s.chunks[j].index).key;
        int lca = std::min(a.level, b.level);
        while (lca > 0 && (a.x >> (a.level - lca) != b.x >> (b.level - lca) || a.z >> (a.level - lca) != b.z >> (b.level - lca))) --lca;
        // lca + 1 exists on both sides: two drawn chunks never contain one another.
        ASSERT_LE(distance2(ancestor(a, lca + 1)), distance2(ancestor(b, lca + 1)))
            << "pose " << pose << ": chunk " << i << " drawn before the nearer chunk " << j;
        ++compared;
      }
  }
  EXPECT_GT(compared, 1000);
}
}  // namespace
}  // namespace sylva::terrain

// Morphing (CDLOD-style): a LOD switch does not pop. Along a flight path, the surface drawn with
// the new selection is compared with the surface the old selection would draw from the same
// camera; the difference at every field sample, projected to pixels, is the pop.
#include <sylva/terrain/frame_mesh.hpp>

#include "support/terrain_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace sylva::terrain {
namespace {

using namespace testing;

struct PopStats {
  double max_px = 0.0;  // largest pop at a switch, in pixels
  int switches = 0;     // frames whose selection changed
};

PopStats fly(const ChunkTree& tree, const HeightField& field, float morph_fraction) {
  LodSelector a(tree), b(tree);
  SeamCache seams;
  LodSettings ls;
  ls.max_pixel_error = 1.0f;
  ls.morph_fraction = morph_fraction;
  ls.frustum_cull = false;
  PopStats st;
  const glm::dvec2 ext = field.extent();
  std::vector<std::uint32_t> previous;
  LodSelector* prev = &a;
  LodSelector* cur = &b;
  const int steps = 90;
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    // Climb away from the terrain while flying across it: chunks coarsen all the time.
    const glm::dvec3 eye(ext.x * (0.1 + 0.8 * t), 20.0 + 300.0 * t * t, ext.y * 0.3);
    const LodView view = look_at_view(eye, eye + glm::dvec3(1.0, -0.6, 0.8), 70.0);
    const Selection& now = cur->select(view, ls);
    std::vector<std::uint32_t> ids;
    for (const SelectedChunk& c : now.chunks) ids.push_back(c.index);
    std::sort(ids.begin(), ids.end());
    if (i > 0 && ids != previous) {
      ++st.switches;
      // The previous selection, re-evaluated from the new camera (its neighbour info is still
      // the previous frame's), against the new selection.
      const VertexFrame frame = make_vertex_frame(tree, view, ls);
      const std::vector<float> h_new = drawn_heights(field, frame, assemble_frame(tree, now, frame, CrackFix::kSeams, seams));
      // Rebuild the previous frame's chunk set for the new camera.
      Selection old_sel;
      for (std::uint32_t id : previous) {
        SelectedChunk s;
        s.index = id;
        old_sel.chunks.push_back(s);
      }
      const std::vector<float> h_old = drawn_heights(field, frame, assemble_frame(tree, old_sel, frame, CrackFix::kNone, seams));
      for (int z = 0; z < field.rows(); ++z) {
        for (int x = 0; x < field.columns(); ++x) {
          const std::size_t k = static_cast<std::size_t>(z) * field.columns() + x;
          if (std::isnan(h_new[k]) || std::isnan(h_old[k])) continue;
          const glm::dvec3 p(field.origin().x + x * field.spacing(), h_new[k], field.origin().y + z * field.spacing());
          const double px = view.k * std::fabs(static_cast<double>(h_new[k]) - h_old[k]) / glm::length(p - eye);
          st.max_px = std::max(st.max_px, px);
        }
      }
    }
    previous = ids;
    std::swap(prev, cur);
  }
  return st;
}

TEST(Morph, LodSwitchesDoNotPop) {
  const HeightField field = fbm_field(193, 193, 2.0, 150.0f, 51);
  ChunkTreeSettings s;
  s.leaf_dimension = 17;
  const ChunkTree tree = std::move(ChunkTree::build(field, s)).value();
  const PopStats morph = fly(tree, field, 0.25f);
  const PopStats none = fly(tree, field, 0.0f);
  ASSERT_GT(morph.switches, 10);
  ASSERT_GT(none.switches, 10);
  // Without morphing a switch moves the surface by up to tau pixels. With it the children have
  // reached the parent surface by the switch; only vertices of the coarser level that were still
  // morphing themselves could move, which the default error growth of 2 per level prevents.
  EXPECT_GT(none.max_px, 0.3) << "the pop measurement must be able to see pops";
  EXPECT_LT(morph.max_px, 0.01);
  RecordProperty("pop_px_morph", std::to_string(morph.max_px));
  RecordProperty("pop_px_none", std::to_string(none.max_px));
  std::printf("max pop: morph %.4f px, no morph %.4f px (%d / %d switches)\n", morph.max_px, none.max_px,
              morph.switches, none.switches);
}

TEST(Morph, WeightIsContinuousAndReachesOneAtTheParentDistance) {
  ChunkVertex v;
  v.gx = 100;
  v.gz = 0;
  v.height = 10.0f;
  v.morph_target = 12.0f;
  v.morph_error = 3.0f;
  v.intro_level = 2;
  VertexFrame f;
  f.spacing = 1.0f;
  f.k_over_tau = 100.0f;  // m1 = 300 m
  f.morph_start = 0.75f;  // m0 = 225 m
  f.morph = true;
  float last = 0.0f;
  for (double cx = 100.0; cx >= -400.0; cx -= 0.5) {
    f.camera = glm::vec3(static_cast<float>(cx), 10.0f, 0.0f);
    const float mu = morph_weight(f, v);
    EXPECT_GE(mu, last);
    EXPECT_LE(mu - last, 0.5f / 75.0f + 1e-5f);  // Lipschitz: 1 / (f * m1) per metre
    last = mu;
  }
  EXPECT_EQ(last, 1.0f);
  f.camera = glm::vec3(100.0f + 302.0f + 0.0f, 10.0f, 0.0f);  // d - |G - h| = 300 = m1
  EXPECT_EQ(morph_weight(f, v), 1.0f);
  EXPECT_EQ(vertex_position(f, v).y + f.camera.y, 12.0f);
  f.morph = false;
  EXPECT_EQ(morph_weight(f, v), 0.0f);
}

}  // namespace
}  // namespace sylva::terrain

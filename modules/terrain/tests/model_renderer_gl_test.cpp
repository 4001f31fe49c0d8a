// The general-model renderer (seed 002 §4) on headless EGL/llvmpipe: it draws the model tree
// with stats and tracked GPU bytes; the render crack test over >= 100 poses of a mesh with an
// overhang at mixed segment levels (clear to magenta: zero background pixels where every sheet
// with the model's outline must be hit); the selection's projected error stays <= tau.
#include <sylva/render/gpu_memory.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/terrain/model_renderer.hpp>
#include <sylva/terrain/subdivision.hpp>

#include "support/gl_support.hpp"
#include "support/terrain_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>

namespace sylva::terrain {
namespace {

using namespace testing;
using ModelGl = render::GlTest;

constexpr int kWidth = 256, kHeight = 144;
constexpr double kSize = 200.0;  // the cage's side [m]

// A 200 m square sheet whose central peak leans over (overhang_cage: x += 0.8 y^2 / size), about
// 8k triangles, in a 5-level tree reduced with `reducer`; and the same mesh as one leaf (the
// full-resolution reference).
struct Model {
  TriangleMesh mesh;
  std::shared_ptr<const ModelTree> tree, full;
  float min_y = 0.0f, max_y = 0.0f;
};
Model make_model(Reducer reducer) {
  Model r;
  SubdivisionSettings s;
  s.level = 3;
  r.mesh = triangulate(subdivide(overhang_cage(8, kSize, 0.8f), s).value());
  ModelTreeSettings ms;
  ms.levels = 5;
  ms.reducer = reducer;
  r.tree = std::make_shared<const ModelTree>(std::move(ModelTree::build(r.mesh, ms)).value());
  ms.levels = 1;
  r.full = std::make_shared<const ModelTree>(std::move(ModelTree::build(r.mesh, ms)).value());
  r.min_y = r.max_y = r.mesh.positions[0].y;
  for (const glm::vec3& p : r.mesh.positions) r.min_y = std::min(r.min_y, p.y), r.max_y = std::max(r.max_y, p.y);
  return r;
}
const Model& model(Reducer reducer = Reducer::kQem) {
  static const Model qem = make_model(Reducer::kQem);
  static const Model seed = make_model(Reducer::kShortestEdge);
  return reducer == Reducer::kQem ? qem : seed;
}

render::Camera camera_looking(const glm::dvec3& eye, const glm::dvec3& target) {
  render::Camera c;
  c.set_position(eye);
  c.look_at(target);
  c.perspective().fov_y = glm::radians(60.0f);
  c.perspective().near_plane = 0.5f;
  c.perspective().far_plane = 0.0f;
  c.set_aspect(kWidth, kHeight);
  return c;
}

std::unique_ptr<ModelRenderer> flat_renderer(std::shared_ptr<const ModelTree> tree, float tau) {
  ModelRenderSettings s;
  s.debug_view = ModelDebugView::kFlat;
  s.flat_color = glm::vec3(0.0f, 1.0f, 0.0f);
  s.lod.max_pixel_error = tau;
  s.receive_shadows = false;
  return std::move(ModelRenderer::create(std::move(tree), s)).value();
}

// Pixels whose ray (through the pixel centre) must hit ANY sheet bounded by the model's outline:
// the camera is above the highest vertex and inside the model's ground square, and the ray
// reaches the plane below the lowest vertex inside the square (shrunk by `margin`). Such a ray
// runs from above the sheet to below it without leaving the square's prism, so it crosses every
// level combination (their outline is the original one, seed §4.2) however the sheet overhangs.
std::vector<std::uint8_t> must_hit_mask(const render::Camera& camera, double bottom_y, glm::dvec2 lo, glm::dvec2 hi) {
  const glm::mat4 inv = glm::inverse(camera.view_projection());
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(kWidth) * kHeight, 0);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      // read_color rows run top-down; the full-resolution render covering every must-hit pixel
      // checks the mapping.
      const glm::vec4 ndc(2.0f * (static_cast<float>(x) + 0.5f) / kWidth - 1.0f,
                          1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / kHeight, 0.5f, 1.0f);
      glm::vec4 p = inv * ndc;
      const glm::dvec3 dir = glm::normalize(glm::dvec3(p) / static_cast<double>(p.w));
      if (dir.y >= -1e-6) continue;
      const double t = (bottom_y - camera.position().y) / dir.y;
      const glm::dvec3 q = camera.position() + t * dir;
      if (q.x > lo.x && q.x < hi.x && q.z > lo.y && q.z < hi.y) mask[static_cast<std::size_t>(y) * kWidth + x] = 1;
    }
  }
  return mask;
}

TEST_F(ModelGl, DrawsTheTreeWithStatsAndTrackedGpuBytes) {
  const Model& m = model();
  ModelRenderSettings s;
  s.receive_shadows = false;
  auto renderer = [&] {
    render::GpuMemoryOwner owner("model_renderer_test");
    return ModelRenderer::create(m.tree, s);
  }();
  ASSERT_TRUE(renderer.ok()) << renderer.error().describe();
  std::size_t index_count = 0;
  for (std::uint32_t i = 0; i < m.tree->segment_count(); ++i) index_count += m.tree->segment(i).indices.size();
  const std::size_t bytes = m.tree->positions().size() * 24 + index_count * 4;
  EXPECT_EQ(render::gpu_memory_usage()["model_renderer_test"].bytes[static_cast<int>(render::GpuMemoryKind::kBuffer)],
            bytes) << "the buffers are tracked";

  GlTarget target = GlTarget::create(kWidth, kHeight);
  const render::Camera cam = camera_looking({100.0, 200.0, 10.0}, {100.0, 30.0, 100.0});
  const Image image = target.render(**renderer, cam, kMagenta);
  const ModelFrameStats& st = (*renderer)->frame_stats();
  EXPECT_GT(st.segments, 0u);
  EXPECT_GT(st.triangles, 0u);
  EXPECT_EQ(st.gpu_bytes, bytes);
  std::uint64_t tris = 0;
  for (std::uint32_t i : (*renderer)->selection().segments) tris += m.tree->segment(i).triangle_count();
  EXPECT_EQ(st.triangles, tris);
  std::size_t covered = 0;
  double sum = 0.0, sum2 = 0.0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (is_color(image, x, y, kMagenta)) continue;
      ++covered;
      const double v = image.at(x, y, 0) + image.at(x, y, 1) + image.at(x, y, 2);
      sum += v, sum2 += v * v;
    }
  EXPECT_GT(covered, image.pixel_count() / 3) << "the model fills much of the view";
  const double mean = sum / static_cast<double>(covered);
  EXPECT_GT(sum2 / static_cast<double>(covered) - mean * mean, 1e-4) << "shaded, not one flat colour";
  save_png(image, "model_shaded");
  (*renderer)->settings().debug_view = ModelDebugView::kLodColors;
  save_png(target.render(**renderer, cam, kMagenta), "model_lod_colors");
}

// With shadows cast, one LOD selection per frame serves the camera and the shadow casters: the
// casters are exactly what a selection without frustum culling picks, the camera's exactly the
// culled one, and the pose sees only part of the model (so the two differ).
TEST_F(ModelGl, OneSelectionPerFrameServesTheCameraAndTheShadowCasters) {
  const Model& m = model();
  ModelRenderSettings s;
  s.receive_shadows = false;
  s.cast_shadows = true;
  auto renderer = ModelRenderer::create(m.tree, s);
  ASSERT_TRUE(renderer.ok()) << renderer.error().describe();
  GlTarget target = GlTarget::create(kWidth, kHeight);
  const render::Camera cam = camera_looking({20.0, 60.0, 20.0}, {60.0, 30.0, 60.0});
  target.render(**renderer, cam, kMagenta);
  const ModelFrameStats& st = (*renderer)->frame_stats();
  EXPECT_EQ(st.selections, 1u) << "one LOD selection per frame";
  const LodView view = TerrainRenderer::view_for(cam, glm::ivec2(kWidth, kHeight));
  LodSettings lod = s.lod.lod();
  const ModelSelection culled = select_segments(*m.tree, view, lod);
  lod.frustum_cull = false;
  const ModelSelection all = select_segments(*m.tree, view, lod);
  EXPECT_EQ((*renderer)->selection().segments, culled.segments);
  EXPECT_EQ(st.culled, culled.culled);
  EXPECT_EQ((*renderer)->caster_selection().segments, all.segments);
  EXPECT_EQ((*renderer)->caster_selection().triangles, all.triangles);
  EXPECT_GT(culled.culled, 0u) << "the pose must see only part of the model";
  EXPECT_LT(culled.segments.size(), all.segments.size());
  (*renderer)->settings().cast_shadows = false;
  target.render(**renderer, cam, kMagenta);
  EXPECT_EQ((*renderer)->frame_stats().selections, 1u);
  EXPECT_TRUE((*renderer)->caster_selection().segments.empty());
}

// Both reducers (QEM passes and the seed's shortest edge, §4.3) with the borders locked (§4.2).
// Seen red: with the border rule switched off in ModelTree::build, the shortest-edge tree showed
// 46631 background pixels over the 150 poses (the QEM tree stays closed: its pass-wise reducer
// also keeps every open-boundary vertex of a segment).
class ModelCracks : public ModelGl, public ::testing::WithParamInterface<Reducer> {};

TEST_P(ModelCracks, MixedLevelsLeaveNoCracksOver150Poses) {
  const Model& m = model(GetParam());
  GlTarget target = GlTarget::create(kWidth, kHeight);
  auto full = flat_renderer(m.full, 1.0f);
  auto mixed = flat_renderer(m.tree, 1.0f);
  const glm::dvec2 o = m.tree->root_origin();
  const double margin = 1.0;
  const glm::dvec2 lo = o + margin, hi = o + m.tree->root_size() - margin;
  std::mt19937 rng(2002);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::size_t must_hit = 0, holes = 0, full_holes = 0, mixed_poses = 0, neighbour_pairs = 0;
  int poses = 0;
  for (; poses < 150; ++poses) {
    // Above the highest vertex, inside the square, looking down at 20..80 degrees.
    const glm::dvec3 eye(lo.x + u(rng) * (hi.x - lo.x), m.max_y + 2.0 + 200.0 * u(rng), lo.y + u(rng) * (hi.y - lo.y));
    const double yaw = 6.2831853 * u(rng), down = glm::radians(20.0 + 60.0 * u(rng));
    const glm::dvec3 dir(std::cos(yaw) * std::cos(down), -std::sin(down), std::sin(yaw) * std::cos(down));
    const render::Camera cam = camera_looking(eye, eye + 100.0 * dir);
    mixed->settings().lod.max_pixel_error = static_cast<float>(0.5 * std::pow(32.0, u(rng)));  // 0.5..16 px
    const std::vector<std::uint8_t> mask = must_hit_mask(cam, m.min_y - 1.0, lo, hi);
    const Image reference = target.render(*full, cam, kMagenta);
    const Image image = target.render(*mixed, cam, kMagenta);
    std::set<int> levels;
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> leaf_level;  // leaf cell -> drawn level
    const int leaf = m.tree->levels() - 1;
    for (std::uint32_t i : mixed->selection().segments) {
      const ChunkKey& k = m.tree->segment(i).key;
      levels.insert(k.level);
      const std::uint32_t span = 1u << (leaf - k.level);
      for (std::uint32_t z = 0; z < span; ++z)
        for (std::uint32_t x = 0; x < span; ++x) leaf_level[{k.x * span + x, k.z * span + z}] = k.level;
    }
    for (const auto& [cell, level] : leaf_level) {
      auto right = leaf_level.find({cell.first + 1, cell.second});
      if (right != leaf_level.end() && right->second != level) ++neighbour_pairs;
    }
    if (levels.size() >= 2) ++mixed_poses;
    std::size_t pose_holes = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        if (!mask[static_cast<std::size_t>(y) * kWidth + x]) continue;
        ++must_hit;
        if (is_color(reference, x, y, kMagenta)) ++full_holes;
        if (is_color(image, x, y, kMagenta)) ++pose_holes;
      }
    if (pose_holes > 0 && holes == 0) save_png(image, "model_crack_pose" + std::to_string(poses));
    holes += pose_holes;
  }
  EXPECT_EQ(full_holes, 0u) << "the full-resolution sheet covers every must-hit pixel (checks the mask)";
  EXPECT_EQ(holes, 0u) << "background pixels through the model at mixed segment levels";
  EXPECT_GT(must_hit, static_cast<std::size_t>(poses) * kWidth * kHeight / 8) << "the poses look at the model";
  EXPECT_GE(mixed_poses, 90u) << "poses must draw segments of different levels";
  EXPECT_GT(neighbour_pairs, 500u) << "neighbouring segments of different levels";
  std::printf("crack test (%s): %d poses, %zu must-hit pixels, %zu holes, %zu mixed-level poses, %zu level borders\n",
              (GetParam() == Reducer::kQem ? "qem" : "shortest_edge"), poses, must_hit, holes, mixed_poses, neighbour_pairs);
}

TEST_P(ModelCracks, SelectedSegmentsStayWithinTau) {
  const Model& m = model(GetParam());
  GlTarget target = GlTarget::create(kWidth, kHeight);
  auto r = flat_renderer(m.tree, 1.0f);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const glm::dvec2 o = m.tree->root_origin();
  std::size_t coarse = 0, checked = 0;
  double worst = 0.0;
  for (float tau : {0.5f, 1.0f, 2.0f, 4.0f}) {
    r->settings().lod.max_pixel_error = tau;
    for (int pose = 0; pose < 30; ++pose) {
      const glm::dvec3 eye(o.x + (u(rng) * 1.6 - 0.3) * kSize, 20.0 + 400.0 * u(rng), o.y + (u(rng) * 1.6 - 0.3) * kSize);
      const render::Camera cam = camera_looking(eye, {o.x + u(rng) * kSize, 40.0, o.y + u(rng) * kSize});
      (void)target.render(*r, cam, kMagenta);
      const LodView view = TerrainRenderer::view_for(cam, target.size());
      for (std::uint32_t i : r->selection().segments) {
        const Segment& s = m.tree->segment(i);
        const double rho = ModelRenderer::projected_error(*m.tree, i, view);
        ++checked;
        if (s.key.level + 1 < m.tree->levels()) {
          ++coarse;
          EXPECT_GT(s.error_bound, 0.0f);
          EXPECT_GE(s.error_bound, s.error);
        }
        EXPECT_LE(rho, tau) << "segment " << i << " level " << s.key.level << " tau " << tau;
        worst = std::max(worst, rho / tau);
      }
      EXPECT_LE(r->frame_stats().max_projected_error_px, tau);
    }
  }
  EXPECT_GT(coarse, checked / 10) << "the bound must be exercised by reduced segments";
  EXPECT_GT(worst, 0.3) << "some segment comes close to tau";
  std::printf("error bound (%s): %zu segments checked, %zu reduced, largest rho/tau %.3f\n", (GetParam() == Reducer::kQem ? "qem" : "shortest_edge"), checked, coarse, worst);
}

INSTANTIATE_TEST_SUITE_P(Reducers, ModelCracks, ::testing::Values(Reducer::kQem, Reducer::kShortestEdge),
                         [](const ::testing::TestParamInfo<Reducer>& info) {
                           return info.param == Reducer::kQem ? std::string("Qem") : std::string("ShortestEdge");
                         });

TEST_F(ModelGl, RefusesANullTree) {
  auto r = ModelRenderer::create(nullptr, ModelRenderSettings{});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("model tree"), std::string::npos);
}

}  // namespace
}  // namespace sylva::terrain

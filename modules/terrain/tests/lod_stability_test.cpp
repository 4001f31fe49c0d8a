// Stability of the height-field chunk LOD on extreme inputs. Each test names the invariant it
// checks; all of them also require: the build succeeds (or fails with a clear error), no NaN/Inf
// in any drawn position, and no crack edge between drawn chunks.
#include <sylva/terrain/frame_mesh.hpp>
#include <sylva/terrain/height_source.hpp>

#include "support/terrain_test_support.hpp"

#include <sylva/core/image.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

namespace sylva::terrain {
namespace {

using namespace testing;

struct FrameCheck {
  std::size_t triangles = 0;
  std::size_t cracks = 0;
  double max_px_over_tau = 0.0;
};

// Selects, assembles and checks one frame: finite positions, watertight, and (when asked) the
// projected error bound.
FrameCheck check_frame(const ChunkTree& tree, const HeightField& field, const LodView& view, LodSettings ls,
                       bool check_bound) {
  LodSelector selector(tree);
  SeamCache seams;
  const Selection& sel = selector.select(view, ls);
  const VertexFrame frame = make_vertex_frame(tree, view, ls);
  const FrameMesh mesh = assemble_frame(tree, sel, frame, CrackFix::kSeams, seams);
  FrameCheck c;
  c.triangles = mesh.triangles();
  for (const glm::vec3& p : mesh.positions) {
    EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << "non-finite drawn position";
  }
  const auto w = check_watertight(tree, selector, frame, mesh);
  c.cracks = w.crack_edges;
  EXPECT_EQ(w.crack_edges, 0u) << w.report;
  if (check_bound) c.max_px_over_tau = projected_error(field, frame, mesh, view.k).max_px / ls.max_pixel_error;
  return c;
}

ChunkTree build(const HeightField& f, int dim = 17, float flat = 0.0f) {
  ChunkTreeSettings s;
  s.leaf_dimension = dim;
  s.flat_tolerance = flat;
  auto r = ChunkTree::build(f, s);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().describe());
  return std::move(r).value();
}

// Invariant: a flat field has zero error everywhere and is drawn with the minimum triangles.
TEST(LodStability, FlatFieldHasZeroErrorAndMinimalMeshes) {
  const HeightField f = make_field(257, 257, 1.0, [](int, int) { return 42.0f; });
  const ChunkTree t = build(f);
  for (std::uint32_t i = 0; i < t.chunk_count(); ++i) EXPECT_EQ(t.chunk(i).error_bound, 0.0f);
  const FrameCheck c = check_frame(t, f, look_at_view({10, 50, 10}, {200, 40, 200}, 60), LodSettings{}, true);
  EXPECT_EQ(c.triangles, 8u) << "the root alone suffices";
  EXPECT_EQ(c.max_px_over_tau, 0.0);
}

// Invariant: a single 10 km spike is kept exactly where needed: the bound holds around it and
// nothing overflows or turns NaN.
TEST(LodStability, TenKilometreSpike) {
  const HeightField f = make_field(129, 129, 1.0, [](int i, int j) { return (i == 77 && j == 40) ? 10000.0f : 0.0f; });
  const ChunkTree t = build(f, 17, 0.0f);
  EXPECT_GE(t.chunk(0).error, 9999.0f);  // the root cannot represent the spike
  const Chunk* leaf = t.find(t.levels() - 1, 77 / 16, 40 / 16);
  ASSERT_NE(leaf, nullptr);
  EXPECT_EQ(leaf->error, 0.0f);
  std::mt19937 rng(3);
  for (int i = 0; i < 20; ++i) {
    PoseOptions po;
    po.max_altitude = 20000.0;
    LodSettings ls;
    ls.frustum_cull = false;
    const FrameCheck c = check_frame(t, f, random_view(rng, t, f, po), ls, true);
    EXPECT_LE(c.max_px_over_tau, 1.0 + 1e-4);
  }
}

// Invariant: degenerate sizes (1x1, 2xN, Nx2) build, select and draw without NaN or cracks.
TEST(LodStability, OneByOneAndTwoByNFields) {
  const HeightField one = make_field(1, 1, 1.0, [](int, int) { return 5.0f; });
  const ChunkTree t1 = build(one);
  EXPECT_EQ(t1.levels(), 1);
  EXPECT_TRUE(t1.chunk(0).present);
  (void)check_frame(t1, one, look_at_view({-3, 10, -3}, {0, 5, 0}, 60), LodSettings{}, false);

  for (int flip = 0; flip < 2; ++flip) {
    const int cols = flip ? 300 : 2, rows = flip ? 2 : 300;
    const HeightField f = make_field(cols, rows, 1.0, [](int i, int j) { return 3.0f * std::sin(0.1f * (i + j)); });
    const ChunkTree t = build(f, 9);
    std::mt19937 rng(5);
    for (int i = 0; i < 10; ++i) {
      LodSettings ls;
      ls.frustum_cull = false;
      const FrameCheck c = check_frame(t, f, random_view(rng, t, f, PoseOptions{}), ls, true);
      EXPECT_LE(c.max_px_over_tau, 1.0 + 1e-4);
    }
  }
}

// Invariant: a non-square, non-power-of-two field is padded, the padding is never drawn as
// field (marked outside) and never counted in the error; the bound holds on the field.
TEST(LodStability, NonSquareFieldIsPaddedAndMarked) {
  const HeightField f = fbm_field(301, 97, 1.0, 60.0f, 7);
  const ChunkTree t = build(f, 17);
  EXPECT_EQ(t.root_intervals(), 512u);
  std::size_t outside = 0, absent = 0;
  for (std::uint32_t i = 0; i < t.chunk_count(); ++i) {
    const Chunk& c = t.chunk(i);
    if (!c.present) {
      ++absent;
      continue;
    }
    for (const ChunkVertex& v : c.mesh.vertices) {
      EXPECT_EQ(v.outside != 0, v.gx > 300u || v.gz > 96u);
      outside += v.outside;
    }
  }
  EXPECT_GT(outside, 0u);
  EXPECT_GT(absent, 0u) << "chunks wholly in padding are not built";
  std::mt19937 rng(6);
  for (int i = 0; i < 10; ++i) {
    const FrameCheck c = check_frame(t, f, random_view(rng, t, f, PoseOptions{}), LodSettings{}, true);
    EXPECT_LE(c.max_px_over_tau, 1.0 + 1e-4);
  }
}

// Invariant: NaN/Inf input is refused with the count and the first position, or repaired on
// request when loading an image; never silently meshed.
TEST(LodStability, NonFiniteSamplesAreReportedOrRepaired) {
  HeightField f = make_field(40, 30, 1.0, [](int, int) { return 1.0f; });
  f.sample(7, 3) = std::numeric_limits<float>::quiet_NaN();
  f.sample(20, 25) = std::numeric_limits<float>::infinity();
  auto r = ChunkTree::build(f, ChunkTreeSettings{});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("2 NaN/Inf"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("column 7 row 3"), std::string::npos) << r.error().message;

  Image img(16, 8, 1, PixelFormat::kF32);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) img.at(x, y) = 0.25f;
  img.at(5, 2) = std::numeric_limits<float>::quiet_NaN();
  const std::filesystem::path path = unique_temp("nan.exr");
  ASSERT_TRUE(write_image(path, img).ok());
  HeightImageSettings hs;
  auto refused = load_height_field(path, hs);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find(path.string()), std::string::npos) << refused.error().message;
  hs.repair_non_finite = true;
  auto repaired = load_height_field(path, hs);
  ASSERT_TRUE(repaired.ok()) << repaired.error().describe();
  EXPECT_TRUE(ChunkTree::build(*repaired, ChunkTreeSettings{}).ok());
  std::filesystem::remove(path);
}

// Invariant: the extremes of a 16-bit height map (0 and 65535 side by side, scaled to Everest)
// keep full precision, measured errors stay within the height range and the bound holds.
TEST(LodStability, SixteenBitExtremes) {
  Image img(129, 129, 1, PixelFormat::kU16);
  for (int y = 0; y < 129; ++y)
    for (int x = 0; x < 129; ++x) img.at(x, y) = ((x / 3 + y / 5) % 2) ? 1.0f : 0.0f;
  const std::filesystem::path path = unique_temp("u16.png");
  ASSERT_TRUE(write_image(path, img).ok());
  HeightImageSettings hs;
  hs.height_scale = 8848.0;
  auto f = load_height_field(path, hs);
  std::filesystem::remove(path);
  ASSERT_TRUE(f.ok()) << f.error().describe();
  EXPECT_EQ(f->max_height(), 8848.0f);
  EXPECT_EQ(f->min_height(), 0.0f);
  const ChunkTree t = build(*f, 17);
  for (std::uint32_t i = 0; i < t.chunk_count(); ++i) EXPECT_LE(t.chunk(i).error, 8848.0f);
  std::mt19937 rng(8);
  for (int i = 0; i < 10; ++i) {
    PoseOptions po;
    po.max_altitude = 30000.0;
    LodSettings ls;
    ls.frustum_cull = false;
    const FrameCheck c = check_frame(t, *f, random_view(rng, t, *f, po), ls, true);
    EXPECT_LE(c.max_px_over_tau, 1.0 + 1e-4);
  }
}

// Invariant: 1e5 m from the origin, a vertex's reconstructed world position does not move when
// the camera moves by millimetres (no jitter), and the frame stays watertight.
TEST(LodStability, FarFromOriginDoesNotJitter) {
  const glm::dvec2 origin(1.0e5, -1.0e5);
  const HeightField f = fbm_field(257, 257, 1.0, 80.0f, 9, origin);
  const ChunkTree t = build(f, 17, 0.02f);
  LodSettings ls;
  ls.morph_fraction = 0.0f;  // morphing moves vertices on purpose; jitter is about precision
  const glm::dvec3 eye(origin.x + 100.0, 150.0, origin.y + 80.0);
  const ChunkVertex& v = t.chunk(t.index(t.levels() - 1, 5, 6)).mesh.vertices[7];
  const glm::dvec2 truth = t.grid_to_world(v.gx, v.gz);
  for (int step = 0; step < 50; ++step) {
    const glm::dvec3 cam = eye + glm::dvec3(0.001 * step, 0.0007 * step, -0.0013 * step);
    const LodView view = look_at_view(cam, cam + glm::dvec3(1, -0.5, 1), 60);
    const VertexFrame frame = make_vertex_frame(t, view, ls);
    const glm::vec3 rel = vertex_position(frame, v);
    const glm::dvec3 world = glm::dvec3(rel) + cam;
    EXPECT_NEAR(world.x, truth.x, 2e-3);
    EXPECT_NEAR(world.z, truth.y, 2e-3);
    EXPECT_NEAR(world.y, v.height, 2e-3);
    if (step % 10 == 0) (void)check_frame(t, f, view, ls, true);
  }
}

// Invariant: a camera under the ground (looking up or down) still gets a valid, watertight
// selection with finite positions and the error bound.
TEST(LodStability, CameraBelowTheGround) {
  const HeightField f = fbm_field(193, 193, 1.0, 80.0f, 10);
  const ChunkTree t = build(f, 17);
  std::mt19937 rng(11);
  for (int i = 0; i < 15; ++i) {
    PoseOptions po;
    po.below_ground = true;
    po.min_pitch_deg = -60.0;
    po.max_pitch_deg = 80.0;
    LodSettings ls;
    ls.frustum_cull = (i % 2) == 0;
    const FrameCheck c = check_frame(t, f, random_view(rng, t, f, po), ls, true);
    EXPECT_LE(c.max_px_over_tau, 1.0 + 1e-4);
  }
}

// Invariant: very narrow (0.5 degree, K ~ 16500) and very wide (170 degree) fields of view give a
// finite K, a bounded selection, no cracks and the bound.
TEST(LodStability, NarrowAndWideFieldOfView) {
  const HeightField f = fbm_field(193, 193, 1.0, 80.0f, 12);
  const ChunkTree t = build(f, 17);
  for (double fov : {0.5, 170.0}) {
    const LodView view = look_at_view({-50, 120, -50}, {150, 20, 150}, fov);
    EXPECT_TRUE(std::isfinite(view.k) && view.k > 0.0);
    LodSettings ls;
    const FrameCheck c = check_frame(t, f, view, ls, true);
    EXPECT_LE(c.max_px_over_tau, 1.0 + 1e-4) << "fov " << fov;
    EXPECT_GT(c.triangles, 0u) << "fov " << fov;
  }
}

// Invariant: a generated field is deterministic for its seed and size (the seed's -seed/-size).
TEST(LodStability, GeneratedFieldsAreDeterministic) {
  GeneratedFieldSettings g;
  g.size = 65;
  g.fbm.seed = 4;
  auto a = generate_height_field(g);
  auto b = generate_height_field(g);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->samples(), b->samples());
  g.fbm.seed = 5;
  EXPECT_NE(generate_height_field(g)->samples(), a->samples());
  g.noise = FieldNoise::kRidged;
  auto r = generate_height_field(g);
  ASSERT_TRUE(r.ok());
  EXPECT_GE(r->min_height(), 0.0f);
  EXPECT_LE(r->max_height(), g.height_scale);
  g.size = 0;
  auto bad = generate_height_field(g);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("terrain.field.size"), std::string::npos) << bad.error().message;
}

}  // namespace
}  // namespace sylva::terrain

// The GL renderer on headless EGL/llvmpipe: pictures of every view, the render crack test
// (>= 100 scripted poses per field, zero background pixels inside the terrain silhouette) and
// the projected-error test from the depth buffer for tau in {0.5, 1, 2, 4}.
#include <sylva/render/testing.hpp>
#include <sylva/terrain/height_source.hpp>
#include <sylva/terrain/height_texture.hpp>
#include <sylva/terrain/renderer.hpp>

#include "support/gl_support.hpp"
#include "support/terrain_test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace sylva::terrain {
namespace {

using namespace testing;
using TerrainGl = render::GlTest;

struct Scene {
  HeightField field;
  std::shared_ptr<const ChunkTree> tree;
};

Scene make_scene(HeightField field, int leaf_dimension, float flat_tolerance = 0.02f) {
  Scene s;
  s.field = std::move(field);
  ChunkTreeSettings ts;
  ts.leaf_dimension = leaf_dimension;
  ts.flat_tolerance = flat_tolerance;
  s.tree = std::make_shared<const ChunkTree>(std::move(ChunkTree::build(s.field, ts)).value());
  return s;
}

render::Camera camera_at(const glm::dvec3& eye, float yaw, float pitch, float fov_deg = 60.0f, int w = 256, int h = 144) {
  render::Camera c;
  c.set_position(eye);
  c.set_yaw_pitch(yaw, pitch);
  c.perspective().fov_y = glm::radians(fov_deg);
  c.perspective().near_plane = 0.05f;
  c.perspective().far_plane = 0.0f;
  c.set_aspect(w, h);
  return c;
}

double variance(const Image& im) {
  double s = 0, s2 = 0;
  const std::size_t n = im.pixel_count();
  for (int y = 0; y < im.height(); ++y)
    for (int x = 0; x < im.width(); ++x) {
      const double v = im.at(x, y, 0) + im.at(x, y, 1) + im.at(x, y, 2);
      s += v;
      s2 += v * v;
    }
  return s2 / n - (s / n) * (s / n);
}

// The GPU height texture other modules may sample: exact samples in metres, the uv mapping of
// height_texture_info, the renderer's accessor, and a clear kLimit beyond GL_MAX_TEXTURE_SIZE.
TEST_F(TerrainGl, HeightTextureHoldsTheSamplesAndMapsWorldPositions) {
  GeneratedFieldSettings g;
  g.size = 37;
  g.rows = 23;
  g.spacing = 3.0;
  g.height_scale = 500.0f;
  g.height_offset = -120.0f;
  const HeightField field = generate_height_field(g).value();
  auto tex = make_height_texture(field);
  ASSERT_TRUE(tex.ok()) << tex.error().describe();
  EXPECT_EQ(tex->width(), 37);
  EXPECT_EQ(tex->height(), 23);
  std::vector<float> back(37 * 23);
  glGetTextureImage(tex->id(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(back.size() * sizeof(float)), back.data());
  EXPECT_EQ(back, field.samples());
  const HeightTextureInfo info = height_texture_info(field);
  for (int j : {0, 11, 22})
    for (int i : {0, 17, 36}) {
      const glm::vec2 world(field.origin().x + i * field.spacing(), field.origin().y + j * field.spacing());
      const glm::vec2 texel = (world * info.uv_scale + info.uv_offset) * glm::vec2(37.0f, 23.0f) - 0.5f;
      EXPECT_NEAR(texel.x, i, 1e-4);
      EXPECT_NEAR(texel.y, j, 1e-4);
    }
  EXPECT_EQ(info.height_range, glm::vec2(field.min_height(), field.max_height()));

  ChunkTreeSettings ts;
  ts.leaf_dimension = 9;
  auto tree = std::make_shared<const ChunkTree>(std::move(ChunkTree::build(field, ts)).value());
  auto with = TerrainRenderer::create(tree, &field, {});
  ASSERT_TRUE(with.ok());
  ASSERT_NE((*with)->height_texture(), nullptr);
  EXPECT_EQ((*with)->height_texture()->width(), 37);
  auto without = TerrainRenderer::create(tree, nullptr, {});
  ASSERT_TRUE(without.ok());
  EXPECT_EQ((*without)->height_texture(), nullptr);

  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  const HeightField wide(max_size + 1, 1, 1.0);
  auto refused = make_height_texture(wide);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, ErrorCode::kLimit);
  EXPECT_NE(refused.error().message.find("GL_MAX_TEXTURE_SIZE"), std::string::npos) << refused.error().message;
}

// Issue 15: painting re-uploads only the stroke's rectangle of the height texture. The same
// 41x41 stroke on a 513^2 and a 2049^2 field uploads 1681 texels on both, and the texture then
// holds every edited sample and still every untouched one; through the renderer's
// apply_height_edit the counter grows by the edit's rectangle only.
TEST_F(TerrainGl, HeightTextureEditUploadsOnlyTheStrokesTexels) {
  for (const int size : {513, 2049}) {
    HeightField field(size, size, 2.0);
    for (std::size_t i = 0; i < field.samples().size(); ++i) field.samples()[i] = static_cast<float>(i % 977);
    auto tex = make_height_texture(field);
    ASSERT_TRUE(tex.ok());
    for (int z = 200; z < 241; ++z)
      for (int x = 300; x < 341; ++x) field.samples()[static_cast<std::size_t>(z) * size + x] += 5.5f;
    EXPECT_EQ(update_height_texture(*tex, field, 300, 200, 341, 241), 41 * 41) << size;
    std::vector<float> back(field.samples().size());
    glGetTextureImage(tex->id(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(back.size() * sizeof(float)), back.data());
    EXPECT_TRUE(back == field.samples()) << size;
    EXPECT_EQ(update_height_texture(*tex, field, size - 3, size - 2, size + 9, size + 9), 3 * 2) << "clamped";
    EXPECT_EQ(update_height_texture(*tex, field, 5, 5, 5, 9), 0) << "empty";
  }

  HeightField field(37, 23, 3.0);
  ChunkTreeSettings ts;
  ts.leaf_dimension = 9;
  auto tree = std::make_shared<const ChunkTree>(std::move(ChunkTree::build(field, ts)).value());
  auto renderer = TerrainRenderer::create(tree, &field, {});
  ASSERT_TRUE(renderer.ok());
  const std::int64_t before = (*renderer)->height_texels_uploaded();
  field.samples()[7 * 37 + 10] = 40.0f;
  ASSERT_TRUE((*renderer)->apply_height_edit(field, 10, 7, 11, 8).ok());
  EXPECT_EQ((*renderer)->height_texels_uploaded() - before, 1);
  std::vector<float> back(field.samples().size());
  glGetTextureImage((*renderer)->height_texture()->id(), 0, GL_RED, GL_FLOAT,
                    static_cast<GLsizei>(back.size() * sizeof(float)), back.data());
  EXPECT_TRUE(back == field.samples());
}

// A ridged 900 m field of `size` samples, and a target lit for pictures in [0, 1] (no tone
// mapping here) with a little haze.
Scene ridged_scene(int size, double spacing) {
  GeneratedFieldSettings g;
  g.size = size;
  g.spacing = spacing;
  g.height_scale = 900.0f;
  g.feature_size = 2500.0f;
  g.noise = FieldNoise::kRidged;
  return make_scene(generate_height_field(g).value(), 33);
}

GlTarget hazy_target(int w, int h) {
  GlTarget target = GlTarget::create(w, h);
  target.lighting.sun_intensity = 1.1f;
  target.lighting.ambient *= 0.6f;
  target.lighting.fog_density = 8e-5f;
  return target;
}

TEST_F(TerrainGl, DrawsShadedTerrainAndEveryDebugView) {
  Scene s = ridged_scene(513, 8.0);
  TerrainRenderSettings rs;
  rs.receive_shadows = false;
  auto r = TerrainRenderer::create(s.tree, &s.field, rs);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  TerrainRenderer& t = **r;
  GlTarget target = hazy_target(512, 288);
  const double ground = s.field.height(600.0, 700.0);
  const render::Camera cam = camera_at({600.0, ground + 260.0, 700.0}, glm::radians(-135.0f), glm::radians(-14.0f), 60.0f, 512, 288);
  const glm::vec4 sky(0.55f, 0.7f, 0.9f, 1.0f);
  const Image shaded = target.render(t, cam, sky);
  save_png(shaded, "shaded");
  EXPECT_GT(variance(shaded), 1e-3) << "the shaded terrain is not flat colour";
  // The lower half is terrain, the upper rows sky.
  std::size_t terrain_px = 0;
  for (int y = 144; y < 288; ++y)
    for (int x = 0; x < 512; ++x) terrain_px += !is_color(shaded, x, y, sky);
  EXPECT_GT(terrain_px, 512u * 144u * 9 / 10);
  EXPECT_GT(t.frame_stats().selection.chunks, 4u);
  int levels = 0;
  for (std::uint32_t n : t.frame_stats().selection.chunks_per_level) levels += n > 0;
  EXPECT_GE(levels, 2) << "the view must mix LOD levels";
  EXPECT_GT(t.frame_stats().seam_triangles, 0u);

  t.settings().debug_view = DebugView::kLodColors;
  const Image lod = target.render(t, cam, sky);
  save_png(lod, "lod_colors");
  EXPECT_GT(variance(lod), variance(shaded) * 0.2);
  t.settings().debug_view = DebugView::kMorph;
  save_png(target.render(t, cam, sky), "morph");
  t.settings().debug_view = DebugView::kShaded;
  t.settings().wireframe = true;
  t.settings().chunk_bounds = true;
  const Image wire = target.render(t, cam, sky);
  save_png(wire, "wireframe_bounds");
  std::size_t differ = 0;
  for (int y = 0; y < 288; ++y)
    for (int x = 0; x < 512; ++x) differ += std::fabs(wire.at(x, y, 0) - shaded.at(x, y, 0)) > 0.05f;
  EXPECT_GT(differ, 2000u) << "wireframe and bounds change the picture";
  t.settings().wireframe = false;
  t.settings().chunk_bounds = false;
  t.settings().lod.crack_fix = CrackFix::kSkirts;
  save_png(target.render(t, cam, sky), "skirts");
  EXPECT_GT(t.frame_stats().skirt_triangles, 0u);
}

// Issue 18: the air over the ground (terrain.render.aerial_perspective). Per vertex (the default:
// extinction per metre evaluated in chunk.vert and interpolated) stays within 2/255 of the
// per-pixel picture on every pixel but is not the same program; off draws the ground without
// air: far ground keeps its own colour instead of fading toward the sky's.
TEST_F(TerrainGl, AerialPerspectivePerVertexMatchesPerPixelAndOffDrawsNoAir) {
  Scene s = ridged_scene(257, 40.0);
  TerrainRenderSettings rs;
  rs.receive_shadows = false;
  auto r = TerrainRenderer::create(s.tree, &s.field, rs);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  TerrainRenderer& t = **r;
  EXPECT_EQ(t.settings().aerial_perspective, AerialPerspective::kPerVertex) << "the default";
  t.settings().aerial_perspective = AerialPerspective::kPerPixel;
  GlTarget target = hazy_target(256, 144);
  const double ground = s.field.height(600.0, 700.0);
  const render::Camera cam = camera_at({600.0, ground + 400.0, 700.0}, glm::radians(-135.0f), glm::radians(-8.0f));
  const glm::vec4 sky(0.55f, 0.7f, 0.9f, 1.0f);
  const Image per_pixel = target.render(t, cam, sky);
  t.settings().aerial_perspective = AerialPerspective::kPerVertex;
  const Image per_vertex = target.render(t, cam, sky);
  t.settings().aerial_perspective = AerialPerspective::kOff;
  const Image off = target.render(t, cam, sky);
  save_png(per_vertex, "air_per_vertex");
  save_png(off, "air_off");
  float max_vertex = 0.0f;
  std::size_t vertex_differs = 0, off_differs = 0, terrain_px = 0;
  for (int y = 0; y < 144; ++y)
    for (int x = 0; x < 256; ++x) {
      if (is_color(per_pixel, x, y, sky)) continue;
      ++terrain_px;
      float dv = 0.0f, doff = 0.0f;
      for (int c = 0; c < 3; ++c) {
        dv = std::max(dv, std::fabs(per_vertex.at(x, y, c) - per_pixel.at(x, y, c)));
        doff = std::max(doff, std::fabs(off.at(x, y, c) - per_pixel.at(x, y, c)));
      }
      max_vertex = std::max(max_vertex, dv);
      vertex_differs += dv > 0.0f;
      off_differs += doff > 8.0f / 255.0f;
    }
  ASSERT_GT(terrain_px, 256u * 144u / 3);
  EXPECT_LE(max_vertex, 2.0f / 255.0f + 1e-6f) << "per-vertex air against per-pixel";
  EXPECT_GT(vertex_differs, 0u) << "per_vertex drew the per-pixel program";
  EXPECT_GT(off_differs, terrain_px / 4) << "off still draws the air";
}


// Records the capabilities glEnable is called with, through libepoxy's public function pointer
// (swapped for the spy's lifetime, then restored). Mesa 22.3.6 llvmpipe clips by the written
// gl_ClipDistance even with GL_CLIP_DISTANCEi disabled (seen: with the renderer's two enables
// dropped the picture is the same), so only this sees a missing enable, which a conformant
// driver needs to clip at all.
class EnableSpy {
 public:
  EnableSpy() {
    glEnable(GL_DITHER);  // called once first: epoxy resolves its function pointer on the first call, which would overwrite the spy
    real_ = epoxy_glEnable;
    epoxy_glEnable = &record;
    seen_.clear();
  }
  ~EnableSpy() { epoxy_glEnable = real_; }
  EnableSpy(const EnableSpy&) = delete;
  EnableSpy& operator=(const EnableSpy&) = delete;
  static bool saw(GLenum cap) { return std::find(seen_.begin(), seen_.end(), cap) != seen_.end(); }

 private:
  static void record(GLenum cap) {
    seen_.push_back(cap);
    real_(cap);
  }
  static inline decltype(epoxy_glEnable) real_ = nullptr;
  static inline std::vector<GLenum> seen_;
};

// Issue 18: the padding a 300^2 field leaves in its 512-interval root grid is not drawn now that
// terrain.frag no longer discards it (that cost llvmpipe its early depth test; chunk.vert clips
// it). Straight down over the field's far corner, one quadrant of the picture is field; the
// padded chunks there reach 21 samples further, inside the view (checked: their vertices
// project into it). The flat view (its own program now) paints exactly its colour. The test
// once stayed green with the renderer's glEnable(GL_CLIP_DISTANCEi) removed: not the pose (it
// sees the padding), llvmpipe clips without the enables (EnableSpy). Seen red with the clip
// distances made positive everywhere (u_field_size forced to 100000: 33410 field pixels, the
// padding drawn) and, for the spy's assertion, with the spy installed only after the frame.
TEST_F(TerrainGl, NothingBeyondTheFieldIsDrawnAndTheFlatViewIsOneColour) {
  GeneratedFieldSettings g;
  g.size = 300;
  g.spacing = 1.0;
  g.height_scale = 20.0f;
  g.feature_size = 60.0f;
  Scene s = make_scene(generate_height_field(g).value(), 33);
  ASSERT_LT(s.field.columns() - 1, static_cast<int>(s.tree->root_intervals())) << "the tree must be padded";
  TerrainRenderSettings rs;
  rs.receive_shadows = false;
  rs.debug_view = DebugView::kFlat;
  auto r = TerrainRenderer::create(s.tree, &s.field, rs);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  GlTarget target = GlTarget::create(200, 200);
  const glm::dvec2 corner = s.field.origin() + s.field.extent();
  const render::Camera cam = camera_at({corner.x, 80.0, corner.y}, 0.0f, glm::radians(-89.9f), 40.0f, 200, 200);
  Image im;
  {
    EnableSpy spy;
    im = target.render(**r, cam, kMagenta);
    EXPECT_TRUE(EnableSpy::saw(GL_CLIP_DISTANCE0) && EnableSpy::saw(GL_CLIP_DISTANCE1))
        << "the renderer must enable the clip distances of a padded tree";
  }
  save_png(im, "padding_clipped");
  // The pose sees the padding: vertices of drawn chunks beyond the field project into the view.
  std::size_t padding_in_view = 0;
  for (const SelectedChunk& c : (*r)->selection().chunks)
    for (const ChunkVertex& v : s.tree->chunk(c.index).mesh.vertices) {
      if (v.outside == 0) continue;
      const glm::dvec3 p(s.field.origin().x + v.gx * g.spacing, v.height, s.field.origin().y + v.gz * g.spacing);
      const glm::vec4 q = cam.view_projection() * glm::vec4(glm::vec3(p - cam.position()), 1.0f);
      padding_in_view += q.w > 0.0f && std::fabs(q.x) < q.w && std::fabs(q.y) < q.w;
    }
  EXPECT_GT(padding_in_view, 100u) << "the pose must see past the field's edge";
  const glm::vec4 flat(0.6f, 0.6f, 0.6f, 1.0f);
  std::size_t field_px = 0, other = 0;
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 200; ++x) {
      field_px += is_color(im, x, y, flat);
      other += !is_color(im, x, y, flat) && !is_color(im, x, y, kMagenta);
    }
  EXPECT_EQ(other, 0u) << "the flat view paints only its colour";
  // 1/4 of 40000 up to the perspective of 20 m of relief 80 m below the eye.
  EXPECT_GT(field_px, 40000u * 18 / 100);
  EXPECT_LT(field_px, 40000u * 34 / 100) << "padding beyond the field was drawn";
}

// The scripted poses of the crack test: grazing, high altitude, fast turns and random views.
std::vector<render::Camera> crack_poses(const HeightField& f, int count, std::uint32_t seed) {
  std::vector<render::Camera> out;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const glm::dvec2 ext = f.extent();
  auto ground = [&](double x, double z) { return static_cast<double>(f.height(x, z)); };
  for (int i = 0; i < count; ++i) {
    const int kind = i % 4;
    double x = f.origin().x + ext.x * (0.1 + 0.8 * u(rng)), z = f.origin().y + ext.y * (0.1 + 0.8 * u(rng));
    float yaw = static_cast<float>(u(rng) * 6.283), pitch = 0.0f, fov = 60.0f;
    double y = 0.0;
    if (kind == 0) {  // grazing: just above the ground, looking along it
      y = ground(x, z) + 0.5 + 3.0 * u(rng);
      pitch = glm::radians(static_cast<float>(-6.0 + 10.0 * u(rng)));
    } else if (kind == 1) {  // high altitude, looking down
      y = ground(x, z) + 300.0 + 2500.0 * u(rng);
      pitch = glm::radians(static_cast<float>(-25.0 - 60.0 * u(rng)));
    } else if (kind == 2) {  // fast turns: a fixed spot, the view swung by large steps
      x = f.origin().x + ext.x * 0.5;
      z = f.origin().y + ext.y * 0.5;
      y = ground(x, z) + 40.0;
      yaw = glm::radians(static_cast<float>(i * 53 % 360));
      pitch = glm::radians(static_cast<float>(-10.0 - 25.0 * u(rng)));
    } else {  // anything, including wide and narrow lenses
      y = ground(x, z) + 2.0 + 600.0 * u(rng);
      pitch = glm::radians(static_cast<float>(-80.0 + 85.0 * u(rng)));
      fov = static_cast<float>(15.0 + 100.0 * u(rng));
    }
    out.push_back(camera_at({x, y, z}, yaw, pitch, fov));
  }
  return out;
}

struct CrackResult {
  std::size_t holes = 0;        // background pixels inside the eroded reference silhouette
  std::size_t inside = 0;       // pixels inside the eroded silhouette, all poses
  int poses = 0;
};

CrackResult crack_test(const Scene& s, CrackFix fix, int poses, std::uint32_t seed, const char* name) {
  TerrainRenderSettings rs;
  rs.receive_shadows = false;
  rs.debug_view = DebugView::kFlat;
  rs.lod.crack_fix = fix;
  rs.lod.max_pixel_error = 1.0f;
  auto r = TerrainRenderer::create(s.tree, &s.field, rs);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().describe());
  GlTarget target = GlTarget::create(256, 144);
  BruteForceField brute = BruteForceField::create(s.field);
  CrackResult out;
  const int radius = 2;  // ceil(tau) + 1: the LOD silhouette may differ from the reference by tau
  bool saved = false;
  for (const render::Camera& cam : crack_poses(s.field, poses, seed)) {
    const Image ref = brute.render(target, cam, kMagenta);
    std::vector<std::uint8_t> mask(256 * 144);
    for (int y = 0; y < 144; ++y)
      for (int x = 0; x < 256; ++x) mask[static_cast<std::size_t>(y) * 256 + x] = !is_color(ref, x, y, kMagenta);
    const std::vector<std::uint8_t> core = erode(mask, 256, 144, radius);
    const Image lod = target.render(**r, cam, kMagenta);
    std::size_t holes = 0;
    for (int y = 0; y < 144; ++y)
      for (int x = 0; x < 256; ++x) {
        if (!core[static_cast<std::size_t>(y) * 256 + x]) continue;
        ++out.inside;
        holes += is_color(lod, x, y, kMagenta);
      }
    if (holes > 0 && !saved) {
      save_png(lod, std::string(name) + "_crack_pose");
      saved = true;
    }
    out.holes += holes;
    ++out.poses;
  }
  return out;
}

TEST_F(TerrainGl, CrackTestFbmFieldAtLeast100Poses) {
  const Scene s = make_scene(fbm_field(193, 193, 3.0, 160.0f, 71), 9);
  const CrackResult c = crack_test(s, CrackFix::kSeams, 104, 1, "fbm");
  EXPECT_EQ(c.poses, 104);
  EXPECT_GT(c.inside, 104u * 256u * 144u / 5) << "the poses must see terrain";
  EXPECT_EQ(c.holes, 0u) << "background pixels inside the terrain silhouette";
}

TEST_F(TerrainGl, CrackTestCliffFieldAtLeast100Poses) {
  const Scene s = make_scene(cliff_field(161, 161, 2.0, 60.0f, 72), 5);
  const CrackResult c = crack_test(s, CrackFix::kSeams, 104, 2, "cliff");
  EXPECT_EQ(c.poses, 104);
  EXPECT_GT(c.inside, 104u * 256u * 144u / 5);
  EXPECT_EQ(c.holes, 0u) << "background pixels inside the terrain silhouette";
}

// The cheap alternative: skirts whose depth comes from the chunks' error bounds cover every gap.
TEST_F(TerrainGl, SkirtsAlsoLeaveNoCracksOnTheCliffField) {
  const Scene s = make_scene(cliff_field(161, 161, 2.0, 60.0f, 72), 5);
  const CrackResult c = crack_test(s, CrackFix::kSkirts, 52, 4, "skirts");
  EXPECT_GT(c.inside, 52u * 256u * 144u / 5);
  EXPECT_EQ(c.holes, 0u) << "background pixels inside the terrain silhouette";
}

TEST_F(TerrainGl, WithoutSeamsTheCrackTestSeesCracks) {
  const Scene s = make_scene(cliff_field(161, 161, 2.0, 60.0f, 72), 5);
  const CrackResult c = crack_test(s, CrackFix::kNone, 40, 3, "no_seams");
  EXPECT_GT(c.holes, 0u) << "the test must be able to fail";
}

// Projected vertical error of every terrain pixel, from the depth buffer, against the
// full-resolution surface: K * |y_drawn - h(x, z)| / distance <= tau.
TEST_F(TerrainGl, ProjectedErrorFromTheDepthBufferStaysWithinTau) {
  const Scene s = make_scene(fbm_field(161, 161, 3.0, 150.0f, 73), 17, 0.0f);
  TerrainRenderSettings rs;
  rs.receive_shadows = false;
  rs.debug_view = DebugView::kFlat;
  auto r = TerrainRenderer::create(s.tree, &s.field, rs);
  ASSERT_TRUE(r.ok());
  GlTarget target = GlTarget::create(256, 144);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (float tau : {0.5f, 1.0f, 2.0f, 4.0f}) {
    (*r)->settings().lod.max_pixel_error = tau;
    double worst = 0.0;
    std::size_t pixels = 0;
    for (int pose = 0; pose < 8; ++pose) {
      const double x = 100.0 + 280.0 * u(rng), z = 100.0 + 280.0 * u(rng);
      const render::Camera cam = camera_at({x, s.field.height(x, z) + 15.0 + 200.0 * u(rng), z},
                                           static_cast<float>(u(rng) * 6.283), glm::radians(-15.0f - 40.0f * static_cast<float>(u(rng))));
      (void)target.render(**r, cam, kMagenta);
      const Image depth = target.depth().value();
      const glm::mat4 inv = glm::inverse(cam.view_projection());
      const double k = TerrainRenderer::view_for(cam, target.size()).k;
      for (int py = 0; py < 144; ++py) {
        for (int px = 0; px < 256; ++px) {
          const float d = depth.at(px, py);
          if (d <= 0.0f) continue;  // cleared: no terrain
          const glm::vec4 ndc(2.0f * (px + 0.5f) / 256.0f - 1.0f, 1.0f - 2.0f * (py + 0.5f) / 144.0f, d, 1.0f);
          const glm::vec4 h = inv * ndc;
          const glm::dvec3 rel = glm::dvec3(h) / static_cast<double>(h.w);
          const glm::dvec3 world = rel + cam.position();
          const double gx = (world.x - s.field.origin().x) / s.field.spacing();
          const double gz = (world.z - s.field.origin().y) / s.field.spacing();
          if (gx < 0 || gz < 0 || gx > s.field.columns() - 1 || gz > s.field.rows() - 1) continue;
          const double err = std::fabs(world.y - full_resolution_height(s.field, gx, gz));
          worst = std::max(worst, k * err / glm::length(rel));
          ++pixels;
        }
      }
    }
    EXPECT_GT(pixels, 8u * 256u * 144u / 4);
    // 0.5 % for depth-buffer and reconstruction rounding.
    EXPECT_LE(worst, tau * 1.005) << "tau " << tau;
    EXPECT_GT(worst, 0.1 * tau) << "tau " << tau << ": the bound must be exercised";
    std::printf("tau %.1f: max projected error %.3f px over %zu pixels\n", tau, worst, pixels);
  }
}

}  // namespace
}  // namespace sylva::terrain

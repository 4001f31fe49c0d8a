// Grass in the render core's cascaded shadow maps (modules/render/README.md "Lighting and
// shadows"): blades cast their simulated, tessellated shape through draw(kShadow) inside
// ShadowMaps::render, and blades, clumps and the far ground layer receive.
// Invariants: shadow geometry = colour-pass geometry (same blade state, same tessellation);
// a box above the meadow darkens the blades in its analytic shadow and leaves the others lit.
#include <sylva/grass/far_field.hpp>
#include <sylva/grass/generator.hpp>
#include <sylva/grass/grass_field.hpp>
#include <sylva/render/frame_context.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/render/vertex_array.hpp>

#include "support/fields.hpp"
#include "support/gl_scene.hpp"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>

namespace sylva::grass {
namespace {

using GrassShadowGl = render::GlTest;

std::vector<float> read_layer(const render::ShadowMaps& maps, int layer) {
  const render::Texture& t = maps.depth_array();
  const int n = t.width();
  std::vector<float> out(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
  glGetTextureSubImage(t.id(), 0, 0, 0, layer, n, n, 1, GL_DEPTH_COMPONENT, GL_FLOAT,
                       static_cast<GLsizei>(out.size() * sizeof(float)), out.data());
  return out;
}

// An axis-aligned box that only casts (depth), drawn from gl_VertexID.
class BoxCaster final : public render::ShadowCaster {
 public:
  BoxCaster(const glm::dvec3& lo, const glm::dvec3& hi) : lo_(lo), hi_(hi) {
    render::register_shader_source("grass_test/box.vert", R"(#version 450 core
uniform mat4 u_vp;
uniform vec3 u_lo;
uniform vec3 u_hi;
const int kCorner[36] = int[](0,1,3, 0,3,2, 4,6,7, 4,7,5, 0,4,5, 0,5,1, 2,3,7, 2,7,6, 0,2,6, 0,6,4, 1,5,7, 1,7,3);
void main() {
  int c = kCorner[gl_VertexID];
  vec3 p = vec3((c & 1) != 0 ? u_hi.x : u_lo.x, (c & 2) != 0 ? u_hi.y : u_lo.y, (c & 4) != 0 ? u_hi.z : u_lo.z);
  gl_Position = u_vp * vec4(p, 1.0);
}
)");
    render::register_shader_source("grass_test/box.frag", "#version 450 core\nvoid main() {}\n");
    program_ = render::Program::create({"grass_test/box.vert", "grass_test/box.frag"}).value();
    vao_ = render::VertexArray::create();
  }
  void draw_shadow(const render::ShadowCasterContext& c) override {
    program_.set("u_vp", c.relative_view_projection);
    program_.set("u_lo", glm::vec3(lo_ - c.camera->position()));
    program_.set("u_hi", glm::vec3(hi_ - c.camera->position()));
    program_.use();
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 36);
    glBindVertexArray(0);
    if (c.stats) c.stats->draw_calls += 1;
  }

 private:
  glm::dvec3 lo_, hi_;
  render::Program program_;
  render::VertexArray vao_;
};

float taper_quadratic(float v) { return 1.0f - v * v; }

TEST_F(GrassShadowGl, ShadowPassCastsTheSimulatedTessellatedBlades) {
  // A few wide, tall blades on a 3 m x 3 m quad, bent hard by the wind; the shadow map's
  // covered texels must be the footprint of the blades the colour pass draws (the GPU state
  // read back), not of their rest pose.
  const glm::dvec3 origin(200.0, 10.0, -300.0);
  GroundMesh quad;
  std::vector<glm::vec3> pos = {{-1.5f, 0, -1.5f}, {1.5f, 0, -1.5f}, {1.5f, 0, 1.5f}, {-1.5f, 0, 1.5f}};
  std::vector<glm::vec3> nrm(4, glm::vec3(0, 1, 0));
  std::vector<std::uint32_t> idx = {0, 2, 1, 0, 3, 2};
  quad.positions = pos;
  quad.normals = nrm;
  quad.indices = idx;
  GrassFieldSettings fs;
  fs.density = 4.0f;
  BladeSettings bs;
  bs.height_min = 1.0f;
  bs.height_max = 1.3f;
  bs.width_min = 0.12f;
  bs.width_max = 0.18f;
  BladeSet set = generate_blades_on_mesh(fs, bs, quad, origin).value();
  ASSERT_GE(set.blades.size(), 20u);
  GrassRenderSettings rs;
  rs.cull.near_distance = 100.0f;
  rs.cull.thinning_start = 100.0f;
  rs.cull.orientation = false;
  rs.cull.pixels_per_segment = 1.0f;  // the full 16 segments: the CPU footprint below is the exact curve
  rs.cull.max_tess_level = 16.0f;
  auto field = GrassField::create(std::move(set), rs);
  ASSERT_TRUE(field.ok()) << field.error().message;

  testing::GlScene scene = testing::GlScene::create(128, 72);
  scene.lighting.sun_direction = glm::normalize(glm::vec3(0.25f, 1.0f, 0.15f));
  scene.camera.set_position(origin + glm::dvec3(0.0, 4.0, 7.0));
  scene.camera.look_at(origin);
  scene.wind = WindField(WindSettings{.direction_deg = 0.0f, .strength = 20.0f, .gust_amplitude = 0.0f, .turbulence_amplitude = 0.0f});
  double t = 0.0;
  for (int i = 0; i < 8; ++i) {
    t += 1.0 / 30.0;
    scene.render(*field, t, 1.0f / 30.0f);
  }
  render::ShadowSettings ss;
  ss.cascade_count = 1;
  ss.resolution = 1024;
  ss.max_distance = 16.0f;
  scene.shadows = render::ShadowMaps::create(ss).value();
  glm::mat4 vp(1.0f);
  render::CallbackShadowCaster record([&](const render::ShadowCasterContext& c) { vp = c.relative_view_projection; });
  render::ShadowCaster* extra[] = {&record};
  scene.render_shadows(*field, extra);
  EXPECT_EQ(field->shadow_stats().cascades, 1u);
  const std::vector<float> depth = read_layer(scene.shadows, 0);
  const int n = ss.resolution;
  {
    Image dimg(n, n, 1);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) dimg.at(x, n - 1 - y) = depth[static_cast<std::size_t>(y) * n + x] > 0.0f ? 1.0f : 0.0f;
    testing::save_png(dimg, "grass_shadow_map");
    std::printf("considered %llu texel %.4f m\n", static_cast<unsigned long long>(field->shadow_stats().considered),
                scene.shadows.cascades().cascades[0].texel_size);
  }

  // CPU footprint of the blades as the colour pass draws them (blade.tesc/.tese).
  const std::vector<Blade> blades = field->read_blades();
  const glm::vec3 to_rel(origin - scene.camera.position());
  auto texel = [&](const glm::vec3& local) {
    const glm::vec4 c = vp * glm::vec4(local + to_rel, 1.0f);
    const glm::vec2 uv = (glm::vec2(c) / c.w) * 0.5f + 0.5f;
    return glm::ivec2(glm::floor(uv * static_cast<float>(n)));
  };
  const float texel_m = scene.shadows.cascades().cascades[0].texel_size;
  // All texels the blade surface touches, and the centre-line texels where the blade is at
  // least two texels wide (rasterisation must cover those; thinner tips may fall between
  // texel centres).
  auto footprint = [&](bool rest, bool wide_only) {
    std::set<std::pair<int, int>> texels;
    for (const Blade& b : blades) {
      const glm::vec3 p0 = b.root();
      glm::vec3 p1 = b.control(), p2 = b.tip();
      if (rest) {
        p2 = p0 + glm::vec3(b.rest);
        p1 = p0 + b.up_dir() * glm::dot(glm::vec3(b.rest), b.up_dir());
      }
      const glm::vec3 w = blade_width_dir(b.up_dir(), b.orientation());
      const float narrowing = std::clamp((1.0f - b.rank()) / 0.1f, 0.0f, 1.0f);
      for (int i = 0; i <= 64; ++i) {
        const float v = static_cast<float>(i) / 64.0f;
        const float width = b.width() * narrowing * taper_quadratic(v);
        if (wide_only && width < 2.0f * texel_m) continue;
        for (int j = wide_only ? 6 : 0; j <= (wide_only ? 6 : 12); ++j) {
          const float u = static_cast<float>(j) / 12.0f - 0.5f;
          const glm::vec3 p = bezier_point(p0, p1, p2, v) + u * width * w;
          const glm::ivec2 tx = texel(p);
          texels.insert({tx.x, tx.y});
        }
      }
    }
    return texels;
  };
  auto covered = [&](int x, int y) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int xx = x + dx, yy = y + dy;
        if (xx >= 0 && yy >= 0 && xx < n && yy < n && depth[static_cast<std::size_t>(yy) * n + xx] > 0.0f) return true;
      }
    return false;
  };
  auto recall = [&](const std::set<std::pair<int, int>>& fp) {
    std::size_t hit = 0;
    for (const auto& [x, y] : fp) hit += covered(x, y);
    return static_cast<double>(hit) / static_cast<double>(fp.size());
  };
  const auto drawn = footprint(false, false);
  // Precision: covered texels lie within one texel of the drawn footprint.
  std::size_t cast = 0, explained = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      if (!(depth[static_cast<std::size_t>(y) * n + x] > 0.0f)) continue;
      ++cast;
      bool near = false;
      for (int dy = -1; dy <= 1 && !near; ++dy)
        for (int dx = -1; dx <= 1 && !near; ++dx) near = drawn.count({x + dx, y + dy}) > 0;
      explained += near;
    }
  ASSERT_GT(cast, 300u) << "the blades must cast";
  {
    Image fimg(n, n, 3);
    for (const auto& [x, y] : drawn)
      if (x >= 0 && y >= 0 && x < n && y < n) fimg.at(x, n - 1 - y, 0) = 1.0f;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        if (depth[static_cast<std::size_t>(y) * n + x] > 0.0f) fimg.at(x, n - 1 - y, 1) = 1.0f;
    testing::save_png(fimg, "grass_shadow_vs_cpu");
  }
  const double r_drawn = recall(footprint(false, true));
  const double precision = static_cast<double>(explained) / static_cast<double>(cast);
  const double r_rest = recall(footprint(true, true));
  std::printf("shadow texels %zu; recall drawn pose %.4f, rest pose %.4f; precision %.4f\n", cast, r_drawn, r_rest, precision);
  RecordProperty("recall_drawn", std::to_string(r_drawn));
  RecordProperty("recall_rest", std::to_string(r_rest));
  RecordProperty("precision", std::to_string(precision));
  EXPECT_GE(r_drawn, 0.97);
  EXPECT_GE(precision, 0.97);
  EXPECT_LT(r_rest, 0.8) << "the wind must bend the blades visibly in the shadow map (test sensitivity)";

  // Outside ShadowMaps::render, draw(kShadow) draws nothing; cast_shadows = false casts nothing.
  render::PassStats none;
  const render::FrameContext frame{scene.camera, t, 0.0f, scene.wind, scene.lighting, scene.size(), 0};
  field->draw(render::Pass::kShadow, frame, none);
  EXPECT_EQ(none.draw_calls, 0u);
  field->settings().cast_shadows = false;
  scene.render_shadows(*field);
  std::size_t after = 0;
  for (float d : read_layer(scene.shadows, 0)) after += d > 0.0f;
  EXPECT_EQ(after, 0u);
}

TEST_F(GrassShadowGl, BoxShadowDarkensBladesClumpsAndGroundUnderIt) {
  // Flat meadow; a 2 m x 2 m slab 3 m above it. Sun from (0.3, 1, 0.2): the slab's shadow on
  // the grass is the slab shifted by -(0.3, 0.2) * (3 - h) for a point at height h.
  const double extent = 40.0;
  HeightField flat(static_cast<int>(extent) + 21, static_cast<int>(extent) + 21, 1.0, {-10.0, -10.0});
  flat.update_range();
  GrassFieldSettings fs;
  fs.density = 300.0f;
  BladeSettings blade;  // wide blades so that the grass covers most pixels seen from above
  blade.width_min = 0.03f;
  blade.width_max = 0.05f;
  const GrassMaps maps = GrassMaps::uniform({{0.0, 0.0}, {extent, extent}});
  const glm::dvec3 origin(extent / 2, 0.0, extent / 2);
  GrassRenderSettings rs;
  rs.simulate = false;
  rs.cull.near_distance = 9.0f;
  rs.cull.thinning_start = 6.0f;
  FarFieldSettings far_settings;
  far_settings.clump_fade_in = 1.0f;
  far_settings.mid_distance = 13.0f;
  far_settings.mid_fade = 1.0f;
  auto field = GrassField::create(generate_blades(fs, blade, maps, flat, origin).value(), rs);
  ASSERT_TRUE(field.ok()) << field.error().message;
  auto far = FarField::create(fs, blade, maps, flat, origin, far_settings);
  ASSERT_TRUE(far.ok()) << far.error().message;
  far->set_near(rs.cull.near_distance, rs.physics.wind_response, 60.0f, rs.base_color, rs.tip_color);

  testing::GlScene scene = testing::GlScene::create(192, 192);
  scene.clear_color = {0.0f, 0.0f, 0.0f, 1.0f};  // background pixels are skipped below
  scene.lighting.sun_direction = glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f));
  // Three slabs: over the blades (3 m), over the clumps (11 m) and over the ground layer (15 m
  // from the camera along x).
  const glm::dvec3 cam = origin + glm::dvec3(0.0, 4.0, 0.0);
  scene.camera.perspective().fov_y = 2.0f * std::atan(1.0f);  // 90 degrees
  scene.camera.set_position(cam);
  scene.camera.look_at(origin + glm::dvec3(8.0, 0.0, 0.0));
  const double slabs_x[3] = {3.0, 10.5, 15.5};
  std::vector<BoxCaster> boxes;
  boxes.reserve(3);
  for (double sx : slabs_x) boxes.emplace_back(origin + glm::dvec3(sx - 1.0, 3.0, -1.0), origin + glm::dvec3(sx + 1.0, 3.2, 1.0));
  std::vector<render::ShadowCaster*> casters;
  for (BoxCaster& b : boxes) casters.push_back(&b);

  render::ShadowSettings ss;
  ss.cascade_count = 2;
  ss.resolution = 1024;
  ss.max_distance = 40.0f;
  const render::FrameContext frame{scene.camera, 0.0, 0.0f, scene.wind, scene.lighting, scene.size(), 0};
  auto draw_all = [&]() {
    scene.begin();
    field->update(frame);
    far->update(frame);
    scene.target.bind();
    field->draw_blades(scene.camera);
    far->draw_far(scene.camera, scene.wind, 0.0);
    return scene.read();
  };
  const Image unshadowed = draw_all();
  field->update(frame);
  scene.shadows = render::ShadowMaps::create(ss).value();
  field->settings().cast_shadows = false;  // the slabs only: grass-on-grass shadows are checked below
  scene.render_shadows(*field, casters);
  const Image slabs_only = draw_all();
  field->settings().cast_shadows = true;
  scene.render_shadows(*field, casters);
  const Image everything = draw_all();
  testing::save_png(unshadowed, "grass_shadow_off");
  testing::save_png(slabs_only, "grass_shadow_slabs");
  testing::save_png(everything, "grass_shadow_all");

  // Sample world points at blade mid height inside / well outside each slab's shadow.
  const glm::mat4 vp = scene.camera.view_projection();
  const int w = scene.size().x, h = scene.size().y;
  auto luminance = [](const Image& im, int x, int y) { return im.at(x, y, 0) + im.at(x, y, 1) + im.at(x, y, 2); };
  const glm::dvec2 shift = -glm::dvec2(0.3, 0.2) * (3.0 - 0.2);  // slab -> shadow at 0.2 m height
  for (int k = 0; k < 3; ++k) {
    double in_sum = 0.0, in_ref = 0.0, out_sum = 0.0, out_ref = 0.0, in_all = 0.0, out_all = 0.0;
    int in_n = 0, out_n = 0;
    for (double dz = -2.5; dz <= 2.5; dz += 0.1)
      for (double dx = -2.5; dx <= 2.5; dx += 0.1) {
        const glm::dvec2 q(slabs_x[k] + dx, dz);
        const glm::dvec2 s = q - glm::dvec2(slabs_x[k], 0.0) - shift;  // relative to the shadow centre
        const bool inside = std::abs(s.x) < 0.6 && std::abs(s.y) < 0.6;
        const bool outside = std::abs(s.x) > 1.6 || std::abs(s.y) > 1.6;
        if (!inside && !outside) continue;
        const glm::vec4 c = vp * glm::vec4(glm::vec3(origin + glm::dvec3(q.x, 0.2, q.y) - scene.camera.position()), 1.0f);
        if (c.w <= 0.0f) continue;
        // Image row 0 is the top of the picture.
        const int x = static_cast<int>((c.x / c.w * 0.5f + 0.5f) * w), y = static_cast<int>((0.5f - c.y / c.w * 0.5f) * h);
        if (x < 0 || y < 0 || x >= w || y >= h) continue;
        const double ref = luminance(unshadowed, x, y);
        if (ref < 0.02) continue;
        if (inside) {
          in_sum += luminance(slabs_only, x, y), in_ref += ref, in_all += luminance(everything, x, y), ++in_n;
        } else {
          out_sum += luminance(slabs_only, x, y), out_ref += ref, out_all += luminance(everything, x, y), ++out_n;
        }
      }
    ASSERT_GT(in_n, 10) << "slab " << k;
    ASSERT_GT(out_n, 10) << "slab " << k;
    const double in_ratio = in_sum / in_ref, out_ratio = out_sum / out_ref;
    std::printf("slab %d (%s): shadowed/unshadowed inside %.3f (%d px), outside %.3f (%d px); with grass casting: "
                "inside %.3f, outside %.3f\n",
                k, k == 0 ? "blades" : k == 1 ? "clumps" : "ground", in_ratio, in_n, out_ratio, out_n, in_all / in_ref,
                out_all / out_ref);
    RecordProperty("inside_ratio_" + std::to_string(k), std::to_string(in_ratio));
    RecordProperty("outside_ratio_" + std::to_string(k), std::to_string(out_ratio));
    EXPECT_LT(in_ratio, 0.75) << "slab " << k << " must darken what is under it";
    EXPECT_GT(out_ratio, 0.97) << "slab " << k << ": no acne or stray shadow outside";
    if (k == 0) {
      // Blades shadow each other: darker than the slab-only picture, still brighter than the slab's shadow.
      EXPECT_LT(out_all / out_ref, out_ratio - 0.01);
      EXPECT_GT(out_all / out_ref, in_ratio);
    }
  }
}

}  // namespace
}  // namespace sylva::grass

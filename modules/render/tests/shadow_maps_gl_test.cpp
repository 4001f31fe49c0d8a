// Cascaded shadow maps end to end on llvmpipe (issue 7): a ground plane with a box lit by the
// sun. Pixels are classified analytically (ray from the ground point toward the sun hits the
// box or not); shadowed/lit must match in >= 99 % of pixels away from a band of PCF radius +
// 1.5 texels around the analytic edge, so acne and peter-panning beyond one texel both fail it.
// Also: sub-texel camera motion leaves shadow-edge values unchanged (texel snapping, and the
// same test without snapping must change them), cascade selection by depth, cascade count and
// resolution changed at run time with the same programs, a vertical and a horizon sun, no NaN.
#include "support/render_test_support.hpp"

#include <sylva/render/buffer.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/lighting.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/shadow_maps.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/render/vertex_array.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace sylva::render {
namespace {

constexpr int kSize = 128;
// The cascade index the test shader writes to blue, times 0.1 (distinct up to 8 cascades in 8 bits).
constexpr float kCascadeCode = 0.1f;

struct Box {
  glm::vec3 lo, hi;
};

struct Vertex {
  glm::vec3 pos;
  glm::vec3 normal;
  float tag;  // 1 on the box, 0 on the ground
};

void add_quad(std::vector<Vertex>& v, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 n, float tag) {
  for (const glm::vec3& p : {a, b, c, a, c, d}) v.push_back({p, n, tag});
}

std::vector<Vertex> scene_vertices(const Box& box, float ground) {
  std::vector<Vertex> v;
  add_quad(v, {-ground, 0, -ground}, {-ground, 0, ground}, {ground, 0, ground}, {ground, 0, -ground}, {0, 1, 0}, 0.0f);
  const glm::vec3 l = box.lo, h = box.hi;
  add_quad(v, {l.x, h.y, l.z}, {l.x, h.y, h.z}, {h.x, h.y, h.z}, {h.x, h.y, l.z}, {0, 1, 0}, 1.0f);   // top
  add_quad(v, {l.x, l.y, l.z}, {h.x, l.y, l.z}, {h.x, l.y, h.z}, {l.x, l.y, h.z}, {0, -1, 0}, 1.0f);  // bottom
  add_quad(v, {l.x, l.y, h.z}, {h.x, l.y, h.z}, {h.x, h.y, h.z}, {l.x, h.y, h.z}, {0, 0, 1}, 1.0f);   // +z
  add_quad(v, {h.x, l.y, l.z}, {l.x, l.y, l.z}, {l.x, h.y, l.z}, {h.x, h.y, l.z}, {0, 0, -1}, 1.0f);  // -z
  add_quad(v, {h.x, l.y, h.z}, {h.x, l.y, l.z}, {h.x, h.y, l.z}, {h.x, h.y, h.z}, {1, 0, 0}, 1.0f);   // +x
  add_quad(v, {l.x, l.y, l.z}, {l.x, l.y, h.z}, {l.x, h.y, h.z}, {l.x, h.y, l.z}, {-1, 0, 0}, 1.0f);  // -x
  return v;
}

// Does the ray from p toward `sun` hit the box? (slab test)
bool ray_hits_box(glm::dvec3 p, glm::dvec3 d, const Box& b) {
  double t0 = 1e-6, t1 = 1e9;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-12) {
      if (p[a] < b.lo[a] || p[a] > b.hi[a]) return false;
      continue;
    }
    double ta = (b.lo[a] - p[a]) / d[a], tb = (b.hi[a] - p[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

void register_sources() {
  embedded::register_render_shaders();
  register_shader_source("rtest/shadow_scene.vert", R"(#version 450 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in float a_tag;
uniform mat4 u_model;            // camera-relative model
uniform mat4 u_view_projection;  // camera view-projection (or the cascade's, for depth)
out vec3 v_rel;
out vec3 v_normal;
out float v_tag;
void main() {
  vec4 rel = u_model * vec4(a_pos, 1.0);
  v_rel = rel.xyz;
  v_normal = a_normal;
  v_tag = a_tag;
  gl_Position = u_view_projection * rel;
}
)");
  register_shader_source("rtest/shadow_depth.frag", R"(#version 450 core
void main() {}
)");
  // Lighting (binding 0), shadows (2) and point lights (3) coexist in one program.
  register_shader_source("rtest/shadow_receive.frag", R"(#version 450 core
#include "render/lib/lighting.glsl"
#include "render/lib/shadows.glsl"
#include "render/lib/point_lights.glsl"
in vec3 v_rel;
in vec3 v_normal;
in float v_tag;
layout(location = 0) out vec4 o_color;
void main() {
  float s = sylva_shadow(v_rel, normalize(v_normal));
  o_color = vec4(s, v_tag, float(sylva_shadow_cascade(v_rel)) * 0.1, 1.0);  // kCascadeCode
}
)");
  // Fixed world points: pixel (x, y) of the target is the ground point u_origin_rel + (x*s, 0, y*s).
  register_shader_source("rtest/shadow_points.vert", R"(#version 450 core
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(p * 2.0 - 1.0, 0.5, 1.0);
}
)");
  register_shader_source("rtest/shadow_points.frag", R"(#version 450 core
#include "render/lib/shadows.glsl"
uniform vec3 u_origin_rel;  // world grid origin minus the camera position
uniform float u_spacing;
layout(location = 0) out vec4 o_color;
void main() {
  vec3 rel = u_origin_rel + vec3((gl_FragCoord.x - 0.5) * u_spacing, 0.0, (gl_FragCoord.y - 0.5) * u_spacing);
  o_color = vec4(sylva_shadow(rel, vec3(0.0, 1.0, 0.0)), float(sylva_shadow_cascade(rel)), 0.0, 1.0);
}
)");
}

class ShadowScene {
 public:
  explicit ShadowScene(const Box& box, float ground = 40.0f) : box_(box) {
    register_sources();
    const std::vector<Vertex> v = scene_vertices(box, ground);
    count_ = static_cast<GLsizei>(v.size());
    vbo_ = Buffer::immutable(std::span<const Vertex>(v));
    vao_ = VertexArray::create();
    vao_.attribute(0, 0, 3, GL_FLOAT, offsetof(Vertex, pos));
    vao_.attribute(1, 0, 3, GL_FLOAT, offsetof(Vertex, normal));
    vao_.attribute(2, 0, 1, GL_FLOAT, offsetof(Vertex, tag));
    vao_.vertex_buffer(0, vbo_, sizeof(Vertex));
    depth_ = test::build_or_fail({"rtest/shadow_scene.vert", "rtest/shadow_depth.frag"});
    receive_ = test::build_or_fail({"rtest/shadow_scene.vert", "rtest/shadow_receive.frag"});
    points_ = test::build_or_fail({"rtest/shadow_points.vert", "rtest/shadow_points.frag"});
    FramebufferDesc desc;
    desc.width = desc.height = kSize;
    desc.color_formats = {GL_RGBA32F};
    Result<Framebuffer> fb = Framebuffer::create(desc);
    EXPECT_TRUE(fb.ok());
    if (fb.ok()) target_ = std::move(*fb);
    caster_.emplace([this](const ShadowCasterContext& ctx) {
      EXPECT_EQ(active_shadow_cascade(), &ctx);  // what Drawable::draw(kShadow) would read
      depth_.use();
      depth_.set("u_model", ctx.camera->relative_model(origin_));
      depth_.set("u_view_projection", ctx.relative_view_projection);
      vao_.bind();
      glDrawArrays(GL_TRIANGLES, 0, count_);
      ctx.stats->draw_calls += 1;
      ctx.stats->triangles += static_cast<std::uint64_t>(count_ / 3);
    });
  }

  ShadowCaster* caster() { return &*caster_; }
  const Box& box() const { return box_; }

  // Renders the receiver view; returns RGBA32F: r = visibility, g = box tag, b = cascade/4.
  Image draw(ShadowMaps& maps, const Camera& cam) {
    target_.bind();
    target_.clear({0, 0, 0, 0}, 0.0f);
    maps.bind();
    receive_.use();
    receive_.set("u_model", cam.relative_model(origin_));
    receive_.set("u_view_projection", cam.view_projection());
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, count_);
    Result<Image> img = read_color(target_);
    EXPECT_TRUE(img.ok());
    return img.ok() ? std::move(*img) : Image{};
  }

  // Visibility of fixed ground points (grid origin world `grid`, spacing s metres per pixel).
  Image draw_points(ShadowMaps& maps, const Camera& cam, glm::dvec3 grid, float spacing) {
    target_.bind();
    target_.clear({0, 0, 0, 0}, 0.0f);
    glDisable(GL_DEPTH_TEST);
    maps.bind();
    points_.use();
    points_.set("u_origin_rel", glm::vec3(grid - cam.position()));
    points_.set("u_spacing", spacing);
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEnable(GL_DEPTH_TEST);
    Result<Image> img = read_color(target_);
    EXPECT_TRUE(img.ok());
    return img.ok() ? std::move(*img) : Image{};
  }

 private:
  Box box_;
  glm::dvec3 origin_{0.0};
  GLsizei count_ = 0;
  Buffer vbo_;
  VertexArray vao_;
  Program depth_, receive_, points_;
  Framebuffer target_;
  std::optional<CallbackShadowCaster> caster_;
};

Camera make_camera(glm::dvec3 pos, glm::dvec3 target) {
  Camera cam;
  cam.set_aspect(kSize, kSize);
  cam.perspective().near_plane = 0.1f;
  cam.set_position(pos);
  cam.look_at(target);
  return cam;
}

// World ground point seen through pixel (x, row) of `cam`, if the ray hits y = 0 in front.
std::optional<glm::dvec3> ground_point(const Camera& cam, int x, int row) {
  const glm::mat4 inv = glm::inverse(cam.view_projection());
  const float nx = (static_cast<float>(x) + 0.5f) / kSize * 2.0f - 1.0f;
  const float ny = 1.0f - (static_cast<float>(row) + 0.5f) / kSize * 2.0f;
  const glm::vec4 p = inv * glm::vec4(nx, ny, 0.5f, 1.0f);
  const glm::dvec3 dir = glm::normalize(glm::dvec3(glm::vec3(p) / p.w));
  if (dir.y > -1e-6) return std::nullopt;
  const double t = -cam.position().y / dir.y;
  return cam.position() + dir * t;
}

struct Classification {
  int shadow_total = 0, shadow_ok = 0, lit_total = 0, lit_ok = 0, nan = 0;
  double worst_lit = 1.0;
};

// Compares `img` with the analytic shadow of `box` for sun direction `sun`.
Classification classify(const Image& img, const Camera& cam, const ShadowMaps& maps, const Box& box, glm::vec3 sun) {
  Classification c;
  const glm::dvec3 l = glm::normalize(glm::dvec3(sun));
  const int pcf = maps.settings().pcf_radius;
  for (int row = 0; row < kSize; ++row) {
    for (int x = 0; x < kSize; ++x) {
      for (int ch = 0; ch < 4; ++ch) {
        if (!std::isfinite(img.at(x, row, ch))) ++c.nan;
      }
      if (img.at(x, row, 3) < 0.5f || img.at(x, row, 1) > 0.5f) continue;  // background or box
      std::optional<glm::dvec3> p = ground_point(cam, x, row);
      if (!p || std::abs(p->x) > 39.0 || std::abs(p->z) > 39.0) continue;
      p->y = 1e-4;  // just above the ground, so a horizontal sun ray still meets the box
      const int cascade = static_cast<int>(std::lround(img.at(x, row, 2) / kCascadeCode));
      if (cascade >= maps.cascades().count) continue;
      const double texel = maps.cascades().cascades[static_cast<std::size_t>(cascade)].texel_size;
      // Edge band in light-space texels (perpendicular to the sun, where texels live): the
      // filter half-width (pcf + 1 with the bilinear tap), the normal offset's edge shift
      // ((pcf + 1) cos^2(elevation), shadow_cascades.hpp) and ONE texel of tolerance.
      const double nl = l.y;
      const double shift = maps.settings().normal_offset * (pcf + 1) * (1.0 - nl * nl);
      const double band = (pcf + 1 + shift + 1.0) * texel;
      const bool in = ray_hits_box(*p, l, box);
      bool edge = false;
      const glm::dvec3 r(maps.cascades().light_right), u(maps.cascades().light_up);
      for (const glm::dvec3 o : {r * band, -r * band, u * band, -u * band, (r + u) * band * 0.7071, (r - u) * band * 0.7071,
                                 (u - r) * band * 0.7071, -(r + u) * band * 0.7071}) {
        if (ray_hits_box(*p + o, l, box) != in) edge = true;
      }
      if (edge) continue;
      const float s = img.at(x, row, 0);
      if (in) {
        ++c.shadow_total;
        if (s < 0.5f) ++c.shadow_ok;
      } else {
        ++c.lit_total;
        if (s > 0.98f) ++c.lit_ok;
        c.worst_lit = std::min(c.worst_lit, static_cast<double>(s));
      }
    }
  }
  return c;
}

void expect_matches_analytic(const Classification& c, const char* what) {
  EXPECT_EQ(c.nan, 0) << what;
  ASSERT_GT(c.shadow_total, 100) << what << ": too few pixels in the analytic shadow to judge";
  ASSERT_GT(c.lit_total, 1000) << what;
  EXPECT_GE(c.shadow_ok, c.shadow_total * 0.99) << what << ": shadowed " << c.shadow_ok << " of " << c.shadow_total;
  EXPECT_GE(c.lit_ok, c.lit_total * 0.99) << what << ": lit " << c.lit_ok << " of " << c.lit_total
                                          << " (acne), darkest lit " << c.worst_lit;
}

ShadowSettings test_settings() {
  ShadowSettings s;
  s.resolution = 512;
  s.cascade_count = 3;
  s.max_distance = 60.0f;
  return s;
}

using ShadowMapsGl = GlTest;

TEST_F(ShadowMapsGl, PlaneAndBoxMatchAnalyticShadow) {
  ShadowScene scene({{-2, 0, -2}, {2, 3, 2}});
  Result<ShadowMaps> maps = ShadowMaps::create(test_settings());
  ASSERT_TRUE(maps.ok()) << maps.error().describe();
  maps->add_caster(scene.caster());
  const Camera cam = make_camera({2.0, 6.0, 8.0}, {0.0, 0.0, -2.0});
  const glm::vec3 sun = sun_direction(-1.9f, 0.7f);
  PassStats stats;
  ASSERT_TRUE(maps->render(cam, sun, nullptr, &stats).ok());
  EXPECT_EQ(stats.draw_calls, 3u);  // one per cascade
  EXPECT_EQ(active_shadow_cascade(), nullptr);
  const Image img = scene.draw(*maps, cam);
  test::save_for_inspection(img, "shadow_plane_box");
  expect_matches_analytic(classify(img, cam, *maps, scene.box(), sun), "sun at 40 deg");
}

// The analytic check can fail: with every bias off the plane shadows itself (acne).
TEST_F(ShadowMapsGl, WithoutBiasTheCheckSeesAcne) {
  ShadowScene scene({{-2, 0, -2}, {2, 3, 2}});
  ShadowSettings settings = test_settings();
  settings.slope_bias = settings.min_bias = settings.normal_offset = 0.0f;
  Result<ShadowMaps> maps = ShadowMaps::create(settings);
  ASSERT_TRUE(maps.ok());
  maps->add_caster(scene.caster());
  const Camera cam = make_camera({-5.0, 7.0, 6.0}, {2.0, 0.0, -2.0});
  const glm::vec3 sun = sun_direction(0.8f, 0.25f);
  ASSERT_TRUE(maps->render(cam, sun).ok());
  const Classification c = classify(scene.draw(*maps, cam), cam, *maps, scene.box(), sun);
  ASSERT_GT(c.lit_total, 1000);
  EXPECT_LT(c.lit_ok, c.lit_total * 0.9) << "acne expected without bias";
}

TEST_F(ShadowMapsGl, LowSunAndTiltedViews) {
  ShadowScene scene({{-2, 0, -2}, {2, 3, 2}});
  Result<ShadowMaps> maps = ShadowMaps::create(test_settings());
  ASSERT_TRUE(maps.ok());
  maps->add_caster(scene.caster());
  const Camera cam = make_camera({-5.0, 7.0, 6.0}, {2.0, 0.0, -2.0});
  for (float elevation : {0.25f, 1.2f}) {
    const glm::vec3 sun = sun_direction(0.8f, elevation);
    ASSERT_TRUE(maps->render(cam, sun).ok());
    const Image img = scene.draw(*maps, cam);
    test::save_for_inspection(img, elevation < 0.5f ? "shadow_low_sun" : "shadow_high_sun");
    expect_matches_analytic(classify(img, cam, *maps, scene.box(), sun), elevation < 0.5f ? "low sun" : "high sun");
  }
}

// Peter-panning measured directly: on the ground just behind the box (the side away from the
// sun) the shadow must start at the box's face. Fixed ground points a quarter texel apart run
// outward from the face; the first one with visibility < 0.5 may be at most one shadow texel
// from the face. Points between one texel and the shadow's far end (minus the filter band) must
// all be shadowed.
struct ContactGap {
  double worst_gap_texels = 0.0;  // largest distance face -> first shadowed point, in texels
  int rows = 0, inside = 0, unshadowed_inside = 0, nan = 0;
  bool shadow_found = true;
};

ContactGap measure_contact_gap(ShadowScene& scene, ShadowMaps& maps, const Camera& cam, float elevation_deg) {
  ContactGap g;
  const float e = glm::radians(elevation_deg);
  const glm::vec3 sun(-std::cos(e), std::sin(e), 0.0f);  // shadow falls toward +x, behind the x = 2 face
  EXPECT_TRUE(maps.render(cam, sun).ok());
  // Texel of the cascade holding the face (checked against the cascade the shader picks).
  const float depth = glm::dot(glm::vec3(glm::dvec3(2.0, 0.0, 0.0) - cam.position()), cam.forward());
  int cascade = 0;
  while (cascade + 1 < maps.cascades().count &&
         depth >= maps.cascades().cascades[static_cast<std::size_t>(cascade)].far_depth) {
    ++cascade;
  }
  const double texel = maps.cascades().cascades[static_cast<std::size_t>(cascade)].texel_size;
  const double spacing = texel / 4.0;
  // Columns run along +x from the face, rows across the middle of the face (|z| <= 1).
  const glm::dvec3 grid(2.0 + 0.5 * spacing, 0.0, -std::min(1.0, 64.0 * spacing));
  const Image img = scene.draw_points(maps, cam, grid, static_cast<float>(spacing));
  const double length = 3.0 / std::tan(static_cast<double>(e));  // analytic shadow length behind the face
  const int pcf = maps.settings().pcf_radius;
  for (int row = 0; row < kSize && grid.z + row * spacing <= 1.0; ++row) {
    ++g.rows;
    EXPECT_EQ(static_cast<int>(std::lround(img.at(0, row, 1))), cascade) << "face not in the expected cascade";
    int first = -1;
    for (int x = 0; x < kSize; ++x) {
      const float v = img.at(x, row, 0);
      if (!std::isfinite(v)) ++g.nan;
      const double dist = (x + 0.5) * spacing;
      if (first < 0 && v < 0.5f) first = x;
      if (dist > texel && dist < length - (pcf + 2) * texel) {
        ++g.inside;
        if (!(v < 0.5f)) ++g.unshadowed_inside;
      }
    }
    if (first < 0) {
      g.shadow_found = false;
      first = kSize;
    }
    g.worst_gap_texels = std::max(g.worst_gap_texels, first * spacing / texel);
  }
  return g;
}

TEST_F(ShadowMapsGl, ShadowStartsAtTheCasterWithinOneTexel) {
  // A solid box and a 10 cm wall (thin casters are where depth bias detaches shadows), both with
  // their shadow-side face at x = 2 and 3 m high.
  for (const Box& caster : {Box{{-2, 0, -2}, {2, 3, 2}}, Box{{1.9f, 0, -2}, {2, 3, 2}}}) {
    const bool wall = caster.lo.x > 0.0f;
    ShadowScene scene(caster);
    Result<ShadowMaps> maps = ShadowMaps::create(test_settings());
    ASSERT_TRUE(maps.ok());
    maps->add_caster(scene.caster());
    const Camera cam = make_camera({6.0, 5.0, 6.0}, {2.0, 0.0, 0.0});
    for (const float elevation_deg : {70.0f, 40.0f, 14.0f}) {
      const ContactGap g = measure_contact_gap(scene, *maps, cam, elevation_deg);
      const char* what = wall ? "wall" : "box";
      ASSERT_GT(g.rows, 10);
      EXPECT_EQ(g.nan, 0);
      EXPECT_TRUE(g.shadow_found) << what << ", " << elevation_deg << " deg sun: no shadow behind the caster";
      EXPECT_LE(g.worst_gap_texels, 1.0) << what << ", " << elevation_deg << " deg sun: the shadow starts "
                                         << g.worst_gap_texels << " texels behind the face (peter-panning)";
      ASSERT_GT(g.inside, g.rows * 8);
      EXPECT_EQ(g.unshadowed_inside, 0) << what << ", " << elevation_deg << " deg sun";
    }
    if (wall) {
      // The check can fail: a constant depth bias of 10 texels detaches the wall's shadow.
      maps->settings().min_bias = 0.1f;
      const ContactGap detached = measure_contact_gap(scene, *maps, cam, 40.0f);
      EXPECT_GT(detached.worst_gap_texels, 2.0) << "a 10-texel depth bias should show peter-panning";
    }
  }
}

TEST_F(ShadowMapsGl, SunStraightUpCastsShadowBelowFloatingBox) {
  ShadowScene scene({{-1.5f, 1.0f, -1.5f}, {1.5f, 2.0f, 1.5f}});
  Result<ShadowMaps> maps = ShadowMaps::create(test_settings());
  ASSERT_TRUE(maps.ok());
  maps->add_caster(scene.caster());
  const Camera cam = make_camera({0.0, 7.0, 7.0}, {0.0, 0.0, 0.0});
  const glm::vec3 sun(0.0f, 1.0f, 0.0f);  // exactly vertical: lookAt with up = +y would be NaN
  ASSERT_TRUE(maps->render(cam, sun).ok());
  for (int i = 0; i < maps->cascades().count; ++i) {
    const glm::mat4& m = maps->cascades().cascades[static_cast<std::size_t>(i)].relative_texture;
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) ASSERT_TRUE(std::isfinite(m[a][b]));
    }
  }
  const Image img = scene.draw(*maps, cam);
  test::save_for_inspection(img, "shadow_vertical_sun");
  expect_matches_analytic(classify(img, cam, *maps, scene.box(), sun), "vertical sun");
}

TEST_F(ShadowMapsGl, SunAtHorizonGivesLongFiniteShadows) {
  // The box reaches 1 m below the ground so the analytic edge band (which also looks below the
  // surface when the sun is level) sees the same shadow there.
  ShadowScene scene({{-2, -1, -2}, {2, 3, 2}});
  ShadowSettings settings = test_settings();
  Result<ShadowMaps> maps = ShadowMaps::create(settings);
  ASSERT_TRUE(maps.ok());
  maps->add_caster(scene.caster());
  const Camera cam = make_camera({7.0, 8.0, 7.0}, {-3.0, 0.0, -3.0});
  const glm::vec3 sun = sun_direction(-2.4f, 0.0f);  // exactly on the horizon
  ASSERT_TRUE(maps->render(cam, sun).ok());
  Image img = scene.draw(*maps, cam);
  test::save_for_inspection(img, "shadow_horizon_sun");
  const Classification c = classify(img, cam, *maps, scene.box(), sun);
  EXPECT_EQ(c.nan, 0);
  // A grazing sun lights nothing on the plane (N.L = 0), but the box's shadow must still be
  // there: it runs to the end of the shadowed range.
  ASSERT_GT(c.shadow_total, 100);
  EXPECT_GE(c.shadow_ok, c.shadow_total * 0.99) << c.shadow_ok << " of " << c.shadow_total;
  // Just above the horizon (1 degree) the plane is lit outside the long shadow.
  const glm::vec3 low = sun_direction(-2.4f, 0.0175f);
  ASSERT_TRUE(maps->render(cam, low).ok());
  img = scene.draw(*maps, cam);
  test::save_for_inspection(img, "shadow_one_degree_sun");
  expect_matches_analytic(classify(img, cam, *maps, scene.box(), low), "1 degree sun");
}

TEST_F(ShadowMapsGl, SubTexelCameraMotionKeepsShadowEdges) {
  ShadowScene scene({{-2, 0, -2}, {2, 3, 2}});
  for (const bool snap : {true, false}) {
    ShadowSettings settings = test_settings();
    settings.snap_to_texels = snap;
    settings.blend_fraction = 0.0f;  // cross-fade weights follow the camera depth by design
    Result<ShadowMaps> maps = ShadowMaps::create(settings);
    ASSERT_TRUE(maps.ok());
    maps->add_caster(scene.caster());
    const glm::vec3 sun = sun_direction(-1.9f, 0.7f);
    const glm::dvec3 grid(-5.0, 0.0, -6.0);  // 128 x 128 points, 8 cm apart, over the shadow
    float worst = 0.0f;
    int edge_pixels = 0;
    std::optional<Image> first;
    for (int step = 0; step < 6; ++step) {
      // Steps of ~0.3 texels of the cascade holding the grid, sideways and forward.
      const double d = 0.015 * step;
      const Camera cam = make_camera({2.0 + d, 6.0 + 0.5 * d, 8.0 - 0.7 * d}, {0.0 + d, 0.0, -2.0 - 0.7 * d});
      ASSERT_TRUE(maps->render(cam, sun).ok());
      Image img = scene.draw_points(*maps, cam, grid, 0.08f);
      if (!first) {
        first = std::move(img);
        for (int y = 0; y < kSize; ++y) {
          for (int x = 0; x < kSize; ++x) {
            const float s = first->at(x, y, 0);
            if (s > 0.02f && s < 0.98f) ++edge_pixels;
          }
        }
        continue;
      }
      int same_cascade = 0;
      for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
          if (first->at(x, y, 1) != img.at(x, y, 1)) continue;  // a split moved past this point
          ++same_cascade;
          worst = std::max(worst, std::abs(first->at(x, y, 0) - img.at(x, y, 0)));
        }
      }
      EXPECT_GT(same_cascade, kSize * kSize * 9 / 10);
    }
    EXPECT_GT(edge_pixels, 100) << "grid must straddle the shadow edge";
    if (snap) {
      EXPECT_LT(worst, 1e-3f) << "snapped shadow edges moved";
    } else {
      EXPECT_GT(worst, 0.05f) << "unsnapped maps should shimmer (otherwise the test proves nothing)";
    }
  }
}

TEST_F(ShadowMapsGl, CascadeSelectionFollowsViewDepth) {
  ShadowScene scene({{-2, 0, -2}, {2, 3, 2}});
  for (const int count : {4, kMaxShadowCascades}) {
    SCOPED_TRACE(count);
    ShadowSettings settings = test_settings();
    settings.cascade_count = count;
    Result<ShadowMaps> maps = ShadowMaps::create(settings);
    ASSERT_TRUE(maps.ok());
    maps->add_caster(scene.caster());
    const Camera cam = make_camera({0.0, 3.0, 10.0}, {0.0, 0.0, -2.0});
    ASSERT_TRUE(maps->render(cam, sun_direction(1.0f, 0.8f)).ok());
    const Image img = scene.draw(*maps, cam);
    int checked = 0, agree = 0;
    float nearest = INFINITY, farthest = 0.0f;  // view depths of the checked ground
    std::vector<int> seen(static_cast<std::size_t>(count) + 1, 0);
    for (int row = 0; row < kSize; ++row) {
      for (int x = 0; x < kSize; ++x) {
        if (img.at(x, row, 3) < 0.5f || img.at(x, row, 1) > 0.5f) continue;
        const std::optional<glm::dvec3> p = ground_point(cam, x, row);
        if (!p || std::abs(p->x) > 39.0 || std::abs(p->z) > 39.0) continue;
        const float depth = glm::dot(glm::vec3(*p - cam.position()), cam.forward());
        nearest = std::min(nearest, depth);
        farthest = std::max(farthest, depth);
        int expected = maps->cascades().count;
        for (int i = maps->cascades().count - 1; i >= 0; --i) {
          if (depth < maps->cascades().cascades[static_cast<std::size_t>(i)].far_depth) expected = i;
        }
        const int got = static_cast<int>(std::lround(img.at(x, row, 2) / kCascadeCode));
        ++checked;
        if (got == expected) ++agree;
        ++seen[static_cast<std::size_t>(std::clamp(got, 0, count))];
      }
    }
    ASSERT_GT(checked, 2000);
    EXPECT_GE(agree, checked * 0.995) << agree << " of " << checked;
    // Every cascade whose depth range the visible ground crosses is used (eight cascades start
    // nearer than the nearest ground in view).
    for (int i = 0; i < count; ++i) {
      const ShadowCascade& c = maps->cascades().cascades[static_cast<std::size_t>(i)];
      if (c.far_depth < nearest + 0.1f || c.near_depth > farthest - 0.1f) continue;
      EXPECT_GT(seen[static_cast<std::size_t>(i)], 0) << "cascade " << i << " never used";
    }
    if (count == 4) {
      EXPECT_GT(std::min({seen[0], seen[1], seen[2], seen[3]}), 0) << "with four cascades the ground crosses all";
    }
    EXPECT_GT(seen[static_cast<std::size_t>(count - 1)], 0) << "the last cascade never used";
    // Splits grow with distance (practical scheme) and each cascade starts where the last ended.
    for (int i = 1; i < count; ++i) {
      const ShadowCascade& a = maps->cascades().cascades[static_cast<std::size_t>(i - 1)];
      const ShadowCascade& b = maps->cascades().cascades[static_cast<std::size_t>(i)];
      EXPECT_EQ(a.far_depth, b.near_depth);
      EXPECT_GT(b.far_depth - b.near_depth, a.far_depth - a.near_depth);
      EXPECT_GT(b.texel_size, a.texel_size);
    }
  }
}

TEST_F(ShadowMapsGl, CascadeCountAndResolutionChangeAtRunTime) {
  ShadowScene scene({{-2, 0, -2}, {2, 3, 2}});
  Result<ShadowMaps> maps = ShadowMaps::create(test_settings());
  ASSERT_TRUE(maps.ok());
  maps->add_caster(scene.caster());
  const Camera cam = make_camera({2.0, 6.0, 8.0}, {0.0, 0.0, -2.0});
  const glm::vec3 sun = sun_direction(-1.9f, 0.7f);
  for (const auto& [count, resolution] :
       {std::pair{1, 512}, std::pair{4, 256}, std::pair{kMaxShadowCascades, 256}, std::pair{2, 1024}, std::pair{3, 512}}) {
    maps->settings().cascade_count = count;
    maps->settings().resolution = resolution;
    PassStats stats;
    ASSERT_TRUE(maps->render(cam, sun, nullptr, &stats).ok());
    EXPECT_EQ(maps->allocated_layers(), count);
    EXPECT_EQ(maps->resolution(), resolution);
    EXPECT_EQ(stats.draw_calls, static_cast<std::uint64_t>(count));
    const Image img = scene.draw(*maps, cam);  // the same programs, never recompiled
    int max_cascade = 0;
    for (int row = 0; row < kSize; ++row) {
      for (int x = 0; x < kSize; ++x) {
        if (img.at(x, row, 3) > 0.5f) {
          max_cascade = std::max(max_cascade, static_cast<int>(std::lround(img.at(x, row, 2) / kCascadeCode)));
        }
      }
    }
    EXPECT_LE(max_cascade, count) << "a cascade beyond the count was selected";
    expect_matches_analytic(classify(img, cam, *maps, scene.box(), sun), "after a count change");
  }
  // A resolution beyond the GL limit is a clear error and keeps the old maps.
  maps->settings().resolution = 1 << 20;
  const Status st = maps->render(cam, sun);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().message.find("shadow.resolution"), std::string::npos) << st.error().message;
  EXPECT_EQ(maps->resolution(), 512);
}

TEST_F(ShadowMapsGl, DisabledShadowsAreLitAndCastersUnregister) {
  ShadowScene scene({{-2, 0, -2}, {2, 3, 2}});
  ShadowSettings settings = test_settings();
  Result<ShadowMaps> maps = ShadowMaps::create(settings);
  ASSERT_TRUE(maps.ok());
  maps->add_caster(scene.caster());
  maps->add_caster(scene.caster());
  EXPECT_EQ(maps->caster_count(), 1u);
  const Camera cam = make_camera({2.0, 6.0, 8.0}, {0.0, 0.0, -2.0});
  maps->settings().enabled = false;
  ASSERT_TRUE(maps->render(cam, sun_direction(-1.9f, 0.7f)).ok());
  Image img = scene.draw(*maps, cam);
  for (int row = 0; row < kSize; ++row) {
    for (int x = 0; x < kSize; ++x) {
      if (img.at(x, row, 3) > 0.5f) {
        ASSERT_EQ(img.at(x, row, 0), 1.0f);
      }
    }
  }
  maps->settings().enabled = true;
  maps->remove_caster(scene.caster());
  EXPECT_EQ(maps->caster_count(), 0u);
  ASSERT_TRUE(maps->render(cam, sun_direction(-1.9f, 0.7f)).ok());
  img = scene.draw(*maps, cam);
  for (int row = 0; row < kSize; ++row) {
    for (int x = 0; x < kSize; ++x) {
      if (img.at(x, row, 3) > 0.5f && img.at(x, row, 1) < 0.5f) {
        ASSERT_GT(img.at(x, row, 0), 0.98f);
      }
    }
  }
}

// Receivers can tell a ShadowMaps' block enabled or disabled on the CPU (no read-back, which
// waits for a hardware GPU): the flag follows every upload, a move keeps it with the buffer, and a
// destroyed or overwritten ShadowMaps forgets its (reusable) GL name.
TEST_F(ShadowMapsGl, ItsBlockSaysOnTheCpuWhetherItIsEnabled) {
  const auto bound_block = [] {
    GLint id = 0;
    glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, kShadowUniformBinding, &id);
    return static_cast<GLuint>(id);
  };
  ShadowScene scene({{-2, 0, -2}, {2, 3, 2}});
  Result<ShadowMaps> created = ShadowMaps::create(test_settings());
  ASSERT_TRUE(created.ok());
  ShadowMaps maps = std::move(*created);
  maps.bind();
  const GLuint id = bound_block();
  ASSERT_NE(id, 0u);
  EXPECT_EQ(shadow_block_enabled(id), false) << "created: disabled until a render";
  maps.add_caster(scene.caster());
  const Camera cam = make_camera({2.0, 6.0, 8.0}, {0.0, 0.0, -2.0});
  ASSERT_TRUE(maps.render(cam, sun_direction(-1.9f, 0.7f)).ok());
  EXPECT_EQ(shadow_block_enabled(id), true);
  maps.settings().enabled = false;
  ASSERT_TRUE(maps.render(cam, sun_direction(-1.9f, 0.7f)).ok());
  EXPECT_EQ(shadow_block_enabled(id), false);
  maps.remove_caster(scene.caster());
  const Buffer own = make_disabled_shadow_block();
  EXPECT_EQ(shadow_block_enabled(own.id()), std::nullopt) << "a host's own block: unknown";
  GLuint other_id = 0;
  {
    ShadowMaps moved = std::move(maps);
    EXPECT_EQ(shadow_block_enabled(id), false) << "the entry moves with the buffer";
    Result<ShadowMaps> other = ShadowMaps::create(test_settings());
    ASSERT_TRUE(other.ok());
    other->bind();
    other_id = bound_block();
    moved = std::move(*other);  // moved's first buffer is deleted here
    EXPECT_EQ(shadow_block_enabled(id), std::nullopt) << "a deleted name is forgotten";
    EXPECT_EQ(shadow_block_enabled(other_id), false);
  }
  ASSERT_NE(other_id, 0u);
  EXPECT_EQ(shadow_block_enabled(other_id), std::nullopt) << "destroyed: forgotten";
}

}  // namespace
}  // namespace sylva::render

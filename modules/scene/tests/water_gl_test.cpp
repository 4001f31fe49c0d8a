// The terrain's water plane (terrain/water.hpp; seed 002 §3.3, issue 15), driven as a user does:
// a scene file with a valley whose floor lies below terrain.water.level, opened like the player,
// switched with set_param like the editor. Raw linear HDR (tone mapping and MSAA off) at 160x90.
//  (a) pixels whose ground lies > 1 m under the level change and turn bluer; ground above the
//      level is bit-identical to the picture without water;
//  (b) Fresnel: at a grazing view the water is closer to the sky in the mirrored direction than
//      looking steeply down;
//  (c) depth tint: deep water has lost more red (over the bed's colour) than shallow water and
//      is darker;
//  (d) no NaN/Inf, also with extreme settings and at the horizon;
//  (e) water off (absent, or enabled and switched off again) draws the same bits as no water;
//  (f) model_terrain.water (the general-model terrain's section) draws the same plane.
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/sky.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/scene.hpp>

#include "scene_test_files.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>

using namespace sylva;
using namespace sylva::scene;

namespace {

using WaterGl = render::GlTest;
constexpr glm::ivec2 kSize(160, 90);

struct Frame {
  Image color;
  Image depth;
  render::Camera camera;
};

// The valley generator: a rolling meadow of a few metres in the middle, mountains at the edges.
nlohmann::json valley_scene(const nlohmann::json& water) {
  nlohmann::json j = nlohmann::json::parse(R"({
    "sylva_scene": 1,
    "camera": {"position": [0, 60, 110], "yaw_deg": 0, "pitch_deg": -35, "fov_deg": 60},
    "sun": {"fog_density": 0.0},
    "render": {"msaa_samples": 1, "tone_map": false, "shadows": {"enabled": false}},
    "terrain": {"size": 600, "resolution": 129, "height": 120, "generator": "valley",
                "noise": {"seed": 3}, "tree": {"leaf_dimension": 17}}})");
  if (!water.is_null()) j["terrain"]["water"] = water;
  return j;
}

std::unique_ptr<Scene> open_valley(const scene::testing::TestDir& dir, const nlohmann::json& water) {
  const auto file = dir.path / "valley.json";
  std::ofstream(file) << valley_scene(water).dump(2);
  return scene::testing::open_scene_file(file);
}

Frame render_frame(Scene& scene, const CameraView& view) {
  auto fb = render::Framebuffer::create({.width = kSize.x, .height = kSize.y, .color_formats = {GL_RGBA32F}}).value();
  render::FrameProfiler profiler;
  render::Camera cam = scene.make_camera(view, kSize);
  scene.update(cam, 0.5, 0.0f, kSize);
  scene.render(fb, profiler);
  return {render::read_color(fb).value(), render::read_depth(fb).value(), cam};
}

glm::vec3 rgb(const Image& im, int x, int y) { return {im.at(x, y, 0), im.at(x, y, 1), im.at(x, y, 2)}; }
float luma(glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

glm::vec3 pixel_ray(const render::Camera& cam, int x, int y) {
  const glm::mat4 inv = glm::inverse(cam.view_projection());
  const float nx = (static_cast<float>(x) + 0.5f) / kSize.x * 2.0f - 1.0f;
  const float ny = 1.0f - (static_cast<float>(y) + 0.5f) / kSize.y * 2.0f;  // Image row 0 is the top
  const glm::vec4 p = inv * glm::vec4(nx, ny, 1.0f, 1.0f);
  return glm::normalize(glm::vec3(p) / p.w);
}

// World height of the ground seen at (x, y), from the depth of the frame without water.
double ground_y(const Frame& f, int x, int y) {
  const float d = f.depth.at(x, y, 0);
  if (d <= 0.0f) return std::nan("");
  const glm::mat4 inv = glm::inverse(f.camera.view_projection());
  const float nx = (static_cast<float>(x) + 0.5f) / kSize.x * 2.0f - 1.0f;
  const float ny = 1.0f - (static_cast<float>(y) + 0.5f) / kSize.y * 2.0f;
  const glm::vec4 p = inv * glm::vec4(nx, ny, d, 1.0f);
  return f.camera.position().y + static_cast<double>(p.y / p.w);
}

int non_finite(const Image& im) {
  int n = 0;
  for (float v : im.data()) n += std::isfinite(v) ? 0 : 1;
  return n;
}

bool same_bits(const Image& a, const Image& b) {
  return a.data().size() == b.data().size() &&
         std::memcmp(a.data().data(), b.data().data(), a.data().size() * sizeof(float)) == 0;
}

void set(Scene& scene, const std::string& key, const std::string& value) {
  Status s = scene.set_param(key, value);
  EXPECT_TRUE(s.ok()) << key << ": " << s.error().message;
}

struct Fixture {
  scene::testing::TestDir dir{"water_gl"};
  std::unique_ptr<Scene> scene;
  double level = 0.0;
  Fixture() {
    scene = open_valley(dir, nlohmann::json{{"ripple_strength", 0.0}});
    // 8 m above the meadow's middle: its hollows flood, the slopes stay dry.
    if (scene) level = scene->ground_height(0.0, 0.0) + 8.0;
  }
  CameraView view() const { return scene->document().camera; }
  void water(bool on) {
    set(*scene, "terrain.water.level", std::to_string(level));
    set(*scene, "terrain.water.enabled", on ? "true" : "false");
  }
};

}  // namespace

TEST_F(WaterGl, FloodsGroundBelowTheLevelOnlyAndTintsByDepth) {
  Fixture fx;
  ASSERT_TRUE(fx.scene);
  const Frame dry = render_frame(*fx.scene, fx.view());
  fx.water(true);
  const Frame wet = render_frame(*fx.scene, fx.view());
  EXPECT_EQ(non_finite(wet.color), 0);

  int under = 0, under_changed = 0, above = 0, above_changed = 0;
  int shallow = 0, deep = 0;
  double bluer_dry = 0.0, bluer_wet = 0.0;
  double shallow_red = 0.0, deep_red = 0.0, shallow_luma = 0.0, deep_luma = 0.0;
  for (int y = 0; y < kSize.y; ++y) {
    for (int x = 0; x < kSize.x; ++x) {
      const double g = ground_y(dry, x, y);
      if (std::isnan(g)) continue;
      const glm::vec3 a = rgb(dry.color, x, y), b = rgb(wet.color, x, y);
      if (g > fx.level + 0.01) {
        ++above;
        above_changed += a != b ? 1 : 0;
      } else if (g < fx.level - 1.0) {
        ++under;
        under_changed += glm::length(b - a) > 0.02f * glm::length(a) ? 1 : 0;
        bluer_dry += a.b - a.r;
        bluer_wet += b.b - b.r;
        // Beer-Lambert takes red first: the wet red/green ratio over the bed's falls with depth.
        const double red_left = (b.r / std::max(b.g, 1e-6f)) / std::max(a.r / std::max(a.g, 1e-6f), 1e-6f);
        const double depth = fx.level - g;
        if (depth < 1.5) {
          ++shallow, shallow_red += red_left, shallow_luma += luma(b);
        } else if (depth > 6.0) {
          ++deep, deep_red += red_left, deep_luma += luma(b);
        }
      }
    }
  }
  std::cout << "level " << fx.level << " m; ground pixels under it: " << under << " (changed " << under_changed
            << "), above: " << above << " (changed " << above_changed << "); shallow " << shallow << " deep " << deep
            << "\n";
  ASSERT_GT(under, 300) << "the view shows flooded ground";
  ASSERT_GT(above, 300) << "the view shows dry ground";
  EXPECT_GE(under_changed, under * 98 / 100) << "(a) ground under the level is covered by water";
  EXPECT_EQ(above_changed, 0) << "(a) ground above the level is untouched";
  EXPECT_GT(bluer_wet / under, bluer_dry / under + 0.005) << "(a) water is bluer than the bed";

  ASSERT_GT(shallow, 30);
  ASSERT_GT(deep, 30);
  std::cout << "red/green over the bed's: shallow " << shallow_red / shallow << " deep " << deep_red / deep
            << "; luminance: shallow "
            << shallow_luma / shallow << " deep " << deep_luma / deep << "\n";
  EXPECT_LT(deep_red / deep, 0.7 * shallow_red / shallow) << "(c) deep water absorbed more red";
  EXPECT_LT(deep_luma / deep, shallow_luma / shallow) << "(c) deep water is darker";
}

TEST_F(WaterGl, FresnelGrazingViewMirrorsTheSky) {
  Fixture fx;
  ASSERT_TRUE(fx.scene);
  fx.water(true);
  // The same lake, seen steeply from above and grazing from 1 m above the surface; the relative
  // distance of each water pixel to the sky in its mirrored direction.
  const auto sky_distance = [&](const CameraView& view, float max_down) {
    const Frame f = render_frame(*fx.scene, view);
    EXPECT_EQ(non_finite(f.color), 0);
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < kSize.y; ++y) {
      for (int x = 0; x < kSize.x; ++x) {
        const glm::vec3 d = pixel_ray(f.camera, x, y);
        if (d.y > -0.01f || d.y < -max_down) continue;
        // A water pixel: the ground behind lies under the level (or there is none), and the plane
        // is within 5 km.
        const double g = ground_y(f, x, y);
        if (!(std::isnan(g) || g < fx.level - 2.0) || (fx.level - f.camera.position().y) / d.y > 5000.0) continue;
        const glm::vec3 sky = render::sky_radiance(fx.scene->lighting(), glm::reflect(d, glm::vec3(0, 1, 0)));
        const glm::vec3 c = rgb(f.color, x, y);
        sum += glm::length(c - sky) / glm::length(sky);
        ++n;
      }
    }
    return n > 0 ? sum / n : 1e9;
  };
  CameraView steep = fx.view(), grazing = fx.view();
  steep.position = {0.0, fx.level + 40.0, 0.0};
  steep.pitch_deg = -85.0f;
  grazing.position = {0.0, fx.level + 1.0, 20.0};
  grazing.pitch_deg = -2.0f;
  grazing.fov_deg = 20.0f;
  steep.height_mode = grazing.height_mode = HeightMode::kAbsolute;
  // Grazing: rays 0.6 to 4 degrees under the horizon (Schlick: F ~ 0.7 to 0.95); steep: all.
  const double d_steep = sky_distance(steep, 1.0f), d_grazing = sky_distance(grazing, 0.07f);
  std::cout << "relative distance to the mirrored sky: steep " << d_steep << ", grazing " << d_grazing << "\n";
  EXPECT_LT(d_grazing, 0.6 * d_steep) << "(b) Fresnel: grazing water reflects the sky";
}

TEST_F(WaterGl, FiniteWithExtremeSettingsAndAtTheHorizon) {
  Fixture fx;
  ASSERT_TRUE(fx.scene);
  fx.water(true);
  set(*fx.scene, "terrain.water.absorption", "[0, 0, 0]");
  set(*fx.scene, "terrain.water.shore_fade_m", "0");
  set(*fx.scene, "terrain.water.ripple_strength", "1");
  set(*fx.scene, "terrain.water.ripple_scale_m", "0.05");
  set(*fx.scene, "terrain.water.sun_glint", "10");
  CameraView horizon = fx.view();
  horizon.position = {0.0, fx.level + 0.01, 0.0};
  horizon.pitch_deg = 0.0f;
  horizon.height_mode = HeightMode::kAbsolute;
  for (const CameraView& v : {fx.view(), horizon}) {
    const Frame f = render_frame(*fx.scene, v);
    EXPECT_EQ(non_finite(f.color), 0) << "(d) NaN/Inf pixels";
  }
  set(*fx.scene, "terrain.water.absorption", "[100, 100, 100]");
  set(*fx.scene, "terrain.water.level", "1e6");  // camera under water: no water drawn, still finite
  EXPECT_EQ(non_finite(render_frame(*fx.scene, fx.view()).color), 0);
}

TEST_F(WaterGl, OffDrawsTheSameBitsAsNoWater) {
  scene::testing::TestDir dir("water_gl_off");
  auto plain = open_valley(dir, nullptr);
  ASSERT_TRUE(plain);
  const CameraView view = plain->document().camera;
  const Frame reference = render_frame(*plain, view);
  plain.reset();
  auto off = open_valley(dir, nlohmann::json{{"enabled", false}, {"level", 30.0}, {"absorption", {1, 1, 1}}});
  ASSERT_TRUE(off);
  EXPECT_TRUE(same_bits(render_frame(*off, view).color, reference.color)) << "(e) water.enabled = false";
  set(*off, "terrain.water.enabled", "true");
  EXPECT_FALSE(same_bits(render_frame(*off, view).color, reference.color)) << "the water shows at 30 m";
  set(*off, "terrain.water.enabled", "false");
  EXPECT_TRUE(same_bits(render_frame(*off, view).color, reference.color)) << "(e) switched off again";
}

// The same renderer under the general-model terrain (model_terrain.water): a mesh terrain alone
// (a 400 m square sheet at y = 0 from an OBJ file), switched on from the editor's path, is covered
// where it lies under the level and the picture stays finite.
TEST_F(WaterGl, ModelTerrainWaterDraws) {
  scene::testing::TestDir dir("water_gl_model");
  std::ofstream(dir.path / "sheet.obj") << "v -200 0 -200\nv 200 0 -200\nv 200 0 200\nv -200 0 200\nf 1 3 2\nf 1 4 3\n";
  nlohmann::json j = nlohmann::json::parse(R"({
    "sylva_scene": 1,
    "camera": {"position": [0, 30, 120], "yaw_deg": 0, "pitch_deg": -30, "fov_deg": 60},
    "sun": {"fog_density": 0.0},
    "render": {"msaa_samples": 1, "tone_map": false, "shadows": {"enabled": false}},
    "model_terrain": {"file": "sheet.obj", "tree": {"levels": 1}}})");
  std::ofstream(dir.path / "sheet.json") << j.dump(2);
  auto scene = scene::testing::open_scene_file(dir.path / "sheet.json");
  ASSERT_TRUE(scene);
  const CameraView view = scene->document().camera;
  const Frame dry = render_frame(*scene, view);
  set(*scene, "model_terrain.water.level", "2");
  set(*scene, "model_terrain.water.enabled", "true");
  const Frame wet = render_frame(*scene, view);
  EXPECT_EQ(non_finite(wet.color), 0);
  int changed = 0, sheet = 0;
  for (int y = 0; y < kSize.y; ++y) {
    for (int x = 0; x < kSize.x; ++x) {
      if (std::isnan(ground_y(dry, x, y))) continue;  // the sky
      ++sheet;
      changed += rgb(wet.color, x, y) != rgb(dry.color, x, y) ? 1 : 0;
    }
  }
  ASSERT_GT(sheet, 3000);
  EXPECT_EQ(changed, sheet) << "model_terrain.water covers the sheet 2 m under it";
}

// The editor's Properties panel is generated from Scene::describe_params() (param_widgets.hpp):
// every water key is listed with help text and a finite range, the level in metres; a value
// outside the range is refused naming the key.
TEST_F(WaterGl, EditorListsTheWaterKeysWithHelpRangeAndUnit) {
  Fixture fx;
  ASSERT_TRUE(fx.scene);
  int listed = 0;
  for (const ParamDescriptor& p : fx.scene->describe_params()) {
    if (p.path.rfind("terrain.water.", 0) != 0) continue;
    ++listed;
    EXPECT_STRNE(p.info.help, "") << p.path;
    if (p.type_name() != "bool") {
      EXPECT_TRUE(std::isfinite(p.info.min) && std::isfinite(p.info.max)) << p.path;
    }
    if (p.path == "terrain.water.level") {
      EXPECT_STREQ(p.info.unit, "m");
    }
    if (p.path == "terrain.water.absorption") {
      EXPECT_STREQ(p.info.unit, "1/m");
    }
  }
  EXPECT_EQ(listed, 9) << "enabled, level, color, absorption, shore_fade_m, ripple_*, sun_glint";
  const Status bad = fx.scene->set_param("terrain.water.ripple_strength", "5");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("terrain.water.ripple_strength"), std::string::npos) << bad.error().message;
}

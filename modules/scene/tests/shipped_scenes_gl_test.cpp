// Every scene shipped in scenes/ and the embedded default scene load, assemble and render
// headless: the picture has no NaN/Inf pixel, is not empty (the scene's modules drew geometry
// that covers pixels, and the image is not one flat colour), and every module of the scene
// reports work in the opaque pass. Scenes asking for a module this build left out are skipped.
//
// Kept small (96x54, 3 frames) so all scenes together stay within seconds at -O2.
//
// Issue 19's picture invariants on the same scenes, rendered as the player shows them (tone
// mapping on, as shipped) at 160x90 with MSAA off for speed:
//  - below the horizon line no pixel is the clear colour (the ground or the atmosphere's haze
//    covers it, never an empty band): the scene clears to magenta (debug show_holes) for this;
//  - the tone-mapped output clips no channel (>= 254/255 or <= 1/255) over more than 2 % of the
//    pixels, the sun disk (1.5 deg around the sun) excluded.
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/render/tone_mapping.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace sylva;
using namespace sylva::scene;

namespace {

// "default" is the embedded scene; other names are files in scenes/.
std::vector<std::string> shipped_scene_names() {
  std::vector<std::string> names{"default"};
  for (const auto& entry : fs::directory_iterator(SYLVA_SCENES_DIR)) {
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin() + 1, names.end());
  return names;
}

class ShippedScene : public render::GlTest, public ::testing::WithParamInterface<std::string> {};

constexpr float kMaxClippedShare = 0.02f;
constexpr float kSunDiskDeg = 1.5f;

glm::vec3 pixel_direction(const render::Camera& cam, glm::ivec2 size, int x, int row) {
  const glm::mat4 inv = glm::inverse(cam.view_projection());
  const float nx = (static_cast<float>(x) + 0.5f) / static_cast<float>(size.x) * 2.0f - 1.0f;
  const float ny = 1.0f - (static_cast<float>(row) + 0.5f) / static_cast<float>(size.y) * 2.0f;
  const glm::vec4 p = inv * glm::vec4(nx, ny, 1.0f, 1.0f);
  return glm::normalize(glm::vec3(p) / p.w);
}

// Three frames at 1/30 s, as the player's first frames.
void run_frames(Scene& scene, const render::Camera& camera, glm::ivec2 size, const render::Framebuffer& fb,
                render::FrameProfiler& profiler) {
  for (int i = 0; i < 3; ++i) {
    scene.update(camera, 1.0 / 30.0 * i, 1.0f / 30.0f, size);
    scene.render(fb, profiler);
  }
}

Result<SceneDocument> load_named(const std::string& name, std::vector<std::string>& warnings) {
  if (name == "default") return default_scene(warnings);
  return SceneDocument::load(fs::path(SYLVA_SCENES_DIR) / (name + ".json"), warnings);
}

}  // namespace

// Invariants: loads without warnings, renders with finite pixels, not empty, every module draws.
TEST_P(ShippedScene, LoadsAndRendersHeadless) {
  std::vector<std::string> warnings;
  auto doc = load_named(GetParam(), warnings);
  if (!doc.ok() && doc.error().message.find("built without") != std::string::npos) GTEST_SKIP() << doc.error().message;
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  std::vector<std::string> modules;
  for (const ModuleSection& s : doc->modules()) modules.push_back(s.name);
  ASSERT_FALSE(modules.empty()) << "a shipped scene shows something";

  auto scene = Scene::create(std::move(*doc));
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  const glm::ivec2 size(96, 54);
  auto fb = render::Framebuffer::create({.width = size.x, .height = size.y, .color_formats = {GL_RGBA16F}});
  ASSERT_TRUE(fb.ok()) << fb.error().message;
  render::FrameProfiler profiler;
  const render::Camera camera = (*scene)->make_camera((*scene)->document().camera, size);
  run_frames(**scene, camera, size, *fb, profiler);
  auto frame = profiler.flush();
  ASSERT_TRUE(frame.has_value());
  const SceneFrameStats stats = split_frame_stats(*frame);

  auto image = render::read_color(*fb);
  ASSERT_TRUE(image.ok()) << image.error().message;
  int non_finite = 0;
  double sum = 0.0, sum2 = 0.0;
  const int n = image->width() * image->height();
  for (int y = 0; y < image->height(); ++y) {
    for (int x = 0; x < image->width(); ++x) {
      float luminance = 0.0f;
      for (int c = 0; c < 3; ++c) {
        const float v = image->at(x, y, c);
        if (!std::isfinite(v)) ++non_finite;
        else luminance += v / 3.0f;
      }
      sum += luminance;
      sum2 += static_cast<double>(luminance) * luminance;
    }
  }
  EXPECT_EQ(non_finite, 0) << "NaN/Inf pixels";
  const double mean = sum / n;
  const double stddev = std::sqrt(std::max(0.0, sum2 / n - mean * mean));
  EXPECT_GT(mean, 0.02) << "not black";
  EXPECT_GT(stddev, 0.01) << "not one flat colour";

  ASSERT_TRUE(stats.passes.count("opaque"));
  EXPECT_GT(stats.passes.at("opaque").triangles, 0u);
  for (const std::string& m : modules) {
    ASSERT_TRUE(stats.modules.count(m)) << m;
    ASSERT_TRUE(stats.modules.at(m).count("opaque")) << m;
    const render::PassStats& s = stats.modules.at(m).at("opaque");
    EXPECT_GT(s.draw_calls, 0u) << m << " drew nothing";
    EXPECT_GT(s.triangles + s.instances, 0u) << m << " drew nothing";
  }
}

// Invariants: no pixel below the horizon is the clear colour; no channel clips over 2 % of pixels.
TEST_P(ShippedScene, NoEmptyBandAndNoLargeClipping) {
  std::vector<std::string> warnings;
  auto doc = load_named(GetParam(), warnings);
  if (!doc.ok() && doc.error().message.find("built without") != std::string::npos) GTEST_SKIP() << doc.error().message;
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  ASSERT_TRUE(doc->render.tone_map) << "shipped scenes are tone-mapped";
  doc->render.msaa_samples = 1;
  auto scene = Scene::create(std::move(*doc));
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  (*scene)->debug().show_holes = true;
  const glm::ivec2 size(160, 90);
  auto fb = render::Framebuffer::create({.width = size.x, .height = size.y, .color_formats = {GL_RGBA8}});
  ASSERT_TRUE(fb.ok()) << fb.error().message;
  render::FrameProfiler profiler;
  const render::Camera camera = (*scene)->make_camera((*scene)->document().camera, size);
  run_frames(**scene, camera, size, *fb, profiler);
  auto image = render::read_color(*fb);
  ASSERT_TRUE(image.ok()) << image.error().message;

  const render::Lighting& lighting = (*scene)->lighting();
  const render::ToneMapSettings& tone = (*scene)->document().render.tone;
  glm::vec3 clear;
  const glm::vec3 magenta(1.0f, 0.0f, 1.0f);
  for (int c = 0; c < 3; ++c) clear[c] = std::round(render::tone_map_channel(magenta[c], tone) * 255.0f) / 255.0f;
  const glm::vec3 sun = glm::normalize(lighting.sun_direction);
  const float cos_sun = std::cos(glm::radians(kSunDiskDeg));

  int below = 0, clear_below = 0, counted = 0;
  std::array<int, 3> high{}, low{};
  for (int row = 0; row < size.y; ++row) {
    for (int x = 0; x < size.x; ++x) {
      const glm::vec3 dir = pixel_direction(camera, size, x, row);
      const glm::vec3 px(image->at(x, row, 0), image->at(x, row, 1), image->at(x, row, 2));
      if (dir.y < 0.0f) {
        ++below;
        if (glm::all(glm::lessThan(glm::abs(px - clear), glm::vec3(0.5f / 255.0f)))) ++clear_below;
      }
      if (glm::dot(dir, sun) > cos_sun) continue;
      ++counted;
      for (int c = 0; c < 3; ++c) {
        high[c] += px[c] >= 253.5f / 255.0f;
        low[c] += px[c] <= 1.5f / 255.0f;
      }
    }
  }
  EXPECT_EQ(clear_below, 0) << clear_below << " of " << below << " pixels below the horizon show the clear colour";
  for (int c = 0; c < 3; ++c) {
    EXPECT_LE(high[c], kMaxClippedShare * counted) << "channel " << c << " clipped white on " << high[c] << " of " << counted;
    EXPECT_LE(low[c], kMaxClippedShare * counted) << "channel " << c << " crushed black on " << low[c] << " of " << counted;
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, ShippedScene, ::testing::ValuesIn(shipped_scene_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

// Scene::render leaves the scene's depth in the caller's target on every path: straight into the
// target, through the MSAA target, through the HDR target for tone mapping, or both. sylva-bench
// reads it for its silhouette metric (foreground = depth written, reversed Z clears to 0). With
// tone mapping (the default) only colour reached the target, so its depth stayed as allocated:
// zeros on Mesa (every frame read as all background), garbage on NVIDIA (an H200 gave 921 600
// NaN of 1280x720 and the bench refused every reference frame).
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/scene.hpp>

#include "scene_test_files.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

using namespace sylva;
using namespace sylva::scene;

namespace {

using TargetDepthGl = render::GlTest;
constexpr glm::ivec2 kSize(96, 54);

// Ground in the lower part of the view, sky above: the camera looks slightly down.
Image rendered_depth(bool tone_map, int msaa) {
  const scene::testing::TestDir dir("target_depth");
  const auto file = dir.path / "ground.json";
  nlohmann::json j = nlohmann::json::parse(R"({
    "sylva_scene": 1,
    "camera": {"position": [0, 20, 0], "height_mode": "above_ground", "yaw_deg": 0, "pitch_deg": -15, "fov_deg": 60},
    "render": {"shadows": {"enabled": false}},
    "ground": {}})");
  j["render"]["tone_map"] = tone_map;
  j["render"]["msaa_samples"] = msaa;
  std::ofstream(file) << j.dump(2);
  std::unique_ptr<Scene> scene = scene::testing::open_scene_file(file);
  auto fb = render::Framebuffer::create({.width = kSize.x, .height = kSize.y, .color_formats = {GL_RGBA8}}).value();
  // What an implementation may hold in fresh storage: the test fills it with a value no frame writes.
  fb.clear({0, 0, 0, 1}, 0.123f);
  render::FrameProfiler profiler;
  const render::Camera cam = scene->make_camera(scene->document().camera, kSize);
  scene->update(cam, 0.5, 0.0f, kSize);
  scene->render(fb, profiler);
  return render::read_depth(fb).value();
}

TEST_F(TargetDepthGl, EveryPathLeavesTheScenesDepthInTheTarget) {
  const Image reference = rendered_depth(false, 1);  // straight into the target
  std::size_t ground = 0;
  for (int y = 0; y < kSize.y; ++y) {
    for (int x = 0; x < kSize.x; ++x) {
      const float d = reference.at(x, y, 0);
      ASSERT_TRUE(std::isfinite(d));
      ASSERT_NE(d, 0.123f) << x << "," << y;
      ground += d > 0.0f ? 1 : 0;
    }
  }
  ASSERT_GT(ground, static_cast<std::size_t>(kSize.x * kSize.y / 4)) << "the ground must fill part of the view";
  ASSERT_LT(ground, static_cast<std::size_t>(kSize.x * kSize.y)) << "the sky must show too";
  for (const auto& [tone_map, msaa] : {std::pair{true, 1}, std::pair{false, 4}, std::pair{true, 4}}) {
    const Image depth = rendered_depth(tone_map, msaa);
    std::size_t differ = 0, stale = 0;
    for (int y = 0; y < kSize.y; ++y) {
      for (int x = 0; x < kSize.x; ++x) {
        const float d = depth.at(x, y, 0);
        stale += d == 0.123f || !std::isfinite(d) ? 1 : 0;
        differ += (d > 0.0f) != (reference.at(x, y, 0) > 0.0f) ? 1 : 0;
      }
    }
    EXPECT_EQ(stale, 0u) << "tone_map " << tone_map << ", msaa " << msaa;
    // MSAA's depth resolve takes one sample: the silhouette may move by a pixel along the horizon.
    EXPECT_LE(differ, static_cast<std::size_t>(kSize.x * 2)) << "tone_map " << tone_map << ", msaa " << msaa;
  }
}

}  // namespace

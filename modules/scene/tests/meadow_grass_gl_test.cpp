// The shipped meadow (scenes/meadow.json) is grass to the horizon: of the pixels that show the
// ground (they change when the ground is added to an empty sky), at least kMinCovered change
// again when the grass is added (blades, clumps or the grass's ground layer drew there), and at
// least kMinGreen of them are grass-coloured (green the strongest channel). Measured 2026-11-27
// (2-core VM, llvmpipe): 100 % covered, 99.96 % green; with the far field ending at the 60 x 80 m
// blade rectangle and no under-layer (the meadow before issue #19) the slope ahead is bare
// ground: 59.9 % covered, which fails. (The built-in ground is green too, so the colour check
// alone would not see bare ground; it catches grass that turns black, grey or blue.)
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace sylva;
using namespace sylva::scene;

namespace {

using MeadowGrassGl = render::GlTest;

constexpr double kMinCovered = 0.97;
constexpr double kMinGreen = 0.95;

Image render_document(const nlohmann::json& j, const render::Camera* camera_in, render::Camera* camera_out, glm::ivec2 size) {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::from_text(j.dump(), "meadow variant", warnings);
  EXPECT_TRUE(doc.ok()) << doc.error().message;
  auto scene = Scene::create(std::move(*doc));
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  auto fb = render::Framebuffer::create({.width = size.x, .height = size.y, .color_formats = {GL_RGBA16F}}).value();
  render::FrameProfiler profiler;
  const render::Camera camera = camera_in ? *camera_in : (*scene)->make_camera((*scene)->document().camera, size);
  if (camera_out) *camera_out = camera;
  for (int i = 0; i < 2; ++i) {
    (*scene)->update(camera, 1.0 / 30.0 * i, 1.0f / 30.0f, size);
    (*scene)->render(fb, profiler);
  }
  return render::read_color(fb).value();
}

bool differs(const Image& a, const Image& b, int x, int y) {
  double d = 0.0, m = 0.0;
  for (int c = 0; c < 3; ++c) {
    d += std::abs(a.at(x, y, c) - b.at(x, y, c));
    m += std::abs(a.at(x, y, c)) + std::abs(b.at(x, y, c));
  }
  return d > 0.02 * m + 1e-4;
}

}  // namespace

TEST_F(MeadowGrassGl, GrassCoversTheVisibleGroundToTheHorizon) {
  if (!find_module("grass") || !find_module("ground")) GTEST_SKIP() << "needs the grass and ground modules";
  std::ifstream in(fs::path(SYLVA_SCENES_DIR) / "meadow.json");
  ASSERT_TRUE(in.good());
  const nlohmann::json meadow = nlohmann::json::parse(in);
  ASSERT_TRUE(meadow.contains("grass"));
  nlohmann::json bare = meadow;
  bare.erase("grass");
  nlohmann::json sky = bare;
  sky.erase("ground");

  const glm::ivec2 size(320, 180);
  render::Camera camera;
  const Image with_grass = render_document(meadow, nullptr, &camera, size);
  const Image ground_only = render_document(bare, &camera, nullptr, size);
  const Image sky_only = render_document(sky, &camera, nullptr, size);

  std::size_t ground = 0, covered = 0, green = 0;
  for (int y = 0; y < size.y; ++y) {
    for (int x = 0; x < size.x; ++x) {
      if (!differs(ground_only, sky_only, x, y)) continue;
      ++ground;
      covered += differs(with_grass, ground_only, x, y) ? 1 : 0;
      const float r = with_grass.at(x, y, 0), g = with_grass.at(x, y, 1), b = with_grass.at(x, y, 2);
      green += (g >= r && g >= b) ? 1 : 0;
    }
  }
  ASSERT_GT(ground, static_cast<std::size_t>(size.x * size.y / 4)) << "the meadow's view is mostly ground";
  const double covered_share = static_cast<double>(covered) / static_cast<double>(ground);
  const double green_share = static_cast<double>(green) / static_cast<double>(ground);
  std::printf("ground pixels %zu, covered by grass %.4f, grass-coloured %.4f\n", ground, covered_share, green_share);
  RecordProperty("covered_share", std::to_string(covered_share));
  RecordProperty("green_share", std::to_string(green_share));
  EXPECT_GE(covered_share, kMinCovered);
  EXPECT_GE(green_share, kMinGreen);
}

// MSAA (render.msaa_samples): the colour passes of a frame are multisampled and resolved into the
// caller's target. A flat square ground seen from above has two slanted side edges; a
// single-sampled frame puts every pixel on one side (ground or sky colour), a 4x frame gives the
// pixels the edges cross a colour between the two (fractional coverage). Leaves switch to
// alpha-to-coverage on multisampled targets (vegetation AlphaMode::kAuto, tested there).
#include <sylva/core/image_metrics.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene.hpp>

#include <gtest/gtest.h>

#include <cmath>

using namespace sylva;
using namespace sylva::scene;

namespace {

using MsaaGl = render::GlTest;

std::string scene_text(int samples) {
  return R"({"camera": {"position": [0, 110, 90], "yaw_deg": 0, "pitch_deg": -50, "fov_deg": 60},
    "sun": {"fog_density": 0},
    "render": {"msaa_samples": )" + std::to_string(samples) + R"(, "shadows": {"enabled": false}},
    "ground": {"size": 100, "resolution": 17, "generator": "flat"}})";
}

Image render_frame(int samples, glm::ivec2 size) {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::from_text(scene_text(samples), "msaa.json", warnings);
  EXPECT_TRUE(doc.ok()) << doc.error().message;
  auto scene = Scene::create(std::move(*doc));
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  auto fb = render::Framebuffer::create({.width = size.x, .height = size.y, .color_formats = {GL_RGBA32F}}).value();
  render::FrameProfiler profiler;
  const render::Camera camera = (*scene)->make_camera((*scene)->document().camera, size);
  (*scene)->update(camera, 0.0, 0.0f, size);
  (*scene)->render(fb, profiler);
  return render::read_color(fb).value();
}

glm::vec3 rgb(const Image& image, int x, int y) { return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)}; }

// Whether v lies on the segment from a to b, well inside it, where a and b differ clearly (ground
// against background; the ground's own texture varies far less).
bool between(glm::vec3 v, glm::vec3 a, glm::vec3 b) {
  const glm::vec3 ab = b - a;
  const float length2 = glm::dot(ab, ab);
  if (length2 < 0.15f * 0.15f) return false;
  const float t = glm::dot(v - a, ab) / length2;
  return t > 0.15f && t < 0.85f && glm::length(v - (a + t * ab)) < 0.05f;
}

// Edge pixels partly covered by each side: between their neighbours left and right, or above and
// below.
int fractional_edge_pixels(const Image& image) {
  int count = 0;
  for (int y = 1; y + 1 < image.height(); ++y) {
    for (int x = 1; x + 1 < image.width(); ++x) {
      const glm::vec3 v = rgb(image, x, y);
      const bool across = between(v, rgb(image, x - 1, y), rgb(image, x + 1, y));
      const bool along = between(v, rgb(image, x, y - 1), rgb(image, x, y + 1));
      count += (across || along) ? 1 : 0;
    }
  }
  return count;
}

}  // namespace

TEST_F(MsaaGl, FourSamplesGiveFractionalCoverageAtEdges) {
  const glm::ivec2 size(192, 108);
  const Image aliased = render_frame(1, size);
  const Image msaa = render_frame(4, size);
  const int aliased_edges = fractional_edge_pixels(aliased);
  const int msaa_edges = fractional_edge_pixels(msaa);
  EXPECT_LE(aliased_edges, 4) << "a single-sampled frame has no partly covered pixels";
  EXPECT_GE(msaa_edges, 30) << "the two slanted side edges cross about 50 rows each";
  EXPECT_EQ(find_non_finite(msaa).count, 0u);
}

TEST_F(MsaaGl, SamplesOutsideOneTwoFourEightAreRefused) {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::from_text(R"({"render": {"msaa_samples": 3}})", "m.json", warnings);
  ASSERT_FALSE(doc.ok());
  EXPECT_NE(doc.error().message.find("render.msaa_samples: 3 is not 1, 2, 4 or 8"), std::string::npos)
      << doc.error().message;
}

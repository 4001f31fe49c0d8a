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

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

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

// Renders `frames` frames of a scene text into a float target (the forest hands its instances
// over at the first update, so plant scenes need two) and reads the last one back.
Image render_text(const std::string& text, glm::ivec2 size, int frames = 1) {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::from_text(text, "msaa.json", warnings);
  EXPECT_TRUE(doc.ok()) << doc.error().message;
  auto scene = Scene::create(std::move(*doc));
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  auto fb = render::Framebuffer::create({.width = size.x, .height = size.y, .color_formats = {GL_RGBA32F}}).value();
  render::FrameProfiler profiler;
  const render::Camera camera = (*scene)->make_camera((*scene)->document().camera, size);
  for (int i = 0; i < frames; ++i) {
    (*scene)->update(camera, 0.0, 0.0f, size);
    (*scene)->render(fb, profiler);
  }
  return render::read_color(fb).value();
}

Image render_frame(int samples, glm::ivec2 size) { return render_text(scene_text(samples), size); }

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

namespace {

// Leaves (alpha-to-coverage) and grass blades against the sky. The same frame without the
// vegetation is the background: a pixel the plants cover fully differs from it by the plant's
// contrast against the sky, a pixel an edge crosses by a share of it. Returns the pixels over sky
// that differ from the background by more than 0.02 but less than half the typical (80th
// percentile) difference of the covered pixels.
struct Coverage {
  int covered = 0;
  int partial = 0;
};

Coverage partial_coverage_over_sky(const std::string& plants, float eye_height, int samples) {
  const glm::ivec2 size(192, 108);
  auto frame = [&](bool with_plants) {
    const std::string text = R"({"camera": {"position": [0, )" + std::to_string(eye_height) + R"(, 30], "height_mode": "above_ground", "yaw_deg": 0, "pitch_deg": 12, "fov_deg": 50},
      "sun": {"fog_density": 0}, "environment": {"time_of_day_h": 12},
      "render": {"msaa_samples": )" + std::to_string(samples) + R"(, "shadows": {"enabled": false}},
      "ground": {"size": 400, "resolution": 17, "generator": "flat"})" + (with_plants ? ", " + plants : std::string()) + "}";
    return render_text(text, size, 2);
  };
  const Image background = frame(false), image = frame(true);
  std::vector<float> differences;
  for (int y = 0; y < size.y; ++y) {
    for (int x = 0; x < size.x; ++x) {
      const glm::vec3 b = rgb(background, x, y);
      if (!(b.b > b.g)) continue;  // over the sky only (the ground is greener than blue)
      const glm::vec3 d = glm::abs(rgb(image, x, y) - b);
      differences.push_back(std::max({d.r, d.g, d.b}));
    }
  }
  std::vector<float> covered;
  for (float d : differences) if (d > 0.02f) covered.push_back(d);
  Coverage c;
  c.covered = static_cast<int>(covered.size());
  if (covered.empty()) return c;
  std::sort(covered.begin(), covered.end());
  const float typical = covered[covered.size() * 8 / 10];
  for (float d : covered) c.partial += d < 0.5f * typical ? 1 : 0;
  return c;
}

}  // namespace

TEST_F(MsaaGl, LeafAndBladeEdgesGetFractionalCoverage) {
  struct Case {
    const char* module;
    std::string section;
    float eye_height;  // metres above the ground: blades stand against the sky only from low down
  };
  const Case cases[] = {
      {"vegetation", R"("vegetation": {"area_min": [-12, -12], "area_max": [12, 12], "trees_per_hectare": 120, "min_spacing": 6,
                                      "leaf_texture_size": 64, "species": "broadleaf"})", 1.2f},
      {"grass", R"("grass": {"area_min": [-10, 20], "area_max": [10, 29], "field": {"density": 300}})", 0.1f},
  };
  for (const Case& c : cases) {
    if (!find_module(c.module)) continue;
    const Coverage aliased = partial_coverage_over_sky(c.section, c.eye_height, 1);
    const Coverage msaa = partial_coverage_over_sky(c.section, c.eye_height, 4);
    SCOPED_TRACE(c.module);
    std::cout << c.module << ": partial pixels over the sky 1x " << aliased.partial << " of " << aliased.covered << ", 4x "
              << msaa.partial << " of " << msaa.covered << "\n";
    ASSERT_GT(msaa.covered, 200) << "the plants stand against the sky";
    // Single-sampled: leaf cards cut by the alpha test and blades are all-or-nothing per pixel;
    // the few partial pixels are translucent or dimly lit parts. 4x: every edge pixel is partial.
    EXPECT_GE(msaa.partial, 2 * aliased.partial + 50)
        << "1x: " << aliased.partial << " partial of " << aliased.covered << "; 4x: " << msaa.partial << " of " << msaa.covered;
  }
}

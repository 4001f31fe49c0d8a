// Stability of the GL-free scene parts under extreme input. Each test names its invariant.
#include <sylva/scene/camera_path.hpp>
#include <sylva/scene/environment.hpp>
#include <sylva/scene/forest_placement.hpp>
#include <sylva/scene/height_source.hpp>
#include <sylva/scene/scene_document.hpp>

#include <gtest/gtest.h>

#include <cmath>

using namespace sylva;
using namespace sylva::scene;

namespace {
bool finite(const CameraView& v) {
  return std::isfinite(v.position.x) && std::isfinite(v.position.y) && std::isfinite(v.position.z) &&
         std::isfinite(v.yaw_deg) && std::isfinite(v.pitch_deg) && std::isfinite(v.fov_deg);
}
}  // namespace

// Invariant: camera paths stay finite and within pitch/fov limits for far coordinates, huge
// times, nearly coincident key times and wild yaw values.
TEST(SceneStability, CameraPathsStayFiniteAndBounded) {
  CameraPath p;
  p.settings.interpolation = PathInterpolation::kCatmullRom;
  const double far = 1.0e8;
  p.keys = {{0.0, {{far, 10.0, -far}, 719.0f, 89.9f, 1.0f, HeightMode::kAbsolute}},
            {1e-6, {{far + 1.0, 10.0, -far}, -719.0f, -89.9f, 170.0f, HeightMode::kAbsolute}},
            {1.0e7, {{-far, 1e6, far}, 0.0f, 0.0f, 60.0f, HeightMode::kAbsolute}}};
  ASSERT_TRUE(p.validate("p").ok());
  for (double t : {-1e9, 0.0, 5e-7, 1e-6, 0.5, 123456.789, 9.99e6, 1e7, 1e12}) {
    const CameraView v = p.evaluate(t);
    EXPECT_TRUE(finite(v)) << t;
    EXPECT_LE(std::abs(v.pitch_deg), 89.9f) << t;
    EXPECT_GE(v.fov_deg, 1.0f);
    EXPECT_LE(v.fov_deg, 170.0f);
    EXPECT_LE(std::abs(v.yaw_deg), 180.0f);
  }
  p.settings.loop = true;
  for (double t : {-1e12, 3.3e9, 1e15}) EXPECT_TRUE(finite(p.evaluate(t))) << t;
}

// Invariant: the environment gives a finite, non-negative lighting for every clock value,
// including the poles and midnight.
TEST(SceneStability, LightingIsFiniteEverywhere) {
  SunSettings sun;
  sun.follow_clock = true;
  EnvironmentSettings env;
  for (float lat : {-90.0f, -66.6f, 0.0f, 45.0f, 90.0f}) {
    for (float h : {0.0f, 6.0f, 12.0f, 23.999f, 24.0f}) {
      for (float season : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
        env.latitude_deg = lat;
        env.time_of_day_h = h;
        env.season = season;
        const render::Lighting l = make_lighting(sun, env);
        EXPECT_TRUE(std::isfinite(l.sun_direction.x) && std::isfinite(l.sun_direction.y) && std::isfinite(l.sun_direction.z));
        EXPECT_NEAR(glm::length(l.sun_direction), 1.0f, 1e-4);
        EXPECT_GE(l.sun_intensity, 0.0f);
        EXPECT_TRUE(std::isfinite(l.sun_intensity));
        EXPECT_GE(l.zenith_color.b, 0.0f);
      }
    }
  }
}

// Invariant: tree placement far from the origin keeps its spacing and stays on the ground
// (double-precision placement, no float collapse of neighbouring trees).
TEST(SceneStability, ForestFarFromTheOrigin) {
  ForestPlacement p;
  p.area_min = {1.0e6, -1.0e6};
  p.area_max = {1.0e6 + 200.0, -1.0e6 + 200.0};
  p.trees_per_hectare = 100.0f;
  p.min_spacing = 6.0f;
  const auto trees = place_trees(p, nullptr, nullptr, p.area_min, p.area_max);
  ASSERT_GT(trees.size(), 300u);
  for (std::size_t a = 0; a < trees.size(); ++a) {
    for (std::size_t b = a + 1; b < trees.size(); ++b) {
      ASSERT_GE(glm::distance(glm::dvec2(trees[a].position.x, trees[a].position.z), glm::dvec2(trees[b].position.x, trees[b].position.z)),
                6.0 - 1e-6);
    }
  }
  // Degenerate inputs place nothing instead of looping or allocating without bound.
  p.trees_per_hectare = 1e-30f;
  EXPECT_TRUE(place_trees(p, nullptr, nullptr, p.area_min, p.area_max).size() <= 1u);
  p.trees_per_hectare = 100.0f;
  p.area_max = p.area_min;
  EXPECT_TRUE(place_trees(p, nullptr, nullptr, p.area_min, p.area_max).empty());
}

// Invariant: generated grounds are finite for extreme sizes, resolutions and heights.
TEST(SceneStability, GeneratedGroundsAreFinite) {
  for (float size : {1.0f, 1.0e6f}) {
    for (int res : {2, 3, 129}) {
      for (HeightGenerator g : {HeightGenerator::kFlat, HeightGenerator::kFbm, HeightGenerator::kRidged, HeightGenerator::kHillsAndRidges}) {
        HeightSourceSettings s;
        s.size = size;
        s.resolution = res;
        s.height = 1.0e4f;
        s.generator = g;
        s.center = {1.0e8, -1.0e8};
        auto grid = make_height_grid(s, std::nullopt);
        ASSERT_TRUE(grid.ok());
        for (float v : grid->values) ASSERT_TRUE(std::isfinite(v));
        EXPECT_NEAR(grid->world(res - 1, 0).x - grid->world(0, 0).x, size, 1e-6 * size);
      }
    }
  }
}

// Invariant: a hostile scene file (deep nesting, huge numbers, wrong types everywhere) is an
// error or a warning, never a crash, and never writes a value outside its range.
TEST(SceneStability, HostileDocumentsAreRejectedCleanly) {
  const char* texts[] = {
      R"({"camera": {"position": [1e400, 0, 0]}})",
      R"({"camera": {"position": [1e300, 0, 0]}})",
      R"({"wind": {"seed": -1}})",
      R"({"wind": {"turbulence_octaves": 2.5}})",
      R"({"camera_paths": {"p": {"keys": [{"time_s": 1e300}]}}})",
      R"({"bookmarks": {"": {}}})",
      R"({"ground": {"resolution": 1e10}})",
      R"({"ground": {"maps": {"height": ""}}})",
      R"({"sylva_scene": 1e30})",
      R"({"a": {"b": {"c": {"d": {"e": {"f": [[[[[[[1]]]]]]]}}}}}})",
  };
  for (const char* t : texts) {
    std::vector<std::string> warnings;
    auto doc = SceneDocument::from_text(t, "hostile.json", warnings);
    if (doc.ok()) {
      EXPECT_TRUE(doc->validate().ok()) << t;
    } else {
      EXPECT_FALSE(doc.error().message.empty()) << t;
    }
  }
}

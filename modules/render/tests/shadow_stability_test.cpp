// Stability of the cascade fit (shadow_cascades.hpp). Invariants, one per test:
//  - "finite matrices": every cascade matrix, split and texel size is finite and positive for
//    cameras 1e7 m from the origin, fov 1e-4..3.1 rad, near 1e-6..10 m, any sun direction
//    (vertical, horizon, below the horizon, zero, NaN, huge) and out-of-range settings;
//  - "no shimmer far away": at 1e6 m from the origin, sub-texel camera steps keep every snapped
//    cascade centre on the same world texel grid (whole-texel moves only);
//  - "cascades cover the view": consecutive cascades share their split, the last ends at
//    max_distance, and a ground point inside a slice maps into [0, 1]^2 of its cascade.
#include <sylva/render/shadow_cascades.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace sylva::render {
namespace {

bool finite(const glm::mat4& m) {
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) {
      if (!std::isfinite(m[a][b])) return false;
    }
  }
  return true;
}

TEST(ShadowStability, FiniteMatricesForExtremeCamerasAndSuns) {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  int cases = 0;
  for (const float fov : {1e-4f, 0.3f, 1.2f, 3.1f}) {
    for (const float near_plane : {1e-6f, 0.1f, 10.0f}) {
      for (const glm::vec3 sun : {glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(1, 0, 0), glm::vec3(0.3f, -0.2f, 0.9f),
                                  glm::vec3(0), glm::vec3(nan, 1, 0), glm::vec3(inf, 0, 0), glm::vec3(1e30f, 1e30f, 0)}) {
        for (const float distance : {0.5f, 150.0f, 1e5f}) {
          Camera cam;
          cam.set_aspect(1920, 1080);
          cam.perspective().fov_y = fov;
          cam.perspective().near_plane = near_plane;
          cam.set_position({1e7, -3e3, -1e7});
          cam.set_yaw_pitch(0.4f, -1.5f);
          ShadowSettings s;
          s.cascade_count = 4;
          s.max_distance = distance;
          const ShadowCascades c = compute_shadow_cascades(cam, sun, s);
          ASSERT_EQ(c.count, 4);
          for (int i = 0; i < c.count; ++i) {
            const ShadowCascade& sc = c.cascades[static_cast<std::size_t>(i)];
            ASSERT_TRUE(finite(sc.relative_texture) && finite(sc.relative_view_projection) && finite(sc.relative_cull))
                << "fov " << fov << " near " << near_plane << " sun " << sun.x << "," << sun.y << "," << sun.z;
            ASSERT_TRUE(std::isfinite(sc.texel_size) && sc.texel_size > 0.0f);
            ASSERT_TRUE(std::isfinite(sc.far_depth) && sc.far_depth > sc.near_depth);
          }
          ++cases;
        }
      }
    }
  }
  EXPECT_EQ(cases, 4 * 3 * 8 * 3);
}

TEST(ShadowStability, NoShimmerFarFromTheOrigin) {
  ShadowSettings s;
  s.cascade_count = 3;
  s.resolution = 2048;
  const glm::vec3 sun = glm::normalize(glm::vec3(0.2f, 0.5f, -0.7f));
  Camera cam;
  cam.set_aspect(16, 9);
  cam.set_position({1e6, 30.0, 1e6});
  cam.set_yaw_pitch(1.0f, -0.3f);
  const ShadowCascades first = compute_shadow_cascades(cam, sun, s);
  for (int k = 1; k <= 50; ++k) {
    cam.set_position({1e6 + 0.0031 * k, 30.0 - 0.0007 * k, 1e6 + 0.0023 * k});
    const ShadowCascades c = compute_shadow_cascades(cam, sun, s);
    for (int i = 0; i < 3; ++i) {
      const ShadowCascade& a = first.cascades[static_cast<std::size_t>(i)];
      const ShadowCascade& b = c.cascades[static_cast<std::size_t>(i)];
      ASSERT_EQ(a.texel_size, b.texel_size);
      const glm::dvec3 d = b.center - a.center;
      for (const glm::vec3& axis : {c.light_right, c.light_up}) {
        const double texels = glm::dot(d, glm::dvec3(axis)) / a.texel_size;
        ASSERT_NEAR(texels, std::round(texels), 1e-4) << "cascade " << i << " step " << k;
      }
    }
  }
}

TEST(ShadowStability, CascadesCoverTheView) {
  ShadowSettings s;
  s.cascade_count = 4;
  s.max_distance = 200.0f;
  Camera cam;
  cam.set_aspect(16, 9);
  cam.set_position({-5e5, 12.0, 3e5});
  cam.set_yaw_pitch(-2.0f, -0.2f);
  const ShadowCascades c = compute_shadow_cascades(cam, glm::vec3(0.1f, 0.05f, 1.0f), s);
  EXPECT_EQ(c.cascades[3].far_depth, 200.0f);
  for (int i = 1; i < 4; ++i) EXPECT_EQ(c.cascades[static_cast<std::size_t>(i - 1)].far_depth, c.cascades[static_cast<std::size_t>(i)].near_depth);
  // Points along the view axis at the middle of every slice land inside their cascade.
  for (int i = 0; i < 4; ++i) {
    const ShadowCascade& sc = c.cascades[static_cast<std::size_t>(i)];
    const float depth = 0.5f * (sc.near_depth + sc.far_depth);
    const glm::vec4 t = sc.relative_texture * glm::vec4(cam.forward() * depth, 1.0f);
    EXPECT_GT(t.x, 0.0f);
    EXPECT_LT(t.x, 1.0f);
    EXPECT_GT(t.y, 0.0f);
    EXPECT_LT(t.y, 1.0f);
    EXPECT_GT(t.z, 0.0f);
    EXPECT_LT(t.z, 1.0f);
  }
}

}  // namespace
}  // namespace sylva::render

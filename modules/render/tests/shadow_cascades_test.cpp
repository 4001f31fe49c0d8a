// GL-free cascade maths (shadow_cascades.hpp): practical splits, bounding spheres that contain
// their frustum slice and do not change size when the camera turns, whole-texel snapping, a
// light basis that never degenerates (vertical and horizon suns), settings reflection.
#include <sylva/core/params.hpp>
#include <sylva/render/shadow_cascades.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace sylva::render {
namespace {

TEST(ShadowCascades, PracticalSplitsBlendLogAndUniform) {
  const auto uniform = practical_splits(1.0f, 100.0f, 4, 0.0f);
  const auto logarithmic = practical_splits(1.0f, 100.0f, 4, 1.0f);
  const auto practical = practical_splits(1.0f, 100.0f, 4, 0.5f);
  for (int i = 0; i < 4; ++i) {
    const float t = static_cast<float>(i + 1) / 4.0f;
    EXPECT_NEAR(uniform[static_cast<std::size_t>(i)], 1.0f + 99.0f * t, 1e-4f);
    EXPECT_NEAR(logarithmic[static_cast<std::size_t>(i)], std::pow(100.0f, t), 1e-3f);
    EXPECT_NEAR(practical[static_cast<std::size_t>(i)],
                0.5f * (uniform[static_cast<std::size_t>(i)] + logarithmic[static_cast<std::size_t>(i)]), 1e-3f);
  }
  EXPECT_EQ(practical[3], 100.0f);
  EXPECT_EQ(practical_splits(0.1f, 60.0f, 1, 0.7f)[0], 60.0f);
}

Camera turned_camera(float yaw, float pitch, glm::dvec3 pos) {
  Camera cam;
  cam.set_aspect(16, 9);
  cam.perspective().near_plane = 0.1f;
  cam.set_position(pos);
  cam.set_yaw_pitch(yaw, pitch);
  return cam;
}

TEST(ShadowCascades, SpheresContainTheirSlicesAndIgnoreRotation) {
  ShadowSettings s;
  s.cascade_count = 4;
  const glm::vec3 sun = glm::normalize(glm::vec3(0.3f, 0.8f, -0.2f));
  const ShadowCascades ref = compute_shadow_cascades(turned_camera(0, 0, {0, 0, 0}), sun, s);
  for (int k = 0; k < 20; ++k) {
    const Camera cam = turned_camera(0.7f * k, 0.13f * k - 1.2f, {1.0e5 + 3.1 * k, 20.0, -2.0e5});
    const ShadowCascades c = compute_shadow_cascades(cam, sun, s);
    const glm::mat4 inv_rot = glm::inverse(cam.view_rotation());
    const float ty = std::tan(cam.perspective().fov_y * 0.5f), tx = ty * cam.perspective().aspect;
    for (int i = 0; i < 4; ++i) {
      const ShadowCascade& sc = c.cascades[static_cast<std::size_t>(i)];
      EXPECT_EQ(sc.radius, ref.cascades[static_cast<std::size_t>(i)].radius) << "texel size changed with rotation";
      for (const float d : {sc.near_depth, sc.far_depth}) {
        for (const float sx : {-1.0f, 1.0f}) {
          for (const float sy : {-1.0f, 1.0f}) {
            const glm::vec3 rel = glm::vec3(inv_rot * glm::vec4(sx * tx * d, sy * ty * d, -d, 0.0f));
            // Every corner maps inside the unit square (snapping moves the centre < 1 texel,
            // the radius was rounded up, so allow one texel).
            const glm::vec4 t = sc.relative_texture * glm::vec4(rel, 1.0f);
            const float slack = 1.0f / static_cast<float>(s.resolution);
            EXPECT_GE(t.x, -slack);
            EXPECT_LE(t.x, 1.0f + slack);
            EXPECT_GE(t.y, -slack);
            EXPECT_LE(t.y, 1.0f + slack);
            EXPECT_GE(t.z, -slack);
            EXPECT_LE(t.z, 1.0f + slack);
          }
        }
      }
    }
  }
}

TEST(ShadowCascades, SnappedCentresMoveInWholeTexels) {
  ShadowSettings s;
  s.cascade_count = 2;
  const glm::vec3 sun = glm::normalize(glm::vec3(-0.5f, 0.6f, 0.3f));
  const ShadowCascades a = compute_shadow_cascades(turned_camera(0.3f, -0.2f, {10, 2, 5}), sun, s);
  for (int k = 1; k < 30; ++k) {
    const ShadowCascades b = compute_shadow_cascades(turned_camera(0.3f, -0.2f, {10 + 0.037 * k, 2, 5 - 0.011 * k}), sun, s);
    for (int i = 0; i < 2; ++i) {
      const ShadowCascade& ca = a.cascades[static_cast<std::size_t>(i)];
      const ShadowCascade& cb = b.cascades[static_cast<std::size_t>(i)];
      const glm::dvec3 d = cb.center - ca.center;
      for (const glm::vec3& axis : {a.light_right, a.light_up}) {
        const double texels = glm::dot(d, glm::dvec3(axis)) / ca.texel_size;
        EXPECT_NEAR(texels, std::round(texels), 1e-6) << "cascade " << i << " step " << k;
      }
    }
  }
}

TEST(ShadowCascades, LightBasisNeverDegenerates) {
  for (const glm::vec3 l : {glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(1e-7f, 1, 0), glm::vec3(1, 0, 0),
                            glm::vec3(0, 0, -1), glm::vec3(0.3f, 0.001f, 0.7f), glm::vec3(0, 0, 0),
                            glm::vec3(NAN, 1, 0)}) {
    glm::dvec3 r, u, b;
    light_basis(l, r, u, b);
    for (const glm::dvec3& v : {r, u, b}) {
      ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
      EXPECT_NEAR(glm::length(v), 1.0, 1e-9);
    }
    EXPECT_NEAR(glm::dot(r, u), 0.0, 1e-9);
    EXPECT_NEAR(glm::dot(r, b), 0.0, 1e-9);
    EXPECT_NEAR(glm::dot(u, b), 0.0, 1e-9);
    EXPECT_NEAR(glm::dot(glm::cross(r, u), b), 1.0, 1e-9) << "right-handed";
  }
}

TEST(ShadowCascades, ExtremeSettingsStayFinite) {
  ShadowSettings s;
  s.cascade_count = 99;
  s.resolution = -5;
  s.max_distance = NAN;
  s.split_lambda = 7.0f;
  s.caster_reach = INFINITY;
  Camera cam = turned_camera(0, 0, {1e7, 0, 0});
  cam.perspective().fov_y = 1e-6f;
  const ShadowCascades c = compute_shadow_cascades(cam, glm::vec3(0, 1, 0), s);
  EXPECT_EQ(c.count, kMaxShadowCascades);
  for (int i = 0; i < c.count; ++i) {
    const ShadowCascade& sc = c.cascades[static_cast<std::size_t>(i)];
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) {
        ASSERT_TRUE(std::isfinite(sc.relative_texture[a][b]));
        ASSERT_TRUE(std::isfinite(sc.relative_cull[a][b]));
      }
    }
    EXPECT_GT(sc.texel_size, 0.0f);
  }
}

TEST(ShadowCascades, SeedBiasFormula) {
  ShadowSettings s;
  EXPECT_FLOAT_EQ(shadow_depth_bias(s, 1.0f, 1.0f), 0.00085f);
  EXPECT_FLOAT_EQ(shadow_depth_bias(s, 0.0f, 1.0f), 0.0085f);
  EXPECT_FLOAT_EQ(shadow_depth_bias(s, 0.5f, 2.0f), 0.0085f);
  EXPECT_FLOAT_EQ(shadow_depth_bias(s, -3.0f, 1.0f), 0.0085f);
}

TEST(ShadowCascades, SettingsReflectThroughParams) {
  ShadowSettings s;
  ASSERT_TRUE(set_param(s, "cascade_count", "2").ok());
  EXPECT_EQ(s.cascade_count, 2);
  ASSERT_TRUE(set_param(s, "cascade_count", "8").ok());  // kMaxShadowCascades (seed 004 R3 ran 5)
  const Status bad = set_param(s, "cascade_count", "9");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("cascade_count"), std::string::npos);
}

}  // namespace
}  // namespace sylva::render

// CPU frustum culling of boxes and spheres (no GL): known cases, a brute-force check that no
// visible box is ever culled, and identical answers 1e7 m from the origin.
#include <sylva/render/camera.hpp>
#include <sylva/render/frustum.hpp>

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace sylva::render {
namespace {

Camera make_camera(const glm::dvec3& position, float far_plane = 0.0f) {
  Camera c;
  c.set_position(position);
  c.perspective() = {.fov_y = 1.5707963f, .aspect = 1.0f, .near_plane = 0.1f, .far_plane = far_plane};
  return c;  // yaw 0, pitch 0: looking along -z
}

Aabb box_at(const glm::dvec3& c, double half) { return {c - glm::dvec3(half), c + glm::dvec3(half)}; }

TEST(Frustum, KnownBoxes) {
  const Camera cam = make_camera({0, 0, 0});
  const Frustum f = cam.frustum();
  EXPECT_EQ(f.classify(box_at({0, 0, -10}, 1)), Containment::kInside);
  EXPECT_EQ(f.classify(box_at({0, 0, 10}, 1)), Containment::kOutside);      // behind
  EXPECT_EQ(f.classify(box_at({-100, 0, -10}, 1)), Containment::kOutside);  // far left
  EXPECT_EQ(f.classify(box_at({100, 0, -10}, 1)), Containment::kOutside);
  EXPECT_EQ(f.classify(box_at({0, 100, -10}, 1)), Containment::kOutside);
  EXPECT_EQ(f.classify(box_at({0, -100, -10}, 1)), Containment::kOutside);
  EXPECT_EQ(f.classify(box_at({-10, 0, -10}, 1)), Containment::kIntersecting);  // on the 45-degree left plane
  EXPECT_EQ(f.classify(box_at({0, 0, -1.0e9}, 1.0e3)), Containment::kInside);  // infinite far plane
  // Entirely between the eye and the near plane (z > -0.1).
  EXPECT_EQ(f.classify(Aabb{{-0.01, -0.01, -0.09}, {0.01, 0.01, 0.5}}), Containment::kOutside);
  // Surrounding the camera.
  EXPECT_EQ(f.classify(box_at({0, 0, 0}, 5)), Containment::kIntersecting);
}

TEST(Frustum, FinitePlane) {
  const Frustum f = make_camera({0, 0, 0}, 100.0f).frustum();
  EXPECT_EQ(f.classify(box_at({0, 0, -50}, 1)), Containment::kInside);
  EXPECT_EQ(f.classify(box_at({0, 0, -1000}, 1)), Containment::kOutside);
  EXPECT_EQ(f.classify(box_at({0, 0, -100}, 1)), Containment::kIntersecting);
}

TEST(Frustum, Spheres) {
  const Frustum f = make_camera({0, 0, 0}).frustum();
  EXPECT_EQ(f.classify(Sphere{{0, 0, -10}, 1}), Containment::kInside);
  EXPECT_EQ(f.classify(Sphere{{0, 0, 10}, 1}), Containment::kOutside);
  EXPECT_EQ(f.classify(Sphere{{0, 0, 10}, 20}), Containment::kIntersecting);
  // Just outside the right plane x = -z: distance from (12, 0, -10) to the plane is 2/sqrt(2).
  EXPECT_FALSE(f.intersects(Sphere{{12, 0, -10}, 1.4}));
  EXPECT_TRUE(f.intersects(Sphere{{12, 0, -10}, 1.45}));
}

// Any box with a sample point inside the clip volume must be reported visible.
TEST(Frustum, NeverCullsAVisibleBox) {
  std::mt19937 rng(1234);
  std::uniform_real_distribution<double> pos(-60.0, 60.0);
  std::uniform_real_distribution<double> size(0.01, 8.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Camera cam = make_camera({0, 0, 0}, 200.0f);
  cam.set_yaw_pitch(0.7f, -0.3f);
  cam.set_aspect(16, 9);
  const Frustum f = cam.frustum();
  const glm::dmat4 clip(cam.view_projection());
  int visible_by_samples = 0;
  int reported = 0;
  for (int i = 0; i < 3000; ++i) {
    const glm::dvec3 c(pos(rng), pos(rng), pos(rng));
    const glm::dvec3 h(size(rng), size(rng), size(rng));
    const Aabb box{c - h, c + h};
    bool any_inside = false;
    for (int s = 0; s < 64 && !any_inside; ++s) {
      const glm::dvec3 p = box.min + (box.max - box.min) * glm::dvec3(unit(rng), unit(rng), unit(rng));
      const glm::dvec4 q = clip * glm::dvec4(p, 1.0);
      any_inside = q.w > 0 && std::abs(q.x) <= q.w && std::abs(q.y) <= q.w && q.z >= 0 && q.z <= q.w;
    }
    const bool culled = !f.intersects(box);
    if (any_inside) {
      ++visible_by_samples;
      ASSERT_FALSE(culled) << "visible box culled: centre " << c.x << "," << c.y << "," << c.z;
    }
    reported += culled ? 0 : 1;
  }
  EXPECT_GT(visible_by_samples, 100);
  // The plane test is conservative near corners but must not keep much more than it should.
  EXPECT_LT(reported, visible_by_samples * 3 / 2 + 50);
}

TEST(Frustum, SameAnswersFarFromOrigin) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> pos(-80.0, 80.0);
  std::uniform_real_distribution<double> size(0.05, 4.0);
  std::vector<Aabb> near_origin;
  for (int i = 0; i < 2000; ++i) near_origin.push_back(box_at({pos(rng), pos(rng), pos(rng)}, size(rng)));
  for (const glm::dvec3 offset : {glm::dvec3(1.0e5, -3.0e4, 2.0e5), glm::dvec3(1.0e7, 5.0e6, -3.0e6)}) {
    Camera a = make_camera({1.25, 0.5, 2.0});
    Camera b = make_camera(glm::dvec3(1.25, 0.5, 2.0) + offset);
    a.set_yaw_pitch(-0.4f, 0.2f);
    b.set_yaw_pitch(-0.4f, 0.2f);
    std::vector<Aabb> moved;
    for (const Aabb& box : near_origin) moved.push_back({box.min + offset, box.max + offset});
    std::vector<unsigned char> va(near_origin.size()), vb(near_origin.size());
    const std::size_t na = a.frustum().cull(near_origin, va);
    const std::size_t nb = b.frustum().cull(moved, vb);
    EXPECT_EQ(na, nb);
    EXPECT_EQ(va, vb);
    EXPECT_GT(na, 50u);
  }
}

TEST(Frustum, RelativeTestsMatchWorldTests) {
  const Camera cam = make_camera({10, 20, 30});
  const Frustum f = cam.frustum();
  const Aabb box = box_at({10, 20, 20}, 1);
  EXPECT_TRUE(f.intersects_relative(glm::vec3(0, 0, -10), glm::vec3(1)));
  EXPECT_TRUE(f.intersects(box));
  EXPECT_FALSE(f.intersects_relative(glm::vec3(0, 0, 10), glm::vec3(1)));
  EXPECT_TRUE(f.intersects_relative_sphere(glm::vec3(0, 0, -10), 0.5f));
  EXPECT_FALSE(f.intersects_relative_sphere(glm::vec3(0, 0, 10), 0.5f));
}

}  // namespace
}  // namespace sylva::render

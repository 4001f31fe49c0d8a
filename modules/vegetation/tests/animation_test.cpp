// CPU reference of the LOD0 animation (seed 000 §3.1): exact rest pose, determinism, direction of
// the bend, orthonormal frames, continuity in time, frame transport, instance transforms.
#include <sylva/vegetation/animation.hpp>

#include <sylva/core/wind.hpp>

#include "support/models.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace sylva::vegetation {
namespace {

InstanceGpu with_wind(const glm::vec3& w, float time_offset = 0.0f) {
  TreeInstance t;
  t.time_offset = time_offset;
  return make_instance_gpu(t, glm::dvec3(0.0), w);
}

bool bit_equal(const glm::vec3& a, const glm::vec3& b) { return std::memcmp(&a, &b, sizeof(a)) == 0; }

TEST(Animation, ZeroWindReproducesTheRestMeshBitForBit) {
  const WindGpuParams wind = WindField().frame(12.5).gpu;
  for (const TreeMesh* mesh : {&testing::preset_mesh(SpeciesPreset::kBroadleaf), &testing::preset_mesh(SpeciesPreset::kBirch)}) {
    for (double time : {0.0, 3.7, 1.0e6}) {
      for (bool transport : {true, false}) {
        AnimationSettings s;  // every level and the leaves enabled
        s.frame_transport = transport;
        const AnimationGpu anim = make_animation_gpu(s, time);
        const InstanceGpu inst = with_wind(glm::vec3(0.0f), 17.0f);
        int mismatches = 0;
        float worst = 0.0f;
        for (const BranchVertex& v : mesh->branch_vertices) {
          const glm::vec3 p = deform_branch_vertex(mesh->data, anim, inst, v).position;
          mismatches += bit_equal(p, v.position) ? 0 : 1;
          worst = std::max(worst, glm::length(p - v.position));
        }
        for (const LeafVertex& v : mesh->leaf_vertices) {
          const DeformedVertex d = deform_leaf_vertex(mesh->data, anim, inst, wind, v);
          mismatches += bit_equal(d.position, v.position) && bit_equal(d.normal, v.normal) ? 0 : 1;
          worst = std::max(worst, glm::length(d.position - v.position));
        }
        if (transport) {
          EXPECT_EQ(mismatches, 0) << "time " << time;  // the rest mesh is built with transport on
        } else {
          // Without transport children use their stored object frames instead of frames carried
          // through the parents: the same pose up to float rounding.
          EXPECT_LT(worst, 1e-5f) << "time " << time;
        }
      }
    }
  }
}

TEST(Animation, DeterministicAndPhaseShiftedPerInstance) {
  const TreeMesh& mesh = testing::preset_mesh(SpeciesPreset::kBroadleaf);
  const AnimationGpu anim = make_animation_gpu(AnimationSettings{}, 42.0);
  const WindGpuParams wind = WindField().frame(42.0).gpu;
  const InstanceGpu a = with_wind({6.0f, 0.0f, 2.0f});
  const InstanceGpu b = with_wind({6.0f, 0.0f, 2.0f}, 11.0f);
  int same = 0;
  int differ = 0;
  for (std::size_t i = 0; i < mesh.leaf_vertices.size(); i += 7) {
    const LeafVertex& v = mesh.leaf_vertices[i];
    const glm::vec3 p1 = deform_leaf_vertex(mesh.data, anim, a, wind, v).position;
    const glm::vec3 p2 = deform_leaf_vertex(mesh.data, anim, a, wind, v).position;
    same += bit_equal(p1, p2) ? 1 : 0;
    differ += glm::length(p1 - deform_leaf_vertex(mesh.data, anim, b, wind, v).position) > 1e-4f ? 1 : 0;
  }
  EXPECT_EQ(same, static_cast<int>((mesh.leaf_vertices.size() + 6) / 7));
  EXPECT_GT(differ, same / 2);
}

TEST(Animation, DirectionalWindBendsTheTreeDownwind) {
  const TreeModel m = testing::small_tree();
  const TreeMesh mesh = build_tree_mesh(m);
  AnimationSettings s;
  for (LevelAnimation* l : {&s.trunk, &s.level1, &s.level2, &s.level3}) l->turbulence = 0.0f;
  const AnimationGpu anim = make_animation_gpu(s, 5.0);
  float previous = 0.0f;
  for (float speed : {2.0f, 8.0f, 20.0f}) {
    const glm::vec3 w(0.0f, 0.0f, speed);
    const InstanceGpu inst = with_wind(w);
    const glm::vec3 tip = branch_axis_point(mesh.data, anim, inst, 0, 1.0f);
    const glm::vec3 rest = m.branches[0].end();
    const float downwind = tip.z - rest.z;
    EXPECT_GT(downwind, previous) << "speed " << speed;
    EXPECT_LT(std::fabs(tip.x - rest.x), 0.2f * downwind + 1e-6f);
    previous = downwind;
    // Every bark vertex moves downwind or stays (no turbulence, wind along +z).
    float mean = 0.0f;
    for (const BranchVertex& v : mesh.branch_vertices) mean += deform_branch_vertex(mesh.data, anim, inst, v).position.z - v.position.z;
    EXPECT_GT(mean / static_cast<float>(mesh.branch_vertices.size()), 0.0f);
  }
}

TEST(Animation, FramesStayOrthonormal) {
  const TreeMesh& mesh = testing::preset_mesh(SpeciesPreset::kConifer);
  const AnimationGpu anim = make_animation_gpu(AnimationSettings{}, 9.25);
  float worst = 0.0f;
  for (float speed : {5.0f, 50.0f, 5000.0f}) {
    const InstanceGpu inst = with_wind({speed, 0.3f * speed, -0.5f * speed});
    for (std::uint32_t b = 0; b < mesh.data.branches.size(); ++b) {
      const ChainState c = evaluate_chain(mesh.data, anim, inst, b, hierarchy_vector(mesh.data, b, 0.77f));
      worst = std::max({worst, std::fabs(glm::length(c.t) - 1.0f), std::fabs(glm::length(c.r) - 1.0f),
                        std::fabs(glm::length(c.s) - 1.0f), std::fabs(glm::dot(c.t, c.r)), std::fabs(glm::dot(c.t, c.s)),
                        std::fabs(glm::dot(c.r, c.s)), glm::length(glm::cross(c.r, c.s) - c.t)});
    }
  }
  EXPECT_LT(worst, 2e-5f);
}

TEST(Animation, MotionIsContinuousInTime) {
  const TreeMesh& mesh = testing::preset_mesh(SpeciesPreset::kBirch);
  const WindField wind;
  TreeInstance ti;
  ti.position = {3.0, 0.0, -2.0};
  const AnimationSettings s;
  for (double t0 : {0.0, 1.0, 12.3456, 1.0e5, 1.0e7}) {
    float worst = 0.0f;
    for (double h : {1.0e-3, 1.0e-4}) {
      const AnimationGpu a0 = make_animation_gpu(s, t0);
      const AnimationGpu a1 = make_animation_gpu(s, t0 + h);
      const InstanceGpu i0 = make_instance_gpu(ti, glm::dvec3(0.0), wind, t0, s);
      const InstanceGpu i1 = make_instance_gpu(ti, glm::dvec3(0.0), wind, t0 + h, s);
      const WindGpuParams w0 = wind.frame(t0).gpu;
      const WindGpuParams w1 = wind.frame(t0 + h).gpu;
      float speed = 0.0f;
      for (std::size_t i = 0; i < mesh.leaf_vertices.size(); i += 11) {
        const LeafVertex& v = mesh.leaf_vertices[i];
        const glm::vec3 p0 = deform_leaf_vertex(mesh.data, a0, i0, w0, v).position;
        const glm::vec3 p1 = deform_leaf_vertex(mesh.data, a1, i1, w1, v).position;
        ASSERT_TRUE(std::isfinite(p0.x + p0.y + p0.z));
        speed = std::max(speed, glm::length(p1 - p0) / static_cast<float>(h));
      }
      worst = std::max(worst, speed);
    }
    // Leaves and twigs move at most a few m/s in a 3 m/s breeze; a jump would show as a huge speed.
    EXPECT_LT(worst, 5.0f) << "t0 " << t0;
  }
}

TEST(Animation, FrameTransportCarriesChildrenAlong) {
  const TreeModel m = testing::small_tree();
  const TreeMesh mesh = build_tree_mesh(m);
  AnimationSettings on;
  AnimationSettings off;
  off.frame_transport = false;
  const InstanceGpu inst = with_wind({0.0f, 0.0f, 25.0f});
  // Without transport a child keeps its rest direction while its parent bends (seed Fig. 3.8b).
  // Branch 1 hangs on the trunk; at x = 0 only the trunk's bend acts on it.
  const ChainState c_off = evaluate_chain(mesh.data, make_animation_gpu(off, 2.0), inst, 1, hierarchy_vector(mesh.data, 1, 0.0f));
  const ChainState c_on = evaluate_chain(mesh.data, make_animation_gpu(on, 2.0), inst, 1, hierarchy_vector(mesh.data, 1, 0.0f));
  const glm::vec3 rest_t = m.branches[1].frame.t;
  EXPECT_LT(glm::length(c_off.t - rest_t), 1e-6f);
  EXPECT_GT(glm::length(c_on.t - rest_t), 1e-3f);
  // Both attach the child at the same bent parent point.
  EXPECT_LT(glm::length(c_off.origin - c_on.origin), 1e-5f);
}

TEST(Animation, LeavesAreRigid) {
  const TreeMesh& mesh = testing::preset_mesh(SpeciesPreset::kShrub);
  const AnimationGpu anim = make_animation_gpu(AnimationSettings{}, 77.0);
  const WindGpuParams wind = WindField().frame(77.0).gpu;
  const InstanceGpu inst = with_wind({30.0f, 0.0f, 10.0f});
  float worst = 0.0f;
  for (std::size_t l = 0; l + 3 < mesh.leaf_vertices.size(); l += 4) {
    glm::vec3 rest[4];
    glm::vec3 bent[4];
    for (int c = 0; c < 4; ++c) {
      rest[c] = mesh.leaf_vertices[l + static_cast<std::size_t>(c)].position;
      bent[c] = deform_leaf_vertex(mesh.data, anim, inst, wind, mesh.leaf_vertices[l + static_cast<std::size_t>(c)]).position;
    }
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        worst = std::max(worst, std::fabs(glm::length(bent[a] - bent[b]) - glm::length(rest[a] - rest[b])));
  }
  EXPECT_LT(worst, 2e-6f);
}

TEST(Animation, InstanceRotationRotatesTheWind) {
  const TreeModel m = testing::small_tree();
  const TreeMesh mesh = build_tree_mesh(m);
  const AnimationGpu anim = make_animation_gpu(AnimationSettings{}, 3.0);
  const glm::vec3 w_world(7.0f, 0.0f, 0.0f);
  TreeInstance a;
  TreeInstance b;
  b.yaw = 1.1f;
  b.position = {100.0, 2.0, -40.0};
  b.scale = 1.0f;
  const glm::dvec3 camera(90.0, 0.0, -30.0);
  const InstanceGpu ia = make_instance_gpu(a, glm::dvec3(0.0), w_world);
  // b sees the wind rotated the same way as its body: deformation in b's object space equals a's
  // object-space deformation under the wind expressed in a's frame.
  const InstanceGpu ib = make_instance_gpu(b, camera, instance_vector(make_instance_gpu(b, camera, glm::vec3(0.0f)), w_world));
  float worst = 0.0f;
  for (const BranchVertex& v : mesh.branch_vertices) {
    const glm::vec3 pa = deform_branch_vertex(mesh.data, anim, ia, v).position;
    const glm::vec3 pb = deform_branch_vertex(mesh.data, anim, ib, v).position;
    worst = std::max(worst, glm::length(pa - pb));
  }
  EXPECT_LT(worst, 1e-5f);
  // World placement: translation relative to the camera, rotation about y.
  const glm::vec3 p = instance_point(ib, {1.0f, 0.0f, 0.0f});
  EXPECT_NEAR(p.x, 10.0f + std::cos(1.1f), 1e-5f);
  EXPECT_NEAR(p.z, -10.0f - std::sin(1.1f), 1e-5f);
}

}  // namespace
}  // namespace sylva::vegetation

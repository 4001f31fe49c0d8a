// Stability of the LOD0 animation under extreme wind, long time steps and degenerate input. Each
// test names the invariant it checks.
//
// Bound achieved (printed by BranchLengthPreservedWithinOnePercent): the amplitude limit is set
// for a 0.9 % length change of the continuous axis (bending.hpp); measured on 33-point polylines of
// every branch of the small model and every third branch of three presets, the worst change is
// 0.900 % at wind x1, x10 and x100.
#include <sylva/vegetation/animation.hpp>

#include <sylva/core/wind.hpp>

#include "support/models.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

namespace sylva::vegetation {
namespace {

struct Case {
  const char* name;
  const TreeMesh* mesh;
};

std::vector<Case> models() {
  static const TreeMesh small = build_tree_mesh(testing::small_tree());
  return {{"small", &small},
          {"broadleaf", &testing::preset_mesh(SpeciesPreset::kBroadleaf)},
          {"conifer", &testing::preset_mesh(SpeciesPreset::kConifer)},
          {"birch", &testing::preset_mesh(SpeciesPreset::kBirch)}};
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Deformed axis length of a branch from a polyline of `n` segments.
double axis_length(const TreeGpuData& d, const AnimationGpu& a, const InstanceGpu& i, std::uint32_t b, int n) {
  double len = 0.0;
  glm::vec3 prev = branch_axis_point(d, a, i, b, 0.0f);
  for (int k = 1; k <= n; ++k) {
    const glm::vec3 p = branch_axis_point(d, a, i, b, static_cast<float>(k) / static_cast<float>(n));
    len += glm::length(glm::dvec3(p - prev));
    prev = p;
  }
  return len;
}

// Invariant: every branch keeps its length within 1 % for wind x1, x10, x100 and time steps of 1 s.
TEST(AnimationStability, BranchLengthPreservedWithinOnePercent) {
  const WindField wind(WindSettings{.direction_deg = 30.0f, .strength = 8.0f, .gust_amplitude = 6.0f});
  double worst = 0.0;
  for (const Case& c : models()) {
    for (float scale : {1.0f, 10.0f, 100.0f}) {
      for (bool transport : {true, false}) {
        AnimationSettings s;
        s.wind_scale = scale;
        s.frame_transport = transport;
        double model_worst = 0.0;
        for (double t = 0.0; t < 4.0; t += 1.0) {  // dt = 1 s
          const AnimationGpu a = make_animation_gpu(s, t);
          const InstanceGpu inst = make_instance_gpu(TreeInstance{}, glm::dvec3(0.0), wind, t, s);
          for (std::uint32_t b = 0; b < c.mesh->data.branches.size(); b += (c.mesh->data.branches.size() > 60 ? 3u : 1u)) {
            const float rest = c.mesh->data.branches[b].r_parent.w;
            if (rest <= 0.0f) continue;
            const double len = axis_length(c.mesh->data, a, inst, b, 32);
            model_worst = std::max(model_worst, std::fabs(len / rest - 1.0));
          }
        }
        EXPECT_LE(model_worst, 0.01) << c.name << " wind x" << scale << " transport " << transport;
        worst = std::max(worst, model_worst);
      }
    }
  }
  std::printf("worst relative branch length change over all models, winds x1..x100, dt = 1 s: %.4f %%\n", 100.0 * worst);
  RecordProperty("worst_branch_length_change_percent", std::to_string(100.0 * worst));
}

// Invariant: a leaf's attachment point stays on its (bent) parent branch axis.
TEST(AnimationStability, LeafOriginsStayOnTheirBranch) {
  const WindField wind(WindSettings{.strength = 10.0f});
  float worst = 0.0f;
  for (const Case& c : models()) {
    const TreeMesh& m = *c.mesh;
    for (float scale : {1.0f, 10.0f, 100.0f}) {
      AnimationSettings s;
      s.wind_scale = scale;
      for (double t : {0.0, 1.0, 2.0, 1.0e6}) {
        const AnimationGpu a = make_animation_gpu(s, t);
        const InstanceGpu inst = make_instance_gpu(TreeInstance{}, glm::dvec3(0.0), wind, t, s);
        const WindGpuParams w = wind.frame(t).gpu;
        for (std::size_t l = 0; l + 3 < m.leaf_vertices.size(); l += 4 * 5) {
          // Corners 0 and 1 are (-w/2, 0) and (+w/2, 0): their midpoint is the attachment point.
          const glm::vec3 p0 = deform_leaf_vertex(m.data, a, inst, w, m.leaf_vertices[l]).position;
          const glm::vec3 p1 = deform_leaf_vertex(m.data, a, inst, w, m.leaf_vertices[l + 1]).position;
          const LeafVertex& v = m.leaf_vertices[l];
          const float x = v.xvec[static_cast<int>(m.data.branches[v.branch].s_object.w)];
          const glm::vec3 on_branch = branch_axis_point(m.data, a, inst, v.branch, x);
          worst = std::max(worst, glm::length(0.5f * (p0 + p1) - on_branch));
        }
      }
    }
  }
  EXPECT_LT(worst, 2e-5f);
  std::printf("worst distance of a leaf origin from its branch axis: %.3g m\n", static_cast<double>(worst));
}

// Invariant: no NaN or Inf for zero-length branches, zero wind, zero derivative (x = 0), huge and
// non-finite wind, huge times and extreme epsilon; displacements stay bounded by the tree size.
TEST(AnimationStability, NoNanForDegenerateInput) {
  const TreeModel model = testing::small_tree();  // branch 14 has length 0, leaf 2 sits at x = 0
  const TreeMesh mesh = build_tree_mesh(model);
  const float size = glm::length(mesh.bounds_max - mesh.bounds_min);
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const glm::vec3 winds[] = {glm::vec3(0.0f), glm::vec3(1e-30f, 0.0f, 0.0f), glm::vec3(3.0f, 0.0f, 1.0f),
                             glm::vec3(1e4f, -1e4f, 1e4f), glm::vec3(3e38f, 0.0f, -3e38f), glm::vec3(inf, 0.0f, 0.0f),
                             glm::vec3(nan, 1.0f, 0.0f)};
  for (float eps : {1e-12f, 1e-6f, 1e-2f}) {
    for (double t : {0.0, 1.0, 1.0e7, 1.0e12, std::numeric_limits<double>::infinity()}) {
      for (const glm::vec3& w : winds) {
        AnimationSettings s;
        s.epsilon = eps;
        s.level3.response = 10.0f;
        s.leaf_amplitude = 10.0f;
        const AnimationGpu a = make_animation_gpu(s, t);
        const InstanceGpu inst = make_instance_gpu(TreeInstance{}, glm::dvec3(0.0), w);
        ASSERT_TRUE(std::isfinite(inst.wind.w)) << "wind " << w.x;
        const WindGpuParams wp = WindField().frame(std::isfinite(t) ? t : 0.0).gpu;
        for (const BranchVertex& v : mesh.branch_vertices) {
          const DeformedVertex d = deform_branch_vertex(mesh.data, a, inst, v);
          ASSERT_TRUE(finite(d.position) && finite(d.normal)) << "eps " << eps << " t " << t << " wind " << w.x;
          ASSERT_LT(glm::length(d.position - v.position), 2.0f * size);
        }
        for (const LeafVertex& v : mesh.leaf_vertices) {
          const DeformedVertex d = deform_leaf_vertex(mesh.data, a, inst, wp, v);
          ASSERT_TRUE(finite(d.position) && finite(d.normal) && finite(d.tangent)) << "eps " << eps << " t " << t;
          ASSERT_NEAR(glm::length(d.normal), 1.0f, 1e-5f);
        }
      }
    }
  }
}

// Invariant: the zero-length branch stays a point at its attachment (no NaN, no spurious length).
TEST(AnimationStability, ZeroLengthBranchStaysAPoint) {
  const TreeMesh mesh = build_tree_mesh(testing::small_tree());
  const AnimationGpu a = make_animation_gpu(AnimationSettings{}, 2.0);
  for (float speed : {0.0f, 10.0f, 1000.0f}) {
    const InstanceGpu inst = make_instance_gpu(TreeInstance{}, glm::dvec3(0.0), glm::vec3(speed, 0.0f, 0.5f * speed));
    const glm::vec3 p0 = branch_axis_point(mesh.data, a, inst, 4, 0.0f);
    const glm::vec3 p1 = branch_axis_point(mesh.data, a, inst, 4, 1.0f);
    EXPECT_TRUE(finite(p0) && finite(p1));
    EXPECT_EQ(glm::length(p1 - p0), 0.0f) << "speed " << speed;
  }
}

// Invariant: under a hurricane held for long (dt = 1 s steps over 10 min) the motion stays
// bounded: no vertex ever leaves a ball of the tree's size around its rest position.
TEST(AnimationStability, HurricaneStaysBounded) {
  const TreeMesh& mesh = testing::preset_mesh(SpeciesPreset::kBroadleaf);
  const WindField wind(WindSettings{.strength = 100.0f, .gust_amplitude = 100.0f, .gust_period = 0.1f,
                                    .turbulence_amplitude = 100.0f, .turbulence_scale = 0.05f});
  const float height = mesh.bounds_max.y - mesh.bounds_min.y;
  AnimationSettings s;
  s.wind_scale = 100.0f;
  float worst = 0.0f;
  for (double t = 0.0; t <= 600.0; t += 1.0) {
    const AnimationGpu a = make_animation_gpu(s, t);
    const InstanceGpu inst = make_instance_gpu(TreeInstance{}, glm::dvec3(0.0), wind, t, s);
    const WindGpuParams w = wind.frame(t).gpu;
    for (std::size_t i = 0; i < mesh.leaf_vertices.size(); i += 97) {
      const glm::vec3 p = deform_leaf_vertex(mesh.data, a, inst, w, mesh.leaf_vertices[i]).position;
      ASSERT_TRUE(finite(p));
      worst = std::max(worst, glm::length(p - mesh.leaf_vertices[i].position));
    }
  }
  EXPECT_LT(worst, height);
  std::printf("hurricane x100, 600 s at dt = 1 s: largest leaf displacement %.2f m (tree height %.2f m)\n",
              static_cast<double>(worst), static_cast<double>(height));
}

}  // namespace
}  // namespace sylva::vegetation

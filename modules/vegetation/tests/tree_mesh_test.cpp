// LOD0 mesh and packed records: the per-vertex data of seed 000 table 3.1, rest positions against
// the model's geometry built independently, and index validity.
#include <sylva/vegetation/tree_mesh.hpp>

#include <sylva/vegetation/animation.hpp>

#include "support/models.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace sylva::vegetation {
namespace {

void check_mesh(const TreeModel& model, const TreeMesh& mesh, float tolerance) {
  // Packed records.
  ASSERT_EQ(mesh.data.branches.size(), model.branches.size());
  ASSERT_EQ(mesh.data.leaves.size(), model.leaves.size());
  for (std::size_t i = 0; i < model.branches.size(); ++i) {
    const Branch& b = model.branches[i];
    const BranchGpu& g = mesh.data.branches[i];
    const std::vector<int> chain = model.chain(static_cast<int>(i));
    for (int k = 0; k < kMaxLevels; ++k)
      EXPECT_EQ(g.chain[k], k < static_cast<int>(chain.size()) ? chain[static_cast<std::size_t>(k)] : -1);
    EXPECT_EQ(g.r_parent.w, b.length);
    EXPECT_EQ(g.s_parent.w, b.c2);
    EXPECT_EQ(g.t_parent.w, b.c4);
    EXPECT_EQ(g.attach_object.w, b.amplitude_limit);
    EXPECT_EQ(static_cast<int>(g.s_object.w), b.level);
  }
  // Bark vertices: table 3.1 and rest positions.
  float worst = 0.0f;
  for (const BranchVertex& v : mesh.branch_vertices) {
    ASSERT_LT(v.branch, model.branches.size());
    const Branch& b = model.branches[v.branch];
    const std::vector<int> chain = model.chain(static_cast<int>(v.branch));
    for (int k = 0; k < b.level; ++k)
      ASSERT_EQ(v.xvec[k], model.branches[static_cast<std::size_t>(chain[static_cast<std::size_t>(k + 1)])].parent_x);
    const float x = v.xvec[b.level];
    ASSERT_GE(x, 0.0f);
    ASSERT_LE(x, 1.0f);
    for (int k = b.level + 1; k < kMaxLevels; ++k) ASSERT_EQ(v.xvec[k], 0.0f);
    const glm::vec3 expected =
        b.axis_point(x) + v.local.x * b.frame.r + v.local.y * b.frame.s + v.local.z * b.frame.t;
    worst = std::max(worst, glm::length(v.position - expected));
    // The offset is the tube radius at x (or the cap point on the axis).
    const float radial = std::hypot(v.local.x, v.local.y);
    if (v.local.z == 0.0f) {
      ASSERT_NEAR(radial, b.radius_at(x), 1e-6f);
    }
  }
  // Leaf vertices.
  for (const LeafVertex& v : mesh.leaf_vertices) {
    ASSERT_LT(v.leaf, model.leaves.size());
    const Leaf& l = model.leaves[v.leaf];
    ASSERT_EQ(static_cast<int>(v.branch), l.parent);
    const Branch& b = model.branches[v.branch];
    ASSERT_EQ(v.xvec[b.level], l.parent_x);
    const glm::vec3 expected = b.axis_point(l.parent_x) + v.corner.x * l.bitangent + v.corner.y * l.tangent;
    worst = std::max(worst, glm::length(v.position - expected));
    EXPECT_LT(glm::length(v.normal - l.normal), 1e-5f);
  }
  EXPECT_LE(worst, tolerance) << model.name;
  std::printf("%s: rest mesh vs model geometry: max |diff| %.3g m\n", model.name.c_str(), static_cast<double>(worst));
  // Indices and bounds.
  ASSERT_EQ(mesh.branch_indices.size() % 3, 0u);
  ASSERT_EQ(mesh.leaf_indices.size(), model.leaves.size() * 6);
  for (std::uint32_t i : mesh.branch_indices) ASSERT_LT(i, mesh.branch_vertices.size());
  for (std::uint32_t i : mesh.leaf_indices) ASSERT_LT(i, mesh.leaf_vertices.size());
  for (const BranchVertex& v : mesh.branch_vertices) {
    ASSERT_TRUE(glm::all(glm::greaterThanEqual(v.position, mesh.bounds_min)));
    ASSERT_TRUE(glm::all(glm::lessThanEqual(v.position, mesh.bounds_max)));
  }
}

TEST(TreeMesh, SmallTreeMatchesItsModel) {
  const TreeModel m = testing::small_tree();
  check_mesh(m, build_tree_mesh(m), 2e-6f);
}

TEST(TreeMesh, PresetsMatchTheirModels) {
  for (SpeciesPreset p : {SpeciesPreset::kBroadleaf, SpeciesPreset::kConifer, SpeciesPreset::kBirch, SpeciesPreset::kShrub})
    check_mesh(testing::preset_tree(p), testing::preset_mesh(p), 2e-5f);
}

TEST(TreeMesh, RingsFollowTheSpacingAndTrianglesAreNotDegenerate) {
  const TreeModel m = testing::small_tree();
  MeshSettings s;
  s.ring_spacing = 0.25f;
  s.level3_segments = 5;
  const TreeMesh mesh = build_tree_mesh(m, s);
  ASSERT_EQ(mesh.rings.size(), m.branches.size());
  EXPECT_EQ(mesh.rings[0], 16);  // 4 m / 0.25 m
  EXPECT_EQ(mesh.rings[4], 1);   // zero-length branch: one ring
  int degenerate = 0;
  for (std::size_t t = 0; t < mesh.branch_indices.size(); t += 3) {
    const glm::vec3 a = mesh.branch_vertices[mesh.branch_indices[t]].position;
    const glm::vec3 b = mesh.branch_vertices[mesh.branch_indices[t + 1]].position;
    const glm::vec3 c = mesh.branch_vertices[mesh.branch_indices[t + 2]].position;
    const std::uint32_t branch = mesh.branch_vertices[mesh.branch_indices[t]].branch;
    if (m.branches[branch].length > 0.0f && glm::length(glm::cross(b - a, c - a)) <= 0.0f) ++degenerate;
  }
  EXPECT_EQ(degenerate, 0);
}

}  // namespace
}  // namespace sylva::vegetation

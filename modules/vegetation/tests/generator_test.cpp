// Procedural generator: presets, determinism, the da Vinci rule, gravitropism, leaves, settings
// validation and output caps.
#include <sylva/vegetation/generator.hpp>

#include <sylva/vegetation/bending.hpp>
#include <sylva/vegetation/objt.hpp>
#include <sylva/vegetation/tree_mesh.hpp>

#include "support/models.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace sylva::vegetation {
namespace {

constexpr SpeciesPreset kPresets[] = {SpeciesPreset::kBroadleaf, SpeciesPreset::kConifer, SpeciesPreset::kBirch,
                                      SpeciesPreset::kShrub};

TEST(Generator, PresetsAreValidTreesOfTheirKind) {
  for (SpeciesPreset p : kPresets) {
    const TreeSpecies species = species_preset(p);
    const TreeModel& m = testing::preset_tree(p);
    ASSERT_TRUE(validate(m).ok()) << species.name << ": " << validate(m).error().message;
    EXPECT_EQ(m.depth(), species.levels) << species.name;
    int roots = 0;
    for (const Branch& b : m.branches) roots += b.parent < 0 ? 1 : 0;
    EXPECT_EQ(roots, species.trunk_count) << species.name;
    const glm::vec3 lo = m.bounds_min();
    const glm::vec3 hi = m.bounds_max();
    const TreeMesh& mesh = testing::preset_mesh(p);
    std::printf("%-9s branches %5zu leaves %5zu  height %5.2f m  width %5.2f m  trunk radius %.3f m  vertices %zu + %zu\n",
                species.name.c_str(), m.branches.size(), m.leaves.size(), static_cast<double>(hi.y - lo.y),
                static_cast<double>(std::max(hi.x - lo.x, hi.z - lo.z)), static_cast<double>(m.branches[0].radius_base),
                mesh.branch_vertices.size(), mesh.leaf_vertices.size());
    EXPECT_GT(m.leaves.size(), 300u) << species.name;
    EXPECT_LT(m.leaves.size(), 20000u) << species.name;
    // Trees stand on the ground and are taller than wide except the shrub.
    EXPECT_GT(lo.y, -0.5f) << species.name;
    if (p != SpeciesPreset::kShrub) {
      EXPECT_GT(hi.y - lo.y, 6.0f) << species.name;
    }
  }
  // Shapes: the conifer is narrow and tall, the shrub low and wide.
  const auto aspect = [](const TreeModel& m) {
    const glm::vec3 e = m.bounds_max() - m.bounds_min();
    return e.y / std::max(e.x, e.z);
  };
  EXPECT_GT(aspect(testing::preset_tree(SpeciesPreset::kConifer)), 1.4f);
  EXPECT_LT(aspect(testing::preset_tree(SpeciesPreset::kShrub)), 1.2f);
}

TEST(Generator, DeterministicForASeed) {
  const TreeSpecies s = species_preset(SpeciesPreset::kBirch, 42);
  Result<TreeModel> a = generate_tree(s);
  Result<TreeModel> b = generate_tree(s);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(format_objt(*a), format_objt(*b));
  Result<TreeModel> c = generate_tree(species_preset(SpeciesPreset::kBirch, 43));
  ASSERT_TRUE(c.ok());
  EXPECT_NE(format_objt(*a), format_objt(*c));
}

TEST(Generator, RadiiFollowTheDaVinciRule) {
  for (SpeciesPreset p : kPresets) {
    const TreeSpecies s = species_preset(p);
    const TreeModel& m = testing::preset_tree(p);
    const double D = s.da_vinci_exponent;
    std::vector<double> children(m.branches.size(), 0.0);
    for (const Branch& b : m.branches)
      if (b.parent >= 0) children[static_cast<std::size_t>(b.parent)] += std::pow(b.radius_base, D);
    for (std::size_t i = 0; i < m.branches.size(); ++i) {
      const Branch& b = m.branches[i];
      const double tip = std::pow(b.radius_tip, D);
      const double expected = tip + (children[i] > 0.0 ? children[i] : tip);
      EXPECT_NEAR(std::pow(b.radius_base, D), expected, 1e-4 * expected) << s.name << " branch " << b.id;
      EXPECT_FLOAT_EQ(b.radius_tip, s.twig_radius);
    }
  }
}

TEST(Generator, BendingDataFollowsTheTaper) {
  const TreeModel& m = testing::preset_tree(SpeciesPreset::kBroadleaf);
  for (const Branch& b : m.branches) {
    const BendConstants c = bend_constants_for_taper(b.radius_tip / b.radius_base);
    EXPECT_EQ(b.c2, c.c2);
    EXPECT_EQ(b.c4, c.c4);
    EXPECT_GT(b.amplitude_limit, 0.0f);
    EXPECT_GE(b.noise_phase, 0.0f);
    EXPECT_LT(b.noise_phase, 64.0f);
  }
}

float mean_child_y(const TreeModel& m, int level) {
  float sum = 0.0f;
  int n = 0;
  for (const Branch& b : m.branches)
    if (b.level == level) {
      sum += b.frame.t.y;
      ++n;
    }
  return n > 0 ? sum / static_cast<float>(n) : 0.0f;
}

TEST(Generator, GravitropismTiltsBranchesUpOrDown) {
  TreeSpecies s = species_preset(SpeciesPreset::kBroadleaf);
  s.level1.gravitropism = 0.0f;
  Result<TreeModel> neutral = generate_tree(s);
  s.level1.gravitropism = 0.8f;
  Result<TreeModel> up = generate_tree(s);
  s.level1.gravitropism = -0.8f;
  Result<TreeModel> down = generate_tree(s);
  ASSERT_TRUE(neutral.ok() && up.ok() && down.ok());
  EXPECT_GT(mean_child_y(*up, 1), mean_child_y(*neutral, 1) + 0.1f);
  EXPECT_LT(mean_child_y(*down, 1), mean_child_y(*neutral, 1) - 0.1f);
}

TEST(Generator, LeafCountSizeAndArrangementFollowTheSettings) {
  TreeSpecies s = species_preset(SpeciesPreset::kShrub);
  Result<TreeModel> base = generate_tree(s);
  s.leaves.per_metre *= 2.0f;
  s.leaves.max_per_branch = 1000;
  Result<TreeModel> dense = generate_tree(s);
  ASSERT_TRUE(base.ok() && dense.ok());
  const double ratio = static_cast<double>(dense->leaves.size()) / static_cast<double>(base->leaves.size());
  EXPECT_GT(ratio, 1.6);
  s.leaves.levels = 0;
  Result<TreeModel> bare = generate_tree(s);
  ASSERT_TRUE(bare.ok());
  EXPECT_TRUE(bare->leaves.empty());
  // Sizes within the variation.
  const TreeSpecies bs = species_preset(SpeciesPreset::kBroadleaf);
  for (const Leaf& l : testing::preset_tree(SpeciesPreset::kBroadleaf).leaves) {
    EXPECT_GE(l.width, bs.leaves.width * (1.0f - bs.leaves.size_variation) - 1e-6f);
    EXPECT_LE(l.length, bs.leaves.length * (1.0f + bs.leaves.size_variation) + 1e-6f);
  }
  // Opposite arrangement: leaves come in pairs at the same x on opposite sides.
  const TreeModel& shrub = testing::preset_tree(SpeciesPreset::kShrub);
  int pairs = 0;
  for (std::size_t i = 1; i < shrub.leaves.size(); ++i) {
    const Leaf& a = shrub.leaves[i - 1];
    const Leaf& b = shrub.leaves[i];
    if (a.parent == b.parent && a.parent_x == b.parent_x && a.parent_x < 1.0f) ++pairs;
  }
  EXPECT_GT(pairs, static_cast<int>(shrub.leaves.size()) / 4);
}

TEST(Generator, BadSettingsNameTheParameter) {
  TreeSpecies s = species_preset(SpeciesPreset::kBroadleaf);
  s.level2.angle_deg = 400.0f;
  Result<TreeModel> m = generate_tree(s);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().message.find("species.level2.angle_deg"), std::string::npos) << m.error().message;
  s = species_preset(SpeciesPreset::kBroadleaf);
  s.level1.start = 0.9f;
  s.level1.end = 0.2f;
  m = generate_tree(s);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().message.find("species.level1.start"), std::string::npos) << m.error().message;
}

TEST(Generator, OutputIsCappedWithAClearError) {
  TreeSpecies s = species_preset(SpeciesPreset::kBroadleaf);
  s.level1.count = 64;
  s.level2.count = 64;
  s.level3.count = 64;
  Result<TreeModel> m = generate_tree(s, GeneratorLimits{.max_branches = 5000, .max_leaves = 1000});
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.error().code, ErrorCode::kLimit);
  EXPECT_NE(m.error().message.find("5000 branches"), std::string::npos) << m.error().message;
  s = species_preset(SpeciesPreset::kShrub);
  m = generate_tree(s, GeneratorLimits{.max_branches = 5000, .max_leaves = 100});
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().message.find("100 leaves"), std::string::npos) << m.error().message;
}

TEST(Generator, SingleLevelTreeAndZeroLengthTrunk) {
  TreeSpecies s = species_preset(SpeciesPreset::kBroadleaf);
  s.levels = 1;
  s.trunk_length = 0.0f;
  s.trunk_length_variation = 0.0f;
  Result<TreeModel> m = generate_tree(s);
  ASSERT_TRUE(m.ok()) << m.error().describe();
  EXPECT_EQ(m->branches.size(), 1u);
  EXPECT_EQ(m->branches[0].length, 0.0f);
  EXPECT_TRUE(validate(*m).ok());
  const TreeMesh mesh = build_tree_mesh(*m);
  for (const BranchVertex& v : mesh.branch_vertices) EXPECT_TRUE(std::isfinite(v.position.x + v.position.y + v.position.z));
}

}  // namespace
}  // namespace sylva::vegetation

// Every settings struct of the module is a parameter list (DESIGN.md §2): it describes itself,
// validates, round-trips through JSON and accepts --set style assignments by dotted path.
#include <sylva/vegetation/forest.hpp>
#include <sylva/vegetation/placement.hpp>

#include <sylva/core/params.hpp>
#include <sylva/core/params_json.hpp>

#include <gtest/gtest.h>

namespace sylva::vegetation {
namespace {

template <class T>
void round_trip(const T& original) {
  const nlohmann::json j = params_to_json(original);
  T back{};
  std::vector<std::string> warnings;
  ASSERT_TRUE(params_from_json(back, j, warnings).ok());
  EXPECT_TRUE(warnings.empty());
  EXPECT_EQ(params_to_json(back), j);
  EXPECT_TRUE(diff_params(original, back).empty());
}

TEST(Settings, DescribeValidateAndRoundTrip) {
  ForestSettings forest;
  forest.animation.level2.frequency = 1.7f;
  forest.shading.alpha_mode = AlphaMode::kHashedAlphaTest;
  EXPECT_TRUE(validate_params(forest).ok());
  round_trip(forest);
  const TreeSpecies species = species_preset(SpeciesPreset::kConifer, 9);
  EXPECT_TRUE(validate_params(species).ok());
  round_trip(species);
  round_trip(PlacementSettings{});
  round_trip(MeshSettings{});
  round_trip(leaf_texture_settings_for(LeafShape::kBirch));
  round_trip(bark_texture_settings_for(SpeciesPreset::kBirch));
  // Paths are stable names the editor and the command line use.
  bool found = false;
  for (const ParamDescriptor& d : describe_params(forest, "forest")) found = found || d.path == "forest.animation.trunk.response";
  EXPECT_TRUE(found);
}

TEST(Settings, SetByPathWithRangeErrors) {
  ForestSettings s;
  ASSERT_TRUE(set_param(s, "animation.level1.turbulence", "0.02").ok());
  EXPECT_FLOAT_EQ(s.animation.level1.turbulence, 0.02f);
  ASSERT_TRUE(set_param(s, "shading.alpha_mode", "alpha_to_coverage").ok());
  EXPECT_EQ(s.shading.alpha_mode, AlphaMode::kAlphaToCoverage);
  ASSERT_TRUE(set_param(s, "animation_level", "trunk").ok());
  EXPECT_EQ(s.animation_level, AnimationLevel::kTrunk);
  const Status bad = set_param(s, "animation.epsilon", "1");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("animation.epsilon"), std::string::npos);
  TreeSpecies t;
  const Status nan = set_param(t, "level2.angle_deg", "nan");
  EXPECT_FALSE(nan.ok());
}

}  // namespace
}  // namespace sylva::vegetation

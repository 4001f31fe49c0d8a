// Settings are data: every grass parameter is reachable by path, defaults are valid, and the
// ranges reject nonsense with the parameter's path in the message.
#include <sylva/core/params.hpp>
#include <sylva/grass/grass_field.hpp>
#include <sylva/grass/settings.hpp>

#include <gtest/gtest.h>

namespace sylva::grass {
namespace {

struct AllSettings {
  GrassFieldSettings field;
  BladeSettings blade;
  GrassRenderSettings render;
  template <class V>
  void visit(V& v) {
    v(field, "field");
    v(blade, "blade");
    v(render, "render");
  }
};

TEST(GrassSettings, DefaultsAreValidAndEveryFieldIsListed) {
  AllSettings s;
  ASSERT_TRUE(validate_params(s, "grass").ok()) << validate_params(s, "grass").error().message;
  const auto params = describe_params(s, "grass");
  EXPECT_GE(params.size(), 35u);
  EXPECT_EQ(find_param(params, "grass.blade.height_max")->info.rebuild, Rebuild::kOffline);
  EXPECT_EQ(find_param(params, "grass.render.cull.near_distance")->info.rebuild, Rebuild::kNone);
  for (const auto& p : params) EXPECT_STRNE(p.info.help, "") << p.path << " needs a help text";
}

TEST(GrassSettings, SetByPathAndRangeErrorsNameThePath) {
  AllSettings s;
  const auto params = describe_params(s, "grass");
  ASSERT_TRUE(set_param(params, "grass.render.cull.near_distance", "80").ok());
  EXPECT_EQ(s.render.cull.near_distance, 80.0f);
  const Status bad = set_param(params, "grass.blade.stiffness_max", "1e9");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("grass.blade.stiffness_max"), std::string::npos);
  EXPECT_EQ(s.blade.stiffness_max, BladeSettings{}.stiffness_max);
  EXPECT_FALSE(set_param(params, "grass.render.physics.gravity", "nan").ok());
  ASSERT_TRUE(set_param(params, "grass.render.tip_color", "0.1,0.2,0.3").ok());
  EXPECT_EQ(s.render.tip_color, glm::vec3(0.1f, 0.2f, 0.3f));
  ASSERT_TRUE(set_param(params, "grass.render.shape", "triangle_tip").ok());
  EXPECT_EQ(s.render.shape, BladeShape::kTriangleTip);
  EXPECT_FALSE(set_param(params, "grass.render.shape", "hexagon").ok());
}

}  // namespace
}  // namespace sylva::grass

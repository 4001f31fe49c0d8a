// Render settings structs reflect through core's visit-based parameters (DESIGN.md §2): every
// field is enumerated, set by dotted path, and range-checked with a message naming the path.
#include <sylva/core/params.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/drawable.hpp>
#include <sylva/render/lighting.hpp>

#include <gtest/gtest.h>

namespace sylva::render {
namespace {

TEST(SettingsParams, LightingFieldsAreParameters) {
  Lighting lighting;
  const std::vector<ParamDescriptor> params = describe_params(lighting, "lighting");
  EXPECT_EQ(params.size(), 18u);  // 10 lighting fields + 8 of the atmosphere
  ASSERT_TRUE(set_param(lighting, "fog_density", "0.002").ok());
  EXPECT_FLOAT_EQ(lighting.fog_density, 0.002f);
  Status bad = set_param(lighting, "fog_density", "5");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("fog_density"), std::string::npos) << bad.error().message;
  EXPECT_TRUE(validate_params(lighting).ok());
  ASSERT_TRUE(set_param(lighting, "atmosphere.mie_g", "0.7").ok());
  EXPECT_FLOAT_EQ(lighting.atmosphere.mie_g, 0.7f);
  Status bad_g = set_param(lighting, "atmosphere.mie_g", "1.5");
  ASSERT_FALSE(bad_g.ok());
  EXPECT_NE(bad_g.error().message.find("mie_g"), std::string::npos) << bad_g.error().message;
}

TEST(SettingsParams, FlySettingsAreParameters) {
  FlySettings fly;
  EXPECT_EQ(describe_params(fly).size(), 3u);
  ASSERT_TRUE(set_param(fly, "speed", "250").ok());
  EXPECT_FLOAT_EQ(fly.speed, 250.0f);
  EXPECT_FALSE(set_param(fly, "mouse_sensitivity", "-1").ok());
  EXPECT_FALSE(set_param(fly, "no_such_field", "1").ok());
}

TEST(FrameContext, PassNames) {
  EXPECT_STREQ(to_string(Pass::kShadow), "shadow");
  EXPECT_STREQ(to_string(Pass::kOpaque), "opaque");
  EXPECT_STREQ(to_string(Pass::kTransparent), "transparent");
}

// A drawable that records what the scene asks of it: the interface is usable as intended.
class CountingDrawable : public Drawable {
 public:
  void update(const FrameContext& frame) override { last_dt = frame.dt; ++updates; }
  void draw(Pass pass, const FrameContext&, PassStats& stats) override {
    stats.draw_calls += 1;
    stats.triangles += pass == Pass::kShadow ? 10 : 20;
  }
  float last_dt = -1.0f;
  int updates = 0;
};

TEST(FrameContext, DrawableContract) {
  Camera camera;
  WindField wind;
  Lighting lighting;
  const FrameContext frame{.camera = camera, .time = 3.0, .dt = 0.0f, .wind = wind, .lighting = lighting,
                           .viewport = {256, 144}, .frame = 5};
  CountingDrawable d;
  Drawable& base = d;
  base.update(frame);
  PassStats stats;
  for (Pass p : {Pass::kShadow, Pass::kOpaque, Pass::kTransparent}) base.draw(p, frame, stats);
  base.on_region_changed({{0.0, 0.0}, {10.0, 10.0}});
  EXPECT_EQ(d.updates, 1);
  EXPECT_EQ(d.last_dt, 0.0f);
  EXPECT_EQ(stats.draw_calls, 3u);
  EXPECT_EQ(stats.triangles, 50u);
}

}  // namespace
}  // namespace sylva::render

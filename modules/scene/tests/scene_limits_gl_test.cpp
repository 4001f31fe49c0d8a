// Sizes that would exhaust the GPU are refused before anything is allocated, with a message
// naming the parameter or file and the limit (a 16384^2 ground used to run the GPU buffer out of
// memory, log 262,000 GL errors and draw no ground with exit code 0).
#include <sylva/render/testing.hpp>
#include <sylva/scene/scene.hpp>

#include <gtest/gtest.h>

using namespace sylva;
using namespace sylva::scene;

using SceneLimitsGl = render::GlTest;

TEST_F(SceneLimitsGl, PlainGroundTooLargeForTheGpuIsRefusedBeforeAllocating) {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::from_text(R"({"ground": {"resolution": 8193, "size": 8192, "generator": "flat"}})",
                                      "big.json", warnings);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  const std::size_t mark = render::gl_error_mark();
  auto scene = Scene::create(std::move(*doc));
  ASSERT_FALSE(scene.ok());
  EXPECT_EQ(scene.error().code, ErrorCode::kLimit);
  EXPECT_NE(scene.error().message.find("ground.resolution = 8193"), std::string::npos) << scene.error().message;
  EXPECT_NE(scene.error().message.find("limit of 1024 MiB"), std::string::npos) << scene.error().message;
  EXPECT_TRUE(render::check_frame_gl_errors(mark, "creation").ok()) << "nothing was allocated, no GL error";
}

TEST_F(SceneLimitsGl, LargestPlainGroundWithinTheLimitBuilds) {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::from_text(R"({"ground": {"resolution": 2049, "size": 2048, "generator": "flat"}})",
                                      "ok.json", warnings);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  auto scene = Scene::create(std::move(*doc));
  ASSERT_TRUE(scene.ok()) << scene.error().message;
}

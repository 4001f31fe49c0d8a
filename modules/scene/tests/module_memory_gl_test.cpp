// GPU memory per module (issue #20): the scene counts what each module allocates under the
// module's name (render/gpu_memory.hpp), its own sky, shadow maps and targets under "scene", a
// finer ground holds more, and destroying the scene returns every byte.
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/gpu_memory.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/frame_stats.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene.hpp>

#include "render_once.hpp"

#include <gtest/gtest.h>

using namespace sylva;
using namespace sylva::scene;

namespace {

using ModuleMemoryGl = render::GlTest;

std::unique_ptr<Scene> make_scene(int ground_resolution, bool grass) {
  std::vector<std::string> warnings;
  std::string text = R"({"ground": {"size": 128, "resolution": )" + std::to_string(ground_resolution) + "}";
  if (grass) text += R"(, "grass": {"area_min": [-10, -10], "area_max": [10, 10]})";
  auto doc = SceneDocument::from_text(text + "}", "memory.json", warnings);
  EXPECT_TRUE(doc.ok()) << doc.error().message;
  auto scene = Scene::create(std::move(*doc));
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  return scene.ok() ? std::move(*scene) : nullptr;
}

std::uint64_t held(const std::string& owner) {
  const auto usage = render::gpu_memory_usage();
  const auto it = usage.find(owner);
  return it == usage.end() ? 0 : it->second.total();
}

using sylva::scene::testing::render_once;

TEST_F(ModuleMemoryGl, EachModuleHoldsItsOwnBytesAndGivesThemBack) {
  const std::uint64_t before_ground = held("ground"), before_scene = held("scene");
  {
    auto coarse = make_scene(33, false);
    ASSERT_TRUE(coarse);
    render_once(*coarse);
    const std::uint64_t coarse_ground = held("ground") - before_ground;
    EXPECT_GT(coarse_ground, 33u * 33u * 4u) << "at least a float per height sample";
    EXPECT_GT(held("scene"), before_scene) << "sky, shadow maps, targets";
    if (find_module("grass")) {
      const std::uint64_t before_grass = held("grass");
      auto with_grass = make_scene(33, true);
      ASSERT_TRUE(with_grass);
      render_once(*with_grass);
      EXPECT_GT(held("grass"), before_grass) << "the grass module's blades and buffers are its own";
    }
    auto fine = make_scene(129, false);
    ASSERT_TRUE(fine);
    render_once(*fine);
    EXPECT_GT(held("ground") - before_ground - coarse_ground, coarse_ground) << "a finer ground holds more";
    const nlohmann::json report = memory_report();
    EXPECT_EQ(report["gpu_bytes"]["ground"]["total"].get<std::uint64_t>(), held("ground"));
  }
  EXPECT_EQ(held("ground"), before_ground) << "destroying the scenes returns every byte";
  EXPECT_EQ(held("scene"), before_scene);
}

}  // namespace

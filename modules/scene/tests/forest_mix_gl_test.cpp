// A vegetation section's mixed stand ("mix": a weight per species preset): every weighted preset
// becomes a species of the forest, trees are shared out in proportion to the weights, the split
// is the same at every load (a hash of each trunk's position picks its species), and an all-zero
// mix keeps the single `species`.
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/module_instance.hpp>
#include <sylva/scene/scene.hpp>

#include <gtest/gtest.h>

#include <cmath>

using namespace sylva;
using namespace sylva::scene;

namespace {

using ForestMixGl = render::GlTest;

std::unique_ptr<Scene> make_scene(const std::string& vegetation) {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::from_text(R"({"ground": {"resolution": 33, "size": 512, "height": 5, "generator": "fbm"},
                                          "vegetation": )" + vegetation + "}",
                                      "test.json", warnings);
  EXPECT_TRUE(doc.ok()) << doc.error().message;
  if (!doc.ok()) return nullptr;
  auto scene = Scene::create(std::move(*doc));
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  return scene.ok() ? std::move(*scene) : nullptr;
}

constexpr const char* kMixed = R"({"area_min": [-200, -200], "area_max": [200, 200], "trees_per_hectare": 40,
                                   "leaf_texture_size": 32, "mix": {"broadleaf": 3, "conifer": 2, "birch": 1}})";

TEST_F(ForestMixGl, WeightsShareTheTreesOutAndTheSplitIsStable) {
  if (!find_module("vegetation")) GTEST_SKIP() << "vegetation is built out";
  auto scene = make_scene(kMixed);
  ASSERT_TRUE(scene);
  const nlohmann::json stats = scene->module_stats()["vegetation"];
  const nlohmann::json per = stats["trees_per_species"];
  ASSERT_EQ(per.size(), 3u) << stats.dump();
  EXPECT_FALSE(per.contains("shrub")) << "a zero weight adds no species";
  const double trees = stats["trees"].get<double>();
  ASSERT_GT(trees, 300.0);
  EXPECT_NEAR(per["broadleaf"].get<double>() / trees, 3.0 / 6.0, 0.06) << per.dump();
  EXPECT_NEAR(per["conifer"].get<double>() / trees, 2.0 / 6.0, 0.06) << per.dump();
  EXPECT_NEAR(per["birch"].get<double>() / trees, 1.0 / 6.0, 0.06) << per.dump();
  // Each species is its own model: a conifer is not a broadleaf mesh.
  const nlohmann::json tris = stats["triangles_per_tree"];
  EXPECT_NE(tris["broadleaf"].get<int>(), tris["conifer"].get<int>());

  auto again = make_scene(kMixed);
  ASSERT_TRUE(again);
  EXPECT_EQ(again->module_stats()["vegetation"]["trees_per_species"], per) << "the split is the same at every load";
}

TEST_F(ForestMixGl, AnAllZeroMixKeepsTheSingleSpecies) {
  if (!find_module("vegetation")) GTEST_SKIP() << "vegetation is built out";
  auto scene = make_scene(R"({"area_min": [-50, -50], "area_max": [50, 50], "trees_per_hectare": 40,
                              "leaf_texture_size": 32, "species": "conifer"})");
  ASSERT_TRUE(scene);
  const nlohmann::json per = scene->module_stats()["vegetation"]["trees_per_species"];
  ASSERT_EQ(per.size(), 1u) << per.dump();
  EXPECT_TRUE(per.contains("conifer")) << per.dump();
}

// The grid layout through a scene file: one tree at a known spot (the thesis experiments'
// single-tree scenes), standing on the ground.
TEST_F(ForestMixGl, AGridLayoutPlacesOneTreeAtTheOrigin) {
  if (!find_module("vegetation")) GTEST_SKIP() << "vegetation is built out";
  auto scene = make_scene(R"({"area_min": [-1, -1], "area_max": [1, 1], "layout": "grid", "trees_per_hectare": 1,
                              "leaf_texture_size": 32})");
  ASSERT_TRUE(scene);
  const std::vector<glm::dvec3> trees = scene->module("vegetation")->placed_positions(10);
  ASSERT_EQ(trees.size(), 1u);
  EXPECT_EQ(trees[0].x, 0.0);
  EXPECT_EQ(trees[0].z, 0.0);
  EXPECT_NEAR(trees[0].y, scene->ground_height(0.0, 0.0), 1e-4);
}

// The forest's LOD switches reach a scene file (`vegetation.forest.lod.*`, what the editor's
// panels and --set edit): a tree 60 m away (LOD1) in a strong wind changes shade with
// color_noise, and vanishes with draw_lod1 off.
TEST_F(ForestMixGl, LodSwitchesReachTheSceneFile) {
  if (!find_module("vegetation")) GTEST_SKIP() << "vegetation is built out";
  std::vector<std::string> warnings;
  auto doc = SceneDocument::from_text(R"({"camera": {"position": [0, 6, 60], "yaw_deg": 0, "pitch_deg": 0, "fov_deg": 12},
      "wind": {"strength": 8, "gust_amplitude": 0},
      "render": {"msaa_samples": 1, "shadows": {"enabled": false}},
      "ground": {"resolution": 33, "size": 512, "generator": "flat"},
      "vegetation": {"area_min": [-1, -1], "area_max": [1, 1], "layout": "grid", "trees_per_hectare": 1,
                     "leaf_texture_size": 32, "forest": {"lod": {"color_noise": 0}}}})", "lod.json", warnings);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  auto scene = Scene::create(std::move(*doc));
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  const glm::ivec2 size(96, 96);
  auto fb = render::Framebuffer::create({.width = size.x, .height = size.y}).value();
  const auto frame = [&] {
    render::FrameProfiler profiler;
    const render::Camera camera = (*scene)->make_camera((*scene)->document().camera, size);
    for (int i = 0; i < 2; ++i) {  // the forest hands its instances over at the first update
      (*scene)->update(camera, 2.0, 0.0f, size);
      (*scene)->render(fb, profiler);
    }
    return render::read_color(fb).value();
  };
  const auto changed = [](const Image& a, const Image& b) {
    int n = 0;
    for (int y = 0; y < a.height(); ++y)
      for (int x = 0; x < a.width(); ++x)
        for (int c = 0; c < 3; ++c) {
          if (std::abs(a.at(x, y, c) - b.at(x, y, c)) > 0.01f) {
            ++n;
            break;
          }
        }
    return n;
  };
  const Image plain = frame();
  EXPECT_EQ((*scene)->module_stats()["vegetation"]["instances_per_lod"]["lod1"].get<int>(), 1) << "the tree is at LOD1";
  ASSERT_TRUE((*scene)->set_param("vegetation.forest.lod.color_noise", "0.05").ok());
  const Image noisy = frame();
  EXPECT_GT(changed(plain, noisy), 30) << "colour noise turns the leaves";
  ASSERT_TRUE((*scene)->set_param("vegetation.forest.lod.draw_lod1", "false").ok());
  const Image gone = frame();
  EXPECT_GT(changed(noisy, gone), 200) << "LOD1 switched off: the tree is not drawn";
}

}  // namespace

// Seed 001's control texture and Sylva's tint map through scene files (issue #16, "Grass").
//
// grass.maps.control names seed 001's RGB control texture (§3.3: R density, G blade height, B
// terrain height); grass.control.channels says which channels fill the density and height maps
// ("rg" by default, "gr" swaps them). grass.maps.tint names an RGB image whose channels fill the
// tint_r/tint_g/tint_b maps, the colour multiplier of the blades and of the far field (clumps and
// ground layer). Checked:
//  - a control texture whose R is 0 on the left half (x < 0) and G 0.5 everywhere grows no blade
//    root left of the middle (within the one-texel bilinear band) and halves the tallest blade;
//    "gr" (density from G, height from R) grows blades on both halves, up to full height;
//  - a tint of pure red on the left half takes the green out of the blades there (and of the far
//    field's clumps and ground layer) and leaves the right half's pixels as they were;
//  - painting the tint or the density map through the scene API and writing the old texels back
//    (what the editor's undo does) gives the first picture and blade count back bit for bit;
//  - a painted map filled from the control texture is saved to its own file, which wins over the
//    channel when the saved scene is opened again;
//  - errors (too few channels, a 1 x 1 image, a missing file, a bad channels string) name the key
//    and the file;
//  - the ground's control.file reads the texture's B channel inverted as the terrain (seed 001
//    §3.2), the blades stand on it, and painting the ground never writes the texture.
#include <sylva/core/atomic_file.hpp>
#include <sylva/core/height_field.hpp>
#include <sylva/core/image.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/map_grid.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene.hpp>

#include "scene_test_files.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

using namespace sylva;
using namespace sylva::scene;
namespace fs = std::filesystem;

namespace {

using GrassControlMapsGl = render::GlTest;

constexpr glm::ivec2 kSize(192, 128);

// 20 x 20 m of grass seen from above and behind; camera x = 0, so world x < 0 is the left half of
// the picture. No wind, no physics: the blades keep their pose from frame to frame.
nlohmann::json stage(const nlohmann::json& grass_extra) {
  nlohmann::json j = nlohmann::json::parse(R"json({
    "sylva_scene": 1,
    "name": "grass control maps stage",
    "camera": {"position": [0.0, 9.0, 9.0], "height_mode": "absolute", "yaw_deg": 0.0, "pitch_deg": -50.0, "fov_deg": 60.0},
    "sun": {"follow_clock": false, "azimuth_deg": 200.0, "elevation_deg": 35.0, "fog_density": 0.0},
    "wind": {"direction_deg": 20.0, "strength": 0.0, "gust_amplitude": 0.0},
    "ground": {"size": 128.0, "resolution": 33, "generator": "flat"},
    "grass": {"area_min": [-10.0, -10.0], "area_max": [10.0, 10.0], "far_field": false,
              "field": {"density": 150.0, "tile_size": 2.0},
              "render": {"simulate": false}},
    "render": {"shadows": {"enabled": false}, "msaa_samples": 1, "tone_map": false}
  })json");
  j["grass"].merge_patch(grass_extra);
  return j;
}


// A w x h image of `channels` whose texel (i, j) is f(i, j, c), written as 8-bit PNG.
void write_png(const fs::path& file, int w, int h, int channels, const std::function<float(int, int, int)>& f) {
  Image im(w, h, channels);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      for (int c = 0; c < channels; ++c) im.at(i, j, c) = f(i, j, c);
  ASSERT_TRUE(write_image(file, im, PixelFormat::kU8).ok());
}


struct Frame {
  Image image;
  std::uint64_t blades = 0;
  double max_height = 0.0;
};

Frame render_frame(Scene& scene) {
  const render::Camera camera = scene.make_camera(scene.document().camera, kSize);
  auto fb = render::Framebuffer::create({.width = kSize.x, .height = kSize.y, .color_formats = {GL_RGBA16F}}).value();
  render::FrameProfiler profiler;
  for (int i = 0; i < 2; ++i) {  // an edited map regenerates at the next frame
    scene.update(camera, 1.0 + i / 30.0, 1.0f / 30.0f, kSize);
    scene.render(fb, profiler);
  }
  const nlohmann::json g = scene.module_stats()["grass"];
  return {render::read_color(fb).value(), g["blades"].get<std::uint64_t>(), g["max_blade_height"].get<double>()};
}

// Mean colour of the pixels of columns [x0, x1) where `a` and `b` differ, and their count.
struct Changed {
  glm::dvec3 mean_a{0.0}, mean_b{0.0};
  std::size_t count = 0;
};
Changed changed_pixels(const Image& a, const Image& b, int x0, int x1) {
  Changed c;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = x0; x < x1; ++x) {
      const glm::dvec3 pa(a.at(x, y, 0), a.at(x, y, 1), a.at(x, y, 2)), pb(b.at(x, y, 0), b.at(x, y, 1), b.at(x, y, 2));
      if (pa == pb) continue;
      c.mean_a += pa;
      c.mean_b += pb;
      ++c.count;
    }
  }
  if (c.count) {
    c.mean_a /= static_cast<double>(c.count);
    c.mean_b /= static_cast<double>(c.count);
  }
  return c;
}

bool same_pixels(const Image& a, const Image& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::equal(a.data().begin(), a.data().end(), b.data().begin());
}

}  // namespace

TEST_F(GrassControlMapsGl, ControlTextureFeedsDensityAndHeightThroughItsChannels) {
  if (!find_module("grass") || !find_module("ground")) GTEST_SKIP() << "needs the grass and ground modules";
  scene::testing::TestDir dir("sylva_grass_maps");
  // R: 0 on the left half (world x < 0), 1 on the right; G: 0.5; B: 0.3 (terrain, not read).
  write_png(dir.path / "control.png", 64, 64, 3, [](int i, int, int c) {
    return c == 0 ? (i < 32 ? 0.0f : 1.0f) : c == 1 ? 0.5f : 0.3f;
  });
  auto roots_left = [](Scene& scene, std::size_t blades, double& left_share) {
    const std::vector<glm::dvec3> roots = scene.module("grass")->placed_positions(blades);
    std::size_t left = 0;
    double min_x = 1e9;
    for (const glm::dvec3& p : roots) {
      left += p.x < 0.0 ? 1 : 0;
      min_x = std::min(min_x, p.x);
    }
    left_share = roots.empty() ? 0.0 : static_cast<double>(left) / static_cast<double>(roots.size());
    return min_x;
  };

  auto rg = scene::testing::scene_from_json(stage({{"maps", {{"control", "control.png"}}}}), dir.path);
  ASSERT_TRUE(rg.ok()) << rg.error().message;
  const Frame f_rg = render_frame(**rg);
  double left_rg = 0.0;
  const double min_x_rg = roots_left(**rg, f_rg.blades, left_rg);

  auto gr = scene::testing::scene_from_json(stage({{"maps", {{"control", "control.png"}}}, {"control", {{"channels", "gr"}}}}), dir.path);
  ASSERT_TRUE(gr.ok()) << gr.error().message;
  const Frame f_gr = render_frame(**gr);
  double left_gr = 0.0;
  roots_left(**gr, f_gr.blades, left_gr);

  auto plain = scene::testing::scene_from_json(stage(nlohmann::json::object()), dir.path);
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  const Frame f_plain = render_frame(**plain);

  std::printf("rg: %llu blades, leftmost root x %.3f, left share %.3f, tallest %.3f m; gr: %llu blades, left share %.3f, "
              "tallest %.3f m; no control: %llu blades, tallest %.3f m\n",
              static_cast<unsigned long long>(f_rg.blades), min_x_rg, left_rg, f_rg.max_height,
              static_cast<unsigned long long>(f_gr.blades), left_gr, f_gr.max_height,
              static_cast<unsigned long long>(f_plain.blades), f_plain.max_height);
  // R = 0 on the left: no root left of the bilinear band (one texel = 20/64 m) around x = 0.
  EXPECT_GT(min_x_rg, -20.0 / 64.0);
  EXPECT_LT(left_rg, 0.01);
  EXPECT_NEAR(static_cast<double>(f_rg.blades) / static_cast<double>(f_plain.blades), 0.5, 0.03);
  // G = 0.5 scales every blade's height by 0.5.
  EXPECT_NEAR(f_rg.max_height / f_plain.max_height, 0.5, 0.01);
  // Swapped: density 0.5 from G on both halves, height from R (1 on the right: full height).
  EXPECT_NEAR(left_gr, 0.5, 0.05);
  EXPECT_NEAR(static_cast<double>(f_gr.blades) / static_cast<double>(f_plain.blades), 0.5, 0.03);
  EXPECT_NEAR(f_gr.max_height / f_plain.max_height, 1.0, 0.01);
  // The control texture filled the density map the editor paints.
  const SceneMap* density = (*rg)->map("grass.density");
  ASSERT_NE(density, nullptr);
  EXPECT_EQ(density->grid.width, 64);
  EXPECT_EQ(density->grid.at(0, 10), 0.0f);
  EXPECT_EQ(density->grid.at(63, 10), 1.0f);
}

TEST_F(GrassControlMapsGl, RedTintOnTheLeftHalfReddensItsBladesAndFarField) {
  if (!find_module("grass") || !find_module("ground")) GTEST_SKIP() << "needs the grass and ground modules";
  scene::testing::TestDir dir("sylva_grass_maps");
  write_png(dir.path / "tint.png", 32, 32, 3, [](int i, int, int c) { return i < 16 && c > 0 ? 0.0f : 1.0f; });
  // Blades only, then the far field only (blades end at 0.5 m: clumps and the ground layer).
  const nlohmann::json far_only = {{"far_field", true},
                                   {"render", {{"cull", {{"near_distance", 0.5}}}}},
                                   {"far", {{"clump_fade_in", 0.0}, {"mid_distance", 10000.0}, {"mid_fade", 0.0}}}};
  // Share of the left columns the tint must change: blades cover 16 % of them (measured), the
  // far field's clumps and ground layer 80 % (12 % with the ground layer left untinted).
  const std::pair<nlohmann::json, double> cases[] = {{nlohmann::json::object(), 0.1}, {far_only, 0.6}};
  for (const auto& [extra, min_share] : cases) {
    SCOPED_TRACE(extra.dump());
    auto plain = scene::testing::scene_from_json(stage(extra), dir.path);
    ASSERT_TRUE(plain.ok()) << plain.error().message;
    nlohmann::json tinted_extra = extra;
    tinted_extra["maps"] = {{"tint", "tint.png"}};
    auto tinted = scene::testing::scene_from_json(stage(tinted_extra), dir.path);
    ASSERT_TRUE(tinted.ok()) << tinted.error().message;
    const Frame a = render_frame(**plain), b = render_frame(**tinted);
    EXPECT_EQ(a.blades, b.blades) << "tint changes colour only";
    // Columns clear of the middle, where blades and billboards rooted within the tint's bilinear
    // band (one texel = 0.625 m) around x = 0 reach across.
    const Changed left = changed_pixels(a.image, b.image, 0, kSize.x * 2 / 5);
    const Changed right = changed_pixels(a.image, b.image, kSize.x * 3 / 5, kSize.x);
    const double left_columns = kSize.x * 2 / 5 * kSize.y;
    std::printf("left: %zu of %.0f pixels changed, rgb (%.4f %.4f %.4f) -> (%.4f %.4f %.4f); right: %zu changed\n",
                left.count, left_columns, left.mean_a.r, left.mean_a.g, left.mean_a.b, left.mean_b.r, left.mean_b.g,
                left.mean_b.b, right.count);
    EXPECT_GT(static_cast<double>(left.count), min_share * left_columns) << "the grass covers the left half";
    EXPECT_LT(left.mean_b.g, 0.05 * left.mean_a.g) << "no green left in the tinted grass";
    EXPECT_LT(left.mean_b.b, 0.05 * left.mean_a.b + 1e-4);
    EXPECT_NEAR(left.mean_b.r, left.mean_a.r, 0.02 * left.mean_a.r) << "red kept";
    EXPECT_EQ(right.count, 0u) << "the white half is as without a tint";
  }
}

TEST_F(GrassControlMapsGl, PaintingThenUndoRestoresThePictureBitForBit) {
  if (!find_module("grass") || !find_module("ground")) GTEST_SKIP() << "needs the grass and ground modules";
  scene::testing::TestDir dir("sylva_grass_maps");
  write_png(dir.path / "control.png", 40, 40, 3, [](int i, int j, int c) { return c == 0 ? 0.5f + 0.5f * ((i + j) % 2) : 0.8f; });
  auto made = scene::testing::scene_from_json(stage({{"maps", {{"control", "control.png"}}}}), dir.path);
  ASSERT_TRUE(made.ok()) << made.error().message;
  Scene& scene = **made;
  const Frame before = render_frame(scene);
  for (const char* id : {"grass.tint_g", "grass.density"}) {
    SCOPED_TRACE(id);
    SceneMap* map = scene.map(id);
    ASSERT_NE(map, nullptr);
    // A dab: a 12 x 12 texel square left of the middle set to 0 (the editor's brush writes texels
    // the same way and keeps copy_rect() of them for undo).
    const TexelRect rect{map->grid.width / 4, map->grid.height / 3, map->grid.width / 4 + 12, map->grid.height / 3 + 12};
    const std::vector<float> old = map->grid.copy_rect(rect);
    for (int j = rect.y0; j < rect.y1; ++j)
      for (int i = rect.x0; i < rect.x1; ++i) map->grid.at(i, j) = 0.0f;
    ASSERT_TRUE(scene.map_changed(id, rect).ok());
    const Frame painted = render_frame(scene);
    EXPECT_FALSE(same_pixels(painted.image, before.image)) << "the dab shows";
    map->grid.paste_rect(rect, old);  // undo
    ASSERT_TRUE(scene.map_changed(id, rect).ok());
    const Frame undone = render_frame(scene);
    std::printf("%s: %llu blades before, %llu painted, %llu undone\n", id, static_cast<unsigned long long>(before.blades),
                static_cast<unsigned long long>(painted.blades), static_cast<unsigned long long>(undone.blades));
    EXPECT_EQ(undone.blades, before.blades);
    EXPECT_TRUE(same_pixels(undone.image, before.image)) << "undo gives the first picture back bit for bit";
  }
}

// A painted map filled from the control texture is saved to its own file, which wins over the
// control texture's channel when the saved scene is opened again (16-bit PNG: within 1/65535).
TEST_F(GrassControlMapsGl, APaintedControlMapIsSavedAndWinsOverTheChannel) {
  if (!find_module("grass") || !find_module("ground")) GTEST_SKIP() << "needs the grass and ground modules";
  scene::testing::TestDir dir("sylva_grass_maps");
  write_png(dir.path / "control.png", 16, 16, 3, [](int i, int, int c) { return c == 0 ? (i < 8 ? 0.0f : 1.0f) : 0.6f; });
  auto made = scene::testing::scene_from_json(stage({{"maps", {{"control", "control.png"}}}}), dir.path);
  ASSERT_TRUE(made.ok()) << made.error().message;
  Scene& scene = **made;
  SceneMap* density = scene.map("grass.density");
  ASSERT_NE(density, nullptr);
  EXPECT_FALSE(density->unsaved()) << "filled from the control texture, not edited";
  for (int j = 2; j < 6; ++j)
    for (int i = 2; i < 6; ++i) density->grid.at(i, j) = 0.25f;
  ASSERT_TRUE(scene.map_changed("grass.density", {2, 2, 6, 6}).ok());
  ASSERT_TRUE(scene.save(dir.path / "saved.json").ok());
  const ModuleSection* grass = scene.document().module("grass");
  ASSERT_NE(grass, nullptr);
  EXPECT_EQ(grass->maps.count("control"), 1u);
  ASSERT_EQ(grass->maps.count("density"), 1u) << "the painted map got its own file";
  EXPECT_EQ(grass->maps.count("height"), 0u) << "the unedited height map stays the control's G";

  std::vector<std::string> warnings;
  auto doc = SceneDocument::load(dir.path / "saved.json", warnings);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  auto again = Scene::create(std::move(*doc));
  ASSERT_TRUE(again.ok()) << again.error().message;
  const SceneMap* loaded = (*again)->map("grass.density");
  const SceneMap* height = (*again)->map("grass.height");
  ASSERT_NE(loaded, nullptr);
  ASSERT_NE(height, nullptr);
  EXPECT_NEAR(loaded->grid.at(3, 3), 0.25f, 1.0f / 65535.0f) << "the painted texels, from the saved file";
  EXPECT_EQ(loaded->grid.at(1, 9), 0.0f);
  EXPECT_EQ(loaded->grid.at(12, 9), 1.0f);
  EXPECT_NEAR(height->grid.at(5, 5), 0.6f, 1.0f / 255.0f) << "G of the control texture";
}

TEST_F(GrassControlMapsGl, BadControlAndTintFilesNameTheKeyAndTheFile) {
  if (!find_module("grass") || !find_module("ground")) GTEST_SKIP() << "needs the grass and ground modules";
  scene::testing::TestDir dir("sylva_grass_maps");
  write_png(dir.path / "gray.png", 8, 8, 1, [](int, int, int) { return 0.5f; });
  write_png(dir.path / "dot.png", 1, 1, 3, [](int, int, int) { return 0.5f; });
  write_png(dir.path / "good.png", 8, 8, 3, [](int, int, int) { return 0.5f; });
  struct Case {
    nlohmann::json grass;
    std::vector<std::string> expected;
  };
  const std::vector<Case> cases = {
      {{{"maps", {{"control", "gray.png"}}}}, {"grass.maps.control", "gray.png", "1 channel", "needs 2"}},
      {{{"maps", {{"control", "dot.png"}}}}, {"grass.maps.control", "dot.png", "1 x 1"}},
      {{{"maps", {{"control", "missing.png"}}}}, {"grass.maps.control", "missing.png"}},
      {{{"maps", {{"tint", "gray.png"}}}}, {"grass.maps.tint", "gray.png", "needs 3"}},
      {{{"maps", {{"control", "good.png"}}}, {"control", {{"channels", "rx"}}}}, {"grass.control.channels", "rx"}},
  };
  for (const Case& c : cases) {
    // The scene opens without its grass and says why (issue 16, Bad input).
    auto warned = scene::testing::open_leaving_out(stage(c.grass), dir.path, "grass");
    ASSERT_TRUE(warned.ok()) << c.grass.dump() << ": " << warned.error().message;
    std::printf("%s", warned->c_str());
    for (const std::string& s : c.expected) EXPECT_NE(warned->find(s), std::string::npos) << *warned;
  }
}

// A left-out grass section comes back when the setting is fixed (the editor's panel and --set go
// through set_param), in its place in the draw order; a setting that still fails keeps it out.
TEST_F(GrassControlMapsGl, LeftOutGrassIsBuiltAgainWhenItsFileIsFixed) {
  if (!find_module("grass") || !find_module("ground")) GTEST_SKIP() << "needs the grass and ground modules";
  scene::testing::TestDir dir("sylva_grass_maps");
  write_png(dir.path / "good.png", 8, 8, 3, [](int, int, int) { return 1.0f; });
  nlohmann::json json = stage({{"maps", {{"control", "missing.png"}}}});
  json["vegetation"] = {{"area_min", {-5, -5}}, {"area_max", {5, 5}}, {"trees_per_hectare", 100}, {"leaf_texture_size", 16}};
  auto made = scene::testing::scene_from_json(json, dir.path);
  ASSERT_TRUE(made.ok()) << made.error().message;
  Scene& scene = **made;
  EXPECT_TRUE(scene.left_out("grass"));
  EXPECT_EQ(scene.module("grass"), nullptr);
  EXPECT_FALSE(scene.set_param("grass.field.density", "120").ok()) << "still the missing file";
  EXPECT_TRUE(scene.left_out("grass"));
  ModuleSection* grass = scene.document().module("grass");
  ASSERT_NE(grass, nullptr);
  grass->maps["control"] = "good.png";
  ASSERT_TRUE(scene.reload_module("grass").ok());
  EXPECT_FALSE(scene.left_out("grass"));
  ASSERT_NE(scene.module("grass"), nullptr);
  std::vector<std::string> order;
  for (const auto& m : scene.modules()) order.push_back(m->module());
  std::vector<std::string> expected;
  for (const ModuleSection& section : scene.document().modules()) expected.push_back(section.name);
  EXPECT_EQ(order, expected) << "grass back in the document's order";
  EXPECT_GE(order.size(), 3u);
  EXPECT_GT(render_frame(scene).blades, 1000u);
}

// Seed 001 §3.2: the terrain comes from the control texture's blue channel, inverted (y =
// max_height * (1 - B)). A ground section naming the same file in `control.file` (with
// map_scale = max_height) gets those heights, the grass the texture's R and G stands on them, and
// painting the ground saves its own height map: the control texture is never written.
TEST_F(GrassControlMapsGl, TheControlTexturesBlueIsTheGroundAndIsNeverWritten) {
  if (!find_module("grass") || !find_module("ground")) GTEST_SKIP() << "needs the grass and ground modules";
  scene::testing::TestDir dir("sylva_grass_maps");
  // B rises along x (dark in the west = high there), R and G full.
  write_png(dir.path / "control.png", 64, 64, 3, [](int i, int, int c) { return c == 2 ? static_cast<float>(i) / 63.0f : 1.0f; });
  nlohmann::json json = stage({{"maps", {{"control", "control.png"}}}});
  json["ground"] = {{"size", 126.0}, {"map_scale", 20.0}, {"control", {{"file", "control.png"}}}};
  auto made = scene::testing::scene_from_json(json, dir.path);
  ASSERT_TRUE(made.ok()) << made.error().message;
  Scene& scene = **made;
  const SceneMap* height = scene.map("ground.height");
  ASSERT_NE(height, nullptr);
  ASSERT_EQ(height->grid.width, 64);
  EXPECT_DOUBLE_EQ(height->grid.texel_size.x, 2.0) << "size 126 m over 63 intervals";
  for (int i : {0, 17, 40, 63}) {
    const float b = std::round(static_cast<float>(i) / 63.0f * 255.0f) / 255.0f;  // the 8-bit texel
    EXPECT_NEAR(height->grid.at(i, 30), 20.0f * (1.0f - b), 1.0e-4f) << "texel " << i;
  }
  const HeightField* ground = scene.ground();
  ASSERT_NE(ground, nullptr);
  EXPECT_NEAR(ground->height(-63.0, 0.0), 20.0, 1.0e-3) << "west edge: B = 0, the highest";
  EXPECT_NEAR(ground->height(63.0, 0.0), 0.0, 1.0e-3) << "east edge: B = 1, the lowest";

  const Frame f = render_frame(scene);
  const std::vector<glm::dvec3> roots = scene.module("grass")->placed_positions(f.blades);
  ASSERT_GT(roots.size(), 1000u);
  double worst = 0.0;
  for (const glm::dvec3& p : roots) worst = std::max(worst, std::abs(p.y - ground->height(p.x, p.z)));
  std::printf("control-texture ground: %zu roots, largest root-to-ground gap %.5f m\n", roots.size(), worst);
  EXPECT_LT(worst, 1.0e-3) << "the blades stand on the blue channel's terrain";

  // Painting the ground and saving writes a height map of its own, not the control texture.
  const std::string before = read_file(dir.path / "control.png").value();
  SceneMap* painted = scene.map("ground.height");
  for (int j = 10; j < 14; ++j)
    for (int i = 10; i < 14; ++i) painted->grid.at(i, j) = 7.0f;
  ASSERT_TRUE(scene.map_changed("ground.height", {10, 10, 14, 14}).ok());
  ASSERT_TRUE(scene.save(dir.path / "saved.json").ok());
  EXPECT_EQ(read_file(dir.path / "control.png").value(), before) << "the control texture is only read";
  const ModuleSection* section = scene.document().module("ground");
  ASSERT_NE(section, nullptr);
  ASSERT_EQ(section->maps.count("height"), 1u) << "the painted heights got their own file";
  std::vector<std::string> warnings;
  auto doc = SceneDocument::load(dir.path / "saved.json", warnings);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  auto again = Scene::create(std::move(*doc));
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_NEAR((*again)->map("ground.height")->grid.at(11, 11), 7.0f, 1.0e-3f) << "the saved map wins over the channel";
  EXPECT_NEAR((*again)->map("ground.height")->grid.at(40, 30), height->grid.at(40, 30), 1.0e-3f);

  // A channel the image lacks names the key and the file.
  write_png(dir.path / "rgb.png", 8, 8, 3, [](int, int, int) { return 0.5f; });
  json["ground"]["control"] = {{"file", "rgb.png"}, {"channel", "a"}};
  auto bad = scene::testing::scene_from_json(json, dir.path);
  ASSERT_FALSE(bad.ok());
  std::printf("%s\n", bad.error().message.c_str());
  for (const char* s : {"ground.control.file", "rgb.png", "control.channel \"a\""})
    EXPECT_NE(bad.error().message.find(s), std::string::npos) << bad.error().message;
}

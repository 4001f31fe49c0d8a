// Tile-local grass regeneration through a scene (issue 16): a dab on the grass density map or on
// the ground regenerates only the tiles it reaches (stats tile_regenerations,
// last_tiles_regenerated), and the blades the field then holds (every blade root, read back from
// the GPU) equal those of a full regeneration of the same maps bit for bit. The far field updates
// tile-locally with them (stats far_tile_updates; grass far_field_edit_gl_test compares its data
// bit for bit): the picture of clumps and ground layer after density, tint, height and ground dabs
// (one of them beside the grass area, under the ground layer's margin) equals that of a full
// regeneration pixel for pixel.
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/map_grid.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

using namespace sylva;
using namespace sylva::scene;

namespace {

using GrassTileEditGl = render::GlTest;

// 40 x 48 m of grass in 2 m tiles (480 tiles) on hilly ground, no physics.
constexpr const char* kStage = R"json({
  "sylva_scene": 1,
  "name": "grass tile edit stage",
  "camera": {"position": [0.0, 6.0, 30.0], "height_mode": "absolute", "yaw_deg": 0.0, "pitch_deg": -15.0, "fov_deg": 60.0},
  "sun": {"follow_clock": false, "azimuth_deg": 200.0, "elevation_deg": 35.0, "fog_density": 0.0},
  "wind": {"strength": 0.0, "gust_amplitude": 0.0},
  "ground": {"resolution": 65, "size": 128, "height": 12, "generator": "fbm", "noise": {"frequency": 0.02}},
  "grass": {"area_min": [-20.0, -24.0], "area_max": [20.0, 24.0],
            "field": {"density": 30.0, "tile_size": 2.0},
            "render": {"simulate": false}},
  "render": {"shadows": {"enabled": false}, "msaa_samples": 1}
})json";

constexpr glm::ivec2 kSize(96, 64);

// The stage, with `patch` merged into its JSON (RFC 7386).
std::unique_ptr<Scene> make_scene(const nlohmann::json& patch = nlohmann::json::object()) {
  std::vector<std::string> warnings;
  nlohmann::json json = nlohmann::json::parse(kStage);
  json.merge_patch(patch);
  auto doc = SceneDocument::from_json(json, "grass tile edit stage", warnings);
  EXPECT_TRUE(doc.ok()) << doc.error().message;
  if (!doc.ok()) return nullptr;
  auto made = Scene::create(std::move(*doc));
  EXPECT_TRUE(made.ok()) << made.error().message;
  return made.ok() ? std::move(*made) : nullptr;
}

// Renders n frames; returns the last picture.
Image frames(Scene& scene, int n) {
  auto fb = render::Framebuffer::create({.width = kSize.x, .height = kSize.y, .color_formats = {GL_RGBA16F}}).value();
  render::FrameProfiler profiler;
  const render::Camera camera = scene.make_camera(scene.document().camera, kSize);
  for (int i = 0; i < n; ++i) {
    scene.update(camera, 1.0 + i / 30.0, 1.0f / 30.0f, kSize);
    scene.render(fb, profiler);
  }
  return render::read_color(fb).value();
}

std::uint64_t stat(Scene& scene, const char* key) { return scene.module_stats()["grass"][key].get<std::uint64_t>(); }

// Sets the texels of map `id` within `radius` texels of (ci, cj) to value(i, j) and tells the scene.
template <class F>
void dab(Scene& scene, const char* id, int ci, int cj, int radius, F value) {
  SceneMap* map = scene.map(id);
  ASSERT_NE(map, nullptr);
  const TexelRect r = TexelRect{ci - radius, cj - radius, ci + radius + 1, cj + radius + 1}.intersect(map->grid.bounds());
  for (int j = r.y0; j < r.y1; ++j)
    for (int i = r.x0; i < r.x1; ++i) map->grid.at(i, j) = value(i, j, map->grid.at(i, j));
  ASSERT_TRUE(scene.map_changed(id, r).ok());
}

}  // namespace

TEST_F(GrassTileEditGl, ADabRegeneratesItsTilesAndEqualsAFullRegeneration) {
  if (!find_module("grass")) GTEST_SKIP() << "grass is built out";
  std::unique_ptr<Scene> scene = make_scene();
  ASSERT_TRUE(scene);
  frames(*scene, 1);
  const std::uint64_t tiles = scene->module_stats()["grass"]["tiles"].get<std::uint64_t>();
  const std::uint64_t full_before = stat(*scene, "regenerations");
  // Three dabs in one frame (a stroke): density to 0 and 0.5 at two spots, the height map at a third.
  dab(*scene, "grass.density", 40, 50, 3, [](int, int, float) { return 0.0f; });
  dab(*scene, "grass.density", 90, 100, 2, [](int i, int, float) { return i % 2 ? 0.5f : 1.0f; });
  frames(*scene, 1);
  EXPECT_EQ(stat(*scene, "tile_regenerations"), 1u) << "the dabs of a frame regenerate once";
  const std::uint64_t reached = stat(*scene, "last_tiles_regenerated");
  dab(*scene, "grass.height", 20, 110, 4, [](int, int, float) { return 0.3f; });
  frames(*scene, 1);
  // A ground dab away from the field's centre (the origin stays): blades follow the ground.
  const glm::dvec2 t = scene->map("ground.height")->grid.texel({10.0, -15.0});
  dab(*scene, "ground.height", static_cast<int>(t.x), static_cast<int>(t.y), 2, [](int, int, float v) { return v + 2.0f; });
  frames(*scene, 2);  // the second frame rebuilds the far field
  EXPECT_EQ(stat(*scene, "tile_regenerations"), 3u);
  EXPECT_EQ(stat(*scene, "regenerations"), full_before + 3) << "no full regeneration";
  const std::uint64_t blades_local = stat(*scene, "blades");
  const std::vector<glm::dvec3> local = scene->module("grass")->placed_positions(blades_local);

  // A full regeneration of the same (painted) maps: any offline parameter rebuilds everything.
  ASSERT_TRUE(scene->set_param("grass.map_resolution", scene->get_param("grass.map_resolution").value()).ok());
  frames(*scene, 1);
  EXPECT_EQ(stat(*scene, "tile_regenerations"), 3u);
  const std::uint64_t blades_full = stat(*scene, "blades");
  const std::vector<glm::dvec3> full = scene->module("grass")->placed_positions(blades_full);
  std::printf("%llu tiles; the two density dabs reached %llu; blades %llu tile-local, %llu full\n",
              static_cast<unsigned long long>(tiles), static_cast<unsigned long long>(reached),
              static_cast<unsigned long long>(blades_local), static_cast<unsigned long long>(blades_full));
  EXPECT_LT(reached * 10, tiles) << "a stroke of two dabs reaches few of the tiles";
  EXPECT_GT(reached, 0u);
  ASSERT_EQ(blades_local, blades_full);
  ASSERT_EQ(local.size(), full.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < local.size(); ++i) differing += local[i] != full[i] ? 1 : 0;
  EXPECT_EQ(differing, 0u) << "every blade root equals the full regeneration's bit for bit";
  // Blades stand on the painted ground.
  double worst = 0.0;
  for (const glm::dvec3& r : local) worst = std::max(worst, std::abs(r.y - scene->ground_height(r.x, r.z)));
  EXPECT_LT(worst, 2e-3);
}

// The stage with blades only within 4 m of the camera (which stands 8.5 m from the field): the
// picture shows the far field alone (clumps from 4 m on, the ground layer), with a clump margin and
// wide billboards, so their tile-local update is what the picture compares.
const nlohmann::json kFarOnly = nlohmann::json::parse(R"json({"grass": {
  "render": {"cull": {"near_distance": 4.0}},
  "far": {"clump_margin": 6.0, "ground_margin": 20.0, "wide_billboards": true, "wide_distance": 30.0}}})json");

TEST_F(GrassTileEditGl, FarFieldAfterDabsLooksLikeAFullRegeneration) {
  if (!find_module("grass")) GTEST_SKIP() << "grass is built out";
  std::unique_ptr<Scene> scene = make_scene(kFarOnly);
  ASSERT_TRUE(scene);
  const Image before = frames(*scene, 1);
  const std::uint64_t full_before = stat(*scene, "regenerations");
  // A tint dab first (the field had no tint map: the far field is made anew once), then density,
  // tint again, height and ground dabs in view, each taken tile-locally.
  dab(*scene, "grass.tint_r", 60, 20, 3, [](int, int, float) { return 0.4f; });
  frames(*scene, 1);
  EXPECT_EQ(stat(*scene, "far_tile_updates"), 0u) << "a tint map that appears rebuilds the far field";
  dab(*scene, "grass.density", 64, 110, 4, [](int, int, float) { return 0.0f; });
  dab(*scene, "grass.tint_g", 40, 120, 4, [](int, int, float) { return 0.6f; });
  frames(*scene, 1);
  dab(*scene, "grass.height", 20, 118, 4, [](int, int, float) { return 0.2f; });
  const glm::dvec2 t = scene->map("ground.height")->grid.texel({-8.0, 18.0});
  dab(*scene, "ground.height", static_cast<int>(t.x), static_cast<int>(t.y), 1, [](int, int, float v) { return v + 1.0f; });
  // A ground dab beside the grass area (x < -20), under the ground layer's 20 m margin.
  const glm::dvec2 u = scene->map("ground.height")->grid.texel({-25.0, -8.0});
  dab(*scene, "ground.height", static_cast<int>(u.x), static_cast<int>(u.y), 1, [](int, int, float v) { return v + 1.0f; });
  const Image local = frames(*scene, 2);
  EXPECT_EQ(stat(*scene, "far_tile_updates"), 2u);
  EXPECT_EQ(stat(*scene, "regenerations"), full_before + 3) << "no full regeneration";
  const std::uint64_t clumps_local = stat(*scene, "clumps");

  ASSERT_TRUE(scene->set_param("grass.map_resolution", scene->get_param("grass.map_resolution").value()).ok());
  const Image full = frames(*scene, 2);
  EXPECT_EQ(stat(*scene, "clumps"), clumps_local);
  std::size_t changed = 0, differing = 0;
  for (std::size_t i = 0; i < full.data().size(); ++i) {
    changed += before.data()[i] != full.data()[i] ? 1 : 0;
    differing += local.data()[i] != full.data()[i] ? 1 : 0;
  }
  std::printf("far picture: %zu of %zu channel values changed by the dabs, %zu differ from the full regeneration\n", changed,
              full.data().size(), differing);
  EXPECT_GT(changed, 100u) << "the dabs are in view";
  EXPECT_EQ(differing, 0u) << "the tile-local far field draws the full regeneration's picture";
}

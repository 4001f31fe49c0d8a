// Running scenes on a headless GL context: only listed modules are created (instance counters and
// live GL objects), the frame loop measures every module per pass, map edits rebuild only the
// chunks they touch, parameters rebuild what they must, grass stands on the ground, and saving
// writes maps that load back bit-exactly.
#include <sylva/core/image_metrics.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene.hpp>

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace sylva;
using namespace sylva::scene;

namespace {

using SceneGl = render::GlTest;

int live_programs() {
  int n = 0;
  for (GLuint id = 1; id < 4096; ++id) n += glIsProgram(id) ? 1 : 0;
  return n;
}

int live_buffers() {
  int n = 0;
  for (GLuint id = 1; id < 4096; ++id) n += glIsBuffer(id) ? 1 : 0;
  return n;
}

SceneDocument doc_from(const std::string& text) {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::from_text(text, "test.json", warnings);
  EXPECT_TRUE(doc.ok()) << doc.error().message;
  return doc.ok() ? std::move(*doc) : SceneDocument{};
}

std::unique_ptr<Scene> make_scene(const std::string& text) {
  auto scene = Scene::create(doc_from(text));
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  return scene.ok() ? std::move(*scene) : nullptr;
}

struct Target {
  render::Framebuffer fb;
  render::FrameProfiler profiler;
  glm::ivec2 size;
};

Target make_target(int w, int h) {
  Target t;
  t.fb = render::Framebuffer::create({.width = w, .height = h, .color_formats = {GL_RGBA8}}).value();
  t.size = {w, h};
  return t;
}

void run_frames(Scene& scene, Target& t, const render::Camera& camera, int frames) {
  for (int i = 0; i < frames; ++i) {
    scene.update(camera, 0.1 * i, 0.1f, t.size);
    scene.render(t.fb, t.profiler);
  }
}

const char* kGround = R"({"ground": {"resolution": 129, "size": 256, "height": 20, "chunk_quads": 32},
  "camera": {"position": [0, 40, 150], "pitch_deg": -15}})";

fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("sylva_scene_gl_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

}  // namespace

// Invariant: a module that is not listed creates no instance, compiles no program and allocates
// no buffer.
TEST_F(SceneGl, OnlyListedModulesAreCreated) {
  const int programs_before = live_programs();
  const int buffers_before = live_buffers();
  int ground_programs = 0, ground_buffers = 0;
  {
    auto scene = make_scene(kGround);
    ASSERT_TRUE(scene);
    for (std::string_view m : known_modules()) {
      EXPECT_EQ(live_module_instances(m), m == "ground" ? 1 : 0) << m;
      if (m != "ground") {
        EXPECT_EQ(created_module_instances(m), 0u) << m;
      }
    }
    ground_programs = live_programs() - programs_before;
    ground_buffers = live_buffers() - buffers_before;
    EXPECT_EQ(ground_programs, 2) << "sky + ground";
    Target t = make_target(64, 36);
    run_frames(*scene, t, scene->make_camera(scene->document().camera, t.size), 2);
  }
  EXPECT_EQ(live_module_instances("ground"), 0);
  if (!find_module("grass")) GTEST_SKIP() << "grass is built out";
  {
    auto scene = make_scene(R"({"ground": {"resolution": 65, "size": 128}, "grass": {"area_min": [-4, -4], "area_max": [4, 4],
                                "field": {"density": 20}}})");
    ASSERT_TRUE(scene);
    EXPECT_EQ(live_module_instances("grass"), 1);
    EXPECT_EQ(created_module_instances("grass"), 1u);
    EXPECT_GT(live_programs() - programs_before, ground_programs) << "grass compiles its own programs";
    EXPECT_GT(live_buffers() - buffers_before, ground_buffers);
  }
  EXPECT_EQ(live_module_instances("grass"), 0);
}

TEST_F(SceneGl, FrameLoopMeasuresEveryModulePerPass) {
  auto scene = make_scene(kGround);
  ASSERT_TRUE(scene);
  Target t = make_target(96, 54);
  int hook_calls = 0, caster_calls = 0;
  scene->set_shadow_hook([&](const render::FrameContext& frame, const std::function<void(render::PassStats&)>& draw) {
    EXPECT_EQ(frame.viewport, glm::ivec2(96, 54));
    ++hook_calls;
    render::PassStats s;
    draw(s);
    ++caster_calls;
  });
  run_frames(*scene, t, scene->make_camera(scene->document().camera, t.size), 4);
  auto frame = t.profiler.flush();
  ASSERT_TRUE(frame.has_value());
  const SceneFrameStats stats = split_frame_stats(*frame);
  EXPECT_EQ(hook_calls, 4);
  EXPECT_EQ(caster_calls, 4);
  for (const char* pass : {"shadow", "opaque", "sky", "transparent"}) EXPECT_TRUE(stats.passes.count(pass)) << pass;
  EXPECT_GT(stats.passes.at("opaque").gpu_ms, 0.0);
  EXPECT_GT(stats.passes.at("opaque").samples, 1000u);
  ASSERT_TRUE(stats.modules.count("ground"));
  const render::PassStats& ground = stats.modules.at("ground").at("opaque");
  EXPECT_GT(ground.triangles, 1000u);
  EXPECT_GT(ground.samples, 1000u);
  EXPECT_GT(ground.gpu_ms, 0.0);
  EXPECT_EQ(stats.passes.at("opaque").triangles, ground.triangles);

  // The picture: sky at the top, ground at the bottom.
  auto image = render::read_color(t.fb);
  ASSERT_TRUE(image.ok());
  EXPECT_GT(image->at(48, 1, 2), image->at(48, 1, 0)) << "top is sky";
  EXPECT_LT(image->at(48, 52, 2), image->at(48, 1, 2)) << "bottom is ground";

  // Debug views draw without GL errors and change the picture.
  scene->debug().wireframe = true;
  scene->debug().chunk_bounds = true;
  scene->debug().lod_colors = true;
  run_frames(*scene, t, scene->make_camera(scene->document().camera, t.size), 1);
  auto debug_image = render::read_color(t.fb);
  ASSERT_TRUE(debug_image.ok());
  EXPECT_GT(rmse(*image, *debug_image).value(), 0.01);
}

TEST_F(SceneGl, FlatGroundIsNotSnow) {
  // A flat floor (the "on flat ground" scenes) has no relief for a snow line: it renders as the
  // grass material, not the half-snow blend a zero height range used to give.
  auto scene = make_scene(R"({"ground": {"resolution": 33, "size": 200, "generator": "flat"},
                              "camera": {"position": [0, 10, 0], "pitch_deg": -60}})");
  ASSERT_TRUE(scene);
  Target t = make_target(64, 36);
  run_frames(*scene, t, scene->make_camera(scene->document().camera, t.size), 1);
  auto image = render::read_color(t.fb);
  ASSERT_TRUE(image.ok());
  const float r = image->at(32, 30, 0), g = image->at(32, 30, 1), b = image->at(32, 30, 2);
  EXPECT_GT(g, r) << "grass green, not snow white";
  EXPECT_GT(g, b);
  // sRGB-encoded (tone mapping on by default) channel ratios are flatter than linear ones.
  EXPECT_LT(b, 0.7f * g);
}

// Invariant: a map edit rebuilds exactly the chunks whose samples or normals it changes.
TEST_F(SceneGl, GroundEditRebuildsOnlyTouchedChunks) {
  auto scene = make_scene(kGround);
  ASSERT_TRUE(scene);
  auto rebuilt = [&] { return scene->module_stats()["ground"]["chunks_rebuilt"].get<std::uint64_t>(); };
  EXPECT_EQ(scene->module_stats()["ground"]["chunks"], 16);
  EXPECT_EQ(rebuilt(), 0u);
  SceneMap* map = scene->map("ground.height");
  ASSERT_NE(map, nullptr);
  EXPECT_EQ(map->kind, MapKind::kHeight);
  // Inside chunk (1, 1) (samples 32..64): one chunk.
  for (int j = 40; j < 44; ++j)
    for (int i = 40; i < 44; ++i) map->grid.at(i, j) += 5.0f;
  ASSERT_TRUE(scene->map_changed("ground.height", {40, 40, 44, 44}).ok());
  EXPECT_EQ(rebuilt(), 1u);
  const glm::dvec2 p = map->grid.world(41, 42);
  EXPECT_FLOAT_EQ(static_cast<float>(scene->ground_height(p.x, p.y)), map->grid.at(41, 42));
  // On the shared corner sample (64, 64): the four chunks around it.
  map->grid.at(64, 64) -= 3.0f;
  ASSERT_TRUE(scene->map_changed("ground.height", {64, 64, 65, 65}).ok());
  EXPECT_EQ(rebuilt(), 5u);
  EXPECT_TRUE(scene->maps_unsaved());
  EXPECT_FALSE(scene->map_changed("nope.map", {0, 0, 1, 1}).ok());
}

TEST_F(SceneGl, ParametersRebuildWhatTheyNeed) {
  auto scene = make_scene(kGround);
  ASSERT_TRUE(scene);
  const std::uint64_t created = created_module_instances("ground");
  ASSERT_TRUE(scene->set_param("sun.elevation_deg", "10").ok());
  EXPECT_EQ(scene->document().sun.elevation_deg, 10.0f);
  EXPECT_EQ(created_module_instances("ground"), created) << "the sun needs no rebuild";
  const double before = scene->ground_height(30.0, 20.0);
  ASSERT_TRUE(scene->set_param("ground.height", "40").ok());
  EXPECT_EQ(created_module_instances("ground"), created + 1) << "a new ground rebuilds the module";
  EXPECT_NEAR(scene->ground_height(30.0, 20.0), 2.0 * before, 1e-3 * std::abs(before) + 1e-4);
  auto bad = scene->set_param("ground.height", "-3");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("ground.height"), std::string::npos);
  EXPECT_EQ(scene->get_param("ground.height").value(), "40");
  EXPECT_FALSE(scene->set_param("ground.nothing", "1").ok());
}

TEST_F(SceneGl, CamerasResolveHeightAboveGround) {
  auto scene = make_scene(R"({"ground": {"resolution": 65, "size": 256, "height": 30},
    "camera_paths": {"walk": {"keys": [{"time_s": 0, "position": [0, 2, 0], "height_mode": "above_ground"},
                                        {"time_s": 4, "position": [40, 2, 0], "height_mode": "above_ground"}]}}})");
  ASSERT_TRUE(scene);
  for (double t : {0.0, 1.0, 2.5, 4.0}) {
    auto view = scene->camera_path_view("walk", t);
    ASSERT_TRUE(view.ok());
    EXPECT_EQ(view->height_mode, HeightMode::kAbsolute);
    EXPECT_NEAR(view->position.y, scene->ground_height(view->position.x, view->position.z) + 2.0, 1e-6);
  }
  auto missing = scene->camera_path_view("run", 0.0);
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("walk"), std::string::npos);
  const render::Camera cam = scene->make_camera(scene->camera_path_view("walk", 1.0).value(), {160, 90});
  const CameraView back = Scene::view_of(cam);
  EXPECT_NEAR(glm::distance(back.position, cam.position()), 0.0, 1e-9);
}

// Invariant: blades stand on the scene's ground, also after the ground is painted.
TEST_F(SceneGl, GrassStandsOnTheGround) {
  if (!find_module("grass")) GTEST_SKIP() << "grass is built out";
  auto scene = make_scene(R"({"ground": {"resolution": 65, "size": 128, "height": 25, "generator": "fbm",
                                         "noise": {"frequency": 0.02}},
                              "grass": {"area_min": [-6, -6], "area_max": [6, 6], "field": {"density": 8},
                                        "render": {"simulate": false}}})");
  ASSERT_TRUE(scene);
  ModuleInstance* grass = scene->module("grass");
  ASSERT_NE(grass, nullptr);
  auto check = [&](const char* when) {
    const std::vector<glm::dvec3> roots = grass->placed_positions(300);
    ASSERT_GT(roots.size(), 100u) << when;
    double worst = 0.0;
    for (const glm::dvec3& r : roots) worst = std::max(worst, std::abs(r.y - scene->ground_height(r.x, r.z)));
    EXPECT_LT(worst, 2e-3) << when;
  };
  check("as built");
  SceneMap* map = scene->map("ground.height");
  const glm::dvec2 t = map->grid.texel({0.0, 0.0});
  const TexelRect r{static_cast<int>(t.x) - 2, static_cast<int>(t.y) - 2, static_cast<int>(t.x) + 3, static_cast<int>(t.y) + 3};
  for (int j = r.y0; j < r.y1; ++j)
    for (int i = r.x0; i < r.x1; ++i) map->grid.at(i, j) += 3.0f;
  ASSERT_TRUE(scene->map_changed("ground.height", r).ok());
  Target target = make_target(32, 32);
  run_frames(*scene, target, scene->make_camera(scene->document().camera, target.size), 1);
  check("after a ground edit");
  EXPECT_EQ(scene->module_stats()["grass"]["regenerations"], 2);
  // An edit far from the field does not regenerate it.
  ASSERT_TRUE(scene->map_changed("ground.height", {0, 0, 2, 2}).ok());
  run_frames(*scene, target, scene->make_camera(scene->document().camera, target.size), 1);
  EXPECT_EQ(scene->module_stats()["grass"]["regenerations"], 2);
}

TEST_F(SceneGl, SavedMapsLoadBackBitExactly) {
  auto scene = make_scene(kGround);
  ASSERT_TRUE(scene);
  SceneMap* map = scene->map("ground.height");
  for (int i = 0; i < 20; ++i) map->grid.at(i + 10, 7) = 0.1f * static_cast<float>(i) + 1e-7f;
  ASSERT_TRUE(scene->map_changed("ground.height", {10, 7, 30, 8}).ok());
  const fs::path dir = temp_dir("save");
  ASSERT_TRUE(scene->save(dir / "edited.json").ok());
  EXPECT_FALSE(scene->maps_unsaved());
  EXPECT_TRUE(fs::exists(dir / "edited_maps" / "ground_height.exr"));
  EXPECT_EQ(scene->document().module("ground")->maps.at("height"), "edited_maps/ground_height.exr");

  std::vector<std::string> warnings;
  auto doc = SceneDocument::load(dir / "edited.json", warnings);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  auto loaded = Scene::create(std::move(*doc));
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const SceneMap* back = (*loaded)->map("ground.height");
  ASSERT_NE(back, nullptr);
  ASSERT_EQ(back->grid.values.size(), map->grid.values.size());
  EXPECT_EQ(std::memcmp(back->grid.values.data(), map->grid.values.data(), map->grid.values.size() * sizeof(float)), 0);
  EXPECT_EQ(back->grid.texel_origin, map->grid.texel_origin);

  // Save-as into another folder copies the map into the new scene's own map folder.
  const fs::path other = temp_dir("other");
  ASSERT_TRUE((*loaded)->save(other / "copy.json").ok());
  const std::string rel = (*loaded)->document().module("ground")->maps.at("height");
  EXPECT_EQ(rel, "copy_maps/ground_height.exr");
  EXPECT_TRUE(fs::exists(other / rel)) << rel;
}

// Invariant: trees stand on the ground; a density or ground edit re-places only the cells it
// touches.
TEST_F(SceneGl, ForestStandsOnTheGroundAndEditsStayLocal) {
  if (!find_module("vegetation")) GTEST_SKIP() << "vegetation is built out";
  auto scene = make_scene(R"({"ground": {"resolution": 65, "size": 256, "height": 20, "generator": "fbm",
                                         "noise": {"frequency": 0.01}},
                              "vegetation": {"area_min": [-60, -60], "area_max": [60, 60], "trees_per_hectare": 25,
                                             "leaf_texture_size": 32}})");
  ASSERT_TRUE(scene);
  ModuleInstance* forest = scene->module("vegetation");
  ASSERT_NE(forest, nullptr);
  const std::vector<glm::dvec3> before = forest->placed_positions(10000);
  ASSERT_GT(before.size(), 20u);
  for (const glm::dvec3& t : before) EXPECT_NEAR(t.y, scene->ground_height(t.x, t.z), 1e-4);
  // Erase the density around (30, 30): trees there vanish, the others stay bit-identical.
  SceneMap* density = scene->map("vegetation.density");
  ASSERT_NE(density, nullptr);
  const glm::dvec2 c = density->grid.texel({30.0, 30.0});
  const TexelRect r{static_cast<int>(c.x) - 10, static_cast<int>(c.y) - 10, static_cast<int>(c.x) + 10, static_cast<int>(c.y) + 10};
  for (int j = r.y0; j < r.y1; ++j)
    for (int i = r.x0; i < r.x1; ++i) density->grid.at(i, j) = 0.0f;
  ASSERT_TRUE(scene->map_changed("vegetation.density", r).ok());
  const std::vector<glm::dvec3> after = forest->placed_positions(10000);
  EXPECT_LT(after.size(), before.size());
  const WorldArea area = changed_world_area(density->grid, r);
  std::size_t kept_outside = 0, outside_before = 0;
  for (const glm::dvec3& t : before) {
    const bool far = t.x < area.min.x - 20 || t.x > area.max.x + 20 || t.z < area.min.y - 20 || t.z > area.max.y + 20;
    if (!far) continue;
    ++outside_before;
    kept_outside += std::count(after.begin(), after.end(), t) == 1 ? 1 : 0;
  }
  EXPECT_EQ(kept_outside, outside_before) << "trees far from the edit are untouched";
  EXPECT_GT(scene->module_stats()["vegetation"]["cells_replaced"].get<int>(), 0);
  Target t = make_target(64, 36);
  run_frames(*scene, t, scene->make_camera(scene->document().camera, t.size), 1);
}

TEST_F(SceneGl, VoxelWorldRenders) {
  if (!find_module("voxel")) GTEST_SKIP() << "voxel is built out";
  auto scene = make_scene(R"({"voxel": {"radius_chunks": 1, "worldgen": {"seed": 3, "variants_per_species": 2}},
                              "camera": {"position": [-40, 60, -40], "yaw_deg": -135, "pitch_deg": -35}})");
  ASSERT_TRUE(scene);
  EXPECT_EQ(scene->ground(), nullptr) << "a voxel world is its own ground";
  Target t = make_target(96, 54);
  run_frames(*scene, t, scene->make_camera(scene->document().camera, t.size), 2);
  auto frame = t.profiler.flush();
  ASSERT_TRUE(frame.has_value());
  const SceneFrameStats stats = split_frame_stats(*frame);
  ASSERT_TRUE(stats.modules.count("voxel"));
  EXPECT_GT(stats.modules.at("voxel").at("opaque").triangles, 1000u);
  EXPECT_GT(scene->module_stats()["voxel"]["chunks_drawn"].get<int>(), 0);
}

// Invariant: a painted terrain height is what the terrain draws and what the grass stands on.
TEST_F(SceneGl, TerrainIsTheGroundAndFollowsEdits) {
  if (!find_module("terrain")) GTEST_SKIP() << "terrain is built out";
  auto scene = make_scene(R"({"terrain": {"resolution": 129, "size": 256, "height": 30, "generator": "fbm",
                                          "noise": {"frequency": 0.01}, "tree": {"leaf_dimension": 17}},
                              "camera": {"position": [0, 80, 160], "pitch_deg": -25}})");
  ASSERT_TRUE(scene);
  ASSERT_NE(scene->ground(), nullptr);
  EXPECT_EQ(live_module_instances("ground"), 0) << "terrain replaces the built-in ground";
  Target t = make_target(96, 54);
  run_frames(*scene, t, scene->make_camera(scene->document().camera, t.size), 2);
  auto frame = t.profiler.flush();
  ASSERT_TRUE(frame.has_value());
  const SceneFrameStats stats = split_frame_stats(*frame);
  EXPECT_GT(stats.modules.at("terrain").at("opaque").samples, 1000u);
  EXPECT_GT(scene->module_stats()["terrain"]["chunks_drawn"].get<int>(), 0);
  const auto rebuilds = scene->module_stats()["terrain"]["tree_rebuilds"].get<int>();
  SceneMap* map = scene->map("terrain.height");
  ASSERT_NE(map, nullptr);
  for (int j = 60; j < 70; ++j)
    for (int i = 60; i < 70; ++i) map->grid.at(i, j) += 12.0f;
  ASSERT_TRUE(scene->map_changed("terrain.height", {60, 60, 70, 70}).ok());
  const glm::dvec2 p = map->grid.world(64, 64);
  EXPECT_FLOAT_EQ(static_cast<float>(scene->ground_height(p.x, p.y)), map->grid.at(64, 64));
  run_frames(*scene, t, scene->make_camera(scene->document().camera, t.size), 1);
  // Issue 9: the stroke rebuilds only the chunks it reaches, not the whole tree.
  const nlohmann::json after = scene->module_stats()["terrain"];
  EXPECT_EQ(after["tree_rebuilds"].get<int>(), rebuilds);
  EXPECT_EQ(after["tree_partial_rebuilds"].get<int>(), 1);
  EXPECT_GT(after["chunks_rebuilt"].get<int>(), 0);
  EXPECT_LT(after["chunks_rebuilt"].get<int>(), after["tree_chunks"].get<int>() / 2) << after.dump();
  EXPECT_GT(scene->module_stats()["terrain"]["chunks_drawn"].get<int>(), 0);
}

// Shadows: the scene's cascades make shaded ground darker where a caster blocks the sun, and
// tone mapping (opt-in) changes the picture but keeps it finite and in range.
TEST_F(SceneGl, ShadowsAndToneMapping) {
  const std::string base = R"({"ground": {"resolution": 33, "size": 64, "height": 0, "generator": "flat"},
    "voxel": {"radius_chunks": 0, "worldgen": {"seed": 3, "variants_per_species": 1}},
    "sun": {"azimuth_deg": 90, "elevation_deg": 35},
    "camera": {"position": [-40, 40, 60], "yaw_deg": -30, "pitch_deg": -30}, "render": RENDER})";
  auto with = [&](const std::string& render) {
    std::string t = base;
    t.replace(t.find("RENDER"), 6, render);
    return t;
  };
  if (!find_module("voxel")) GTEST_SKIP() << "the test uses a voxel world as the shadow caster";
  Target t = make_target(96, 54);
  auto lit = make_scene(with(R"({"shadows": {"enabled": false}, "tone_map": false})"));
  auto shadowed = make_scene(with(R"({"shadows": {"enabled": true, "max_distance": 200}, "tone_map": false})"));
  auto toned = make_scene(with(R"({"shadows": {"enabled": false}, "tone_map": true})"));
  ASSERT_TRUE(lit && shadowed && toned);
  auto picture = [&](Scene& s) {
    run_frames(s, t, s.make_camera(s.document().camera, t.size), 2);
    return render::read_color(t.fb).value();
  };
  const Image a = picture(*lit), b = picture(*shadowed), c = picture(*toned);
  double sum_a = 0.0, sum_b = 0.0;
  for (float v : a.data()) sum_a += v;
  for (float v : b.data()) sum_b += v;
  EXPECT_LT(sum_b, sum_a * 0.995) << "shadows darken part of the picture";
  EXPECT_GT(rmse(a, c).value(), 0.01) << "tone mapping changes the picture";
  for (float v : c.data()) {
    ASSERT_GE(v, 0.0f);
    ASSERT_LE(v, 1.0f);
  }
  auto frame = t.profiler.flush();
  ASSERT_TRUE(frame.has_value());
  EXPECT_TRUE(split_frame_stats(*frame).passes.count("tone_map"));
}

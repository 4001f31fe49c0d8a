// The general-model terrain (seed 002 §4) reached through a scene file's "model_terrain" section:
// the shipped scenes/model_terrain.json (an OBJ with an overhanging cliff) builds its model tree
// and draws it, covering every pixel where it must be seen, with segments, triangles and GPU bytes
// in the stats; the seed's reduce per pass is reachable from the file; missing and broken meshes
// are clear errors naming the file (and line). The same mesh written as OBJ, Open Inventor .iv and
// glTF (.gltf + .bin) draws the same picture; a control cage is refined by "subdivision"; hostile
// .iv and glTF files are errors naming the file.
#include <sylva/core/atomic_file.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/gpu_memory.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/frame_stats.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene.hpp>

#include "render_once.hpp"

#include <gtest/gtest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <unistd.h>

namespace fs = std::filesystem;
using namespace sylva;
using namespace sylva::scene;

namespace {

using ModelTerrainGl = render::GlTest;

const fs::path kScene = fs::path(SYLVA_SCENES_DIR) / "model_terrain.json";

// The shipped scene, less the modules in `drop`.
std::unique_ptr<Scene> shipped(std::initializer_list<const char*> drop) {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::load(kScene, warnings);
  EXPECT_TRUE(doc.ok()) << doc.error().message;
  if (!doc.ok()) return nullptr;
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  for (const char* m : drop) doc->remove_module(m);
  doc->render.shadows.enabled = false;  // speed; the shipped scene's shadows run in shipped_scenes
  auto scene = Scene::create(std::move(*doc));
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  return scene.ok() ? std::move(*scene) : nullptr;
}

Image frame(Scene& scene, const render::Camera& camera, glm::ivec2 size) {
  auto fb = render::Framebuffer::create({.width = size.x, .height = size.y}).value();
  render::FrameProfiler profiler;
  scene.update(camera, 0.0, 0.0f, size);
  scene.render(fb, profiler);
  return render::read_color(fb).value();
}

std::size_t differing_pixels(const Image& a, const Image& b) {
  std::size_t n = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x)
      for (int c = 0; c < 3; ++c)
        if (std::abs(a.at(x, y, c) - b.at(x, y, c)) > 1.5f / 255.0f) {
          ++n;
          break;
        }
  return n;
}

TEST_F(ModelTerrainGl, ShippedSceneDrawsTheModelWhereItMustBeSeen) {
  if (!find_module("model_terrain")) GTEST_SKIP() << "terrain is built out";
  auto with = shipped({"ground"});
  auto without = shipped({"ground", "model_terrain"});
  ASSERT_TRUE(with && without);
  const glm::ivec2 size(128, 72);
  // Straight down from 150 m over the 400 m square (heights 0..~75 m): every pixel's ray runs
  // from above the sheet to below it inside the square, so the model must cover the whole frame
  // (any sheet with the square as its outline is crossed, at any mix of segment levels).
  render::Camera down = with->make_camera(with->document().camera, size);
  down.set_position({10.0, 150.0, -5.0});
  down.set_yaw_pitch(0.3f, -1.55f);
  const Image model = frame(*with, down, size), sky = frame(*without, down, size);
  EXPECT_EQ(differing_pixels(model, sky), model.pixel_count()) << "every pixel shows the model, none the sky";
  const nlohmann::json s = with->module_stats()["model_terrain"];
  EXPECT_GT(s["segments_drawn"].get<std::uint64_t>(), 0u);
  EXPECT_GT(s["triangles"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(s["mesh_triangles"].get<std::uint64_t>(), 32768u) << "128 x 128 quads (scripts/make-model-terrain-mesh)";
  EXPECT_EQ(s["tree_levels"].get<int>(), 5);
  EXPECT_LE(s["max_projected_error_px"].get<double>(), 1.0) << "render.lod.max_pixel_error of the file";
  EXPECT_GT(s["gpu_bytes"].get<std::uint64_t>(), 32768u * 3u * 4u) << "at least the leaves' indices";
  EXPECT_GE(render::gpu_memory_usage()["model_terrain"].bytes[static_cast<int>(render::GpuMemoryKind::kBuffer)],
            s["gpu_bytes"].get<std::uint64_t>()) << "tracked under the module's name";

  // The file's own view: the cliff stands in the frame; a coarser tau draws fewer triangles.
  const render::Camera view = with->make_camera(with->document().camera, size);
  const Image a = frame(*with, view, size), b = frame(*without, view, size);
  EXPECT_GT(differing_pixels(a, b), a.pixel_count() / 4);
  const std::uint64_t fine = with->module_stats()["model_terrain"]["triangles"].get<std::uint64_t>();
  ASSERT_TRUE(with->set_param("model_terrain.render.lod.max_pixel_error", "8").ok());
  (void)frame(*with, view, size);
  const nlohmann::json coarse = with->module_stats()["model_terrain"];
  EXPECT_LT(coarse["triangles"].get<std::uint64_t>(), fine);
  EXPECT_GT(coarse["segments_drawn"].get<std::uint64_t>(), 0u);
  std::printf("model_terrain: from above %s segments, %s triangles, %s GPU bytes; the file's view at tau 1: %llu "
              "triangles, at tau 8: %s\n", s["segments_drawn"].dump().c_str(), s["triangles"].dump().c_str(),
              s["gpu_bytes"].dump().c_str(), static_cast<unsigned long long>(fine), coarse["triangles"].dump().c_str());
}

// Shadows: the model casts into the scene's cascades (the shadow pass draws its segments) and
// what it casts darkens the picture (onto itself and the ground) against cast_shadows = false.
TEST_F(ModelTerrainGl, CastsShadowsIntoTheScene) {
  if (!find_module("model_terrain")) GTEST_SKIP() << "terrain is built out";
  std::vector<std::string> warnings;
  auto doc = SceneDocument::load(kScene, warnings);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  ASSERT_TRUE(doc->render.shadows.enabled);
  auto scene = Scene::create(std::move(*doc));
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  const glm::ivec2 size(160, 90);
  // A sun behind the cliff (azimuth 90, 30 degrees up) lays its shadow toward the file's camera.
  ASSERT_TRUE((*scene)->set_param("sun.azimuth_deg", "90").ok());
  ASSERT_TRUE((*scene)->set_param("sun.elevation_deg", "30").ok());
  const render::Camera down = (*scene)->make_camera((*scene)->document().camera, size);
  const auto shot = [&](std::uint64_t& shadow_triangles) {
    auto fb = render::Framebuffer::create({.width = size.x, .height = size.y}).value();
    render::FrameProfiler profiler;
    for (int i = 0; i < 2; ++i) {
      (*scene)->update(down, 0.0, 0.0f, size);
      (*scene)->render(fb, profiler);
    }
    auto stats = profiler.flush();
    shadow_triangles = stats ? split_frame_stats(*stats).modules["model_terrain"]["shadow"].triangles : 0;
    return render::read_color(fb).value();
  };
  std::uint64_t cast = 0, none = 0;
  const Image lit = shot(cast);
  ASSERT_TRUE((*scene)->set_param("model_terrain.render.cast_shadows", "false").ok());
  const Image unshadowed = shot(none);
  EXPECT_GT(cast, 0u) << "the shadow pass draws the model";
  EXPECT_EQ(none, 0u);
  std::size_t darker = 0;
  for (int y = 0; y < lit.height(); ++y)
    for (int x = 0; x < lit.width(); ++x) {
      const float a = lit.at(x, y, 0) + lit.at(x, y, 1) + lit.at(x, y, 2);
      const float b = unshadowed.at(x, y, 0) + unshadowed.at(x, y, 1) + unshadowed.at(x, y, 2);
      if (a < 0.9f * b) ++darker;  // the sun term is lost, the sky light stays
    }
  EXPECT_GT(darker, lit.pixel_count() / 20) << "the model's shadow shows";
  std::printf("shadows: %llu triangles in the shadow pass, %zu of %zu pixels darker\n",
              static_cast<unsigned long long>(cast), darker, lit.pixel_count());
}

// Tab. 4.6-4.11's axis from a file: tree.reduce_per_pass (seed -reduce) and tree.levels.
TEST_F(ModelTerrainGl, ReducePerPassIsSetFromTheSceneFile) {
  if (!find_module("model_terrain")) GTEST_SKIP() << "terrain is built out";
  std::uint64_t previous = 0;
  for (const char* reduce : {"0.25", "0.75"}) {
    std::vector<std::string> warnings;
    auto doc = SceneDocument::load(kScene, warnings);
    ASSERT_TRUE(doc.ok()) << doc.error().message;
    ASSERT_TRUE(doc->params().set("model_terrain.tree.levels", "3").ok());
    ASSERT_TRUE(doc->params().set("model_terrain.tree.reduce_per_pass", reduce).ok());
    doc->remove_module("ground");
    auto scene = Scene::create(std::move(*doc));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    sylva::scene::testing::render_once(**scene);
    const nlohmann::json s = (*scene)->module_stats()["model_terrain"];
    const std::uint64_t root = s["tree_triangles"]["level0"].get<std::uint64_t>();
    EXPECT_EQ(s["tree_triangles"]["level2"].get<std::uint64_t>(), 32768u) << "leaves are the original";
    if (previous != 0) {
      EXPECT_LT(root, previous / 2) << "removing 75 % per pass keeps far fewer than 25 %";
    }
    std::printf("reduce_per_pass %s, 3 levels: %s\n", reduce, s["tree_triangles"].dump().c_str());
    previous = root;
  }
}

TEST_F(ModelTerrainGl, MissingOrBrokenMeshIsAClearError) {
  if (!find_module("model_terrain")) GTEST_SKIP() << "terrain is built out";
  const fs::path dir = fs::temp_directory_path() / ("sylva_model_terrain_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const auto scene_with = [&](const std::string& file) {
    std::vector<std::string> warnings;
    EXPECT_TRUE(write_file_atomic(dir / "s.json", R"({"model_terrain": {"file": ")" + file + R"("}})").ok());
    auto doc = SceneDocument::load(dir / "s.json", warnings);
    EXPECT_TRUE(doc.ok()) << doc.error().message;
    return Scene::create(std::move(*doc));
  };
  auto missing = scene_with("nowhere.obj");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("nowhere.obj"), std::string::npos) << missing.error().message;
  EXPECT_NE(missing.error().message.find("model_terrain.file"), std::string::npos) << missing.error().message;

  ASSERT_TRUE(write_file_atomic(dir / "broken.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 x\n").ok());
  auto broken = scene_with("broken.obj");
  ASSERT_FALSE(broken.ok());
  EXPECT_NE(broken.error().message.find("broken.obj:4"), std::string::npos) << broken.error().message;
  std::printf("errors: %s | %s\n", missing.error().message.c_str(), broken.error().message.c_str());

  auto none = scene_with("");
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.error().message.find("model_terrain.file"), std::string::npos) << none.error().message;
  fs::remove_all(dir);
}

// A small hill of n x n quads over 64 m (heights multiples of 1/16 m, so that the glTF's node
// translation by 8 m restores them exactly), as a vertex grid and quads (a, b, c, d).
struct Grid {
  std::vector<glm::vec3> points;
  std::vector<std::array<int, 4>> quads;
};
Grid hill(int n) {
  Grid g;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float x = -32.0f + 64.0f * static_cast<float>(i) / static_cast<float>(n);
      const float z = -32.0f + 64.0f * static_cast<float>(j) / static_cast<float>(n);
      const float h = std::round(16.0f * (12.0f * std::exp(-(x * x + z * z) / 400.0f) + 0.05f * x)) / 16.0f;
      g.points.emplace_back(x, h, z);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i;
      g.quads.push_back({a, a + n + 1, a + n + 2, a + 1});  // counter-clockwise seen from above (+y)
    }
  return g;
}

// OBJ with the quads as two triangles each (the fan triangulate() makes of a quad).
std::string as_obj(const Grid& g, bool quads) {
  std::string out = "# hill\n";
  for (const glm::vec3& p : g.points) out += fmt::format("v {} {} {}\n", p.x, p.y, p.z);
  for (const auto& q : g.quads) {
    if (quads) {
      out += fmt::format("f {} {} {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
    } else {
      out += fmt::format("f {} {} {}\nf {} {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[0] + 1, q[2] + 1, q[3] + 1);
    }
  }
  return out;
}

// The seed's Inventor subset: quads, comments, DEF, a Separator and nodes to be skipped.
std::string as_iv(const Grid& g) {
  std::string out = "#Inventor V2.1 ascii\n\n# hill\nSeparator {\n  Material { diffuseColor 0.5 0.4 0.3 }\n"
                    "  ShapeHints { vertexOrdering COUNTERCLOCKWISE }\n  DEF Hill Coordinate3 {\n    point [\n";
  for (const glm::vec3& p : g.points) out += fmt::format("      {} {} {},\n", p.x, p.y, p.z);
  out += "    ]\n  }\n  IndexedFaceSet {\n    coordIndex [\n";
  for (const auto& q : g.quads) out += fmt::format("      {}, {}, {}, {}, -1,\n", q[0], q[1], q[2], q[3]);
  out += "    ]\n  }\n}\n";
  return out;
}

// glTF 2.0: one node translated by +8 m in y over the mesh lowered by 8 m; float positions and
// uint32 triangles in `bin` (an external buffer).
nlohmann::json as_gltf(const Grid& g, const std::string& bin, std::string& bytes) {
  std::vector<float> pos;
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : g.points) {
    const glm::vec3 q(p.x, p.y - 8.0f, p.z);
    pos.insert(pos.end(), {q.x, q.y, q.z});
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  std::vector<std::uint32_t> idx;
  for (const auto& q : g.quads) {
    for (int k : {0, 1, 2, 0, 2, 3}) idx.push_back(static_cast<std::uint32_t>(q[static_cast<std::size_t>(k)]));
  }
  bytes.assign(reinterpret_cast<const char*>(pos.data()), pos.size() * 4);
  bytes.append(reinterpret_cast<const char*>(idx.data()), idx.size() * 4);
  nlohmann::json j;
  j["asset"]["version"] = "2.0";
  j["scene"] = 0;
  j["scenes"] = nlohmann::json::array({{{"nodes", {0}}}});
  j["nodes"] = nlohmann::json::array({{{"mesh", 0}, {"translation", {0.0, 8.0, 0.0}}}});
  nlohmann::json primitive = {{"indices", 1}, {"mode", 4}};
  primitive["attributes"]["POSITION"] = 0;
  j["meshes"] = nlohmann::json::array({{{"primitives", nlohmann::json::array({primitive})}}});
  j["buffers"] = nlohmann::json::array({{{"uri", bin}, {"byteLength", bytes.size()}}});
  j["bufferViews"] = nlohmann::json::array(
      {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", pos.size() * 4}},
       {{"buffer", 0}, {"byteOffset", pos.size() * 4}, {"byteLength", idx.size() * 4}}});
  j["accessors"] = nlohmann::json::array(
      {{{"bufferView", 0}, {"componentType", 5126}, {"count", g.points.size()}, {"type", "VEC3"},
        {"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}},
       {{"bufferView", 1}, {"componentType", 5125}, {"count", idx.size()}, {"type", "SCALAR"}}});
  return j;
}

// The build has no libtinygltf (terrain/mesh.hpp load_gltf says so).
bool without_gltf(const Error& e) { return e.message.find("configured without") != std::string::npos; }

class MeshFiles : public ModelTerrainGl {
 protected:
  void SetUp() override {
    ModelTerrainGl::SetUp();
    dir_ = fs::temp_directory_path() / ("sylva_model_formats_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    fs::remove_all(dir_);
    ModelTerrainGl::TearDown();
  }
  void write(const std::string& name, const std::string& text) { ASSERT_TRUE(write_file_atomic(dir_ / name, text).ok()); }
  // A scene of the mesh file alone, seen from the south-west above the hill, shadows off.
  Result<std::unique_ptr<Scene>> scene_of(const std::string& file, const std::string& extra = "") {
    const std::string json = R"({"camera": {"position": [-45.0, 30.0, -45.0], "yaw_deg": -135.0, "pitch_deg": -25.0},
      "render": {"shadows": {"enabled": false}},
      "model_terrain": {"file": ")" + file + R"(", "tree": {"levels": 2})" + extra + "}}";
    EXPECT_TRUE(write_file_atomic(dir_ / "s.json", json).ok());
    std::vector<std::string> warnings;
    auto doc = SceneDocument::load(dir_ / "s.json", warnings);
    if (!doc.ok()) return doc.error();
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    return Scene::create(std::move(*doc));
  }
  fs::path dir_;
};

TEST_F(MeshFiles, ObjIvAndGltfOfOneMeshDrawTheSamePicture) {
  if (!find_module("model_terrain")) GTEST_SKIP() << "terrain is built out";
  const Grid g = hill(16);
  write("hill.obj", as_obj(g, false));
  write("hill.iv", as_iv(g));
  std::string bytes;
  write("hill.gltf", as_gltf(g, "hill.bin", bytes).dump(1));
  write("hill.bin", bytes);
  std::vector<std::string> files = {"hill.obj", "hill.iv", "hill.gltf"};
  const glm::ivec2 size(128, 80);
  std::vector<Image> pictures;
  for (const std::string& f : files) {
    auto scene = scene_of(f);
    if (!scene.ok() && without_gltf(scene.error())) {
      files.pop_back();
      break;
    }
    ASSERT_TRUE(scene.ok()) << f << ": " << scene.error().message;
    const render::Camera camera = (*scene)->make_camera((*scene)->document().camera, size);
    pictures.push_back(frame(**scene, camera, size));
    const nlohmann::json s = (*scene)->module_stats()["model_terrain"];
    EXPECT_EQ(s["mesh_triangles"].get<std::uint64_t>(), 2u * 16u * 16u) << f;
    EXPECT_EQ(s["mesh_vertices"].get<std::uint64_t>(), 17u * 17u) << f;
    EXPECT_GT(s["triangles"].get<std::uint64_t>(), 0u) << f;
    std::printf("%s: %s triangles drawn of %s\n", f.c_str(), s["triangles"].dump().c_str(), s["mesh_triangles"].dump().c_str());
  }
  // The hill fills a good part of the frame (against the same scene without it).
  std::vector<std::string> warnings;
  auto doc = SceneDocument::load(dir_ / "s.json", warnings);
  ASSERT_TRUE(doc.ok());
  doc->remove_module("model_terrain");
  auto none = Scene::create(std::move(*doc));
  ASSERT_TRUE(none.ok()) << none.error().message;
  const Image blank = frame(**none, (*none)->make_camera((*none)->document().camera, size), size);
  EXPECT_GT(differing_pixels(pictures[0], blank), pictures[0].pixel_count() / 4) << "the hill is in view";
  for (std::size_t i = 1; i < pictures.size(); ++i) {
    EXPECT_EQ(differing_pixels(pictures[0], pictures[i]), 0u) << files[i] << " against " << files[0];
  }
  std::printf("formats: %zu files, hill covers %zu of %zu pixels\n", files.size(), differing_pixels(pictures[0], blank),
              pictures[0].pixel_count());
}

TEST_F(MeshFiles, ControlCageIsRefinedBySubdivision) {
  if (!find_module("model_terrain")) GTEST_SKIP() << "terrain is built out";
  write("cage.obj", as_obj(hill(4), true));  // 16 quads
  auto coarse = scene_of("cage.obj");
  ASSERT_TRUE(coarse.ok()) << coarse.error().message;
  auto fine = scene_of("cage.obj", R"(, "subdivision": {"scheme": "catmull_clark", "level": 2})");
  ASSERT_TRUE(fine.ok()) << fine.error().message;
  const glm::ivec2 size(96, 64);
  const Image a = frame(**coarse, (*coarse)->make_camera((*coarse)->document().camera, size), size);
  const Image b = frame(**fine, (*fine)->make_camera((*fine)->document().camera, size), size);
  const std::uint64_t cage = (*coarse)->module_stats()["model_terrain"]["mesh_triangles"].get<std::uint64_t>();
  const nlohmann::json s = (*fine)->module_stats()["model_terrain"];
  EXPECT_EQ(cage, 32u) << "16 quads, two triangles each";
  EXPECT_EQ(s["mesh_triangles"].get<std::uint64_t>(), 16u * cage) << "two levels: 4 x 4 quads per quad";
  EXPECT_GT(s["triangles"].get<std::uint64_t>(), 0u);
  EXPECT_GT(differing_pixels(a, b), 0u) << "the refined surface is smoother than the cage";
  std::printf("subdivision: cage %llu triangles, level 2: %s, %zu pixels differ\n", static_cast<unsigned long long>(cage),
              s["mesh_triangles"].dump().c_str(), differing_pixels(a, b));
}

TEST_F(MeshFiles, HostileIvAndGltfAreErrorsNamingTheFile) {
  if (!find_module("model_terrain")) GTEST_SKIP() << "terrain is built out";
  const std::string whole = as_iv(hill(2));
  write("truncated.iv", whole.substr(0, whole.find("coordIndex") + 20));
  write("range.iv", "#Inventor V2.1 ascii\nSeparator {\n Coordinate3 { point [ 0 0 0, 1 0 0, 0 0 1 ] }\n"
                    " IndexedFaceSet { coordIndex [ 0, 1, 2, -1,\n 0, 2, 3, -1 ] }\n}\n");
  const auto error_of = [&](const std::string& file) {
    auto scene = scene_of(file);
    EXPECT_FALSE(scene.ok()) << file;
    return scene.ok() ? std::string() : scene.error().message;
  };
  const std::string truncated = error_of("truncated.iv");
  EXPECT_NE(truncated.find("truncated.iv:"), std::string::npos) << truncated;
  EXPECT_NE(truncated.find("end of file"), std::string::npos) << truncated;
  const std::string range = error_of("range.iv");
  EXPECT_NE(range.find("range.iv:5: coordIndex 3 is outside the 3 points"), std::string::npos) << range;
  std::printf("errors: %s | %s\n", truncated.c_str(), range.c_str());
  std::string bytes;
  const nlohmann::json gltf = as_gltf(hill(2), "gone.bin", bytes);
  write("missing.gltf", gltf.dump());
  if (auto s = scene_of("missing.gltf"); !s.ok() && without_gltf(s.error())) return;
  const std::string missing = error_of("missing.gltf");
  EXPECT_NE(missing.find("missing.gltf"), std::string::npos) << missing;
  EXPECT_NE(missing.find("gone.bin"), std::string::npos) << missing;
  nlohmann::json past = as_gltf(hill(2), "past.bin", bytes);
  past["accessors"][1]["count"] = 1000;  // more indices than the view holds
  write("past.gltf", past.dump());
  write("past.bin", bytes);
  const std::string beyond = error_of("past.gltf");
  EXPECT_NE(beyond.find("past.gltf: accessors[1]"), std::string::npos) << beyond;
  const nlohmann::json outside = as_gltf(hill(2), "outside.bin", bytes);
  const std::uint32_t nine = 9;  // hill(2) has 9 vertices: 0..8
  bytes.replace(9 * 12, 4, reinterpret_cast<const char*>(&nine), 4);  // the first index
  write("outside.gltf", outside.dump());
  write("outside.bin", bytes);
  const std::string index = error_of("outside.gltf");
  EXPECT_NE(index.find("outside.gltf: meshes[0].primitives[0].indices: index 9 is outside the 9 vertices"),
            std::string::npos) << index;
  std::printf("errors: %s | %s | %s\n", missing.c_str(), beyond.c_str(), index.c_str());
}

}  // namespace

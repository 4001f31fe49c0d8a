// Grass on any mesh through scene files (issue #16, "Grass": grass.surface = "mesh").
//
// The mesh is a box written as OBJ by the test: x, z in [-2, 2], y in [0, 3], lifted by
// grass.mesh.offset (0, 2, 0) to y in [2, 5], so it has four vertical walls and an overhang (its
// bottom face, normal -y). Each face is an 8 x 8 grid of quads with outward winding. Checked:
//  - every blade root lies on the box (signed distance under 1 mm), blades grow on all six faces
//    along their normals (the stats' up_axes: walls' up vectors horizontal, the bottom face's
//    pointing down, none in between) in numbers within 10 % of face area x density;
//  - a density map of 0 over x < 0, or vertex colours (OBJ `v x y z r g b`, glTF COLOR_0) whose
//    red is 0 there, leave the -x wall bare and no root left of x = -0.5 m (the vertices' grid
//    step: triangles touching x = 0 see density above 0 there), while the +x wall keeps its
//    blades (the glTF box grows exactly the OBJ box's blades);
//  - the rendered picture, seen from below the box, has grass-green pixels above the horizon,
//    where the same section on the ground surface (the default) has none;
//  - saving the scene into another folder rebases grass.mesh.file ("../box.obj"), and the saved
//    scene grows the same blades;
//  - with grass.far_field on, a gently rolling height-field OBJ gets the seed-003 far field
//    (clumps placed and drawn, far grass in the picture where blades end), while the box (its
//    bottom faces down) gets none, with a warning and stats far_field_off naming the file;
//  - a missing file, a broken OBJ, an unknown extension, a colour above 1, a vertex without a
//    colour among coloured ones and "mesh" without a file give errors naming grass.mesh.file and
//    the file (and line).
#include <sylva/core/image.hpp>
#include <sylva/core/log.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene.hpp>

#include "scene_test_files.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

using namespace sylva;
using namespace sylva::scene;
namespace fs = std::filesystem;

namespace {

using GrassMeshGl = render::GlTest;

constexpr glm::ivec2 kSize(192, 128);
constexpr double kDensity = 150.0;  // grass.field.density [blades / m^2]
const glm::dvec3 kBoxCentre(0.0, 3.5, 0.0), kBoxHalf(2.0, 1.5, 2.0);  // after the offset

// Camera 10 m in front of the box's +z wall at y = 1.2, below the box, looking along -z
// (yaw 0) level: the box and its overhang fill the upper half of the picture.
nlohmann::json stage(const nlohmann::json& grass_extra) {
  nlohmann::json j = nlohmann::json::parse(R"json({
    "sylva_scene": 1,
    "name": "grass mesh stage",
    "camera": {"position": [0.0, 1.2, 12.0], "height_mode": "absolute", "yaw_deg": 0.0, "pitch_deg": 0.0, "fov_deg": 60.0},
    "sun": {"follow_clock": false, "azimuth_deg": 200.0, "elevation_deg": 35.0, "fog_density": 0.0},
    "wind": {"direction_deg": 20.0, "strength": 0.0, "gust_amplitude": 0.0},
    "ground": {"size": 128.0, "resolution": 33, "generator": "flat"},
    "grass": {"area_min": [-4.0, -4.0], "area_max": [4.0, 4.0], "far_field": false,
              "field": {"density": 150.0, "tile_size": 2.0},
              "blade": {"height_min": 0.2, "height_max": 0.4},
              "render": {"simulate": false}},
    "render": {"shadows": {"enabled": false}, "msaa_samples": 1, "tone_map": false}
  })json");
  j["grass"].merge_patch(grass_extra);
  return j;
}

nlohmann::json on_mesh(const std::string& file) {
  return {{"surface", "mesh"}, {"mesh", {{"file", file}, {"offset", {0.0, 2.0, 0.0}}}}};
}


// The box (before the offset): six faces of n x n quads, corner c, edges u and v with u x v
// along the outward normal, so every triangle's winding faces out. Colours: red (the density)
// 0 where x < 0, else 1.
struct BoxMesh {
  std::vector<glm::vec3> positions, colors;
  std::vector<std::uint32_t> indices;
};
BoxMesh make_box(int n) {
  struct Face {
    glm::dvec3 c, u, v;
  };
  const Face faces[6] = {
      {{2, 0, -2}, {0, 3, 0}, {0, 0, 4}},   // +x
      {{-2, 0, -2}, {0, 0, 4}, {0, 3, 0}},  // -x
      {{-2, 3, -2}, {0, 0, 4}, {4, 0, 0}},  // +y
      {{-2, 0, -2}, {4, 0, 0}, {0, 0, 4}},  // -y: the overhang
      {{-2, 0, 2}, {4, 0, 0}, {0, 3, 0}},   // +z
      {{-2, 0, -2}, {0, 3, 0}, {4, 0, 0}},  // -z
  };
  BoxMesh box;
  for (const Face& f : faces) {
    const auto base = static_cast<std::uint32_t>(box.positions.size());
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const glm::vec3 p(f.c + f.u * (double(i) / n) + f.v * (double(j) / n));
        box.positions.push_back(p);
        box.colors.emplace_back(p.x < 0.0f ? 0.0f : 1.0f, 0.5f, 0.2f);
      }
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::uint32_t a = base + static_cast<std::uint32_t>(j * (n + 1) + i), b = a + 1,
                            c = b + static_cast<std::uint32_t>(n + 1), d = a + static_cast<std::uint32_t>(n + 1);
        box.indices.insert(box.indices.end(), {a, b, c, a, c, d});
      }
  }
  return box;
}

// As OBJ; `colored`: every vertex with its colour (`v x y z r g b`).
void write_box_obj(const fs::path& file, int n, bool colored = false) {
  const BoxMesh box = make_box(n);
  std::ofstream out(file);
  for (std::size_t i = 0; i < box.positions.size(); ++i) {
    const glm::vec3 p = box.positions[i], c = box.colors[i];
    out << "v " << p.x << ' ' << p.y << ' ' << p.z;
    if (colored) out << ' ' << c.r << ' ' << c.g << ' ' << c.b;
    out << '\n';
  }
  for (std::size_t t = 0; t < box.indices.size(); t += 3) {
    out << "f " << box.indices[t] + 1 << ' ' << box.indices[t + 1] + 1 << ' ' << box.indices[t + 2] + 1 << '\n';
  }
}

std::string base64(const std::vector<unsigned char>& bytes) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t v = (std::uint32_t{bytes[i]} << 16) | (i + 1 < bytes.size() ? std::uint32_t{bytes[i + 1]} << 8 : 0u) |
                            (i + 2 < bytes.size() ? std::uint32_t{bytes[i + 2]} : 0u);
    for (std::size_t k = 0; k < 4; ++k) out += i + k <= bytes.size() ? kDigits[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

// As glTF with one data-URI buffer: POSITION and COLOR_0 (VEC3 FLOAT) and uint32 indices.
void write_box_gltf(const fs::path& file, int n) {
  const BoxMesh box = make_box(n);
  std::vector<unsigned char> bytes;
  auto put = [&](const void* data, std::size_t size) {
    const auto* b = static_cast<const unsigned char*>(data);
    bytes.insert(bytes.end(), b, b + size);
  };
  put(box.positions.data(), box.positions.size() * 12);
  put(box.colors.data(), box.colors.size() * 12);
  put(box.indices.data(), box.indices.size() * 4);
  const std::size_t vsize = box.positions.size() * 12, isize = box.indices.size() * 4;
  const nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"COLOR_0", 1}}}, {"indices", 2}, {"mode", 4}}}}}}},
      {"buffers", {{{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", vsize}},
                       {{"buffer", 0}, {"byteOffset", vsize}, {"byteLength", vsize}},
                       {{"buffer", 0}, {"byteOffset", 2 * vsize}, {"byteLength", isize}}}},
      {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", box.positions.size()}, {"type", "VEC3"},
                      {"min", {-2.0, 0.0, -2.0}}, {"max", {2.0, 3.0, 2.0}}},
                     {{"bufferView", 1}, {"componentType", 5126}, {"count", box.colors.size()}, {"type", "VEC3"}},
                     {{"bufferView", 2}, {"componentType", 5125}, {"count", box.indices.size()}, {"type", "SCALAR"}}}},
  };
  std::ofstream(file) << j.dump();
}


struct Frame {
  Image image;
  nlohmann::json stats;
  std::vector<glm::dvec3> roots;
};

Frame render_frame(Scene& scene) {
  const render::Camera camera = scene.make_camera(scene.document().camera, kSize);
  auto fb = render::Framebuffer::create({.width = kSize.x, .height = kSize.y, .color_formats = {GL_RGBA16F}}).value();
  render::FrameProfiler profiler;
  for (int i = 0; i < 2; ++i) {
    scene.update(camera, 1.0 + i / 30.0, 1.0f / 30.0f, kSize);
    scene.render(fb, profiler);
  }
  Frame f{render::read_color(fb).value(), scene.module_stats()["grass"], {}};
  f.roots = scene.module("grass")->placed_positions(f.stats["blades"].get<std::size_t>());
  return f;
}

// Signed distance of p to the lifted box.
double box_distance(const glm::dvec3& p) {
  const glm::dvec3 q = glm::abs(p - kBoxCentre) - kBoxHalf;
  return glm::length(glm::max(q, 0.0)) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0);
}

// Pixels of rows [0, rows) where green clearly leads red and blue (blades; the sky is blue).
std::size_t green_pixels(const Image& im, int rows) {
  std::size_t n = 0;
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < im.width(); ++x) {
      const float r = im.at(x, y, 0), g = im.at(x, y, 1), b = im.at(x, y, 2);
      n += (g > r + 0.03f && g > b + 0.03f) ? 1 : 0;
    }
  return n;
}

std::uint64_t axis(const Frame& f, const char* name) { return f.stats["up_axes"][name].get<std::uint64_t>(); }

// Density 0 over x < 0 (vertices at x = 0 have 1 from colours, 0.5 from the bilinear map): the
// -x wall is bare, no root lies left of the triangles touching x = 0, the +x wall is full.
void expect_left_half_bare(const Frame& f, const char* how) {
  double min_x = 1e9;
  for (const glm::dvec3& p : f.roots) min_x = std::min(min_x, p.x);
  std::printf("%s: %s, leftmost root x %.3f\n", how, f.stats.dump().c_str(), min_x);
  EXPECT_EQ(axis(f, "-x"), 0u) << how << ": the wall at x = -2 has density 0 at every vertex";
  EXPECT_GT(min_x, -0.5 - 1e-3) << how << ": no root beyond the triangles touching x = 0";
  EXPECT_NEAR(axis(f, "+x"), 12.0 * kDensity, 0.1 * 12.0 * kDensity) << how;
  EXPECT_GT(f.roots.size(), 0u);
}

}  // namespace

TEST_F(GrassMeshGl, BladesCoverWallsAndOverhangAlongTheirNormals) {
  if (!find_module("grass") || !find_module("ground") || !find_module("model_terrain")) {
    GTEST_SKIP() << "needs the grass, ground and terrain modules";
  }
  scene::testing::TestDir dir("sylva_grass_mesh");
  write_box_obj(dir.path / "box.obj", 8);
  auto made = scene::testing::scene_from_json(stage(on_mesh("box.obj")), dir.path);
  ASSERT_TRUE(made.ok()) << made.error().message;
  const Frame f = render_frame(**made);
  std::printf("mesh: %s\n", f.stats.dump().c_str());
  EXPECT_EQ(f.stats["surface"], "mesh");
  EXPECT_EQ(f.stats["mesh_triangles"].get<int>(), 6 * 8 * 8 * 2);
  ASSERT_EQ(f.roots.size(), f.stats["blades"].get<std::size_t>());
  double worst = 0.0;
  for (const glm::dvec3& p : f.roots) worst = std::max(worst, std::abs(box_distance(p)));
  std::printf("%zu roots, farthest %.2e m from the box\n", f.roots.size(), worst);
  EXPECT_LT(worst, 1e-3);
  // Up vectors along the faces' normals: walls horizontal, the overhang's blades hanging down.
  EXPECT_EQ(axis(f, "other"), 0u);
  const double wall = 12.0 * kDensity, cap = 16.0 * kDensity;  // face area x density
  for (const char* a : {"+x", "-x", "+z", "-z"}) EXPECT_NEAR(axis(f, a), wall, 0.1 * wall) << a;
  for (const char* a : {"+y", "-y"}) EXPECT_NEAR(axis(f, a), cap, 0.1 * cap) << a;
}

TEST_F(GrassMeshGl, DensityMapZeroOnHalfTheMeshLeavesItBare) {
  if (!find_module("grass") || !find_module("ground") || !find_module("model_terrain")) {
    GTEST_SKIP() << "needs the grass, ground and terrain modules";
  }
  scene::testing::TestDir dir("sylva_grass_mesh");
  write_box_obj(dir.path / "box.obj", 8);
  Image map(64, 64, 1);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) map.at(i, j, 0) = i < 32 ? 0.0f : 1.0f;  // 0 over x < 0
  ASSERT_TRUE(write_image(dir.path / "half.png", map, PixelFormat::kU8).ok());
  nlohmann::json extra = on_mesh("box.obj");
  extra["maps"] = {{"density", "half.png"}};
  auto made = scene::testing::scene_from_json(stage(extra), dir.path);
  ASSERT_TRUE(made.ok()) << made.error().message;
  expect_left_half_bare(render_frame(**made), "density map");
}

TEST_F(GrassMeshGl, VertexColourZeroOnHalfTheMeshLeavesItBare) {
  if (!find_module("grass") || !find_module("ground") || !find_module("model_terrain")) {
    GTEST_SKIP() << "needs the grass, ground and terrain modules";
  }
  scene::testing::TestDir dir("sylva_grass_mesh");
  write_box_obj(dir.path / "colored.obj", 8, true);
  auto made = scene::testing::scene_from_json(stage(on_mesh("colored.obj")), dir.path);  // the density map is 1 everywhere
  ASSERT_TRUE(made.ok()) << made.error().message;
  expect_left_half_bare(render_frame(**made), "vertex colour");
}

TEST_F(GrassMeshGl, GltfColourZeroOnHalfTheMeshLeavesItBare) {
  if (!find_module("grass") || !find_module("ground") || !find_module("model_terrain")) {
    GTEST_SKIP() << "needs the grass, ground and terrain modules";
  }
  scene::testing::TestDir dir("sylva_grass_mesh");
  write_box_gltf(dir.path / "colored.gltf", 8);
  auto made = scene::testing::scene_from_json(stage(on_mesh("colored.gltf")), dir.path);
  if (!made.ok() && made.error().code == ErrorCode::kUnsupported) GTEST_SKIP() << made.error().message;
  ASSERT_TRUE(made.ok()) << made.error().message;
  expect_left_half_bare(render_frame(**made), "glTF COLOR_0");
}

TEST_F(GrassMeshGl, PictureShowsGrassOnTheMeshNotOnTheGroundOnlyScene) {
  if (!find_module("grass") || !find_module("ground") || !find_module("model_terrain")) {
    GTEST_SKIP() << "needs the grass, ground and terrain modules";
  }
  scene::testing::TestDir dir("sylva_grass_mesh");
  write_box_obj(dir.path / "box.obj", 8);
  auto mesh = scene::testing::scene_from_json(stage(on_mesh("box.obj")), dir.path);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  auto ground = scene::testing::scene_from_json(stage(nlohmann::json::object()), dir.path);
  ASSERT_TRUE(ground.ok()) << ground.error().message;
  const Frame fm = render_frame(**mesh), fg = render_frame(**ground);
  // Rows above the horizon (the camera is level at y = 1.2; ground blades are at most 0.4 m).
  const int rows = kSize.y / 2 - 2;
  const std::size_t gm = green_pixels(fm.image, rows), gg = green_pixels(fg.image, rows);
  const std::size_t ground_below = green_pixels(fg.image, kSize.y) - gg;
  std::printf("green pixels above the horizon: mesh %zu, ground %zu (ground scene below it: %zu; %llu ground blades)\n", gm,
              gg, ground_below, static_cast<unsigned long long>(fg.stats["blades"].get<std::uint64_t>()));
  EXPECT_GT(gm, 200u);
  EXPECT_EQ(gg, 0u);
  EXPECT_GT(ground_below, 0u) << "the ground-surface grass is drawn, below the horizon";
}

TEST_F(GrassMeshGl, SaveAsElsewhereRebasesTheMeshFile) {
  if (!find_module("grass") || !find_module("ground") || !find_module("model_terrain")) {
    GTEST_SKIP() << "needs the grass, ground and terrain modules";
  }
  scene::testing::TestDir dir("sylva_grass_mesh");
  write_box_obj(dir.path / "box.obj", 8);
  auto made = scene::testing::scene_from_json(stage(on_mesh("box.obj")), dir.path);
  ASSERT_TRUE(made.ok()) << made.error().message;
  fs::create_directories(dir.path / "elsewhere");
  ASSERT_TRUE((*made)->save(dir.path / "elsewhere" / "saved.json").ok());
  std::vector<std::string> warnings;
  auto doc = SceneDocument::load(dir.path / "elsewhere" / "saved.json", warnings);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  const nlohmann::json saved = nlohmann::json::parse(std::ifstream(dir.path / "elsewhere" / "saved.json"));
  std::printf("saved grass.mesh: %s\n", saved["grass"]["mesh"].dump().c_str());
  EXPECT_EQ(saved["grass"]["mesh"]["file"], "../box.obj");
  auto again = Scene::create(std::move(*doc));
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_EQ(render_frame(**again).stats["blades"], render_frame(**made).stats["blades"]);
}

TEST_F(GrassMeshGl, BadMeshFilesNameTheKeyAndTheFile) {
  if (!find_module("grass") || !find_module("ground") || !find_module("model_terrain")) {
    GTEST_SKIP() << "needs the grass, ground and terrain modules";
  }
  scene::testing::TestDir dir("sylva_grass_mesh");
  std::ofstream(dir.path / "broken.obj") << "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 7\n";
  std::ofstream(dir.path / "bright.obj") << "v 0 0 0 1 1 1\nv 1 0 0 2 1 1\nv 0 0 1 1 1 1\nf 1 2 3\n";
  std::ofstream(dir.path / "mixed.obj") << "v 0 0 0 1 1 1\nv 1 0 0\nv 0 0 1 1 1 1\nf 1 2 3\n";
  struct Case {
    nlohmann::json grass;
    std::vector<std::string> expected;
  };
  const std::vector<Case> cases = {
      {on_mesh("missing.obj"), {"grass.mesh.file", "missing.obj"}},
      {on_mesh("broken.obj"), {"grass.mesh.file", "broken.obj:4"}},
      {on_mesh("box.stl"), {"grass.mesh.file", "box.stl"}},
      {on_mesh("bright.obj"), {"grass.mesh.file", "bright.obj:2", "colour '2' is outside [0, 1]"}},
      {on_mesh("mixed.obj"), {"grass.mesh.file", "mixed.obj:2", "without a colour"}},
  };
  for (const Case& c : cases) {
    // The scene opens without its grass and says why (issue 16, Bad input).
    auto warned = scene::testing::open_leaving_out(stage(c.grass), dir.path, "grass");
    ASSERT_TRUE(warned.ok()) << c.grass.dump() << ": " << warned.error().message;
    std::printf("%s", warned->c_str());
    for (const std::string& s : c.expected) EXPECT_NE(warned->find(s), std::string::npos) << *warned;
  }
  // No mesh named at all is a mistake in the scene file itself: the document is refused.
  auto unnamed = scene::testing::scene_from_json(stage({{"surface", "mesh"}}), dir.path);
  ASSERT_FALSE(unnamed.ok());
  for (const char* s : {"grass.mesh.file", "no mesh"}) EXPECT_NE(unnamed.error().message.find(s), std::string::npos) << unnamed.error().message;
}

// --- grass.mesh.density_source "uv_map" (issue 16: density from a map over the mesh's UVs) ---
// One quad x, z in [-2, 2] at y = 0.5, u = (x + 2) / 4, v (image rows) = (z + 2) / 4, as ONE
// OBJ face fanned into two triangles whose diagonal crosses x = 0: a per-vertex density cannot
// make a sharp edge there, a per-root one does. The image is black over u < 0.5 (x < 0), white
// over the rest; its bilinear ramp between the two middle pixel centres is 4 m / 64 wide.
namespace {

constexpr double kUvRamp = 4.0 / 64.0;  // [m]: one pixel of the density image on the quad

void write_uv_quad_obj(const fs::path& file, bool with_uvs) {
  std::ofstream out(file);
  out << "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\n";
  // vt v grows upwards in OBJ: the image row (z + 2) / 4 is 1 - vt.v.
  out << "vt 0 1\nvt 1 1\nvt 1 0\nvt 0 0\n";
  out << (with_uvs ? "f 1/1 4/4 3/3 2/2\n" : "f 1 4 3 2\n");
}

Image half_black_half_white() {
  Image map(64, 64, 3);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i)
      for (int c = 0; c < 3; ++c) map.at(i, j, c) = i < 32 ? 0.0f : 1.0f;
  return map;
}

// Looking straight down on the quad from 6 m, without a ground section (flat ground at y = 0).
nlohmann::json uv_stage(const std::string& mesh, const std::string& density_file) {
  nlohmann::json j = stage({{"surface", "mesh"},
                            {"mesh", {{"file", mesh}, {"offset", {0.0, 0.5, 0.0}}, {"density_source", "uv_map"},
                                      {"density_file", density_file}}}});
  j["camera"] = {{"position", {0.0, 6.5, 0.0}}, {"height_mode", "absolute"}, {"yaw_deg", 0.0}, {"pitch_deg", -89.0},
                 {"fov_deg", 60.0}};
  j.erase("ground");
  return j;
}

// Pixels of columns [x0, x1) darker than the sky behind the quad (seen from above, a blade is a
// small dark stroke against the bright sky: the scene has no ground section to draw).
std::size_t blade_pixels(const Image& im, int x0, int x1) {
  std::size_t n = 0;
  for (int y = 0; y < im.height(); ++y)
    for (int x = x0; x < x1; ++x) n += std::max({im.at(x, y, 0), im.at(x, y, 1), im.at(x, y, 2)}) < 0.25f ? 1 : 0;
  return n;
}

// quad.obj (with UVs) and half.png written into `dir`, and the scene growing grass on them.
Result<std::unique_ptr<Scene>> uv_quad_scene(const fs::path& dir) {
  write_uv_quad_obj(dir / "quad.obj", true);
  SYLVA_TRY(write_image(dir / "half.png", half_black_half_white(), PixelFormat::kU8));
  return scene::testing::scene_from_json(uv_stage("quad.obj", "half.png"), dir);
}

}  // namespace

TEST_F(GrassMeshGl, UvDensityMapGrowsBladesOnlyOnTheWhiteHalf) {
  if (!find_module("grass") || !find_module("model_terrain")) GTEST_SKIP() << "needs the grass and terrain modules";
  scene::testing::TestDir dir("sylva_grass_mesh");
  auto made = uv_quad_scene(dir.path);
  ASSERT_TRUE(made.ok()) << made.error().message;
  const Frame f = render_frame(**made);
  std::size_t black = 0, white = 0;
  for (const glm::dvec3& p : f.roots) {
    black += p.x < -kUvRamp ? 1 : 0;
    white += p.x > kUvRamp ? 1 : 0;
  }
  const double white_expected = (2.0 - kUvRamp) * 4.0 * kDensity;
  // Image columns: the camera looks down with yaw 0, so world +x is to the right.
  const std::size_t left = blade_pixels(f.image, 0, kSize.x / 2 - 4), right = blade_pixels(f.image, kSize.x / 2 + 4, kSize.x);
  std::printf("uv map: %s; roots black half %zu, white half %zu (expected %.0f); blade pixels left %zu, right %zu\n",
              f.stats.dump().c_str(), black, white, white_expected, left, right);
  if (const char* dump = std::getenv("SYLVA_TEST_DUMP")) (void)write_image(fs::path(dump) / "uv_map.png", f.image, PixelFormat::kU8);
  ASSERT_EQ(f.roots.size(), f.stats["blades"].get<std::size_t>());
  EXPECT_EQ(black, 0u);
  EXPECT_NEAR(static_cast<double>(white), white_expected, 0.08 * white_expected);
  EXPECT_GT(right, 50u);
  EXPECT_LT(left * 20, right) << "the black half shows (almost) no grass";
}

// The same quad as glTF: TEXCOORD_0 (glTF's v is already the image row) grows the OBJ's blades.
TEST_F(GrassMeshGl, UvDensityMapOnAGltfQuadGrowsTheObjBlades) {
  if (!find_module("grass") || !find_module("model_terrain")) GTEST_SKIP() << "needs the grass and terrain modules";
  scene::testing::TestDir dir("sylva_grass_mesh");
  const float positions[12] = {-2, 0, -2, 2, 0, -2, 2, 0, 2, -2, 0, 2};
  const float uvs[8] = {0, 0, 1, 0, 1, 1, 0, 1};
  const std::uint32_t indices[6] = {0, 3, 2, 0, 2, 1};  // the OBJ face's fan
  std::vector<unsigned char> bytes;
  for (const auto& [data, size] : {std::pair<const void*, std::size_t>{positions, 48}, {uvs, 32}, {indices, 24}}) {
    bytes.insert(bytes.end(), static_cast<const unsigned char*>(data), static_cast<const unsigned char*>(data) + size);
  }
  const nlohmann::json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}, {"mode", 4}}}}}}},
      {"buffers", {{{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                       {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 32}},
                       {{"buffer", 0}, {"byteOffset", 80}, {"byteLength", 24}}}},
      {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
                      {"min", {-2.0, 0.0, -2.0}}, {"max", {2.0, 0.0, 2.0}}},
                     {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
                     {{"bufferView", 2}, {"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}}}},
  };
  std::ofstream(dir.path / "quad.gltf") << gltf.dump();
  auto obj = uv_quad_scene(dir.path);
  ASSERT_TRUE(obj.ok()) << obj.error().message;
  auto made = scene::testing::scene_from_json(uv_stage("quad.gltf", "half.png"), dir.path);
  if (!made.ok() && made.error().code == ErrorCode::kUnsupported) GTEST_SKIP() << made.error().message;
  ASSERT_TRUE(made.ok()) << made.error().message;
  const Frame a = render_frame(**obj), b = render_frame(**made);
  EXPECT_GT(b.roots.size(), 1000u);
  EXPECT_EQ(a.roots, b.roots);
}

TEST_F(GrassMeshGl, UvDensityMapFileIsRebasedBySaveAs) {
  if (!find_module("grass") || !find_module("model_terrain")) GTEST_SKIP() << "needs the grass and terrain modules";
  scene::testing::TestDir dir("sylva_grass_mesh");
  auto made = uv_quad_scene(dir.path);
  ASSERT_TRUE(made.ok()) << made.error().message;
  fs::create_directories(dir.path / "elsewhere");
  ASSERT_TRUE((*made)->save(dir.path / "elsewhere" / "saved.json").ok());
  const nlohmann::json saved = nlohmann::json::parse(std::ifstream(dir.path / "elsewhere" / "saved.json"));
  EXPECT_EQ(saved["grass"]["mesh"]["density_file"], "../half.png");
  auto again = scene::testing::open_scene_file(dir.path / "elsewhere" / "saved.json");
  ASSERT_TRUE(again);
  EXPECT_EQ(render_frame(*again).stats["blades"], render_frame(**made).stats["blades"]);
}

TEST_F(GrassMeshGl, UvDensityMapErrorsNameTheSettingAndTheFile) {
  if (!find_module("grass") || !find_module("model_terrain")) GTEST_SKIP() << "needs the grass and terrain modules";
  scene::testing::TestDir dir("sylva_grass_mesh");
  write_uv_quad_obj(dir.path / "bare.obj", false);
  write_uv_quad_obj(dir.path / "quad.obj", true);
  ASSERT_TRUE(write_image(dir.path / "half.png", half_black_half_white(), PixelFormat::kU8).ok());
  std::ofstream(dir.path / "text.png") << "not a picture";
  struct Case {
    nlohmann::json scene;
    std::vector<std::string> expected;
  };
  const std::vector<Case> cases = {
      {uv_stage("bare.obj", "half.png"), {"grass.mesh.density_source", "uv_map", "texture coordinates", "bare.obj"}},
      {uv_stage("quad.obj", "missing.png"), {"grass.mesh.density_file", "missing.png"}},
      {uv_stage("quad.obj", "text.png"), {"grass.mesh.density_file", "text.png"}},
      {uv_stage("quad.obj", ""), {"grass.mesh.density_file", "no density image"}},
  };
  for (const Case& c : cases) {
    auto warned = scene::testing::open_leaving_out(c.scene, dir.path, "grass");
    ASSERT_TRUE(warned.ok()) << c.scene["grass"].dump() << ": " << warned.error().message;
    std::printf("%s", warned->c_str());
    for (const std::string& s : c.expected) EXPECT_NE(warned->find(s), std::string::npos) << *warned;
  }
}

namespace {

// A 60 x 60 m grid of 30 x 30 quads at y = 1 + 0.8 sin(0.15 x) cos(0.1 z), wound to face up: a
// height field.
void write_rolling_obj(const fs::path& file) {
  constexpr int n = 30;
  std::ofstream out(file);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -30.0 + 2.0 * i, z = -30.0 + 2.0 * j;
      out << "v " << x << ' ' << 1.0 + 0.8 * std::sin(0.15 * x) * std::cos(0.1 * z) << ' ' << z << '\n';
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i + 1, b = a + 1, d = a + n + 1, c = d + 1;
      out << "f " << a << ' ' << d << ' ' << b << "\nf " << b << ' ' << d << ' ' << c << '\n';
    }
}

// The rolling mesh seen from 5 m above its +z edge; blades end 8 m from the camera.
nlohmann::json rolling_stage(bool far_field) {
  nlohmann::json j = stage({{"surface", "mesh"}, {"mesh", {{"file", "rolling.obj"}}}, {"far_field", far_field},
                            {"area_min", {-30.0, -30.0}}, {"area_max", {30.0, 30.0}},
                            {"field", {{"density", 4.0}}}, {"render", {{"cull", {{"near_distance", 8.0}}}}}});
  j["camera"]["position"] = {0.0, 6.0, 34.0};
  j["camera"]["pitch_deg"] = -12.0;
  return j;
}

}  // namespace

TEST_F(GrassMeshGl, HeightFieldMeshGetsAFarField) {
  if (!find_module("grass") || !find_module("ground") || !find_module("model_terrain")) {
    GTEST_SKIP() << "needs the grass, ground and terrain modules";
  }
  scene::testing::TestDir dir("sylva_grass_mesh");
  write_rolling_obj(dir.path / "rolling.obj");
  auto far = scene::testing::scene_from_json(rolling_stage(true), dir.path);
  ASSERT_TRUE(far.ok()) << far.error().message;
  auto near_only = scene::testing::scene_from_json(rolling_stage(false), dir.path);
  ASSERT_TRUE(near_only.ok()) << near_only.error().message;
  const Frame ff = render_frame(**far), fn = render_frame(**near_only);
  std::printf("rolling mesh: %s\n", ff.stats.dump().c_str());
  EXPECT_FALSE(ff.stats.contains("far_field_off"));
  ASSERT_TRUE(ff.stats.contains("clumps"));
  EXPECT_GT(ff.stats["clumps"].get<std::uint64_t>(), 1000u);
  EXPECT_GT(ff.stats["clumps_drawn"].get<std::uint64_t>(), 0u);
  EXPECT_GT(ff.stats["ground_chunks_drawn"].get<std::uint64_t>(), 0u);
  EXPECT_FALSE(fn.stats.contains("clumps"));
  // Below the horizon the picture looks at the mesh from 5.5 m on, nearly all beyond the blades'
  // 8 m: the far field's clumps and ground layer change most of it.
  std::size_t changed = 0;
  for (int y = 0; y < kSize.y; ++y)
    for (int x = 0; x < kSize.x; ++x) {
      float d = 0.0f;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(ff.image.at(x, y, c) - fn.image.at(x, y, c)));
      changed += d > 0.02f ? 1 : 0;
    }
  std::printf("%zu of %d pixels changed by the far field\n", changed, kSize.x * kSize.y);
  EXPECT_GT(changed, static_cast<std::size_t>(kSize.x * kSize.y / 3));
}

TEST_F(GrassMeshGl, MeshThatIsNoHeightFieldGetsNoFarFieldAndAWarning) {
  if (!find_module("grass") || !find_module("ground") || !find_module("model_terrain")) {
    GTEST_SKIP() << "needs the grass, ground and terrain modules";
  }
  scene::testing::TestDir dir("sylva_grass_mesh");
  write_box_obj(dir.path / "box.obj", 8);
  nlohmann::json extra = on_mesh("box.obj");
  extra["far_field"] = true;
  std::vector<std::string> warnings;
  set_log_sink([&](LogLevel level, std::string_view m) {
    if (level == LogLevel::kWarn) warnings.emplace_back(m);
  });
  auto made = scene::testing::scene_from_json(stage(extra), dir.path);
  set_log_sink(nullptr);
  ASSERT_TRUE(made.ok()) << made.error().message;
  const Frame f = render_frame(**made);
  std::printf("box: far_field_off \"%s\"\n", f.stats.value("far_field_off", "").c_str());
  EXPECT_FALSE(f.stats.contains("clumps"));
  EXPECT_GT(f.stats["blades"].get<std::uint64_t>(), 0u) << "the blades are still grown";
  const std::string off = f.stats.value("far_field_off", "");
  EXPECT_NE(off.find("box.obj"), std::string::npos) << off;
  EXPECT_NE(off.find("faces down"), std::string::npos) << off;
  const bool warned = std::any_of(warnings.begin(), warnings.end(), [](const std::string& w) {
    return w.find("grass.far_field") != std::string::npos && w.find("box.obj") != std::string::npos;
  });
  EXPECT_TRUE(warned) << "a warning names the setting and the file";
}

// Stability of running scenes. Each test names its invariant.
#include <sylva/core/image_metrics.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/height_source.hpp>
#include <sylva/scene/scene.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <unistd.h>

using namespace sylva;
using namespace sylva::scene;

namespace {
using SceneStabilityGl = render::GlTest;

std::unique_ptr<Scene> make(const std::string& text) {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::from_text(text, "stability.json", warnings);
  EXPECT_TRUE(doc.ok()) << doc.error().message;
  if (!doc.ok()) return nullptr;
  auto scene = Scene::create(std::move(*doc));
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  return scene.ok() ? std::move(*scene) : nullptr;
}

// A float target, as sylva-bench's stability cases use: an 8-bit one stores NaN as some number,
// so "no NaN in the picture" could never fail there.
Image render_once(Scene& scene, const CameraView& view, glm::ivec2 size, double time, float dt, int frames = 1) {
  auto fb = render::Framebuffer::create({.width = size.x, .height = size.y, .color_formats = {GL_RGBA32F}}).value();
  render::FrameProfiler profiler;
  const render::Camera cam = scene.make_camera(view, size);
  for (int i = 0; i < frames; ++i) {
    scene.update(cam, time + i * dt, dt, size);
    scene.render(fb, profiler);
  }
  return render::read_color(fb).value();
}
}  // namespace

// Invariant: camera-relative rendering; the same ground 1000 km from the origin renders like the
// one at the origin (no float jitter of the vertices).
TEST_F(SceneStabilityGl, FarFromTheOriginLooksTheSame) {
  // The same height map at both places (a generator would sample different noise there).
  HeightSourceSettings source;
  source.resolution = 65;
  source.size = 256.0f;
  source.height = 20.0f;
  source.generator = HeightGenerator::kFbm;
  source.noise.frequency = 0.01f;
  const MapGrid grid = make_height_grid(source, std::nullopt).value();
  const std::filesystem::path map = std::filesystem::temp_directory_path() / ("sylva_far_" + std::to_string(::getpid()) + ".exr");
  ASSERT_TRUE(write_map_image(map, grid, 1.0f, 0.0f).ok());
  auto text = [&](const char* cx, const char* cz) {
    return std::string(R"({"ground": {"size": 256, "center": [)") + cx + ", " + cz + R"(], "maps": {"height": ")" +
           map.string() + R"("}}, "sun": {"fog_density": 0.0}})";
  };
  auto near = make(text("0", "0"));
  auto far = make(text("1000000", "-1000000"));
  ASSERT_TRUE(near && far);
  CameraView v{{0.0, 60.0, 150.0}, 0.0f, -20.0f, 60.0f, HeightMode::kAbsolute};
  const Image a = render_once(*near, v, {96, 54}, 0.0, 0.0f);
  v.position += glm::dvec3(1.0e6, 0.0, -1.0e6);
  const Image b = render_once(*far, v, {96, 54}, 0.0, 0.0f);
  EXPECT_LT(rmse(a, b).value(), 0.01) << "jittering vertices would tear the picture apart";
  EXPECT_FLOAT_EQ(static_cast<float>(far->ground_height(1.0e6 + 10.0, -1.0e6 + 20.0)),
                  static_cast<float>(near->ground_height(10.0, 20.0)));
  std::filesystem::remove(map);
}

// Invariant: any frame time (0, tiny, huge) keeps every module stable: no GL error, placed
// objects finite and on the ground.
TEST_F(SceneStabilityGl, AnyFrameTimeIsStable) {
  std::string text = R"({"ground": {"resolution": 33, "size": 64, "height": 5}, "wind": {"strength": 40, "gust_amplitude": 30})";
  if (find_module("grass")) text += R"(, "grass": {"area_min": [-4, -4], "area_max": [4, 4], "field": {"density": 10}})";
  if (find_module("vegetation")) {
    text += R"(, "vegetation": {"area_min": [-20, -20], "area_max": [20, 20], "trees_per_hectare": 20, "leaf_texture_size": 32})";
  }
  text += "}";
  auto scene = make(text);
  ASSERT_TRUE(scene);
  const CameraView v{{0.0, 8.0, 20.0}, 0.0f, -15.0f, 60.0f, HeightMode::kAbsolute};
  for (float dt : {0.0f, 1e-6f, 1.0f / 60.0f, 1.0f, 100.0f, 1.0e4f}) {
    const Image img = render_once(*scene, v, {48, 32}, 1.0e6, dt, 2);
    for (float c : img.data()) ASSERT_TRUE(std::isfinite(c)) << dt;
    for (const auto& m : scene->modules()) {
      for (const glm::dvec3& p : m->placed_positions(200)) {
        ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << m->module() << " dt " << dt;
        EXPECT_NEAR(p.y, scene->ground_height(p.x, p.z), 5e-3) << m->module() << " dt " << dt;
      }
    }
  }
}

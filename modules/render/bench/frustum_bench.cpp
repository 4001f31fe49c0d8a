// Frustum culling throughput on the CPU: 100k boxes scattered around a camera 1e6 m from the
// origin (world boxes in double, the API modules use), and the same test on boxes already in
// camera-relative float form.
#include <sylva/render/camera.hpp>
#include <sylva/render/frustum.hpp>

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

namespace {

using sylva::render::Aabb;
using sylva::render::Camera;

struct Scene {
  Camera camera;
  std::vector<Aabb> boxes;
  std::vector<glm::vec3> rel_centers, rel_halves;
};

Scene make_scene(std::size_t count) {
  Scene s;
  const glm::dvec3 origin(1.0e6, 120.0, -2.5e5);
  s.camera.set_position(origin);
  s.camera.set_yaw_pitch(0.6f, -0.15f);
  s.camera.set_aspect(1920, 1080);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> pos(-2000.0, 2000.0);
  std::uniform_real_distribution<double> height(-50.0, 150.0);
  std::uniform_real_distribution<double> size(0.5, 20.0);
  for (std::size_t i = 0; i < count; ++i) {
    const glm::dvec3 c = origin + glm::dvec3(pos(rng), height(rng), pos(rng));
    const glm::dvec3 h(size(rng), size(rng), size(rng));
    s.boxes.push_back({c - h, c + h});
    s.rel_centers.emplace_back(c - origin);
    s.rel_halves.emplace_back(h);
  }
  return s;
}

void BM_CullWorldBoxes(benchmark::State& state) {
  const Scene s = make_scene(static_cast<std::size_t>(state.range(0)));
  std::vector<unsigned char> visible(s.boxes.size());
  std::size_t count = 0;
  for (auto _ : state) {
    const sylva::render::Frustum f = s.camera.frustum();
    count = f.cull(s.boxes, visible);
    benchmark::DoNotOptimize(visible.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
  state.counters["visible"] = static_cast<double>(count);
}
BENCHMARK(BM_CullWorldBoxes)->Arg(100000)->Unit(benchmark::kMillisecond);

void BM_CullRelativeBoxes(benchmark::State& state) {
  const Scene s = make_scene(static_cast<std::size_t>(state.range(0)));
  std::size_t count = 0;
  for (auto _ : state) {
    const sylva::render::Frustum f = s.camera.frustum();
    count = 0;
    for (std::size_t i = 0; i < s.rel_centers.size(); ++i) {
      count += f.intersects_relative(s.rel_centers[i], s.rel_halves[i]) ? 1 : 0;
    }
    benchmark::DoNotOptimize(count);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
  state.counters["visible"] = static_cast<double>(count);
}
BENCHMARK(BM_CullRelativeBoxes)->Arg(100000)->Unit(benchmark::kMillisecond);

void BM_ExtractFrustum(benchmark::State& state) {
  const Scene s = make_scene(1);
  for (auto _ : state) benchmark::DoNotOptimize(s.camera.frustum());
}
BENCHMARK(BM_ExtractFrustum);

}  // namespace

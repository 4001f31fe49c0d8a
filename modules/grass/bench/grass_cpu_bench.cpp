// CPU kernels of the grass module: placement, the physics reference, the culling formulas and
// the closed-form arc length. Rates are reported as items (blades) per second.
#include <sylva/grass/culling.hpp>
#include <sylva/grass/generator.hpp>
#include <sylva/grass/physics.hpp>

#include <benchmark/benchmark.h>
#include <glm/gtc/matrix_transform.hpp>

namespace {

using namespace sylva;
using namespace sylva::grass;

BladeSet make_set(float density) {
  GrassFieldSettings field;
  field.density = density;
  HeightField ground(101, 101, 1.0);
  return generate_blades(field, BladeSettings{}, GrassMaps::uniform({{0, 0}, {100, 100}}), ground, {50, 0, 50}).value();
}

void BM_GenerateBlades(benchmark::State& state) {
  GrassFieldSettings field;
  field.density = static_cast<float>(state.range(0)) / 1.0e4f;
  HeightField ground(101, 101, 1.0);
  Image density(64, 64, 1);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) density.at(x, y) = 0.5f + 0.5f * static_cast<float>((x * 7 + y * 3) % 10) / 10.0f;
  const GrassMaps maps = GrassMaps::from_images({{0, 0}, {100, 100}}, &density, nullptr, nullptr).value();
  std::size_t n = 0;
  for (auto _ : state) {
    auto set = generate_blades(field, BladeSettings{}, maps, ground, {50, 0, 50});
    n = set->blades.size();
    benchmark::DoNotOptimize(set->blades.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(n) * state.iterations());
  state.counters["blades"] = static_cast<double>(n);
}
BENCHMARK(BM_GenerateBlades)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);

void BM_SimulateBlades(benchmark::State& state) {
  BladeSet set = make_set(10.0f);  // 100k blades
  const PhysicsSettings settings;
  const float dt = state.range(0) == 0 ? 1.0f / 60.0f : 1.0f;
  const WindSampler wind = [](const glm::vec3& p) { return glm::vec3(6.0f + 0.1f * p.x, 0.0f, 2.0f); };
  for (auto _ : state) {
    simulate_blades(set.blades, wind, dt, settings);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(set.blades.size()) * state.iterations());
  state.SetLabel(state.range(0) == 0 ? "dt=1/60 (1 substep)" : "dt=1 s (4 substeps)");
}
BENCHMARK(BM_SimulateBlades)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_CullBladeSet(benchmark::State& state) {
  const BladeSet set = make_set(20.0f);  // 200k blades
  const glm::mat4 proj = glm::perspective(glm::radians(60.0f), 16.0f / 9.0f, 0.1f, 1000.0f);
  const glm::vec3 eye(0.0f, 1.7f, 0.0f), target(10.0f, 0.5f, -10.0f);
  const CullView view = make_cull_view(proj * glm::lookAt(eye, target, {0, 1, 0}), eye, glm::normalize(target - eye), 1080.0f,
                                       glm::radians(60.0f));
  CullSettings s;
  CullCounts counts;
  for (auto _ : state) {
    counts = cull_blade_set(set, view, s);
    benchmark::DoNotOptimize(counts);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(set.blades.size()) * state.iterations());
  state.counters["visible_share"] = static_cast<double>(counts.visible) / static_cast<double>(counts.considered);
}
BENCHMARK(BM_CullBladeSet)->Unit(benchmark::kMillisecond);

void BM_BezierLength(benchmark::State& state) {
  std::vector<glm::vec3> tips;
  for (int i = 0; i < 1024; ++i) tips.emplace_back(0.3f * std::sin(0.1f * i), 0.2f + 0.3f * std::cos(0.07f * i), 0.1f);
  float sum = 0.0f;
  for (auto _ : state) {
    for (const glm::vec3& t : tips) sum += bezier_length({0, 0, 0}, {0, 0.3f, 0}, t);
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(tips.size()) * state.iterations());
}
BENCHMARK(BM_BezierLength);

}  // namespace

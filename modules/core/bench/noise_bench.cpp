// Cost of the procedural kernels: RNG and hash, gradient noise, fBm / ridged fBm (what terrain
// generation and procedural textures pay per sample) and the wind field (what a CPU-animated
// blade or branch pays per sample). items_per_second = samples per second.
#include <sylva/core/noise.hpp>
#include <sylva/core/rng.hpp>
#include <sylva/core/wind.hpp>

#include <benchmark/benchmark.h>

#include <cstdint>

namespace {

using sylva::FbmSettings;

// A 64 x 64 grid of sample points per iteration, spaced off the lattice.
constexpr int kGrid = 64;

template <class F>
void run_grid(benchmark::State& state, F f) {
  float sink = 0.0f;
  for (auto _ : state) {
    for (int y = 0; y < kGrid; ++y)
      for (int x = 0; x < kGrid; ++x) sink += f(static_cast<float>(x) * 0.173f, static_cast<float>(y) * 0.219f);
    benchmark::DoNotOptimize(sink);
  }
  state.SetItemsProcessed(state.iterations() * kGrid * kGrid);
}

void BM_Pcg32(benchmark::State& state) {
  sylva::Pcg32 rng(1u);
  std::uint32_t sink = 0;
  for (auto _ : state) {
    for (int i = 0; i < 4096; ++i) sink ^= rng.next_u32();
    benchmark::DoNotOptimize(sink);
  }
  state.SetItemsProcessed(state.iterations() * 4096);
}
BENCHMARK(BM_Pcg32);

void BM_HashXYSeed(benchmark::State& state) {
  std::uint32_t sink = 0;
  for (auto _ : state) {
    for (int y = 0; y < kGrid; ++y)
      for (int x = 0; x < kGrid; ++x) sink ^= sylva::hash_i32(x, y, 7u);
    benchmark::DoNotOptimize(sink);
  }
  state.SetItemsProcessed(state.iterations() * kGrid * kGrid);
}
BENCHMARK(BM_HashXYSeed);

void BM_Noise1(benchmark::State& state) {
  run_grid(state, [](float x, float y) { return sylva::gradient_noise1(x + y, 1u); });
}
BENCHMARK(BM_Noise1);

void BM_Noise2(benchmark::State& state) {
  run_grid(state, [](float x, float y) { return sylva::gradient_noise2(glm::vec2(x, y), 1u); });
}
BENCHMARK(BM_Noise2);

void BM_Noise3(benchmark::State& state) {
  run_grid(state, [](float x, float y) { return sylva::gradient_noise3(glm::vec3(x, y, 0.5f * x), 1u); });
}
BENCHMARK(BM_Noise3);

void BM_Noise3Double(benchmark::State& state) {
  run_grid(state, [](float x, float y) { return sylva::gradient_noise3(glm::dvec3(x, y, 0.5 * x), 1u); });
}
BENCHMARK(BM_Noise3Double);

void BM_Fbm2(benchmark::State& state) {
  FbmSettings s;
  s.octaves = static_cast<int>(state.range(0));
  run_grid(state, [&](float x, float y) { return sylva::fbm2(glm::vec2(x, y), s); });
}
BENCHMARK(BM_Fbm2)->Arg(1)->Arg(4)->Arg(8);

void BM_Fbm2Double(benchmark::State& state) {
  FbmSettings s;
  s.octaves = static_cast<int>(state.range(0));
  run_grid(state, [&](float x, float y) { return sylva::fbm2(glm::dvec2(x, y), s); });
}
BENCHMARK(BM_Fbm2Double)->Arg(8);

void BM_Fbm3(benchmark::State& state) {
  FbmSettings s;
  s.octaves = static_cast<int>(state.range(0));
  run_grid(state, [&](float x, float y) { return sylva::fbm3(glm::vec3(x, y, 0.3f * y), s); });
}
BENCHMARK(BM_Fbm3)->Arg(4)->Arg(8);

void BM_Ridged2(benchmark::State& state) {
  FbmSettings s;
  s.octaves = static_cast<int>(state.range(0));
  run_grid(state, [&](float x, float y) { return sylva::ridged2(glm::vec2(x, y), s); });
}
BENCHMARK(BM_Ridged2)->Arg(8);

// A whole 1025 x 1025 height field from 8-octave fBm in double coordinates (the terrain
// generator's inner loop, single thread).
void BM_HeightField1025(benchmark::State& state) {
  FbmSettings s;
  s.octaves = 8;
  s.frequency = 1.0f / 256.0f;
  float sink = 0.0f;
  for (auto _ : state) {
    for (int y = 0; y < 1025; ++y)
      for (int x = 0; x < 1025; ++x) sink += sylva::fbm2(glm::dvec2(x, y), s);
    benchmark::DoNotOptimize(sink);
  }
  state.SetItemsProcessed(state.iterations() * 1025 * 1025);
}
BENCHMARK(BM_HeightField1025)->Unit(benchmark::kMillisecond);

// Wind per sample through a precomputed frame (the per-blade / per-branch CPU path).
void BM_WindFrame(benchmark::State& state) {
  sylva::WindSettings ws;
  ws.turbulence_octaves = static_cast<int>(state.range(0));
  const sylva::WindField wind(ws);
  const sylva::WindFrame frame = wind.frame(123.0, glm::dvec3(1000.0, 0.0, -500.0));
  glm::vec3 sink(0.0f);
  for (auto _ : state) {
    for (int y = 0; y < kGrid; ++y)
      for (int x = 0; x < kGrid; ++x) sink += sylva::WindField::evaluate(frame, glm::vec3(x * 0.5f, 1.0f, y * 0.5f));
    benchmark::DoNotOptimize(sink);
  }
  state.SetItemsProcessed(state.iterations() * kGrid * kGrid);
}
BENCHMARK(BM_WindFrame)->Arg(1)->Arg(2)->Arg(4);

// Wind per sample with a double world position (builds a frame per call).
void BM_WindWorld(benchmark::State& state) {
  const sylva::WindField wind;
  glm::vec3 sink(0.0f);
  for (auto _ : state) {
    for (int y = 0; y < kGrid; ++y)
      for (int x = 0; x < kGrid; ++x) sink += wind.evaluate(glm::dvec3(x * 0.5, 1.0, y * 0.5), 123.0);
    benchmark::DoNotOptimize(sink);
  }
  state.SetItemsProcessed(state.iterations() * kGrid * kGrid);
}
BENCHMARK(BM_WindWorld);

}  // namespace

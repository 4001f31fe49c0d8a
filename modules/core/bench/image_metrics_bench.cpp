// Cost of the image metrics sylva-bench computes per frame against its reference render:
// PSNR, SSIM (luminance and per channel), the threshold share and silhouette coverage, at the
// test size 256x144 and at 1280x720. items_per_second = pixels per second.
#include <sylva/core/image_metrics.hpp>
#include <sylva/core/rng.hpp>

#include <benchmark/benchmark.h>

#include <cmath>

namespace {

// A structured RGBA picture plus a perturbed copy, so SSIM has real work (no flat regions).
struct Pair {
  sylva::Image a;
  sylva::Image b;
};

Pair make_images(int w, int h) {
  Pair p{sylva::Image(w, h, 4), sylva::Image(w, h, 4)};
  sylva::Pcg32 rng(1u);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < 4; ++c) {
        const float v = 0.5f + 0.4f * std::sin(0.05f * static_cast<float>(x * (c + 1)) + 0.07f * static_cast<float>(y));
        p.a.at(x, y, c) = c == 3 ? (v > 0.5f ? 1.0f : 0.0f) : v;
        p.b.at(x, y, c) = c == 3 ? p.a.at(x, y, c) : v + 0.05f * (rng.next_float() - 0.5f);
      }
    }
  }
  return p;
}

void set_pixels(benchmark::State& state, const Pair& p) {
  state.SetItemsProcessed(state.iterations() * p.a.width() * p.a.height());
}

void BM_Psnr(benchmark::State& state) {
  const Pair p = make_images(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  for (auto _ : state) benchmark::DoNotOptimize(sylva::psnr(p.a, p.b));
  set_pixels(state, p);
}
BENCHMARK(BM_Psnr)->Args({256, 144})->Args({1280, 720});

void BM_SsimLuminance(benchmark::State& state) {
  const Pair p = make_images(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  for (auto _ : state) benchmark::DoNotOptimize(sylva::ssim(p.a, p.b));
  set_pixels(state, p);
}
BENCHMARK(BM_SsimLuminance)->Args({256, 144})->Args({1280, 720})->Unit(benchmark::kMillisecond);

void BM_SsimPerChannel(benchmark::State& state) {
  const Pair p = make_images(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const sylva::SsimOptions options{.channels = sylva::SsimChannels::kPerChannel};
  for (auto _ : state) benchmark::DoNotOptimize(sylva::ssim(p.a, p.b, options));
  set_pixels(state, p);
}
BENCHMARK(BM_SsimPerChannel)->Args({256, 144})->Args({1280, 720})->Unit(benchmark::kMillisecond);

void BM_ShareExceeding(benchmark::State& state) {
  const Pair p = make_images(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  for (auto _ : state) benchmark::DoNotOptimize(sylva::share_exceeding(p.a, p.b, 0.02f));
  set_pixels(state, p);
}
BENCHMARK(BM_ShareExceeding)->Args({256, 144})->Args({1280, 720});

void BM_SilhouetteCoverage(benchmark::State& state) {
  const Pair p = make_images(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  for (auto _ : state) benchmark::DoNotOptimize(sylva::silhouette_coverage(p.a, p.b));
  set_pixels(state, p);
}
BENCHMARK(BM_SilhouetteCoverage)->Args({256, 144})->Args({1280, 720});

}  // namespace

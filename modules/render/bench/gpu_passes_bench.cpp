// GPU cost on the headless context (llvmpipe on the CI machine): the sky pass and a framebuffer
// read-back at the test resolution 256x144 and at 1280x720. Each iteration ends with glFinish
// so wall time is the real cost; the GPU time from timestamp queries is reported beside it.
#include <sylva/render/camera.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/gl_context.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/sky.hpp>

#include <benchmark/benchmark.h>

#include <memory>

namespace {

using namespace sylva::render;

GlContext* context() {
  static std::unique_ptr<GlContext> ctx = [] {
    auto created = GlContext::create_headless({.debug = false});
    return created.ok() ? std::make_unique<GlContext>(std::move(created).value()) : nullptr;
  }();
  return ctx.get();
}

void BM_SkyPass(benchmark::State& state) {
  if (context() == nullptr) {
    state.SkipWithError("no headless GL context");
    return;
  }
  const int w = static_cast<int>(state.range(0));
  const int h = static_cast<int>(state.range(1));
  auto fb = Framebuffer::create({.width = w, .height = h});
  auto sky = SkyRenderer::create();
  if (!fb.ok() || !sky.ok()) {
    state.SkipWithError("setup failed");
    return;
  }
  Camera cam;
  cam.set_aspect(w, h);
  Lighting lighting;
  apply_reversed_z_state();
  PassQuery query = PassQuery::create(true);
  double gpu_ms = 0.0;
  std::uint64_t frame = 0;
  for (auto _ : state) {
    fb->bind();
    fb->clear({0, 0, 0, 1});
    query.begin(++frame);
    sky->draw(cam, lighting);
    query.end();
    glFinish();
    if (auto r = query.poll()) gpu_ms += r->gpu_ms;
  }
  state.counters["gpu_ms"] = gpu_ms / static_cast<double>(state.iterations());
}
BENCHMARK(BM_SkyPass)->Args({256, 144})->Args({1280, 720})->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ReadBack(benchmark::State& state) {
  if (context() == nullptr) {
    state.SkipWithError("no headless GL context");
    return;
  }
  const int w = static_cast<int>(state.range(0));
  const int h = static_cast<int>(state.range(1));
  auto fb = Framebuffer::create({.width = w, .height = h});
  if (!fb.ok()) {
    state.SkipWithError("setup failed");
    return;
  }
  fb->bind();
  fb->clear({0.2f, 0.4f, 0.6f, 1.0f});
  for (auto _ : state) {
    auto image = read_color(*fb);
    benchmark::DoNotOptimize(image.ok());
  }
}
BENCHMARK(BM_ReadBack)->Args({256, 144})->Args({1280, 720})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

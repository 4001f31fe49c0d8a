// LOD0 forest cost on the headless context (llvmpipe on the CI machine): trees per frame and frame
// time for 10..1000 instances of the broadleaf preset, all in view (the seed's FOREST scene, §5.2),
// and the cost of each animation level (static, + trunk, + branches, + leaves) for 10..100
// instances, after the seed's table 5.5. Each iteration updates the forest (culling, instance
// records, wind), draws the opaque pass and ends with glFinish, so the wall time is the real cost
// on a software rasteriser; the GPU time from timestamp queries is reported beside it (llvmpipe's
// timestamps underestimate, see render/queries.hpp).
#include <sylva/core/wind.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/gl_context.hpp>
#include <sylva/render/lighting_uniforms.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/vegetation/forest.hpp>

#include "support/bench_view.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

namespace {

using namespace sylva;
using namespace sylva::vegetation;

using bench::BenchView;

struct Bench : BenchView {
  Forest forest;
};

// n trees on a square grid 12 m apart, the camera 30 m up at the grid's edge looking across it.
std::unique_ptr<Bench> make_bench(int n, int width, int height) {
  auto b = std::make_unique<Bench>();
  if (!bench::init_view(*b, width, height)) return nullptr;
  ForestSettings settings;
  settings.lod.enabled = false;  // LOD0 costs; lod_bench.cpp measures the image-based levels
  Result<Forest> f = Forest::create(settings);
  if (!f.ok()) return nullptr;
  b->forest = std::move(f).value();
  b->forest.settings().receive_shadows = false;  // no shadow maps in this benchmark
  if (!b->forest.add_preset(SpeciesPreset::kBroadleaf, 1, 128).ok()) return nullptr;
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  std::vector<TreeInstance> trees;
  for (int i = 0; i < n; ++i) {
    TreeInstance t;
    t.position = {(i % side) * 12.0, 0.0, -(i / side) * 12.0};
    t.yaw = 0.7f * static_cast<float>(i);
    t.time_offset = static_cast<float>(i % 97);
    trees.push_back(t);
  }
  if (!b->forest.set_instances(0, trees).ok()) return nullptr;
  const double extent = (side - 1) * 12.0;
  b->camera.set_position({0.5 * extent, 30.0 + 0.3 * extent, 25.0});
  b->camera.look_at({0.5 * extent, 0.0, -0.55 * extent});
  b->camera.perspective().fov_y = 1.1f;
  return b;
}

void run(benchmark::State& state, Bench& b) {
  render::PassQuery query = render::PassQuery::create(true);
  double gpu_ms = 0.0;
  double update_ms = 0.0;
  std::uint64_t frame = 0;
  render::PassStats last;
  render::apply_reversed_z_state();
  for (auto _ : state) {
    const double time = 0.05 * static_cast<double>(frame);
    render::FrameContext ctx{b.camera, time, 0.05f, b.wind, b.lighting, b.target.size(), frame};
    b.forest.update(ctx);
    b.target.bind();
    b.target.clear({0.6f, 0.75f, 0.95f, 1.0f});
    b.lighting_ubo.update(b.lighting, b.camera.position().y, time);
    b.lighting_ubo.bind();
    render::PassStats stats;
    query.begin(++frame);
    b.forest.draw(render::Pass::kOpaque, ctx, stats);
    query.end();
    glFinish();
    if (auto r = query.poll()) gpu_ms += r->gpu_ms;
    update_ms += b.forest.stats().update_cpu_ms;
    last = stats;
  }
  if (auto r = query.wait_all()) gpu_ms += r->gpu_ms;
  const auto it = static_cast<double>(state.iterations());
  state.counters["trees"] = static_cast<double>(last.instances);
  state.counters["triangles"] = static_cast<double>(last.triangles);
  state.counters["timestamp_ms"] = gpu_ms / it;
  state.counters["update_cpu_ms"] = update_ms / it;
}

void BM_ForestLod0(benchmark::State& state) {
  auto b = make_bench(static_cast<int>(state.range(0)), 256, 144);
  if (!b) {
    state.SkipWithError("no headless GL context or setup failed");
    return;
  }
  run(state, *b);
}
BENCHMARK(BM_ForestLod0)->Arg(10)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

void BM_ForestLod0_720p(benchmark::State& state) {
  auto b = make_bench(static_cast<int>(state.range(0)), 1280, 720);
  if (!b) {
    state.SkipWithError("no headless GL context or setup failed");
    return;
  }
  run(state, *b);
}
BENCHMARK(BM_ForestLod0_720p)->Arg(100)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

// Animation levels (seed table 5.5): arg 0 = level (0 static, 1 + trunk, 2 + branches, 3 + leaves),
// arg 1 = instances.
void BM_AnimationLevel(benchmark::State& state) {
  auto b = make_bench(static_cast<int>(state.range(1)), 256, 144);
  if (!b) {
    state.SkipWithError("no headless GL context or setup failed");
    return;
  }
  b->forest.settings().animation_level = static_cast<AnimationLevel>(state.range(0));
  run(state, *b);
}
BENCHMARK(BM_AnimationLevel)
    ->ArgsProduct({{0, 1, 2, 3}, {10, 25, 50, 100}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(1.0);

}  // namespace

// Image-based LOD costs and errors on the headless context (llvmpipe on the CI machine).
//
// BM_Level: frame time of the opaque pass for 10..10,000 broadleaf trees forced to LOD0, LOD1,
//   LOD2, or left to the default selection (mixed), after the seed's tables 5.1-5.4 (its FOREST
//   scene: a grid seen from above its edge). Time = render::FrameProfiler in synchronous mode
//   (glFinish around the scope, wall time; llvmpipe's timestamps underestimate, queries.hpp).
// BM_Sweep: image error of the default view against the all-LOD0 picture (PSNR, SSIM) and its
//   time, sweeping v1 and v2 (the seed's "LOD transition thresholds", §3.4), at ground level.
// BM_Update: CPU cost of Forest::update (LOD selection, culling, sorting, instance records) for
//   up to 100,000 instances.
#include <sylva/core/image_metrics.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/gl_context.hpp>
#include <sylva/render/lighting_uniforms.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/vegetation/forest.hpp>

#include "support/bench_view.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>

namespace {

using namespace sylva;
using namespace sylva::vegetation;

using bench::BenchView;

struct Bench : BenchView {
  LodSettings defaults;  // the shipped thresholds (the shared forest's are overwritten per run)
};

// One forest per process (the bake is cached on disk as well).
Forest* shared_forest() {
  static std::unique_ptr<Forest> f = []() -> std::unique_ptr<Forest> {
    if (bench::gl_context() == nullptr) return nullptr;
    Result<Forest> r = Forest::create();
    if (!r.ok()) return nullptr;
    auto forest = std::make_unique<Forest>(std::move(r).value());
    forest->settings().receive_shadows = false;
    if (!forest->add_preset(SpeciesPreset::kBroadleaf, 1, 128).ok()) return nullptr;
    return forest;
  }();
  return f.get();
}

std::vector<TreeInstance> grid(int n, double spacing) {
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  std::vector<TreeInstance> trees;
  for (int i = 0; i < n; ++i) {
    TreeInstance t;
    t.position = {(i % side) * spacing, 0.0, -(i / side) * spacing};
    t.yaw = 0.7f * static_cast<float>(i);
    t.time_offset = static_cast<float>(i % 97);
    trees.push_back(t);
  }
  return trees;
}

void force(Forest& f, int mode, const LodSettings& defaults) {
  LodSettings& l = f.settings().lod;
  l = defaults;
  if (mode == 0) l.enabled = false;
  if (mode == 1) {
    l.v1 = 0.0f;
    l.v2 = 1.0e7f;
    l.band = 0.0f;
  }
  if (mode == 2) {
    l.v1 = 0.0f;
    l.v2 = 0.0f;
    l.band = 0.0f;
  }
}

struct Frame {
  double sync_ms = 0.0;
  render::PassStats stats;
  Image picture;
};

Frame render_frame(Bench& b, Forest& f, double time, bool read) {
  static render::FrameProfiler profiler = [] {
    render::FrameProfiler p;
    p.set_synchronous(true);
    return p;
  }();
  render::apply_reversed_z_state();
  render::FrameContext ctx{b.camera, time, 0.05f, b.wind, b.lighting, b.target.size(), profiler.frame() + 1};
  f.update(ctx);
  b.target.bind();
  b.target.clear({0.6f, 0.75f, 0.95f, 1.0f});
  b.lighting_ubo.update(b.lighting, b.camera.position().y, time);
  b.lighting_ubo.bind();
  Frame out;
  profiler.begin_frame();
  profiler.begin("trees", false);
  f.draw(render::Pass::kOpaque, ctx, out.stats);
  profiler.end("trees");
  profiler.end_frame();
  if (auto s = profiler.flush()) out.sync_ms = s->passes["trees"].sync_ms;
  if (read) out.picture = render::read_color(b.target).value();
  return out;
}

std::unique_ptr<Bench> make_bench(int width, int height) {
  Forest* f = shared_forest();
  if (f == nullptr) return nullptr;
  auto b = std::make_unique<Bench>();
  if (!bench::init_view(*b, width, height)) return nullptr;
  return b;
}

// arg 0: mode (0 LOD0, 1 LOD1, 2 LOD2, 3 mixed), arg 1: trees.
void BM_Level(benchmark::State& state) {
  auto b = make_bench(256, 144);
  Forest* f = shared_forest();
  if (!b || f == nullptr) {
    state.SkipWithError("no headless GL context or setup failed");
    return;
  }
  const int mode = static_cast<int>(state.range(0));
  const int n = static_cast<int>(state.range(1));
  force(*f, mode, b->defaults);
  if (!f->set_instances(0, grid(n, 12.0)).ok()) {
    state.SkipWithError("instances");
    return;
  }
  // The seed's FOREST view: the grid from above its near edge, every tree in view.
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  const double extent = (side - 1) * 12.0;
  b->camera.set_position({0.5 * extent, 30.0 + 0.3 * extent, 25.0});
  b->camera.look_at({0.5 * extent, 0.0, -0.55 * extent});
  b->camera.perspective().fov_y = 1.1f;
  double ms = 0.0;
  std::uint64_t frame = 0;
  Frame last;
  for (auto _ : state) {
    last = render_frame(*b, *f, 0.05 * static_cast<double>(++frame), false);
    ms += last.sync_ms;
  }
  state.counters["sync_ms"] = ms / static_cast<double>(state.iterations());
  state.counters["trees"] = static_cast<double>(f->stats().visible);
  state.counters["lod0"] = static_cast<double>(f->stats().lod[0]);
  state.counters["lod1"] = static_cast<double>(f->stats().lod[1]);
  state.counters["lod2"] = static_cast<double>(f->stats().lod[2]);
  state.counters["triangles"] = static_cast<double>(last.stats.triangles);
  state.counters["update_cpu_ms"] = f->stats().update_cpu_ms;
}
BENCHMARK(BM_Level)
    ->ArgsProduct({{1, 2, 3}, {10, 100, 1000, 10000}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3);
// LOD0 is ~13 ms per tree on llvmpipe: 10,000 would take minutes per frame.
BENCHMARK(BM_Level)->ArgsProduct({{0}, {10, 100, 1000}})->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

// arg 0: v1 [m], arg 1: v2 [m]. 225 trees 9 m apart seen from 2 m above the ground at their edge,
// so distances run from 5 to 190 m.
void BM_Sweep(benchmark::State& state) {
  auto b = make_bench(256, 144);
  Forest* f = shared_forest();
  if (!b || f == nullptr) {
    state.SkipWithError("no headless GL context or setup failed");
    return;
  }
  std::vector<TreeInstance> trees = grid(225, 9.0);
  if (!f->set_instances(0, trees).ok()) {
    state.SkipWithError("instances");
    return;
  }
  b->camera.set_position({-8.0, 4.0, 12.0});
  b->camera.look_at({60.0, 5.0, -90.0});
  b->camera.perspective().fov_y = 0.9f;
  const double time = 4.0;
  static std::map<int, Frame> reference;  // all LOD0, computed once
  if (reference.find(0) == reference.end()) {
    force(*f, 0, b->defaults);
    reference[0] = render_frame(*b, *f, time, true);
  }
  f->settings().lod = b->defaults;
  f->settings().lod.v1 = static_cast<float>(state.range(0));
  f->settings().lod.v2 = static_cast<float>(state.range(1));
  if (!f->set_instances(0, trees).ok()) return;  // fresh LOD state
  double ms = 0.0;
  Frame last;
  for (auto _ : state) {
    last = render_frame(*b, *f, time, true);
    ms += last.sync_ms;
  }
  const Image& ref = reference[0].picture;
  state.counters["sync_ms"] = ms / static_cast<double>(state.iterations());
  state.counters["lod0_ms"] = reference[0].sync_ms;
  state.counters["psnr_db"] = psnr(ref, last.picture).value();
  state.counters["ssim"] = ssim(ref, last.picture).value().mean;
  state.counters["lod0"] = static_cast<double>(f->stats().lod[0]);
  state.counters["lod1"] = static_cast<double>(f->stats().lod[1]);
  state.counters["lod2"] = static_cast<double>(f->stats().lod[2]);
  state.counters["triangles"] = static_cast<double>(last.stats.triangles);
}
BENCHMARK(BM_Sweep)
    ->Args({10, 25})
    ->Args({10, 60})
    ->Args({25, 60})
    ->Args({25, 110})
    ->Args({45, 110})
    ->Args({45, 200})
    ->Args({70, 160})
    ->Args({100, 300})
    ->Args({1000, 1000})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(2);

// CPU side only: Forest::update for n instances spread over a 3 km square, camera inside.
void BM_Update(benchmark::State& state) {
  auto b = make_bench(1280, 720);
  Forest* f = shared_forest();
  if (!b || f == nullptr) {
    state.SkipWithError("no headless GL context or setup failed");
    return;
  }
  f->settings().lod = b->defaults;
  const int n = static_cast<int>(state.range(0));
  std::vector<TreeInstance> trees;
  std::uint32_t h = 12345u;
  for (int i = 0; i < n; ++i) {
    TreeInstance t;
    h = h * 1664525u + 1013904223u;
    const double x = static_cast<double>((h >> 8) % 3000u) - 1500.0;
    h = h * 1664525u + 1013904223u;
    const double z = static_cast<double>((h >> 8) % 3000u) - 1500.0;
    t.position = {x, 0.0, z};
    t.yaw = 0.3f * static_cast<float>(i);
    trees.push_back(t);
  }
  if (!f->set_instances(0, trees).ok()) return;
  b->camera.set_position({0.0, 10.0, 0.0});
  b->camera.look_at({100.0, 5.0, -100.0});
  b->camera.perspective().fov_y = 1.0f;
  std::uint64_t frame = 0;
  double select = 0.0, total = 0.0;
  for (auto _ : state) {
    render::FrameContext ctx{b->camera, 0.05 * static_cast<double>(++frame), 0.05f, b->wind, b->lighting, {1280, 720}, frame};
    f->update(ctx);
    select += f->stats().select_cpu_ms;
    total += f->stats().update_cpu_ms;
  }
  const auto it = static_cast<double>(state.iterations());
  state.counters["select_ms"] = select / it;
  state.counters["update_ms"] = total / it;
  state.counters["visible"] = static_cast<double>(f->stats().visible);
  state.counters["lod0"] = static_cast<double>(f->stats().lod[0]);
  state.counters["lod1"] = static_cast<double>(f->stats().lod[1]);
  state.counters["lod2"] = static_cast<double>(f->stats().lod[2]);
}
BENCHMARK(BM_Update)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(0.5);

}  // namespace

// GPU frame of the grass module on the headless context (llvmpipe here): blades considered,
// drawn and triangles per frame, GPU ms of physics / culling / drawing, culling shares, against
// the blade count (10k .. 2M). One iteration = one frame (update + draw + glFinish).
#include <sylva/core/log.hpp>
#include <sylva/grass/generator.hpp>
#include <sylva/grass/grass_field.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/gl_context.hpp>
#include <sylva/render/lighting_uniforms.hpp>

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

namespace {

using namespace sylva;
using namespace sylva::grass;

render::GlContext* context() {
  static std::unique_ptr<render::GlContext> ctx = [] {
    auto c = render::GlContext::create_headless({.debug = false});
    if (!c) {
      std::fprintf(stderr, "no GL context: %s\n", c.error().describe().c_str());
      return std::unique_ptr<render::GlContext>();
    }
    return std::make_unique<render::GlContext>(std::move(*c));
  }();
  return ctx.get();
}

void BM_GrassFrame(benchmark::State& state) {
  if (!context()) {
    state.SkipWithError("no headless GL context");
    return;
  }
  context()->make_current();
  const auto blades = static_cast<double>(state.range(0));  // requested blade count
  const bool simulate = state.range(1) != 0;
  // A 100 m x 100 m meadow; the density gives the requested blade count. One GrassField holds at
  // most ~1.39M blades (96 B each in one storage buffer of GL_MAX_SHADER_STORAGE_BLOCK_SIZE =
  // 128 MB on llvmpipe), so larger meadows are split into x strips; placement is world-anchored,
  // so the strips hold exactly the blades of the whole meadow.
  GrassFieldSettings fs;
  fs.density = static_cast<float>(blades / 1.0e4);
  HeightField ground(101, 101, 1.0);
  const int strips = static_cast<int>(std::ceil(blades / 1.2e6));
  GrassRenderSettings rs;
  rs.simulate = simulate;
  std::vector<GrassField> fields;
  for (int k = 0; k < strips; ++k) {
    const Rect strip{{100.0 * k / strips, 0.0}, {100.0 * (k + 1) / strips, 100.0}};
    auto set = generate_blades(fs, BladeSettings{}, GrassMaps::uniform(strip), ground, {50, 0, 50});
    auto field = GrassField::create(std::move(*set), rs);
    if (!field) {
      state.SkipWithError(field.error().message.c_str());
      return;
    }
    fields.push_back(std::move(*field));
  }
  render::FramebufferDesc desc;
  desc.width = 512;
  desc.height = 288;
  auto target = render::Framebuffer::create(desc).value();
  auto lighting = render::LightingUniforms::create();
  render::Lighting light;
  render::apply_reversed_z_state();
  render::Camera camera;
  camera.set_aspect(desc.width, desc.height);
  camera.set_position({45.0, 1.7, 55.0});
  camera.look_at({60.0, 0.3, 40.0});
  WindField wind;
  double t = 0.0;
  double update_ms = 0.0, draw_ms = 0.0;
  std::uint64_t prims = 0;
  using Clock = std::chrono::steady_clock;
  auto ms = [](Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
  for (auto _ : state) {
    t += 1.0 / 60.0;
    target.bind();
    target.clear({0.3f, 0.25f, 0.2f, 1.0f});
    lighting.update(light, camera.position().y, t);
    lighting.bind();
    glFinish();
    // llvmpipe runs "GPU" work on the CPU threads and its timer queries do not bracket that work
    // reliably, so each phase is timed on the wall clock between glFinish calls.
    const auto t0 = Clock::now();
    for (GrassField& f : fields) f.update(camera, target.size(), t, 1.0f / 60.0f, wind);
    glFinish();
    const auto t1 = Clock::now();
    target.bind();
    for (GrassField& f : fields) f.draw_blades(camera);
    glFinish();
    const auto t2 = Clock::now();
    update_ms += ms(t0, t1);
    draw_ms += ms(t1, t2);
    prims = 0;
    for (GrassField& f : fields)
      if (auto g = f.gpu_times(true)) prims += g->primitives;
  }
  std::uint64_t considered = 0, in_culled_tiles = 0, drawn = 0, frustum = 0, distance = 0, orient = 0, total = 0;
  for (const GrassField& f : fields) {
    const GrassFrameStats st = f.read_frame_stats();
    considered += st.counts.considered;
    in_culled_tiles += st.blades_in_culled_tiles;
    drawn += st.counts.visible;
    frustum += st.counts.frustum;
    distance += st.counts.distance;
    orient += st.counts.orientation;
    total += f.blade_count();
  }
  const double all = static_cast<double>(total);
  const double iters = static_cast<double>(state.iterations());
  state.counters["blades"] = all;
  state.counters["considered"] = static_cast<double>(considered);
  state.counters["drawn"] = static_cast<double>(drawn);
  state.counters["triangles"] = static_cast<double>(prims);
  state.counters["sh_tile"] = static_cast<double>(in_culled_tiles) / all;
  state.counters["sh_frustum"] = static_cast<double>(frustum) / all;
  state.counters["sh_distance"] = static_cast<double>(distance) / all;
  state.counters["sh_orient"] = static_cast<double>(orient) / all;
  state.counters["update_ms"] = update_ms / iters;
  state.counters["draw_ms"] = draw_ms / iters;
  state.counters["fields"] = static_cast<double>(strips);
}
BENCHMARK(BM_GrassFrame)
    ->ArgsProduct({{10000, 100000, 500000, 1000000, 2000000}, {1}})
    ->Args({1000000, 0})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(6);

}  // namespace

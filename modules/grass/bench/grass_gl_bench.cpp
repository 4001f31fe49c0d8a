// GPU frame of the grass module on the headless context (llvmpipe here): blades considered,
// drawn and triangles per frame, GPU ms of physics / culling / drawing, culling shares, against
// the blade count (10k .. 2M). One iteration = one frame (update + draw + glFinish).
#include <sylva/core/image_metrics.hpp>
#include <sylva/core/log.hpp>
#include <sylva/grass/far_field.hpp>
#include <sylva/grass/generator.hpp>
#include <sylva/grass/grass_field.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/gl_context.hpp>
#include <sylva/render/lighting_uniforms.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/shadow_maps.hpp>

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
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
  const bool overview = state.range(2) != 0;
  // A 100 m x 100 m meadow; the density gives the requested blade count. One GrassField holds
  // any count: it splits its blades into storage buffers of GL_MAX_SHADER_STORAGE_BLOCK_SIZE
  // (128 MB = 1.39 M blades on llvmpipe) by itself.
  GrassFieldSettings fs;
  fs.density = static_cast<float>(blades / 1.0e4);
  HeightField ground(101, 101, 1.0);
  GrassRenderSettings rs;
  rs.simulate = simulate;
  if (overview) rs.cull.near_distance = 150.0f;  // every tile within reach: considered = all blades
  std::vector<GrassField> fields;
  {
    auto set = generate_blades(fs, BladeSettings{}, GrassMaps::uniform({{0.0, 0.0}, {100.0, 100.0}}), ground, {50, 0, 50});
    if (!set) {
      state.SkipWithError(set.error().message.c_str());
      return;
    }
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
  if (overview) {
    // Above the meadow looking down at all of it (the whole field is in the frustum).
    camera.perspective().fov_y = 1.75f;
    camera.set_position({50.0, 45.0, 110.0});
    camera.look_at({50.0, 0.0, 48.0});
  } else {
    // A walker at eye height looking across the meadow: the typical view.
    camera.set_position({45.0, 1.7, 55.0});
    camera.look_at({60.0, 0.3, 40.0});
  }
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
  state.counters["chunks"] = static_cast<double>(fields.front().chunk_count());
}
// Args: blades, physics on, view (0 walker, 1 overview where every blade is considered).
BENCHMARK(BM_GrassFrame)
    ->ArgsProduct({{10000, 100000, 500000, 1000000, 2000000}, {1}, {0}})
    ->Args({1000000, 0, 0})
    ->ArgsProduct({{10000, 100000, 1000000, 2000000}, {1}, {1}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(6);

// Shadow pass: the walker view, 3 cascades of 2048^2 over 150 m (render core defaults except
// the resolution), blades casting into the nearest 2 within shadow_distance. Args: blades,
// grass casts (0 = the pass without grass).
void BM_GrassShadowPass(benchmark::State& state) {
  if (!context()) {
    state.SkipWithError("no headless GL context");
    return;
  }
  context()->make_current();
  GrassFieldSettings fs;
  fs.density = static_cast<float>(static_cast<double>(state.range(0)) / 1.0e4);
  HeightField ground(101, 101, 1.0);
  auto set = generate_blades(fs, BladeSettings{}, GrassMaps::uniform({{0.0, 0.0}, {100.0, 100.0}}), ground, {50, 0, 50});
  GrassRenderSettings rs;
  rs.simulate = false;
  rs.cast_shadows = state.range(1) != 0;  // 0: the shadow pass without grass (its fixed cost)
  auto field = GrassField::create(std::move(*set), rs);
  if (!field) {
    state.SkipWithError(field.error().message.c_str());
    return;
  }
  render::ShadowSettings ss;
  ss.resolution = 2048;
  auto maps = render::ShadowMaps::create(ss);
  if (!maps) {
    state.SkipWithError(maps.error().message.c_str());
    return;
  }
  render::Camera camera;
  camera.set_aspect(512, 288);
  camera.set_position({45.0, 1.7, 55.0});
  camera.look_at({60.0, 0.3, 40.0});
  const WindField wind;
  render::Lighting light;
  const render::FrameContext frame{camera, 0.0, 0.0f, wind, light, {512, 288}, 1};
  render::CallbackShadowCaster caster([&](const render::ShadowCasterContext& c) { field->draw(render::Pass::kShadow, frame, *c.stats); });
  maps->add_caster(&caster);
  field->update(frame);
  double total_ms = 0.0;
  for (auto _ : state) {
    glFinish();
    const auto t0 = std::chrono::steady_clock::now();
    (void)maps->render(camera, glm::normalize(glm::vec3(0.4f, 0.8f, 0.3f)), &frame, nullptr);
    glFinish();
    total_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }
  maps->remove_caster(&caster);
  state.counters["shadow_ms"] = total_ms / static_cast<double>(state.iterations());
  state.counters["considered_per_frame"] = static_cast<double>(field->shadow_stats().considered) / static_cast<double>(state.iterations());
  state.counters["cascades_drawn"] = static_cast<double>(field->shadow_stats().cascades) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_GrassShadowPass)->Args({100000, 1})->Args({1000000, 1})->Args({1000000, 0})->Unit(benchmark::kMillisecond)->Iterations(3);

// Image error against time: the walker view of a 100 m meadow at 40 blades/m^2 (physics off, so
// every picture shows the same poses), one LOD setting changed at a time, PSNR against a
// reference with blades to 120 m, no thinning, 1 px per segment and up to 16 segments.
// Args: kind (0 near_distance [m] with thinning from near/4 and the reference tessellation,
// 1 pixels_per_segment [px] with the reference distances, 2 reference), value.
struct LodScene {
  std::unique_ptr<GrassField> field;
  render::Framebuffer target;
  render::LightingUniforms lighting;
  render::Lighting light;
  render::Camera camera;
  WindField wind;
  Image reference;

  static LodScene& get() {
    static LodScene scene = [] {
      LodScene s;
      GrassFieldSettings fs;
      fs.density = 40.0f;
      HeightField ground(101, 101, 1.0);
      auto set = generate_blades(fs, BladeSettings{}, GrassMaps::uniform({{0.0, 0.0}, {100.0, 100.0}}), ground, {50, 0, 50});
      s.field = std::make_unique<GrassField>(GrassField::create(std::move(*set), {}).value());
      render::FramebufferDesc desc;
      desc.width = 512;
      desc.height = 288;
      s.target = render::Framebuffer::create(desc).value();
      s.lighting = render::LightingUniforms::create();
      s.light.fog_density = 0.0f;
      s.camera.set_aspect(desc.width, desc.height);
      s.camera.set_position({45.0, 1.7, 55.0});
      s.camera.look_at({60.0, 0.3, 40.0});
      s.reference = s.render(reference_settings(), nullptr);
      return s;
    }();
    return scene;
  }
  static GrassRenderSettings reference_settings() {
    GrassRenderSettings rs;
    rs.simulate = false;
    rs.cull.near_distance = 120.0f;
    rs.cull.distance_thinning = false;
    rs.cull.pixels_per_segment = 1.0f;
    rs.cull.max_tess_level = 16.0f;
    return rs;
  }
  Image render(const GrassRenderSettings& rs, double* ms) {
    field->settings() = rs;
    render::apply_reversed_z_state();
    target.bind();
    target.clear({0.3f, 0.25f, 0.2f, 1.0f});
    lighting.update(light, camera.position().y, 0.0);
    lighting.bind();
    glFinish();
    const auto t0 = std::chrono::steady_clock::now();
    field->update(camera, target.size(), 0.0, 0.0f, wind);
    target.bind();
    field->draw_blades(camera);
    glFinish();
    if (ms) *ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return render::read_color(target).value();
  }
};

void BM_GrassLodError(benchmark::State& state) {
  if (!context()) {
    state.SkipWithError("no headless GL context");
    return;
  }
  context()->make_current();
  LodScene& scene = LodScene::get();
  GrassRenderSettings rs = LodScene::reference_settings();
  const auto value = static_cast<float>(state.range(1));
  if (state.range(0) == 0) {
    rs.cull.near_distance = value;
    rs.cull.distance_thinning = true;
    rs.cull.thinning_start = value / 4.0f;
  } else if (state.range(0) == 1) {
    rs.cull.pixels_per_segment = value;
  }
  double total_ms = 0.0;
  Image img;
  for (auto _ : state) {
    double ms = 0.0;
    img = scene.render(rs, &ms);
    total_ms += ms;
  }
  const GrassFrameStats st = scene.field->read_frame_stats();
  state.counters["frame_ms"] = total_ms / static_cast<double>(state.iterations());
  state.counters["psnr_db"] = std::min(psnr(scene.reference, img).value_or(0.0), 99.0);
  state.counters["drawn"] = static_cast<double>(st.counts.visible);
  state.counters["segments"] = static_cast<double>(st.counts.segments);
}
BENCHMARK(BM_GrassLodError)
    ->Args({2, 0})
    ->ArgsProduct({{0}, {15, 30, 50, 80, 120}})
    ->ArgsProduct({{1}, {2, 3, 4, 6, 8, 16}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

// Map edits (issue 16): what a dab on the default meadow costs (60 x 80 m at 100 blades/m^2 =
// 480k blades, 4 m tiles, the meadow's far field: clumps 150 m and ground layer 800 m beyond the
// field, on a 1.6 km ground of 257^2 samples). Args: 0 = full regeneration (maps, every tile,
// GrassField::create, FarField::create: what every dab cost before), 1 = the blades of a dab
// (regenerate_tiles of a 1 m-radius dab's area plus GrassField::set_blades), 2 = the far field
// alone (FarField::create), 3 = the dab's blades on the CPU only (regenerate_tiles), 4 = the whole
// dab: its blades as 1 plus the far field's tile-local update (FarField::update_region), what the
// scene's grass module does per dab now, 5 = the far field's update alone, 6 = the far field's
// update after a ground dab instead (the 3 x 3 ground samples around the dab up and down by 1 m).
// One iteration = one dab with glFinish; the dab alternates between density 0.2 and 1 so that
// every iteration changes the maps.
void BM_GrassMapEdit(benchmark::State& state) {
  if (!context()) {
    state.SkipWithError("no headless GL context");
    return;
  }
  context()->make_current();
  const int mode = static_cast<int>(state.range(0));
  GrassFieldSettings fs;
  fs.density = 100.0f;
  BladeSettings bs;
  FarFieldSettings far;
  far.clump_margin = 150.0f;
  far.ground_margin = 800.0f;
  far.ground_spacing = 6.25f;
  HeightField ground(257, 257, 6.25, {-800.0, -800.0});
  const Rect rect{{-30.0, -40.0}, {30.0, 40.0}};
  Image density(96, 128, 1);  // the scene's map_resolution 128 along the longer side
  for (float& v : density.data()) v = 1.0f;
  const glm::dvec3 origin(0.0, 0.0, 0.0);
  auto maps = GrassMaps::from_images(rect, &density, nullptr, nullptr);
  auto set = generate_blades(fs, bs, *maps, ground, origin);
  auto field = GrassField::create(*set);
  if (!maps || !set || !field) {
    state.SkipWithError("setup failed");
    return;
  }
  // The dab: 1 m radius at (3, -7), the texels it writes grown by one texel (changed_world_area).
  const glm::dvec2 texel = rect.size() / glm::dvec2(96.0, 128.0);
  const Rect area{glm::dvec2(3.0, -7.0) - (1.0 + 2.0 * texel.x), glm::dvec2(3.0, -7.0) + (1.0 + 2.0 * texel.x)};
  auto far_field = FarField::create(fs, bs, *maps, ground, origin, far);
  if (!far_field) {
    state.SkipWithError(far_field.error().message.c_str());
    return;
  }
  std::size_t blades = 0, iteration = 0;
  for (auto _ : state) {
    for (int j = 0; j < 128; ++j)
      for (int i = 0; i < 96; ++i) {
        const glm::dvec2 p = rect.min + (glm::dvec2(i, j) + 0.5) * texel;
        if (glm::length(p - glm::dvec2(3.0, -7.0)) < 1.0) density.at(i, j) = iteration % 2 == 0 ? 0.2f : 1.0f;
      }
    ++iteration;
    auto m = GrassMaps::from_images(rect, &density, nullptr, nullptr);
    if (mode == 0) {
      auto s = generate_blades(fs, bs, *m, ground, origin);
      auto f = GrassField::create(std::move(*s));
      auto ff = FarField::create(fs, bs, *m, ground, origin, far);
      if (!f || !ff) state.SkipWithError("regeneration failed");
      blades = f->blade_count();
    } else if (mode == 1 || mode == 3 || mode == 4) {
      auto first = regenerate_tiles(*set, fs, bs, *m, ground, area);
      if (!first) state.SkipWithError(first.error().message.c_str());
      if (mode != 3 && !field->set_blades(*set).ok()) state.SkipWithError("set_blades failed");
      if (mode == 4 && !far_field->update_region(fs, bs, *m, ground, {&area, 1}, false).ok()) state.SkipWithError("update_region failed");
      blades = set->blades.size();
    } else if (mode == 6) {
      const int ci = static_cast<int>((3.0 + 800.0) / 6.25), cj = static_cast<int>((-7.0 + 800.0) / 6.25);
      for (int j = cj - 1; j <= cj + 1; ++j)
        for (int i = ci - 1; i <= ci + 1; ++i) ground.sample(i, j) += iteration % 2 == 0 ? 1.0f : -1.0f;
      const Rect ground_area{{-800.0 + 6.25 * (ci - 2), -800.0 + 6.25 * (cj - 2)}, {-800.0 + 6.25 * (ci + 2), -800.0 + 6.25 * (cj + 2)}};
      if (!far_field->update_region(fs, bs, *m, ground, {&ground_area, 1}, true).ok()) state.SkipWithError("update_region failed");
    } else if (mode == 5) {
      if (!far_field->update_region(fs, bs, *m, ground, {&area, 1}, false).ok()) state.SkipWithError("update_region failed");
    } else {
      auto ff = FarField::create(fs, bs, *m, ground, origin, far);
      if (!ff) state.SkipWithError(ff.error().message.c_str());
    }
    glFinish();
  }
  state.counters["blades"] = static_cast<double>(blades);
}
BENCHMARK(BM_GrassMapEdit)->DenseRange(0, 6)->Unit(benchmark::kMillisecond)->Iterations(5);

}  // namespace

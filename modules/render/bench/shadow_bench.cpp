// Shadow pass cost (issue 7 benchmark): ShadowMaps::render for 1/2/3/4 cascades at 1024² and
// 2048² on a fixed scene (a 120 m ground plane and 400 boxes of 1-4 m, 4 802 triangles, drawn by
// one caster per cascade), sun at 35 deg. Each iteration ends with glFinish, so wall time is the
// real cost on llvmpipe; gpu_ms from timestamp queries is reported beside it (an underestimate
// on llvmpipe, see the README's known limits).
#include <sylva/render/buffer.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/gl_context.hpp>
#include <sylva/render/lighting.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/shadow_maps.hpp>
#include <sylva/render/vertex_array.hpp>

#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

namespace {

using namespace sylva::render;

GlContext* context() {
  static std::unique_ptr<GlContext> ctx = [] {
    auto created = GlContext::create_headless({.debug = false});
    return created.ok() ? std::make_unique<GlContext>(std::move(created).value()) : nullptr;
  }();
  return ctx.get();
}

void add_box(std::vector<glm::vec3>& v, glm::vec3 lo, glm::vec3 hi) {
  const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                          {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};
  for (const auto& f : faces) {
    for (int i : {f[0], f[1], f[2], f[0], f[2], f[3]}) v.push_back(c[i]);
  }
}

struct BenchScene {
  Program depth;
  Buffer vbo;
  VertexArray vao;
  GLsizei count = 0;
};

bool make_scene(BenchScene& s) {
  register_shader_source("rbench/shadow_depth.vert", R"(#version 450 core
layout(location = 0) in vec3 a_pos;
uniform mat4 u_mvp;
void main() { gl_Position = u_mvp * vec4(a_pos, 1.0); }
)");
  register_shader_source("rbench/shadow_depth.frag", "#version 450 core\nvoid main() {}\n");
  auto program = Program::create({"rbench/shadow_depth.vert", "rbench/shadow_depth.frag"});
  if (!program.ok()) return false;
  s.depth = std::move(*program);
  std::vector<glm::vec3> v = {{-60, 0, -60}, {-60, 0, 60}, {60, 0, 60}, {-60, 0, -60}, {60, 0, 60}, {60, 0, -60}};
  for (int z = 0; z < 20; ++z) {
    for (int x = 0; x < 20; ++x) {
      const float size = 1.0f + static_cast<float>((x * 7 + z * 13) % 4);
      const glm::vec3 lo(-50.0f + 5.0f * x, 0.0f, -50.0f + 5.0f * z);
      add_box(v, lo, lo + glm::vec3(size * 0.5f, size, size * 0.5f));
    }
  }
  s.count = static_cast<GLsizei>(v.size());
  s.vbo = Buffer::immutable(std::span<const glm::vec3>(v));
  s.vao = VertexArray::create();
  s.vao.attribute(0, 0, 3, GL_FLOAT, 0);
  s.vao.vertex_buffer(0, s.vbo, sizeof(glm::vec3));
  return true;
}

void BM_ShadowPass(benchmark::State& state) {
  if (context() == nullptr) {
    state.SkipWithError("no headless GL context");
    return;
  }
  BenchScene scene;
  if (!make_scene(scene)) {
    state.SkipWithError("shader build failed");
    return;
  }
  ShadowSettings settings;
  settings.cascade_count = static_cast<int>(state.range(0));
  settings.resolution = static_cast<int>(state.range(1));
  settings.max_distance = 120.0f;
  auto maps = ShadowMaps::create(settings);
  if (!maps.ok()) {
    state.SkipWithError(maps.error().message.c_str());
    return;
  }
  CallbackShadowCaster caster([&scene](const ShadowCasterContext& ctx) {
    scene.depth.use();
    scene.depth.set("u_mvp", ctx.relative_view_projection * ctx.camera->relative_model(glm::dvec3(0.0)));
    scene.vao.bind();
    glDrawArrays(GL_TRIANGLES, 0, scene.count);
  });
  maps->add_caster(&caster);
  Camera cam;
  cam.set_aspect(1280, 720);
  cam.set_position({0.0, 15.0, 45.0});
  cam.look_at({0.0, 0.0, -10.0});
  apply_reversed_z_state();
  const glm::vec3 sun = sun_direction(0.6f, 0.61f);
  PassQuery query = PassQuery::create(true);
  double gpu_ms = 0.0;
  int polled = 0;
  std::uint64_t frame = 0;
  for (auto _ : state) {
    query.begin(++frame);
    const sylva::Status st = maps->render(cam, sun);
    query.end();
    glFinish();
    if (!st.ok()) {
      state.SkipWithError("render failed");
      return;
    }
    if (auto r = query.poll()) {
      gpu_ms += r->gpu_ms;
      ++polled;
    }
  }
  state.counters["gpu_ms"] = polled > 0 ? gpu_ms / polled : 0.0;
  state.counters["triangles"] = static_cast<double>(scene.count / 3 * settings.cascade_count);
}
BENCHMARK(BM_ShadowPass)
    ->ArgsProduct({{1, 2, 3, 4}, {1024, 2048}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(0.5);

}  // namespace

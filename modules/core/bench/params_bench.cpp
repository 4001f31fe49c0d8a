// Cost of the visit()-driven parameter operations on a settings tree of realistic size
// (three module sections, 24 parameters), to tell the editor (describe every frame?) and the
// player (--set, scene load) what they pay.

#include <sylva/core/params.hpp>
#include <sylva/core/params_json.hpp>

#include <benchmark/benchmark.h>

#include <array>
#include <string>

namespace {

enum class Criterion { kScreenSpace, kDistance };
constexpr std::array<sylva::EnumName<Criterion>, 2> enum_names(Criterion) {
  return {{{Criterion::kScreenSpace, "screen_space"}, {Criterion::kDistance, "distance"}}};
}

struct Lod {
  float max_pixel_error = 1.f;
  float morph_fraction = 0.25f;
  int leaf_dimension = 33;
  Criterion criterion = Criterion::kScreenSpace;
  template <class V> void visit(V& v) {
    v(max_pixel_error, "max_pixel_error", {.min = 0.05f, .max = 64.f, .unit = "px"});
    v(morph_fraction, "morph_fraction", {.min = 0.f, .max = 1.f});
    v(leaf_dimension, "leaf_dimension", {.min = 3, .max = 1025, .rebuild = sylva::Rebuild::kOffline});
    v(criterion, "criterion");
  }
};

struct Terrain {
  std::string height_map = "maps/height.png";
  double world_scale = 1.0;
  float height_scale = 500.f;
  glm::vec3 sun_dir{0.f, 1.f, 0.f};
  bool skirts = true;
  std::uint32_t seed = 1;
  Lod lod;
  template <class V> void visit(V& v) {
    v(height_map, "height_map");
    v(world_scale, "world_scale", {.min = 1e-3, .max = 1e4, .unit = "m"});
    v(height_scale, "height_scale", {.min = 0.f, .max = 1e5f, .unit = "m"});
    v(sun_dir, "sun_dir", {.min = -1.f, .max = 1.f});
    v(skirts, "skirts");
    v(seed, "seed");
    v(lod, "lod");
  }
};

struct Grass {
  float density = 400.f, blade_height = 0.5f, blade_width = 0.02f, stiffness = 1.f, lod_near = 30.f, lod_far = 200.f;
  int max_blades = 1 << 20;
  template <class V> void visit(V& v) {
    v(density, "density", {.min = 0.f, .max = 1e5f});
    v(blade_height, "blade_height", {.min = 0.f, .max = 10.f});
    v(blade_width, "blade_width", {.min = 0.f, .max = 1.f});
    v(stiffness, "stiffness", {.min = 0.f, .max = 1e6f});
    v(lod_near, "lod_near", {.min = 0.f});
    v(lod_far, "lod_far", {.min = 0.f});
    v(max_blades, "max_blades", {.min = 0});
  }
};

struct Wind {
  glm::vec2 direction{1.f, 0.f};
  float strength = 3.f, gust_strength = 1.f, gust_period = 8.f, turbulence = 0.5f;
  template <class V> void visit(V& v) {
    v(direction, "direction");
    v(strength, "strength", {.min = 0.f, .max = 100.f, .unit = "m/s"});
    v(gust_strength, "gust_strength", {.min = 0.f, .max = 100.f});
    v(gust_period, "gust_period", {.min = 0.01f, .max = 1000.f, .unit = "s"});
    v(turbulence, "turbulence", {.min = 0.f, .max = 10.f});
  }
};

struct Settings {
  Terrain terrain;
  Grass grass;
  Wind wind;
  template <class V> void visit(V& v) {
    v(terrain, "terrain");
    v(grass, "grass");
    v(wind, "wind");
  }
};

void BM_Describe(benchmark::State& state) {
  Settings s;
  for (auto _ : state) benchmark::DoNotOptimize(sylva::describe_params(s));
  state.counters["params"] = static_cast<double>(sylva::describe_params(s).size());
}
BENCHMARK(BM_Describe);

void BM_SetParamByPath(benchmark::State& state) {
  Settings s;
  for (auto _ : state) benchmark::DoNotOptimize(sylva::set_param(s, "wind.gust_period", "12.5").ok());
}
BENCHMARK(BM_SetParamByPath);

void BM_SetThroughDescriptor(benchmark::State& state) {
  Settings s;
  const auto d = *sylva::find_param(sylva::describe_params(s), "terrain.lod.max_pixel_error");
  for (auto _ : state) benchmark::DoNotOptimize(d.set_string("2.5").ok());
}
BENCHMARK(BM_SetThroughDescriptor);

void BM_Validate(benchmark::State& state) {
  Settings s;
  for (auto _ : state) benchmark::DoNotOptimize(sylva::validate_params(s).ok());
}
BENCHMARK(BM_Validate);

void BM_ToJson(benchmark::State& state) {
  Settings s;
  for (auto _ : state) benchmark::DoNotOptimize(sylva::params_to_json(s));
}
BENCHMARK(BM_ToJson);

void BM_FromJson(benchmark::State& state) {
  Settings s;
  const nlohmann::json j = sylva::params_to_json(s);
  std::vector<std::string> warnings;
  for (auto _ : state) benchmark::DoNotOptimize(sylva::params_from_json(s, j, warnings).ok());
}
BENCHMARK(BM_FromJson);

}  // namespace

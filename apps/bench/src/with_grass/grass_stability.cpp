// Grass stability cases for --stability from the public API of modules/grass: the CPU physics
// reference and the GL field (physics and culling compute shaders) under hurricane wind, 1 s
// frames, zero and huge stiffness, and a field far from the origin.
#include "stability.hpp"

#include <sylva/core/height_field.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/grass/generator.hpp>
#include <sylva/grass/grass_field.hpp>
#include <sylva/grass/maps.hpp>
#include <sylva/grass/physics.hpp>
#include <sylva/render/camera.hpp>

#include <fmt/format.h>

#include <cmath>

namespace sylva::bench {
namespace {

WindSettings hurricane() {
  WindSettings w;
  w.strength = 60.0f;
  w.gust_amplitude = 40.0f;
  w.turbulence_amplitude = 30.0f;
  w.turbulence_scale = 2.0f;
  return w;
}

struct BladeCheck {
  std::uint64_t non_finite = 0;
  float min_tip_height = INFINITY;
  float max_length_error = 0.0f;
};

BladeCheck check_all(const std::vector<grass::Blade>& blades) {
  BladeCheck c;
  for (const grass::Blade& b : blades) {
    const grass::BladeInvariants inv = grass::check_blade(b);
    if (!inv.finite) {
      ++c.non_finite;
      continue;
    }
    c.min_tip_height = std::min(c.min_tip_height, inv.tip_height);
    c.max_length_error = std::max(c.max_length_error, inv.length_error);
  }
  return c;
}

Result<grass::BladeSet> meadow(glm::dvec3 origin, float stiffness_min, float stiffness_max) {
  grass::GrassFieldSettings field;
  field.density = 60.0f;
  field.seed = 4;
  grass::BladeSettings blade;
  blade.stiffness_min = stiffness_min;
  blade.stiffness_max = stiffness_max;
  const grass::Rect rect{{origin.x - 6.0, origin.z - 6.0}, {origin.x + 6.0, origin.z + 6.0}};
  HeightField ground(33, 33, 0.5, {origin.x - 8.0, origin.z - 8.0});
  return grass::generate_blades(field, blade, grass::GrassMaps::uniform(rect), ground, origin);
}

StabilityOutcome judge(const BladeCheck& c, std::size_t blades, float length_bound) {
  StabilityOutcome o;
  o.nan_count = c.non_finite;
  o.passed = blades > 0 && c.non_finite == 0 && c.min_tip_height >= -1e-4f && c.max_length_error <= length_bound;
  o.detail = fmt::format("{} blades: lowest tip {:.4f} of its height above ground, largest length error {:.2e} "
                         "(allowed {:.0e})",
                         blades, c.min_tip_height, c.max_length_error, length_bound);
  return o;
}

StabilityOutcome cpu_hurricane_1s_steps(float stiffness_min, float stiffness_max) {
  auto set = meadow({0, 0, 0}, stiffness_min, stiffness_max);
  if (!set.ok()) return {false, 0, set.error().message};
  const WindField wind(hurricane());
  const grass::PhysicsSettings physics;
  double t = 0.0;
  for (float dt : {1.0f, 1.0f, 0.0f, 1e-6f, 1.0f, 0.25f, 1.0f}) {
    t += dt;
    grass::simulate_blades(set->blades, [&](const glm::vec3& p) { return wind.evaluate(glm::dvec3(p), t); }, dt,
                           physics);
  }
  return judge(check_all(set->blades), set->blades.size(), 1e-4f);
}

StabilityOutcome gpu_field(glm::dvec3 origin, const WindSettings& wind_settings, std::initializer_list<float> steps) {
  auto set = meadow(origin, 40.0f, 80.0f);
  if (!set.ok()) return {false, 0, set.error().message};
  const std::size_t n = set->blades.size();
  auto field = grass::GrassField::create(std::move(*set));
  if (!field.ok()) return {false, 0, field.error().message};
  const WindField wind(wind_settings);
  render::Camera camera;
  camera.set_position(origin + glm::dvec3(0.0, 3.0, 9.0));
  camera.set_yaw_pitch(0.0f, -0.3f);
  camera.set_aspect(128, 72);
  double t = 0.0;
  for (float dt : steps) {
    t += dt;
    field->update(camera, {128, 72}, t, dt, wind);
  }
  return judge(check_all(field->read_blades()), n, 1e-3f);
}

}  // namespace

void add_grass_stability_cases(std::vector<StabilityCase>& cases) {
  cases.push_back({"grass", "cpu_hurricane_1s_steps", "CPU physics, 100 m/s wind, 1 s steps (and 0 and 1e-6 s): no NaN, "
                   "tips never under the ground, blade length kept within 1e-4", false,
                   [] { return cpu_hurricane_1s_steps(40.0f, 80.0f); }});
  cases.push_back({"grass", "cpu_zero_and_huge_stiffness", "stiffness 0 and 1e6 1/s under hurricane wind at 1 s steps: "
                   "no NaN, tips above ground, length within 1e-4", false,
                   [] { return cpu_hurricane_1s_steps(0.0f, 1.0e6f); }});
  cases.push_back({"grass", "gpu_hurricane_1s_steps", "GL physics.comp with 100 m/s wind and 1 s frames: no NaN, tips "
                   "above ground, length within 1e-3", true,
                   [] { return gpu_field({0, 0, 0}, hurricane(), {1.0f, 1.0f, 0.0f, 1.0f, 0.5f}); }});
  cases.push_back({"grass", "gpu_field_1e6m_from_origin", "a field 1e6 m from the origin simulated on the GPU: no NaN, "
                   "tips above ground, length within 1e-3", true,
                   [] { return gpu_field({1e6, 20.0, -1e6}, WindSettings{}, {1.0f / 60, 1.0f / 60, 1.0f / 30}); }});
}

}  // namespace sylva::bench

// Sky renderer and the sky-derived lighting (sky.hpp). sky_radiance mirrors shaders/lib/sky.glsl.
#include <sylva/render/sky.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace sylva::render {
namespace {

glm::vec3 unit_sun(const Lighting& l) {
  const float len = glm::length(l.sun_direction);
  return len > 1.0e-6f && std::isfinite(len) ? l.sun_direction / len : glm::vec3(0.0f, 1.0f, 0.0f);
}

// The inputs a sky table depends on, compared bit for bit.
struct SkyKey {
  AtmosphereSettings atmosphere;
  glm::vec3 sun_direction{0.0f};
  glm::vec3 sun_top{0.0f};
};

bool same_key(const SkyKey& a, const SkyKey& b) {
  return std::memcmp(&a.atmosphere, &b.atmosphere, sizeof(AtmosphereSettings)) == 0 &&
         a.sun_direction == b.sun_direction && a.sun_top == b.sun_top;
}

}  // namespace

glm::vec3 sun_top_of_atmosphere(const Lighting& l) {
  const glm::vec3 t = atmosphere_transmittance(l.atmosphere, 0.0f, unit_sun(l));
  const glm::vec3 at_viewer = glm::max(l.sun_color * l.sun_intensity, glm::vec3(0.0f));
  return at_viewer / glm::max(t, glm::vec3(1.0e-4f));
}

const SkyTable& sky_table(const Lighting& l) {
  thread_local SkyKey key;
  thread_local SkyTable table;
  thread_local bool valid = false;
  SkyKey now{l.atmosphere, unit_sun(l), sun_top_of_atmosphere(l)};
  if (!valid || !same_key(key, now)) {
    table = compute_sky_table(now.atmosphere, now.sun_direction, now.sun_top);
    key = now;
    valid = true;
  }
  return table;
}

glm::vec3 sky_radiance(const Lighting& l, const glm::vec3& direction) {
  return sky_table_radiance(sky_table(l), l.atmosphere.mie_g, unit_sun(l), direction);
}

void derive_sky_lighting(Lighting& l, float ambient_scale) {
  const SkyTable& table = sky_table(l);
  const glm::vec3 sun = unit_sun(l);
  const float g = l.atmosphere.mie_g;
  l.ambient = sky_table_irradiance(table, g, sun) * std::max(ambient_scale, 0.0f);
  glm::vec3 horizon(0.0f);
  constexpr int kAzimuths = 16;
  for (int i = 0; i < kAzimuths; ++i) {
    const float az = (static_cast<float>(i) + 0.5f) / kAzimuths * 6.2831853f;
    horizon += sky_table_radiance(table, g, sun, {std::sin(az), 0.0f, -std::cos(az)});
  }
  l.horizon_color = horizon / static_cast<float>(kAzimuths);
  l.zenith_color = sky_table_radiance(table, g, sun, {0.0f, 1.0f, 0.0f});
  l.fog_color = l.horizon_color;
  // The ground under the sky reflects sun and sky light diffusely (radiance = albedo * light).
  const glm::vec3 sun_light = glm::max(l.sun_color * l.sun_intensity, glm::vec3(0.0f)) * std::max(sun.y, 0.0f);
  l.ground_color = std::clamp(l.atmosphere.ground_albedo, 0.0f, 1.0f) * (sun_light + l.ambient);
}

Result<SkyRenderer> SkyRenderer::create() {
  embedded::register_render_shaders();
  Result<Program> program = Program::create({"render/sky.vert", "render/sky.frag"});
  if (!program.ok()) return program.error();
  SkyRenderer sky;
  sky.program_ = std::move(program).value();
  sky.vao_ = VertexArray::create();
  sky.uniforms_ = LightingUniforms::create();
  return sky;
}

void SkyRenderer::draw(const Camera& camera, const Lighting& lighting, double time) {
  program_.reload_if_changed();
  uniforms_.update(lighting, camera.position().y, time);
  uniforms_.bind();
  program_.set("u_inv_view_projection", glm::inverse(camera.view_projection()));
  program_.use();
  vao_.bind();
  GLboolean depth_mask = GL_TRUE;
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask);
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_GEQUAL);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthFunc(GL_GREATER);
  glDepthMask(depth_mask);
}

}  // namespace sylva::render

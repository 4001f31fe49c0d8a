// Sky renderer and the sky-derived lighting (sky.hpp). sky_radiance mirrors shaders/lib/sky.glsl.
#include <sylva/render/sky.hpp>

#include <sylva/render/sky_dome.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>

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
  Result<Program> nadir = Program::create({"render/sky.vert", "render/sky_nadir.frag"});
  if (!nadir.ok()) return nadir.error();
  SkyRenderer sky;
  sky.program_ = std::move(program).value();
  sky.nadir_program_ = std::move(nadir).value();
  const SkyDomeMesh dome = build_sky_dome();
  sky.vertices_ = Buffer::immutable(std::span<const glm::vec3>(dome.directions));
  sky.indices_ = Buffer::immutable(std::span<const std::uint32_t>(dome.indices));
  sky.index_count_ = static_cast<int>(dome.indices.size());
  sky.nadir_cap_indices_ = dome.nadir_cap_indices;
  sky.vao_ = VertexArray::create();
  sky.vao_.attribute(0, 0, 3, GL_FLOAT, 0);
  sky.vao_.vertex_buffer(0, sky.vertices_, sizeof(glm::vec3));
  sky.vao_.index_buffer(sky.indices_);
  sky.uniforms_ = LightingUniforms::create();
  return sky;
}

void SkyRenderer::draw(const Camera& camera, const Lighting& lighting, double time) {
  program_.reload_if_changed();
  nadir_program_.reload_if_changed();
  uniforms_.update(lighting, camera.position().y, time);
  uniforms_.bind();
  program_.set("u_view_projection", camera.view_projection());
  nadir_program_.set("u_view_projection", camera.view_projection());
  vao_.bind();
  GLboolean depth_mask = GL_TRUE;
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask);
  const GLboolean cull = glIsEnabled(GL_CULL_FACE);
  const GLboolean clip = glIsEnabled(GL_CLIP_DISTANCE0);
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_GEQUAL);
  glDisable(GL_CULL_FACE);  // seen from inside
  glEnable(GL_CLIP_DISTANCE0);  // sky.vert: directions behind the camera
  nadir_program_.use();
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(nadir_cap_indices_), GL_UNSIGNED_INT, nullptr);
  program_.use();
  glDrawElements(GL_TRIANGLES, index_count_ - static_cast<GLsizei>(nadir_cap_indices_), GL_UNSIGNED_INT,
                 reinterpret_cast<const void*>(nadir_cap_indices_ * sizeof(std::uint32_t)));
  if (!clip) glDisable(GL_CLIP_DISTANCE0);
  if (cull) glEnable(GL_CULL_FACE);
  glDepthFunc(GL_GREATER);
  glDepthMask(depth_mask);
}

}  // namespace sylva::render

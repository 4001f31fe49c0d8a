#include "ground_scene.hpp"

#include <sylva/core/height_field.hpp>
#include <sylva/render/lighting.hpp>

#include <glm/gtc/constants.hpp>

#include <cstddef>
#include <vector>

namespace sylva::render::embedded {
void register_player_shaders();  // generated from apps/player/shaders by sylva_embed_shaders
}  // namespace sylva::render::embedded

namespace sylva::player {

render::Lighting make_lighting(const SunSettings& sun) {
  render::Lighting lighting;
  lighting.sun_direction =
      render::sun_direction(glm::radians(sun.azimuth_deg), glm::radians(sun.elevation_deg));
  lighting.fog_density = sun.fog_density;
  return lighting;
}

render::Camera make_camera(const CameraBookmark& bookmark, glm::ivec2 viewport) {
  render::Camera camera;
  camera.set_position(glm::dvec3(bookmark.position));
  camera.set_yaw_pitch(glm::radians(bookmark.yaw_deg), glm::radians(bookmark.pitch_deg));
  camera.perspective().fov_y = glm::radians(bookmark.fov_deg);
  camera.perspective().near_plane = 0.5f;
  camera.set_aspect(viewport.x, viewport.y);
  return camera;
}

namespace {

struct GroundVertex {
  glm::vec3 position;
  glm::vec3 normal;
};

HeightField generate_field(const GroundSettings& s) {
  const double spacing = static_cast<double>(s.size) / (s.resolution - 1);
  const double half = 0.5 * static_cast<double>(s.size);
  HeightField field(s.resolution, s.resolution, spacing, {-half, -half});
  for (int j = 0; j < s.resolution; ++j) {
    for (int i = 0; i < s.resolution; ++i) {
      const glm::dvec2 p(-half + i * spacing, -half + j * spacing);
      // Ridged mountains blended over rolling fBm hills.
      const float hills = fbm2(p, s.noise);
      const float ridges = ridged2(p * 0.8, s.noise);
      field.sample(i, j) = s.height * (0.45f * hills + 0.75f * ridges * ridges);
    }
  }
  field.update_range();
  return field;
}

}  // namespace

Result<GroundRenderer> GroundRenderer::create(const GroundSettings& settings) {
  render::embedded::register_player_shaders();
  auto program = render::Program::create({"player/ground.vert", "player/ground.frag"});
  if (!program.ok()) return program.error();

  const HeightField field = generate_field(settings);
  const int n = settings.resolution;
  std::vector<GroundVertex> vertices;
  vertices.reserve(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const glm::dvec2 xz = field.origin() + glm::dvec2(i, j) * field.spacing();
      vertices.push_back({glm::vec3(static_cast<float>(xz.x), field.sample(i, j), static_cast<float>(xz.y)),
                          field.sample_normal(i, j)});
    }
  }
  std::vector<std::uint32_t> indices;
  indices.reserve(static_cast<std::size_t>(n - 1) * static_cast<std::size_t>(n - 1) * 6);
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const auto v = static_cast<std::uint32_t>(j * n + i);
      const auto w = static_cast<std::uint32_t>(n);
      // Counter-clockwise seen from above (+y).
      indices.insert(indices.end(), {v, v + w, v + 1, v + 1, v + w, v + w + 1});
    }
  }

  GroundRenderer ground;
  ground.program_ = std::move(*program);
  ground.vertices_ = render::Buffer::immutable(std::span<const GroundVertex>(vertices));
  ground.indices_ = render::Buffer::immutable(std::span<const std::uint32_t>(indices));
  ground.vao_ = render::VertexArray::create();
  ground.vao_.attribute(0, 0, 3, GL_FLOAT, offsetof(GroundVertex, position));
  ground.vao_.attribute(1, 0, 3, GL_FLOAT, offsetof(GroundVertex, normal));
  ground.vao_.vertex_buffer(0, ground.vertices_, sizeof(GroundVertex));
  ground.vao_.index_buffer(ground.indices_);
  ground.index_count_ = indices.size();
  // Snow on the top fifth of the relief.
  ground.snow_line_ = field.min_height() + 0.8f * (field.max_height() - field.min_height());
  return ground;
}

void GroundRenderer::draw(const render::Camera& camera, render::PassStats& stats) {
  program_.use();
  program_.set("u_view_projection", camera.view_projection());
  program_.set("u_model", camera.relative_model(glm::dvec3(0.0)));
  program_.set("u_snow_line", snow_line_);
  vao_.bind();
  glEnable(GL_CULL_FACE);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(index_count_), GL_UNSIGNED_INT, nullptr);
  glDisable(GL_CULL_FACE);
  stats.draw_calls += 1;
  stats.triangles += index_count_ / 3;
  stats.instances += 1;
}

}  // namespace sylva::player

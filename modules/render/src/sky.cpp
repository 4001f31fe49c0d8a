// Sky gradient renderer (sky.hpp). The CPU gradient mirrors shaders/lib/sky.glsl.
#include <sylva/render/sky.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::render {

glm::vec3 sky_gradient(const Lighting& l, const glm::vec3& direction) {
  const float y = std::clamp(direction.y, -1.0f, 1.0f);
  if (y >= 0.0f) return glm::mix(l.horizon_color, l.zenith_color, std::sqrt(y));
  return glm::mix(l.horizon_color, l.ground_color, std::clamp(-y * 8.0f, 0.0f, 1.0f));
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

#include <sylva/terrain/water.hpp>

#include <sylva/core/log.hpp>
#include <sylva/render/blend_state.hpp>
#include <sylva/render/gpu_memory.hpp>

#include <cmath>
#include <numbers>

namespace sylva::render::embedded {
void register_terrain_shaders();  // generated from modules/terrain/shaders (cmake/embed_shaders.cmake)
}  // namespace sylva::render::embedded

namespace sylva::terrain {

namespace {
constexpr double kGravity = 9.81;  // [m/s^2], deep-water dispersion omega^2 = g k
constexpr GLuint kDepthUnit = 0;
}  // namespace

std::array<RippleWave, kRippleWaves> ripple_waves(const WaterSettings& s) {
  // Wavelengths fall by irregular ratios and directions spread over +-140 degrees around one
  // wind direction (+x), with nearly equal slopes: no single train of parallel crests shows
  // (with the longest wave dominant the water looked like corduroy).
  static constexpr double kLength[kRippleWaves] = {1.0, 0.73, 0.53, 0.39, 0.28, 0.2, 0.145, 0.1};
  static constexpr double kAngle[kRippleWaves] = {0.0, 1.6, -1.1, 0.55, 2.4, -2.0, -0.35, 1.05};
  static constexpr float kShare[kRippleWaves] = {1.0f, 0.95f, 0.9f, 0.85f, 0.8f, 0.75f, 0.7f, 0.65f};
  std::array<RippleWave, kRippleWaves> waves{};
  for (int i = 0; i < kRippleWaves; ++i) {
    const double length = static_cast<double>(s.ripple_scale_m) * kLength[i];
    const double k = 2.0 * std::numbers::pi / length;
    waves[i].k = glm::dvec2(std::cos(kAngle[i]), std::sin(kAngle[i])) * k;
    waves[i].omega = std::sqrt(kGravity * k) * static_cast<double>(s.ripple_speed);
    waves[i].slope = s.ripple_strength * kShare[i] * 0.5f;
  }
  return waves;
}

Result<std::unique_ptr<WaterRenderer>> WaterRenderer::create(const WaterSettings& settings, const std::string& prefix) {
  SYLVA_TRY(validate_params(settings, prefix));
  render::embedded::register_terrain_shaders();
  render::embedded::register_render_shaders();
  auto program = render::Program::create({"terrain/water.vert", "terrain/water.frag"});
  if (!program.ok()) return program.error();
  std::unique_ptr<WaterRenderer> r(new WaterRenderer());
  r->settings_ = settings;
  r->program_ = std::move(program).value();
  r->vao_ = render::VertexArray::create();
  return r;
}

WaterRenderer::~WaterRenderer() = default;

// Copies the bound draw framebuffer's depth (resolving MSAA) into depth_copy_. False when that
// target's depth is not 32-bit float (the blit needs equal formats); the water is then deep.
bool WaterRenderer::copy_scene_depth(glm::ivec2 size) {
  GLint bound = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
  const GLuint source = static_cast<GLuint>(bound);
  const GLenum attachment = source == 0 ? GL_DEPTH : GL_DEPTH_ATTACHMENT;
  GLint type = GL_NONE, bits = 0;
  glGetNamedFramebufferAttachmentParameteriv(source, attachment, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
  if (type != GL_NONE) {
    glGetNamedFramebufferAttachmentParameteriv(source, attachment, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &type);
    glGetNamedFramebufferAttachmentParameteriv(source, attachment, GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &bits);
  }
  if (type != GL_FLOAT || bits != 32 || size.x < 1 || size.y < 1) {
    if (!depth_warned_) {
      log_warn("water: the target has no 32-bit float depth; the water is drawn as deep (no depth tint)");
      depth_warned_ = true;
    }
    return false;
  }
  if (!depth_copy_ || depth_copy_.size() != size) {
    depth_copy_ = {};
    auto made = render::Framebuffer::create({.width = size.x, .height = size.y, .color_formats = {}});
    if (!made.ok()) {
      if (!depth_warned_) log_warn("water: no depth copy ({}); the water is drawn as deep", made.error().message);
      depth_warned_ = true;
      return false;
    }
    depth_copy_ = std::move(*made);
  }
  glBlitNamedFramebuffer(source, depth_copy_.id(), 0, 0, size.x, size.y, 0, 0, size.x, size.y, GL_DEPTH_BUFFER_BIT,
                         GL_NEAREST);
  return true;
}

void WaterRenderer::draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) {
  if (pass != render::Pass::kTransparent) return;
  stats_.drawn = false;
  const WaterSettings& s = settings_;
  const double height = s.level - frame.camera.position().y;  // level relative to the camera [m]
  if (!s.enabled || !(height < 0.0)) return;
  GLint viewport[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_VIEWPORT, viewport);
  const glm::ivec2 size(viewport[0] + viewport[2], viewport[1] + viewport[3]);
  stats_.scene_depth = copy_scene_depth(size);
  stats_.gpu_bytes = depth_copy_ ? render::Framebuffer::estimated_bytes(depth_copy_.desc()) : 0;

  program_.reload_if_changed();
  program_.use();
  const glm::mat4 vp = frame.camera.view_projection();
  program_.set("u_view_projection", vp);
  program_.set("u_inv_view_projection", glm::inverse(vp));
  program_.set("u_viewport", glm::vec4(viewport[0], viewport[1], viewport[2], viewport[3]));
  program_.set("u_height", static_cast<float>(height));
  program_.set("u_has_depth", stats_.scene_depth);
  program_.set("u_color", s.color);
  program_.set("u_absorption", s.absorption);
  program_.set("u_shore_fade", s.shore_fade_m);
  program_.set("u_sun_glint", s.sun_glint);
  // Ripple phases at the camera in double (k . camera_xz - omega t, wrapped), so the shader adds
  // only k . rel_xz: exact at any distance from the origin and any time.
  const glm::dvec2 cam(frame.camera.position().x, frame.camera.position().z);
  std::array<glm::vec4, kRippleWaves> waves{};
  const std::array<RippleWave, kRippleWaves> ripple = ripple_waves(s);
  for (int i = 0; i < kRippleWaves; ++i) {
    const double phase = std::remainder(glm::dot(ripple[i].k, cam) - ripple[i].omega * frame.time, 2.0 * std::numbers::pi);
    waves[i] = glm::vec4(glm::vec2(ripple[i].k), static_cast<float>(phase), ripple[i].slope);
  }
  program_.set("u_waves", std::span<const glm::vec4>(waves));
  // The domain warp: two waves 3 and 3.4 times longer than the longest ripple, slower, across it.
  const glm::dvec2 k0 = ripple[0].k;
  const glm::dvec2 warp_k[2] = {glm::dvec2(-k0.y, k0.x) * 0.29, k0 * 0.34};
  std::array<glm::vec4, 2> warp{};
  for (int i = 0; i < 2; ++i) {
    const double phase = std::remainder(glm::dot(warp_k[i], cam) - 0.3 * ripple[0].omega * frame.time, 2.0 * std::numbers::pi);
    warp[i] = glm::vec4(glm::vec2(warp_k[i]), static_cast<float>(phase), 0.3f * s.ripple_scale_m);
  }
  program_.set("u_warp", std::span<const glm::vec4>(warp));
  // Pixel footprint per metre of distance (radians per pixel, vertical), for the ripple fade.
  const float fy = vp[1][1] != 0.0f ? 2.0f / (std::abs(vp[1][1]) * static_cast<float>(std::max(viewport[3], 1))) : 0.0f;
  program_.set("u_pixel_angle", fy);
  if (stats_.scene_depth) depth_copy_.depth_texture().bind(kDepthUnit);

  // out = src0 + dst x src1 (dual-source blending), depth tested, not written.
  {
    const render::SavedBlendState saved;
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_SRC1_COLOR, GL_ZERO, GL_ONE);
    glDisable(GL_CULL_FACE);
    glDepthMask(GL_FALSE);
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
  }
  stats.draw_calls += 1;
  stats.triangles += 1;
  stats_.drawn = true;
}

void sync_water(std::unique_ptr<WaterRenderer>& water, const WaterSettings& wanted, const std::string& prefix) {
  if (water) {
    water->settings() = wanted;
    return;
  }
  if (!wanted.enabled) return;
  static thread_local std::string last_failure;
  auto made = WaterRenderer::create(wanted, prefix);
  if (made.ok()) {
    water = std::move(*made);
  } else if (made.error().message != last_failure) {
    last_failure = made.error().message;
    log_warn("{}: no water: {}", prefix, last_failure);
  }
}

}  // namespace sylva::terrain

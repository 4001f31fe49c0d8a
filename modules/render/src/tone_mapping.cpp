// HDR tone mapping post pass; see tone_mapping.hpp.
#include <sylva/render/tone_mapping.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::render {

float tone_map_aces(float x) {
  const float v = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
  return std::clamp(v, 0.0f, 1.0f);
}

float tone_map_reinhard(float x) { return x / (1.0f + x); }

float linear_to_srgb_exact(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  return x < 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

float tone_map_channel(float hdr, const ToneMapSettings& s) {
  // Same order as tone_map.frag: NaN/negative -> 0, exposure, clamp huge values, curve, sRGB.
  float x = (std::isnan(hdr) || hdr < 0.0f) ? 0.0f : hdr;
  x = std::min(x * std::max(s.exposure, 0.0f), 6.0e4f);
  const float t = s.tone_operator == ToneOperator::kAces ? tone_map_aces(x) : tone_map_reinhard(x);
  return s.srgb_encode ? linear_to_srgb_exact(t) : t;
}

Result<ToneMapper> ToneMapper::create() {
  embedded::register_render_shaders();
  auto program = Program::create({"render/tone_map.vert", "render/tone_map.frag"});
  if (!program.ok()) return program.error();
  ToneMapper t;
  t.program_ = std::move(*program);
  t.vao_ = VertexArray::create();
  return t;
}

void ToneMapper::apply(const Texture& hdr, const ToneMapSettings& s) {
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  hdr.bind(0);
  glBindSampler(0, 0);
  program_.use();
  program_.set("u_exposure", std::max(s.exposure, 0.0f));
  program_.set("u_operator", s.tone_operator == ToneOperator::kAces ? 0 : 1);
  program_.set("u_srgb", s.srgb_encode);
  vao_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glEnable(GL_DEPTH_TEST);
}

}  // namespace sylva::render

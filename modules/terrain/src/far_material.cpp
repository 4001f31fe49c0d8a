#include "far_material.hpp"

#include <sylva/render/saved_target_state.hpp>

#include <fmt/format.h>

#include <algorithm>

namespace sylva::terrain {
namespace {

render::GlHandle<render::FramebufferDeleter> make_fbo() {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  return render::GlHandle<render::FramebufferDeleter>(id);
}

}  // namespace

Result<FarMaterialBake> FarMaterialBake::create(int columns, int rows) {
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  if (columns <= 0 || rows <= 0 || columns > max_size || rows > max_size) {
    return make_error(ErrorCode::kLimit, fmt::format("terrain: a {}x{} far material bake exceeds GL_MAX_TEXTURE_SIZE {}",
                                                     columns, rows, max_size));
  }
  auto program = render::Program::create({"render/tone_map.vert", "terrain/far_material_bake.frag"},
                                         {{"SYLVA_TERRAIN_FIRST_SCALE", "3"}});
  if (!program.ok()) return program.error();
  FarMaterialBake b;
  b.program_ = std::move(program).value();
  b.texture_ = render::Texture::create_2d(columns, rows, GL_SRGB8_ALPHA8, render::mip_levels(columns, rows));
  b.texture_.set_filter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
  b.texture_.set_wrap(GL_CLAMP_TO_EDGE);
  b.empty_vao_ = render::VertexArray::create();
  b.draw_fbo_ = make_fbo();
  b.read_fbo_ = make_fbo();
  return b;
}

void FarMaterialBake::mark_dirty(const SampleRect& r) {
  if (r.x0 >= r.x1 || r.z0 >= r.z1) return;
  if (dirty_.x0 >= dirty_.x1) {
    dirty_ = r;
    return;
  }
  dirty_ = {std::min(dirty_.x0, r.x0), std::min(dirty_.z0, r.z0), std::max(dirty_.x1, r.x1), std::max(dirty_.z1, r.z1)};
}

void FarMaterialBake::refresh(const render::Texture& heights, const render::Texture& shape,
                              const MaterialUniforms& material) {
  if (!baked_ || !(material == baked_with_)) {
    bake(heights, shape, material, SampleRect{0, 0, texture_.width(), texture_.height()});
    baked_ = true;
    baked_with_ = material;
  } else if (dirty_.x0 < dirty_.x1) {
    bake(heights, shape, material, dirty_);
  }
  dirty_ = {};
}

void FarMaterialBake::bake(const render::Texture& heights, const render::Texture& shape,
                           const MaterialUniforms& material, SampleRect rect) {
  const int w = texture_.width(), h = texture_.height();
  int x0 = std::max(rect.x0, 0), z0 = std::max(rect.z0, 0), x1 = std::min(rect.x1, w), z1 = std::min(rect.z1, h);
  if (x0 >= x1 || z0 >= z1) return;
  const render::SavedTargetState saved;
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glEnable(GL_FRAMEBUFFER_SRGB);  // the shader writes linear values; mips average in linear space

  // Level 0: one fragment per texel of the rectangle (the scissor), at the texel's centre.
  const GLuint draw_fbo = draw_fbo_.get(), read_fbo = read_fbo_.get();
  glNamedFramebufferTexture(draw_fbo, GL_COLOR_ATTACHMENT0, texture_.id(), 0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, draw_fbo);
  glViewport(0, 0, w, h);
  glEnable(GL_SCISSOR_TEST);
  glScissor(x0, z0, x1 - x0, z1 - z0);
  program_.use();
  set_material_uniforms(program_, material);
  shape.bind(2);
  heights.bind(4);
  empty_vao_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisable(GL_SCISSOR_TEST);
  texels_baked_ += static_cast<std::int64_t>(x1 - x0) * (z1 - z0);

  // Mips over the rectangle: each level's texel is the linear-space mean of the 2x2 below it (a
  // 2:1 linear blit samples exactly between them), so an edit costs its rectangle, not the field.
  for (int level = 1; level < texture_.levels(); ++level) {
    const int pw = std::max(w >> (level - 1), 1), ph = std::max(h >> (level - 1), 1);
    const int lw = std::max(w >> level, 1), lh = std::max(h >> level, 1);
    x0 = x0 / 2, z0 = z0 / 2, x1 = std::min((x1 + 1) / 2, lw), z1 = std::min((z1 + 1) / 2, lh);
    glNamedFramebufferTexture(read_fbo, GL_COLOR_ATTACHMENT0, texture_.id(), level - 1);
    glNamedFramebufferTexture(draw_fbo, GL_COLOR_ATTACHMENT0, texture_.id(), level);
    glBlitNamedFramebuffer(read_fbo, draw_fbo, 2 * x0, 2 * z0, std::min(2 * x1, pw), std::min(2 * z1, ph), x0, z0, x1,
                           z1, GL_COLOR_BUFFER_BIT, GL_LINEAR);
  }
}

}  // namespace sylva::terrain

#include <sylva/render/blend_state.hpp>

namespace sylva::render {

SavedBlendState::SavedBlendState() {
  blend_ = glIsEnabled(GL_BLEND);
  cull_ = glIsEnabled(GL_CULL_FACE);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask_);
  glGetIntegerv(GL_BLEND_SRC_RGB, &func_[0]);
  glGetIntegerv(GL_BLEND_DST_RGB, &func_[1]);
  glGetIntegerv(GL_BLEND_SRC_ALPHA, &func_[2]);
  glGetIntegerv(GL_BLEND_DST_ALPHA, &func_[3]);
}

SavedBlendState::~SavedBlendState() {
  glDepthMask(depth_mask_);
  glBlendFuncSeparate(static_cast<GLenum>(func_[0]), static_cast<GLenum>(func_[1]), static_cast<GLenum>(func_[2]),
                      static_cast<GLenum>(func_[3]));
  if (blend_) {
    glEnable(GL_BLEND);
  } else {
    glDisable(GL_BLEND);
  }
  if (cull_) {
    glEnable(GL_CULL_FACE);
  } else {
    glDisable(GL_CULL_FACE);
  }
}

}  // namespace sylva::render

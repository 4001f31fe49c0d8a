// See saved_target_state.hpp.
#include <sylva/render/saved_target_state.hpp>

namespace sylva::render {

SavedTargetState::SavedTargetState() {
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_fbo_);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_fbo_);
  glGetIntegerv(GL_VIEWPORT, viewport_);
  glGetIntegerv(GL_CLIP_ORIGIN, &clip_origin_);
  glGetIntegerv(GL_CLIP_DEPTH_MODE, &clip_depth_);
  glGetIntegerv(GL_DEPTH_FUNC, &depth_func_);
  glGetFloatv(GL_DEPTH_CLEAR_VALUE, &clear_depth_);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask_);
  for (std::size_t i = 0; i < kCaps.size(); ++i) enabled_[i] = glIsEnabled(kCaps[i]);
}

SavedTargetState::~SavedTargetState() {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw_fbo_));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read_fbo_));
  glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  glClipControl(static_cast<GLenum>(clip_origin_), static_cast<GLenum>(clip_depth_));
  glDepthFunc(static_cast<GLenum>(depth_func_));
  glClearDepth(static_cast<double>(clear_depth_));
  glDepthMask(depth_mask_);
  for (std::size_t i = 0; i < kCaps.size(); ++i) (enabled_[i] ? glEnable : glDisable)(kCaps[i]);
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace sylva::render

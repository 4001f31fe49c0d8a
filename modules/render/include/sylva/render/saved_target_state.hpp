#pragma once
// Saves the state an off-screen pass (a bake into a texture: the vegetation's slices, the
// terrain's far material) changes and puts it back when it goes out of scope, so the host's frame
// goes on as it was: the draw and read framebuffers, the viewport, clip control, depth function,
// depth clear value and write mask, and the enables of depth test, multisample, face culling,
// blending, scissor test and sRGB framebuffer writes. On restore no vertex array and no program
// are bound (the pass's own may be deleted before the host draws again). GL thread only; reads
// the state with glGet at construction.
#include <epoxy/gl.h>

#include <array>

namespace sylva::render {

class SavedTargetState {
 public:
  SavedTargetState();
  ~SavedTargetState();
  SavedTargetState(const SavedTargetState&) = delete;
  SavedTargetState& operator=(const SavedTargetState&) = delete;

 private:
  static constexpr std::array<GLenum, 6> kCaps = {GL_DEPTH_TEST, GL_MULTISAMPLE, GL_CULL_FACE,
                                                  GL_BLEND,      GL_SCISSOR_TEST, GL_FRAMEBUFFER_SRGB};
  GLint draw_fbo_ = 0, read_fbo_ = 0, viewport_[4] = {0, 0, 0, 0};
  GLint clip_origin_ = GL_LOWER_LEFT, clip_depth_ = GL_NEGATIVE_ONE_TO_ONE, depth_func_ = GL_LESS;
  GLfloat clear_depth_ = 1.0f;
  GLboolean depth_mask_ = GL_TRUE;
  std::array<GLboolean, kCaps.size()> enabled_{};
};

}  // namespace sylva::render

#pragma once
// Saves the fixed-function state a blended pass changes (blend enable and functions, depth write
// mask, face culling enable) and puts it back when it goes out of scope, so a drawable that
// blends in the transparent pass (the voxel translucent blocks, the terrain's water) leaves the
// host's state as it found it. GL thread only; reads the state with glGet at construction.
#include <epoxy/gl.h>

namespace sylva::render {

class SavedBlendState {
 public:
  SavedBlendState();
  ~SavedBlendState();
  SavedBlendState(const SavedBlendState&) = delete;
  SavedBlendState& operator=(const SavedBlendState&) = delete;

 private:
  GLboolean blend_ = GL_FALSE;
  GLboolean cull_ = GL_FALSE;
  GLboolean depth_mask_ = GL_TRUE;
  GLint func_[4] = {GL_ONE, GL_ZERO, GL_ONE, GL_ZERO};  // src rgb, dst rgb, src alpha, dst alpha
};

}  // namespace sylva::render

#pragma once
// Sampler objects: filtering and wrapping state kept apart from texture storage so one texture
// can be read with different settings (e.g. a shadow map with and without comparison).

#include <sylva/render/gl_handle.hpp>

#include <epoxy/gl.h>

namespace sylva::render {

struct SamplerDeleter {
  void operator()(GLuint id) const { glDeleteSamplers(1, &id); }
};

struct SamplerDesc {
  GLenum min_filter = GL_LINEAR_MIPMAP_LINEAR;
  GLenum mag_filter = GL_LINEAR;
  GLenum wrap_s = GL_REPEAT;
  GLenum wrap_t = GL_REPEAT;
  GLenum wrap_r = GL_REPEAT;
  float max_anisotropy = 1.0f;  // > 1 when the driver offers it; clamped to its limit
  float lod_bias = 0.0f;
  bool depth_compare = false;   // GL_COMPARE_REF_TO_TEXTURE for sampler2DShadow
  GLenum compare_func = GL_GEQUAL;  // reversed-Z: nearer is larger
  float border_color[4] = {0.0f, 0.0f, 0.0f, 0.0f};
};

class Sampler {
 public:
  Sampler() = default;
  static Sampler create(const SamplerDesc& desc = {});

  GLuint id() const { return handle_.get(); }
  explicit operator bool() const { return static_cast<bool>(handle_); }
  void bind(GLuint unit) const;
  static void unbind(GLuint unit);

 private:
  GlHandle<SamplerDeleter> handle_;
};

}  // namespace sylva::render

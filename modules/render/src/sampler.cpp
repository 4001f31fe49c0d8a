// Sampler objects (sampler.hpp).
#include <sylva/render/sampler.hpp>

#include <algorithm>

namespace sylva::render {

Sampler Sampler::create(const SamplerDesc& d) {
  GLuint id = 0;
  glCreateSamplers(1, &id);
  Sampler s;
  s.handle_ = GlHandle<SamplerDeleter>(id);
  glSamplerParameteri(id, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(d.min_filter));
  glSamplerParameteri(id, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(d.mag_filter));
  glSamplerParameteri(id, GL_TEXTURE_WRAP_S, static_cast<GLint>(d.wrap_s));
  glSamplerParameteri(id, GL_TEXTURE_WRAP_T, static_cast<GLint>(d.wrap_t));
  glSamplerParameteri(id, GL_TEXTURE_WRAP_R, static_cast<GLint>(d.wrap_r));
  glSamplerParameterf(id, GL_TEXTURE_LOD_BIAS, d.lod_bias);
  glSamplerParameterfv(id, GL_TEXTURE_BORDER_COLOR, d.border_color);
  if (d.depth_compare) {
    glSamplerParameteri(id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glSamplerParameteri(id, GL_TEXTURE_COMPARE_FUNC, static_cast<GLint>(d.compare_func));
  }
  if (d.max_anisotropy > 1.0f &&
      (epoxy_gl_version() >= 46 || epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic") ||
       epoxy_has_gl_extension("GL_ARB_texture_filter_anisotropic"))) {
    GLfloat limit = 1.0f;
    glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &limit);
    glSamplerParameterf(id, GL_TEXTURE_MAX_ANISOTROPY, std::min(d.max_anisotropy, limit));
  }
  return s;
}

void Sampler::bind(GLuint unit) const { glBindSampler(unit, id()); }
void Sampler::unbind(GLuint unit) { glBindSampler(unit, 0); }

}  // namespace sylva::render

// The per-process headless context for GL tests (sylva/render/testing.hpp). Compiled into
// sylva_render so every module's tests share one implementation; it needs no GoogleTest.
#include <sylva/render/testing.hpp>

#include <sylva/render/camera.hpp>

#include <epoxy/gl.h>

#include <mutex>

namespace sylva::render {

GlContext* shared_test_context(std::string* error) {
  static std::once_flag once;
  // Deliberately never destroyed: tearing down Mesa from a static destructor at exit races
  // with its own atexit handlers, and the process is about to end anyway.
  static GlContext* context = nullptr;
  static std::string creation_error;
  std::call_once(once, [] {
    Result<GlContext> created = GlContext::create_headless({.debug = true});
    if (created.ok()) {
      context = new GlContext(std::move(created).value());
    } else {
      creation_error = created.error().describe();
    }
  });
  if (context == nullptr && error != nullptr) *error = creation_error;
  return context;
}

void reset_test_gl_state() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glBindVertexArray(0);
  glUseProgram(0);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_MULTISAMPLE);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  apply_reversed_z_state();
}

}  // namespace sylva::render

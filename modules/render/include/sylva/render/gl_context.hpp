#pragma once
// OpenGL 4.5 core contexts: headless EGL for tests, benchmarks and the headless player, and a
// GLFW window for the player and editor (DESIGN.md §2 "Headless first"). GL is loaded through
// libepoxy, so every GL call in Sylva includes <epoxy/gl.h> and needs no loader setup.
//
// Headless creation tries EGL_MESA_platform_surfaceless first (no display, no device node
// needed), then the EGL device platform (EGL_EXT_platform_device, first device that gives a
// 4.5 core context). Rendering is to framebuffer objects only; there is no default framebuffer.
//
// Ownership: a GlContext owns its EGL display/context or its GLFW window and destroys them.
// Exactly one context is current per thread; creation makes the new context current.
// Failure: every creation error is a Result with ErrorCode::kGl naming the step that failed
// (platform, display init, config, context, version) rather than a crash.

#include <sylva/core/result.hpp>

#include <glm/glm.hpp>

#include <memory>
#include <string>

struct GLFWwindow;

namespace sylva::render {

enum class ContextKind { kHeadless, kWindow };

struct HeadlessContextOptions {
  bool debug = true;  // a KHR_debug context whose messages go to the sylva log (see gl_debug.hpp)
};

struct WindowContextOptions {
  int width = 1280;  // window size in screen coordinates, > 0
  int height = 720;
  std::string title = "Sylva";
  bool visible = true;
  bool vsync = true;
  bool debug = true;
};

// True when a window system is reachable: $DISPLAY or $WAYLAND_DISPLAY is set and GLFW can
// initialise. Never throws or aborts; the player uses this to fall back to headless.
bool display_available();

class GlContext {
 public:
  static Result<GlContext> create_headless(const HeadlessContextOptions& options = {});
  static Result<GlContext> create_window(const WindowContextOptions& options = {});

  GlContext(GlContext&&) noexcept;
  GlContext& operator=(GlContext&&) noexcept;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;
  ~GlContext();

  ContextKind kind() const;
  void make_current() const;

  // GL_RENDERER / GL_VERSION strings and which EGL platform or window system was used.
  const std::string& renderer() const;
  const std::string& version() const;
  const std::string& platform() const;

  // Window only (null / no-ops for headless contexts).
  GLFWwindow* window() const;
  bool should_close() const;
  void swap_buffers() const;
  void poll_events() const;
  glm::ivec2 framebuffer_size() const;  // pixels; {0, 0} for headless

 private:
  struct Impl;
  explicit GlContext(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace sylva::render

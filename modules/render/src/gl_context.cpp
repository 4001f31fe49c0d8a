// Headless EGL and windowed GLFW contexts (see gl_context.hpp for the contract).
#include <sylva/render/gl_context.hpp>

#include <sylva/core/log.hpp>
#include <sylva/render/gl_debug.hpp>

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::render {

struct GlContext::Impl {
  ContextKind kind = ContextKind::kHeadless;
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  GLFWwindow* window = nullptr;
  std::string renderer;
  std::string version;
  std::string platform;
  ~Impl();
};

namespace {

bool has_extension(const char* list, std::string_view name) {
  if (list == nullptr) return false;
  std::string_view all(list);
  std::size_t pos = 0;
  while (pos < all.size()) {
    std::size_t end = all.find(' ', pos);
    if (end == std::string_view::npos) end = all.size();
    if (all.substr(pos, end - pos) == name) return true;
    pos = end + 1;
  }
  return false;
}

std::string egl_error_name(EGLint code) {
  switch (code) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    default: return fmt::format("EGL error 0x{:x}", code);
  }
}

// EGL displays are per process singletons: eglTerminate would destroy every context on the
// display, so displays are reference counted by the contexts using them.
std::mutex g_display_mutex;
std::map<EGLDisplay, int> g_display_refs;

void retain_display(EGLDisplay d) {
  std::lock_guard lock(g_display_mutex);
  ++g_display_refs[d];
}

void release_display(EGLDisplay d) {
  std::lock_guard lock(g_display_mutex);
  auto it = g_display_refs.find(d);
  if (it == g_display_refs.end()) return;
  if (--it->second == 0) {
    g_display_refs.erase(it);
    eglTerminate(d);
  }
}

// GLFW's init is process-wide; keep it alive while any window exists.
std::mutex g_glfw_mutex;
int g_glfw_refs = 0;
std::string g_glfw_last_error;

void glfw_error_callback(int code, const char* description) {
  g_glfw_last_error = fmt::format("GLFW error 0x{:x}: {}", code, description != nullptr ? description : "");
}

bool glfw_acquire() {
  std::lock_guard lock(g_glfw_mutex);
  if (g_glfw_refs == 0) {
    glfwSetErrorCallback(glfw_error_callback);
    if (glfwInit() != GLFW_TRUE) return false;
  }
  ++g_glfw_refs;
  return true;
}

void glfw_release() {
  std::lock_guard lock(g_glfw_mutex);
  if (g_glfw_refs > 0 && --g_glfw_refs == 0) glfwTerminate();
}

// Checks what a fresh context gives and fills the description strings. Needs it current.
Status check_gl_version(const std::string& platform, std::string& renderer_out, std::string& version_out) {
  const int version = epoxy_gl_version();
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const char* version_string = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  renderer_out = renderer != nullptr ? renderer : "?";
  version_out = version_string != nullptr ? version_string : "?";
  if (version < 45) {
    return make_error(ErrorCode::kGl, fmt::format("OpenGL 4.5 core is required, {} offers {} ({})", platform,
                                                  version_out, renderer_out));
  }
  GLint mask = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
  if ((mask & GL_CONTEXT_CORE_PROFILE_BIT) == 0) {
    return make_error(ErrorCode::kGl, fmt::format("{} gave a compatibility context; a core profile is required",
                                                  platform));
  }
  return ok_status();
}

// Tries to create a 4.5 core context on an initialised display. Empty string on success.
std::string create_egl_context(EGLDisplay display, bool debug, EGLContext& out) {
  const char* exts = eglQueryString(display, EGL_EXTENSIONS);
  if (!has_extension(exts, "EGL_KHR_surfaceless_context")) {
    return "EGL_KHR_surfaceless_context is missing";
  }
  if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
    return "eglBindAPI(EGL_OPENGL_API) failed: " + egl_error_name(eglGetError());
  }
  EGLConfig config = EGL_NO_CONFIG_KHR;
  if (!has_extension(exts, "EGL_KHR_no_config_context")) {
    const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
    EGLint count = 0;
    if (eglChooseConfig(display, config_attribs, &config, 1, &count) != EGL_TRUE || count < 1) {
      return "no EGL config renders OpenGL: " + egl_error_name(eglGetError());
    }
  }
  const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                    4,
                                    EGL_CONTEXT_MINOR_VERSION,
                                    5,
                                    EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                    EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                    EGL_CONTEXT_OPENGL_DEBUG,
                                    debug ? EGL_TRUE : EGL_FALSE,
                                    EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attribs);
  if (context == EGL_NO_CONTEXT) {
    return "eglCreateContext(4.5 core) failed: " + egl_error_name(eglGetError());
  }
  if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context) != EGL_TRUE) {
    const std::string why = egl_error_name(eglGetError());
    eglDestroyContext(display, context);
    return "eglMakeCurrent(surfaceless) failed: " + why;
  }
  out = context;
  return {};
}

// Initialises `display` and creates a context on it; on failure terminates nothing that other
// contexts may use and returns why.
std::string try_display(EGLDisplay display, bool debug, EGLContext& context) {
  if (display == EGL_NO_DISPLAY) return "no display: " + egl_error_name(eglGetError());
  EGLint major = 0;
  EGLint minor = 0;
  if (eglInitialize(display, &major, &minor) != EGL_TRUE) {
    return "eglInitialize failed: " + egl_error_name(eglGetError());
  }
  retain_display(display);
  std::string why = create_egl_context(display, debug, context);
  if (!why.empty()) release_display(display);
  return why;
}

}  // namespace

GlContext::Impl::~Impl() {
  if (kind == ContextKind::kHeadless) {
    if (context != EGL_NO_CONTEXT) {
      if (eglGetCurrentContext() == context) eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(display, context);
      release_display(display);
    }
  } else if (window != nullptr) {
    glfwDestroyWindow(window);
    glfw_release();
  }
}

GlContext::GlContext(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
GlContext::GlContext(GlContext&&) noexcept = default;
GlContext& GlContext::operator=(GlContext&&) noexcept = default;
GlContext::~GlContext() = default;

Result<GlContext> GlContext::create_headless(const HeadlessContextOptions& options) {
  auto impl = std::make_unique<Impl>();
  impl->kind = ContextKind::kHeadless;
  const char* client_exts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (client_exts == nullptr) {
    return make_error(ErrorCode::kGl, "EGL has no client extensions (EGL 1.5 / EGL_EXT_client_extensions needed)");
  }
  std::vector<std::string> attempts;

  // 1. Surfaceless Mesa platform: needs neither a display server nor a device node.
  if (has_extension(client_exts, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    std::string why = try_display(display, options.debug, impl->context);
    if (why.empty()) {
      impl->display = display;
      impl->platform = "EGL surfaceless (EGL_MESA_platform_surfaceless)";
    } else {
      attempts.push_back("surfaceless platform: " + why);
    }
  } else {
    attempts.push_back("surfaceless platform: EGL_MESA_platform_surfaceless not offered");
  }

  // 2. Device platform: every EGL device in turn.
  if (impl->context == EGL_NO_CONTEXT) {
    if (has_extension(client_exts, "EGL_EXT_platform_device") && has_extension(client_exts, "EGL_EXT_device_enumeration")) {
      EGLint count = 0;
      eglQueryDevicesEXT(0, nullptr, &count);
      std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(std::max(count, 0)));
      if (count > 0) eglQueryDevicesEXT(count, devices.data(), &count);
      for (EGLint i = 0; i < count && impl->context == EGL_NO_CONTEXT; ++i) {
        EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[static_cast<std::size_t>(i)], nullptr);
        std::string why = try_display(display, options.debug, impl->context);
        if (why.empty()) {
          impl->display = display;
          impl->platform = fmt::format("EGL device platform (device {})", i);
        } else {
          attempts.push_back(fmt::format("device {}: {}", i, why));
        }
      }
      if (count == 0) attempts.push_back("device platform: no EGL devices");
    } else {
      attempts.push_back("device platform: EGL_EXT_platform_device / EGL_EXT_device_enumeration not offered");
    }
  }

  if (impl->context == EGL_NO_CONTEXT) {
    std::string all;
    for (const std::string& a : attempts) all += "; " + a;
    return make_error(ErrorCode::kGl, "cannot create a headless OpenGL 4.5 core context" + all);
  }
  if (Status s = check_gl_version(impl->platform, impl->renderer, impl->version); !s.ok()) return s.error();
  if (options.debug) install_debug_output();
  log_debug("GL context: {} | {} | {}", impl->platform, impl->renderer, impl->version);
  return GlContext(std::move(impl));
}

Result<GlContext> GlContext::create_window(const WindowContextOptions& options) {
  if (options.width <= 0 || options.height <= 0) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("window size {}x{} must be positive", options.width, options.height));
  }
  if (!glfw_acquire()) {
    return make_error(ErrorCode::kGl, "glfwInit failed (no display?): " + g_glfw_last_error);
  }
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_DEPTH_BITS, 24);
  GLFWwindow* window = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
  if (window == nullptr) {
    glfw_release();
    return make_error(ErrorCode::kGl, "cannot open a window with OpenGL 4.5 core: " + g_glfw_last_error);
  }
  auto impl = std::make_unique<Impl>();
  impl->kind = ContextKind::kWindow;
  impl->window = window;
  impl->platform = fmt::format("GLFW {} window", glfwGetVersionString());
  glfwMakeContextCurrent(window);
  glfwSwapInterval(options.vsync ? 1 : 0);
  if (Status s = check_gl_version(impl->platform, impl->renderer, impl->version); !s.ok()) return s.error();
  if (options.debug) install_debug_output();
  log_debug("GL context: {} | {} | {}", impl->platform, impl->renderer, impl->version);
  return GlContext(std::move(impl));
}

bool display_available() {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  const bool env = (x11 != nullptr && x11[0] != '\0') || (wayland != nullptr && wayland[0] != '\0');
  if (!env) return false;
  // Keep GLFW (and its X connection) once it came up instead of terminating it here: the window
  // that follows would open a second connection right after the first closed, and that second
  // XOpenDisplay failed about one run in three under Xvfb ("X11: Failed to open display :0").
  static const bool available = glfw_acquire();
  return available;
}

ContextKind GlContext::kind() const { return impl_->kind; }

void GlContext::make_current() const {
  if (impl_->kind == ContextKind::kHeadless) {
    if (eglGetCurrentContext() != impl_->context) {
      eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context);
    }
  } else {
    glfwMakeContextCurrent(impl_->window);
  }
}

const std::string& GlContext::renderer() const { return impl_->renderer; }
const std::string& GlContext::version() const { return impl_->version; }
const std::string& GlContext::platform() const { return impl_->platform; }
GLFWwindow* GlContext::window() const { return impl_->window; }

bool GlContext::should_close() const {
  return impl_->window != nullptr && glfwWindowShouldClose(impl_->window) == GLFW_TRUE;
}

void GlContext::swap_buffers() const {
  if (impl_->window != nullptr) glfwSwapBuffers(impl_->window);
}

void GlContext::poll_events() const {
  if (impl_->window != nullptr) glfwPollEvents();
}

glm::ivec2 GlContext::framebuffer_size() const {
  if (impl_->window == nullptr) return {0, 0};
  int w = 0;
  int h = 0;
  glfwGetFramebufferSize(impl_->window, &w, &h);
  return {w, h};
}

}  // namespace sylva::render

// KHR_debug output into the sylva log, and the GL error recorder tests use.
#include <sylva/render/gl_debug.hpp>

#include <sylva/core/log.hpp>

#include <epoxy/gl.h>

#include <atomic>
#include <cstring>
#include <mutex>
#include <string>

namespace sylva::render {
namespace {

std::atomic<bool> g_recording{false};
std::atomic<std::size_t> g_error_count{0};
std::mutex g_errors_mutex;
std::vector<std::string> g_errors;
std::string g_first_since_mark;  // guarded by g_errors_mutex

// A broken frame can raise the same error hundreds of thousands of times; the first few lines
// say what is wrong, the rest would only bury it.
constexpr std::size_t kLoggedErrors = 20;

void log_gl_error(const std::string& line) {
  const std::size_t seen = g_error_count.load();
  if (seen < kLoggedErrors) log_error("{}", line);
  else if (seen == kLoggedErrors) log_error("further GL errors are counted but not logged");
}

void record_error(std::string message) {
  {
    std::lock_guard lock(g_errors_mutex);
    if (g_first_since_mark.empty()) g_first_since_mark = message;
  }
  ++g_error_count;
  if (!g_recording) return;
  std::lock_guard lock(g_errors_mutex);
  g_errors.push_back(std::move(message));
}

const char* source_name(GLenum source) {
  switch (source) {
    case GL_DEBUG_SOURCE_API: return "api";
    case GL_DEBUG_SOURCE_WINDOW_SYSTEM: return "window-system";
    case GL_DEBUG_SOURCE_SHADER_COMPILER: return "shader-compiler";
    case GL_DEBUG_SOURCE_THIRD_PARTY: return "third-party";
    case GL_DEBUG_SOURCE_APPLICATION: return "application";
    default: return "other";
  }
}

const char* type_name(GLenum type) {
  switch (type) {
    case GL_DEBUG_TYPE_ERROR: return "error";
    case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR: return "deprecated";
    case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR: return "undefined-behaviour";
    case GL_DEBUG_TYPE_PORTABILITY: return "portability";
    case GL_DEBUG_TYPE_PERFORMANCE: return "performance";
    case GL_DEBUG_TYPE_MARKER: return "marker";
    default: return "other";
  }
}

void GLAPIENTRY debug_callback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                               const GLchar* message, const void* /*user*/) {
  const std::string_view text(message, length >= 0 ? static_cast<std::size_t>(length) : std::strlen(message));
  const std::string line = fmt::format("GL {} {} #{}: {}", source_name(source), type_name(type), id, text);
  // Compile and link failures reach the caller as Result errors with file:line mapping; they
  // are not GL errors and must not fail a test that provokes them on purpose.
  const bool is_error = type == GL_DEBUG_TYPE_ERROR && source != GL_DEBUG_SOURCE_SHADER_COMPILER;
  if (source == GL_DEBUG_SOURCE_SHADER_COMPILER) {
    log_debug("{}", line);  // the caller gets the mapped log in its Result
  } else if (is_error) {
    log_gl_error(line);
    record_error(line);
  } else if (severity == GL_DEBUG_SEVERITY_HIGH || type == GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR) {
    log_warn("{}", line);
  } else if (severity != GL_DEBUG_SEVERITY_NOTIFICATION) {
    log_debug("{}", line);
  }
}

}  // namespace

void install_debug_output() {
  GLint flags = 0;
  glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
  if ((flags & GL_CONTEXT_FLAG_DEBUG_BIT) == 0) {
    log_debug("GL context is not a debug context; debug output may be silent");
  }
  glEnable(GL_DEBUG_OUTPUT);
  // Synchronous so the message arrives inside the offending call (useful in a debugger and
  // so tests attribute errors to the right test).
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(debug_callback, nullptr);
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

void set_gl_error_recording(bool on) { g_recording = on; }
bool gl_error_recording() { return g_recording; }
std::size_t gl_error_count() { return g_error_count; }

std::size_t gl_error_mark() {
  std::lock_guard lock(g_errors_mutex);
  g_first_since_mark.clear();
  return g_error_count;
}

Status check_frame_gl_errors(std::size_t mark, std::string_view where) {
  const Status drained = check_gl_errors(where);
  const std::size_t errors = gl_error_count() - mark;
  if (errors == 0) return ok_status();
  std::string first;
  {
    std::lock_guard lock(g_errors_mutex);
    first = g_first_since_mark;
  }
  std::string message = fmt::format("{} GL error(s) during {}; the picture cannot be trusted. First: {}", errors, where,
                                    first.empty() && !drained.ok() ? drained.error().message : first);
  if (message.find("GL_OUT_OF_MEMORY") != std::string::npos || message.find("out of memory") != std::string::npos) {
    message += " (out of GPU memory: use a smaller --size, smaller maps or fewer instances)";
  }
  return make_error(ErrorCode::kGl, message);
}

std::vector<std::string> take_gl_errors() {
  std::lock_guard lock(g_errors_mutex);
  std::vector<std::string> out;
  out.swap(g_errors);
  return out;
}

const char* gl_error_name(unsigned int code) {
  switch (code) {
    case GL_NO_ERROR: return "GL_NO_ERROR";
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    default: return "unknown GL error";
  }
}

Status check_gl_errors(std::string_view where) {
  std::string codes;
  // glGetError keeps one flag per error kind; a handful of iterations drains them all.
  for (int i = 0; i < 16; ++i) {
    const GLenum code = glGetError();
    if (code == GL_NO_ERROR) break;
    const std::string line = fmt::format("glGetError at {}: {} (0x{:x})", where, gl_error_name(code), code);
    log_gl_error(line);
    record_error(line);
    codes += codes.empty() ? "" : ", ";
    codes += gl_error_name(code);
  }
  if (codes.empty()) return ok_status();
  return make_error(ErrorCode::kGl, fmt::format("GL error(s) at {}: {}", where, codes));
}

}  // namespace sylva::render

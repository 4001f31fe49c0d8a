#pragma once
// GL debug output (KHR_debug, core in 4.3) routed into the sylva log, and an error recorder
// that tests use so that any GL error fails the test that caused it.
//
// install_debug_output() is called by GlContext creation when options.debug is set. Messages of
// type ERROR (and glGetError codes seen by check_gl_errors) are counted; when recording is on
// they are also kept so a test can print them. High-severity messages log as warnings,
// notifications as debug.

#include <sylva/core/result.hpp>

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::render {

// Enables GL_DEBUG_OUTPUT (synchronous) with a callback into the sylva log. Needs a current
// context. Safe to call more than once.
void install_debug_output();

// When recording is on, every GL error message is stored until take_gl_errors(). Off by default.
void set_gl_error_recording(bool on);
bool gl_error_recording();

// Total number of GL errors seen since start (debug callback + check_gl_errors).
std::size_t gl_error_count();

// For the frame loops of the player, editor and bench (only the first 20 GL error lines of a
// process are logged; every error is counted):
//   const std::size_t mark = gl_error_mark();     // before scene creation or a frame
//   ... GL work ...
//   SYLVA_TRY(check_frame_gl_errors(mark, "frame 3"));
// check_frame_gl_errors drains glGetError() and returns kGl when any GL error happened since the
// mark, with the count and the first message since the mark (an out-of-memory error says so and
// what to reduce). A run whose frame had a GL error must fail (exit 1), not write a picture.
std::size_t gl_error_mark();
Status check_frame_gl_errors(std::size_t mark, std::string_view where);

// Returns and clears the recorded error messages.
std::vector<std::string> take_gl_errors();

// Drains glGetError(); every code is logged and recorded with `where` in the message.
// Returns kGl naming `where` and the codes when there were any.
Status check_gl_errors(std::string_view where);

// "GL_INVALID_ENUM" etc.
const char* gl_error_name(unsigned int code);

}  // namespace sylva::render

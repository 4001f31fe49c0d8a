#pragma once
// Shader sources and programs (DESIGN.md §2 "Shaders").
//
// Every module's shaders/ folder is embedded at build time by cmake/embed_shaders.cmake into a
// generated .cpp that calls register_embedded_shaders() from
// sylva::render::embedded::register_<module>_shaders(). A module calls its register function
// once before building programs (calling it again is harmless). Names are "<module>/<path
// relative to the module's shaders/ folder>", e.g. "render/lib/sky.glsl".
//
// Preprocessing: `#include "render/lib/x.glsl"` (a full name, or a path relative to the
// including file) is expanded with once-semantics (a file included twice in one stage is
// expanded once; include cycles are errors) and `#line` directives, so compile errors name the
// original file and line: "render/lib/fog.glsl:12(3): error: ...". File i of a stage gets the
// #line range i * kShaderLineStride + line, because Mesa reports source-string number 0 for
// most errors even after `#line N S`; the line number alone then identifies the file. Defines are inserted after
// the #version line. The stage is taken from the extension: .vert .tesc .tese .geom .frag .comp.
//
// Hot reload: when enabled (default on in builds configured with SYLVA_HOT_RELOAD, which
// defines SYLVA_SHADER_SOURCE_DIR), sources are read from the file each embedded shader came
// from (its absolute source path) when that file exists, and Program::reload_if_changed()
// rebuilds a program when any file it used changed on disk. A failed rebuild keeps the old
// program and logs the error, so a typo never kills the running editor.
//
// Failure: unknown names (kNotFound, listing the name and the including file:line), include
// cycles and malformed #include lines (kParse with file:line), compile and link errors (kGl,
// with every driver message mapped to the original file:line).

#include <sylva/core/result.hpp>
#include <sylva/render/gl_handle.hpp>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include <filesystem>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace sylva::render {

struct EmbeddedShader {
  std::string_view name;         // "<module>/<relative path>"
  std::string_view source_path;  // absolute path of the file in the source tree at build time
  std::string_view source;       // the file's text
};

// Adds (or replaces, by name) shaders in the global library. Thread-safe. The views must stay
// valid for the program's lifetime (the generated tables are static).
void register_embedded_shaders(std::span<const EmbeddedShader> shaders);

namespace embedded {
void register_render_shaders();
}  // namespace embedded

// Registers an in-memory source under `name` (tests, tools, generated code). The text is copied.
void register_shader_source(std::string_view name, std::string_view source);

// Whether sources are read from their source-tree files when present (see above).
void set_shader_hot_reload(bool on);
bool shader_hot_reload();

// True when `name` is registered.
bool has_shader(std::string_view name);
// All registered names, sorted (for tools and the editor).
std::vector<std::string> shader_names();

// The current text of one file: from its source file when hot reload is on and the file
// exists, else the embedded text.
Result<std::string> shader_source(std::string_view name);

// GL stage for a name's extension (GL_VERTEX_SHADER ...), or 0 if unknown.
GLenum shader_stage_for(std::string_view name);

// Line-number stride between the files of one preprocessed stage (files are < 100000 lines).
inline constexpr int kShaderLineStride = 100000;

using ShaderDefines = std::vector<std::pair<std::string, std::string>>;  // #define first second

struct PreprocessedShader {
  std::string text;                 // what is handed to glShaderSource
  std::vector<std::string> files;   // source-string number i -> file name (for #line mapping)
};

// Expands includes and inserts defines. Errors as described at the top.
Result<PreprocessedShader> preprocess_shader(std::string_view name, const ShaderDefines& defines = {});

// Rewrites driver messages "S:L(C): ..." / "S(L) : ..." into "file:line(C): ..." using `files`
// (file = L / kShaderLineStride, line = L % kShaderLineStride; S is ignored). Lines without a
// location, or naming a file index outside `files`, are kept as they are.
std::string map_shader_log(std::string_view log, std::span<const std::string> files);

struct ProgramDeleter {
  void operator()(GLuint id) const { glDeleteProgram(id); }
};

class Program {
 public:
  Program() = default;

  // Compiles and links one program from stage file names, e.g.
  //   Program::create({"render/sky.vert", "render/sky.frag"});
  static Result<Program> create(std::initializer_list<std::string_view> stages, const ShaderDefines& defines = {});
  static Result<Program> create(std::span<const std::string> stages, const ShaderDefines& defines = {});

  GLuint id() const { return handle_.get(); }
  explicit operator bool() const { return static_cast<bool>(handle_); }
  void use() const;

  // Hot reload: rebuilds when any file used by the program changed on disk since the last
  // build. Returns true when the program was replaced. A failed rebuild returns false, keeps
  // the old program and logs the mapped error (also available via last_reload_error()).
  bool reload_if_changed();
  const std::string& last_reload_error() const { return last_reload_error_; }

  // Uniform location, cached; -1 (and one warning per name) when the uniform is not active.
  GLint location(std::string_view name) const;

  // glProgramUniform* (DSA, no use() needed). Unknown names are ignored after the warning.
  void set(std::string_view name, int v) const;
  void set(std::string_view name, unsigned v) const;
  void set(std::string_view name, float v) const;
  void set(std::string_view name, bool v) const { set(name, v ? 1 : 0); }
  void set(std::string_view name, const glm::vec2& v) const;
  void set(std::string_view name, const glm::vec3& v) const;
  void set(std::string_view name, const glm::vec4& v) const;
  void set(std::string_view name, const glm::ivec2& v) const;
  void set(std::string_view name, const glm::ivec3& v) const;
  void set(std::string_view name, const glm::mat3& v) const;
  void set(std::string_view name, const glm::mat4& v) const;
  void set(std::string_view name, std::span<const glm::mat4> v) const;
  void set(std::string_view name, std::span<const glm::vec4> v) const;
  void set(std::string_view name, std::span<const float> v) const;

  // Names of the files used (stages and their includes) at the last successful build.
  const std::vector<std::string>& files() const { return files_; }

 private:
  struct Watched {
    std::filesystem::path path;
    std::filesystem::file_time_type time;
  };
  GlHandle<ProgramDeleter> handle_;
  std::vector<std::string> stages_;
  ShaderDefines defines_;
  std::vector<std::string> files_;
  std::vector<Watched> watched_;
  std::string last_reload_error_;
  mutable std::unordered_map<std::string, GLint> locations_;
};

}  // namespace sylva::render

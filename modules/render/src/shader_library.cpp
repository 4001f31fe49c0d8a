// Shader registry, #include preprocessor with #line mapping, programs and hot reload
// (shader_library.hpp).
#include <sylva/render/shader_library.hpp>

#include <sylva/core/log.hpp>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <system_error>

namespace sylva::render {
namespace {

struct Entry {
  std::string source_path;
  std::string text;
};

std::mutex g_mutex;
std::map<std::string, Entry, std::less<>>& registry() {
  static std::map<std::string, Entry, std::less<>> r;
  return r;
}

#ifdef SYLVA_SHADER_SOURCE_DIR
std::atomic<bool> g_hot_reload{true};
#else
std::atomic<bool> g_hot_reload{false};
#endif

bool read_file(const std::string& path, std::string& out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream ss;
  ss << in.rdbuf();
  out = ss.str();
  return static_cast<bool>(in) || in.eof();
}

// The registered entry for `name` (copied under the lock), or false.
bool lookup(std::string_view name, Entry& out) {
  std::lock_guard lock(g_mutex);
  auto it = registry().find(name);
  if (it == registry().end()) return false;
  out = it->second;
  return true;
}

std::string trim(std::string_view s) {
  std::size_t b = 0;
  std::size_t e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return std::string(s.substr(b, e - b));
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) {
      if (pos < text.size()) lines.push_back(text.substr(pos));
      break;
    }
    std::string line = text.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(std::move(line));
    pos = end + 1;
  }
  return lines;
}

// "a/b/../c" -> "a/c"; keeps names in the "<module>/<path>" form.
std::string normalise_name(const std::string& name) {
  std::vector<std::string> parts;
  std::size_t pos = 0;
  while (pos <= name.size()) {
    std::size_t end = name.find('/', pos);
    if (end == std::string::npos) end = name.size();
    std::string part = name.substr(pos, end - pos);
    if (part == "..") {
      if (!parts.empty()) parts.pop_back();
    } else if (!part.empty() && part != ".") {
      parts.push_back(part);
    }
    pos = end + 1;
  }
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : "/") + p;
  return out;
}

// What a line is, for the preprocessor: the directive keyword after '#', or empty.
std::string directive_of(const std::string& line) {
  std::size_t i = 0;
  while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
  if (i >= line.size() || line[i] != '#') return {};
  ++i;
  while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
  std::size_t b = i;
  while (i < line.size() && std::isalpha(static_cast<unsigned char>(line[i]))) ++i;
  return line.substr(b, i - b);
}

// Updates the block-comment state across one line; returns whether the line starts inside one.
bool advance_comment_state(const std::string& line, bool& in_block) {
  const bool started_inside = in_block;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (in_block) {
      if (i + 1 < line.size() && line[i] == '*' && line[i + 1] == '/') {
        in_block = false;
        ++i;
      }
    } else {
      if (i + 1 < line.size() && line[i] == '/' && line[i + 1] == '/') break;
      if (i + 1 < line.size() && line[i] == '/' && line[i + 1] == '*') {
        in_block = true;
        ++i;
      }
    }
  }
  return started_inside;
}

// First #line number of file `index`: files get disjoint line ranges, so a reported line
// number alone identifies the file (Mesa's compiler resets the source-string number to 0 for
// most messages even after "#line N S", so S cannot be trusted).
int line_base(int index) { return index * kShaderLineStride; }

struct Preprocessor {
  std::vector<std::string> files;  // source-string number -> name
  std::vector<std::string> stack;  // include chain, for cycle detection
  std::vector<std::string> done;   // once-semantics: files already expanded in this stage
  std::string out;

  int file_index(const std::string& name) {
    auto it = std::find(files.begin(), files.end(), name);
    if (it != files.end()) return static_cast<int>(it - files.begin());
    files.push_back(name);
    return static_cast<int>(files.size()) - 1;
  }

  std::string resolve(const std::string& target, const std::string& from) {
    const std::string direct = normalise_name(target);
    if (has_shader(direct)) return direct;
    const std::size_t slash = from.rfind('/');
    if (slash != std::string::npos) {
      const std::string relative = normalise_name(from.substr(0, slash + 1) + target);
      if (has_shader(relative)) return relative;
    }
    return {};
  }

  // Expands `name` into out. `top` is the stage file (its #version was already emitted and is
  // blanked here).
  Status expand(const std::string& name, bool top) {
    Result<std::string> text = shader_source(name);
    if (!text.ok()) return text.error();
    stack.push_back(name);
    done.push_back(name);
    const int index = file_index(name);
    out += fmt::format("#line {} {}\n", line_base(index) + 1, index);
    const std::vector<std::string> lines = split_lines(*text);
    bool in_block = false;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const std::string& line = lines[i];
      const int line_no = static_cast<int>(i) + 1;
      const bool commented = advance_comment_state(line, in_block);
      const std::string dir = commented ? std::string() : directive_of(line);
      if (dir == "version") {
        if (!top) {
          return make_error(ErrorCode::kParse,
                            fmt::format("{}:{}: #version in an included file (only the stage file has one)", name, line_no));
        }
        out += '\n';
        continue;
      }
      if (dir == "pragma" && trim(line).ends_with("once")) {
        out += '\n';
        continue;
      }
      if (dir != "include") {
        out += line;
        out += '\n';
        continue;
      }
      const std::size_t q1 = line.find('"');
      const std::size_t q2 = q1 == std::string::npos ? std::string::npos : line.find('"', q1 + 1);
      if (q1 == std::string::npos || q2 == std::string::npos || q2 == q1 + 1) {
        return make_error(ErrorCode::kParse,
                          fmt::format("{}:{}: malformed #include (expected #include \"module/path.glsl\")", name, line_no));
      }
      const std::string target = line.substr(q1 + 1, q2 - q1 - 1);
      const std::string resolved = resolve(target, name);
      if (resolved.empty()) {
        return make_error(ErrorCode::kNotFound,
                          fmt::format("{}:{}: cannot include \"{}\": no such shader (registered names are "
                                      "\"<module>/<path>\"; was the module's register_<module>_shaders() called?)",
                                      name, line_no, target));
      }
      if (std::find(stack.begin(), stack.end(), resolved) != stack.end()) {
        std::string chain;
        for (const std::string& s : stack) chain += s + " -> ";
        return make_error(ErrorCode::kParse,
                          fmt::format("{}:{}: #include cycle: {}{}", name, line_no, chain, resolved));
      }
      if (std::find(done.begin(), done.end(), resolved) == done.end()) {
        SYLVA_TRY(expand(resolved, false));
      }
      // Back in this file: the next line is line_no + 1.
      out += fmt::format("#line {} {}\n", line_base(index) + line_no + 1, index);
    }
    stack.pop_back();
    return ok_status();
  }
};

// Matches "S:L(C)", "S(L)" or "S:L:" at `pos` (S = source-string number). Returns the length
// consumed, 0 when there is no location.
std::size_t parse_location(std::string_view s, std::size_t pos, int& file, int& line, int& col) {
  auto number = [&](std::size_t& p, int& v) {
    const std::size_t b = p;
    v = 0;
    while (p < s.size() && std::isdigit(static_cast<unsigned char>(s[p])) && p - b < 9) v = v * 10 + (s[p++] - '0');
    return p > b;
  };
  std::size_t p = pos;
  col = -1;
  if (!number(p, file)) return 0;
  if (p < s.size() && s[p] == ':') {
    ++p;
    if (!number(p, line)) return 0;
    if (p < s.size() && s[p] == '(') {
      std::size_t q = p + 1;
      int c = 0;
      if (number(q, c) && q < s.size() && s[q] == ')') {
        col = c;
        p = q + 1;
      }
    }
    return p - pos;
  }
  if (p < s.size() && s[p] == '(') {
    ++p;
    if (!number(p, line) || p >= s.size() || s[p] != ')') return 0;
    return p + 1 - pos;
  }
  return 0;
}

void gather_watch_list(const std::vector<std::string>& files, std::vector<std::filesystem::path>& paths) {
  for (const std::string& f : files) {
    Entry e;
    if (lookup(f, e) && !e.source_path.empty()) paths.emplace_back(e.source_path);
  }
}

std::string shader_info_log(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  log.resize(std::strlen(log.c_str()));
  return log;
}

std::string program_info_log(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  glGetProgramInfoLog(program, length, nullptr, log.data());
  log.resize(std::strlen(log.c_str()));
  return log;
}

struct BuiltProgram {
  GLuint id = 0;
  std::vector<std::string> files;
};

Result<BuiltProgram> build(std::span<const std::string> stages, const ShaderDefines& defines) {
  if (stages.empty()) return make_error(ErrorCode::kInvalidArgument, "program: no shader stages given");
  std::vector<GLuint> shaders;
  std::vector<std::string> all_files;
  auto cleanup = [&] {
    for (GLuint s : shaders) glDeleteShader(s);
  };
  std::string stage_list;
  for (const std::string& stage_name : stages) {
    stage_list += (stage_list.empty() ? "" : ", ") + stage_name;
    const GLenum stage = shader_stage_for(stage_name);
    if (stage == 0) {
      cleanup();
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: unknown shader stage (extension must be .vert .tesc .tese .geom .frag .comp)",
                                    stage_name));
    }
    Result<PreprocessedShader> pre = preprocess_shader(stage_name, defines);
    if (!pre.ok()) {
      cleanup();
      return pre.error();
    }
    GLuint shader = glCreateShader(stage);
    shaders.push_back(shader);
    const char* text = pre->text.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    const std::string log = shader_info_log(shader);
    if (ok != GL_TRUE) {
      cleanup();
      return make_error(ErrorCode::kGl, fmt::format("compiling {} failed:\n{}", stage_name,
                                                    map_shader_log(log, pre->files)));
    }
    if (!trim(log).empty()) log_debug("compiling {}:\n{}", stage_name, map_shader_log(log, pre->files));
    for (const std::string& f : pre->files) {
      if (std::find(all_files.begin(), all_files.end(), f) == all_files.end()) all_files.push_back(f);
    }
  }
  GLuint program = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(program, s);
  glLinkProgram(program);
  for (GLuint s : shaders) glDetachShader(program, s);
  cleanup();
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = program_info_log(program);
    glDeleteProgram(program);
    return make_error(ErrorCode::kGl, fmt::format("linking [{}] failed:\n{}", stage_list, trim(log)));
  }
  return BuiltProgram{program, std::move(all_files)};
}

}  // namespace

void register_embedded_shaders(std::span<const EmbeddedShader> shaders) {
  std::lock_guard lock(g_mutex);
  for (const EmbeddedShader& s : shaders) {
    registry()[std::string(s.name)] = Entry{std::string(s.source_path), std::string(s.source)};
  }
}

void register_shader_source(std::string_view name, std::string_view source) {
  std::lock_guard lock(g_mutex);
  registry()[std::string(name)] = Entry{std::string(), std::string(source)};
}

void set_shader_hot_reload(bool on) { g_hot_reload = on; }
bool shader_hot_reload() { return g_hot_reload; }

bool has_shader(std::string_view name) {
  std::lock_guard lock(g_mutex);
  return registry().find(name) != registry().end();
}

std::vector<std::string> shader_names() {
  std::lock_guard lock(g_mutex);
  std::vector<std::string> names;
  for (const auto& [name, entry] : registry()) names.push_back(name);
  return names;
}

Result<std::string> shader_source(std::string_view name) {
  Entry e;
  if (!lookup(name, e)) {
    return make_error(ErrorCode::kNotFound,
                      fmt::format("shader \"{}\" is not registered (names are \"<module>/<path>\"; call the module's "
                                  "register_<module>_shaders() first)",
                                  name));
  }
  if (g_hot_reload && !e.source_path.empty()) {
    std::string text;
    if (read_file(e.source_path, text)) return text;
  }
  return e.text;
}

GLenum shader_stage_for(std::string_view name) {
  if (name.ends_with(".vert")) return GL_VERTEX_SHADER;
  if (name.ends_with(".tesc")) return GL_TESS_CONTROL_SHADER;
  if (name.ends_with(".tese")) return GL_TESS_EVALUATION_SHADER;
  if (name.ends_with(".geom")) return GL_GEOMETRY_SHADER;
  if (name.ends_with(".frag")) return GL_FRAGMENT_SHADER;
  if (name.ends_with(".comp")) return GL_COMPUTE_SHADER;
  return 0;
}

Result<PreprocessedShader> preprocess_shader(std::string_view name, const ShaderDefines& defines) {
  Result<std::string> text = shader_source(name);
  if (!text.ok()) return text.error();
  // The #version line must come first; defines follow it, then the file from line 1 with its
  // own #version blanked so line numbers stay those of the file.
  std::string version;
  bool in_block = false;
  const std::vector<std::string> lines = split_lines(*text);
  for (const std::string& line : lines) {
    const bool commented = advance_comment_state(line, in_block);
    if (!commented && directive_of(line) == "version") {
      version = trim(line);
      break;
    }
  }
  if (version.empty()) {
    return make_error(ErrorCode::kParse, fmt::format("{}:1: no #version line (stage files start with #version 450 core)",
                                                     name));
  }
  Preprocessor pp;
  pp.out = version + "\n";
  for (const auto& [key, value] : defines) {
    if (key.empty() || key.find_first_of(" \t\n") != std::string::npos) {
      return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: bad define name \"{}\"", name, key));
    }
    pp.out += fmt::format("#define {} {}\n", key, value);
  }
  SYLVA_TRY(pp.expand(std::string(name), true));
  return PreprocessedShader{std::move(pp.out), std::move(pp.files)};
}

std::string map_shader_log(std::string_view log, std::span<const std::string> files) {
  std::string out;
  std::size_t pos = 0;
  while (pos < log.size()) {
    std::size_t end = log.find('\n', pos);
    if (end == std::string_view::npos) end = log.size();
    std::string_view line = log.substr(pos, end - pos);
    // Optional "ERROR: " / "WARNING: " prefixes (other drivers) before the location.
    std::size_t at = 0;
    for (std::string_view prefix : {"ERROR: ", "WARNING: "}) {
      if (line.starts_with(prefix)) at = prefix.size();
    }
    int file = 0;
    int line_no = 0;
    int col = -1;
    const std::size_t used = parse_location(line, at, file, line_no, col);
    // The line number carries the file (see line_base); the printed source number is ignored.
    file = line_no / kShaderLineStride;
    line_no = line_no % kShaderLineStride;
    if (used > 0 && static_cast<std::size_t>(file) < files.size()) {
      out += line.substr(0, at);
      out += files[static_cast<std::size_t>(file)];
      out += fmt::format(":{}", line_no);
      if (col >= 0) out += fmt::format("({})", col);
      std::string_view rest = line.substr(at + used);
      if (!rest.empty() && rest.front() != ':' && rest.front() != ' ') out += ':';
      out += rest;
    } else {
      out += line;
    }
    out += '\n';
    pos = end + 1;
  }
  while (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}

Result<Program> Program::create(std::initializer_list<std::string_view> stages, const ShaderDefines& defines) {
  std::vector<std::string> names;
  for (std::string_view s : stages) names.emplace_back(s);
  return create(std::span<const std::string>(names), defines);
}

Result<Program> Program::create(std::span<const std::string> stages, const ShaderDefines& defines) {
  Result<BuiltProgram> built = build(stages, defines);
  if (!built.ok()) return built.error();
  Program p;
  p.handle_ = GlHandle<ProgramDeleter>(built->id);
  p.stages_.assign(stages.begin(), stages.end());
  p.defines_ = defines;
  p.files_ = std::move(built->files);
  std::vector<std::filesystem::path> paths;
  gather_watch_list(p.files_, paths);
  for (const std::filesystem::path& path : paths) {
    std::error_code ec;
    const auto time = std::filesystem::last_write_time(path, ec);
    if (!ec) p.watched_.push_back({path, time});
  }
  return p;
}

void Program::use() const { glUseProgram(id()); }

bool Program::reload_if_changed() {
  if (!shader_hot_reload() || !handle_) return false;
  bool changed = false;
  for (Watched& w : watched_) {
    std::error_code ec;
    const auto time = std::filesystem::last_write_time(w.path, ec);
    if (!ec && time != w.time) {
      w.time = time;  // remember even if the rebuild fails, so a broken file is reported once
      changed = true;
    }
  }
  if (!changed) return false;
  Result<Program> rebuilt = create(std::span<const std::string>(stages_), defines_);
  if (!rebuilt.ok()) {
    last_reload_error_ = rebuilt.error().message;
    log_error("shader hot reload kept the previous program: {}", last_reload_error_);
    return false;
  }
  handle_ = std::move(rebuilt->handle_);
  files_ = std::move(rebuilt->files_);
  watched_ = std::move(rebuilt->watched_);
  locations_.clear();
  last_reload_error_.clear();
  log_info("shader hot reload: rebuilt [{}]", fmt::join(stages_, ", "));
  return true;
}

GLint Program::location(std::string_view name) const {
  auto it = locations_.find(std::string(name));
  if (it != locations_.end()) return it->second;
  const std::string key(name);
  const GLint loc = glGetUniformLocation(id(), key.c_str());
  if (loc < 0) log_warn("uniform \"{}\" is not active in program [{}]", key, fmt::join(stages_, ", "));
  locations_.emplace(key, loc);
  return loc;
}

void Program::set(std::string_view name, int v) const {
  if (GLint l = location(name); l >= 0) glProgramUniform1i(id(), l, v);
}
void Program::set(std::string_view name, unsigned v) const {
  if (GLint l = location(name); l >= 0) glProgramUniform1ui(id(), l, v);
}
void Program::set(std::string_view name, float v) const {
  if (GLint l = location(name); l >= 0) glProgramUniform1f(id(), l, v);
}
void Program::set(std::string_view name, const glm::vec2& v) const {
  if (GLint l = location(name); l >= 0) glProgramUniform2fv(id(), l, 1, glm::value_ptr(v));
}
void Program::set(std::string_view name, const glm::vec3& v) const {
  if (GLint l = location(name); l >= 0) glProgramUniform3fv(id(), l, 1, glm::value_ptr(v));
}
void Program::set(std::string_view name, const glm::vec4& v) const {
  if (GLint l = location(name); l >= 0) glProgramUniform4fv(id(), l, 1, glm::value_ptr(v));
}
void Program::set(std::string_view name, const glm::ivec2& v) const {
  if (GLint l = location(name); l >= 0) glProgramUniform2iv(id(), l, 1, glm::value_ptr(v));
}
void Program::set(std::string_view name, const glm::ivec3& v) const {
  if (GLint l = location(name); l >= 0) glProgramUniform3iv(id(), l, 1, glm::value_ptr(v));
}
void Program::set(std::string_view name, const glm::mat3& v) const {
  if (GLint l = location(name); l >= 0) glProgramUniformMatrix3fv(id(), l, 1, GL_FALSE, glm::value_ptr(v));
}
void Program::set(std::string_view name, const glm::mat4& v) const {
  if (GLint l = location(name); l >= 0) glProgramUniformMatrix4fv(id(), l, 1, GL_FALSE, glm::value_ptr(v));
}
void Program::set(std::string_view name, std::span<const glm::mat4> v) const {
  if (GLint l = location(name); l >= 0 && !v.empty()) {
    glProgramUniformMatrix4fv(id(), l, static_cast<GLsizei>(v.size()), GL_FALSE, glm::value_ptr(v[0]));
  }
}
void Program::set(std::string_view name, std::span<const glm::vec4> v) const {
  if (GLint l = location(name); l >= 0 && !v.empty()) {
    glProgramUniform4fv(id(), l, static_cast<GLsizei>(v.size()), glm::value_ptr(v[0]));
  }
}
void Program::set(std::string_view name, std::span<const float> v) const {
  if (GLint l = location(name); l >= 0 && !v.empty()) glProgramUniform1fv(id(), l, static_cast<GLsizei>(v.size()), v.data());
}

}  // namespace sylva::render

#include "script.hpp"

#include <sylva/core/render_size.hpp>

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <map>

namespace sylva::editor {
namespace {

struct Arity {
  int min;
  int max;  // -1: unbounded
  const char* usage;
};

const std::map<std::string, Arity, std::less<>>& commands() {
  static const std::map<std::string, Arity, std::less<>> table = {
      {"load", {1, 1, "load PATH"}},
      {"new", {0, 0, "new"}},
      {"load_default", {0, 0, "load_default"}},
      {"add_module", {1, 1, "add_module NAME"}},
      {"remove_module", {1, 1, "remove_module NAME"}},
      {"set", {1, 2, "set PATH VALUE"}},
      {"brush", {1, -1, "brush KEY=VALUE..."}},
      {"stroke", {2, -1, "stroke MAP X,Z [X,Z ...]"}},
      {"undo", {0, 1, "undo [N]"}},
      {"redo", {0, 1, "redo [N]"}},
      {"camera", {2, 6, "camera X Y Z [YAW PITCH [FOV]] | camera bookmark NAME"}},
      {"bookmark", {1, 1, "bookmark NAME"}},
      {"frames", {1, 1, "frames N"}},
      {"debug", {2, 2, "debug VIEW on|off"}},
      {"screenshot", {1, 2, "screenshot PATH [WxH]"}},
      {"screenshot_ui", {1, 1, "screenshot_ui PATH"}},
      {"export_tree", {1, 1, "export_tree FOLDER"}},
      {"import_terrain", {1, 4, "import_terrain PATH [bake OUT [hold]]"}},
      {"wait_import", {0, 1, "wait_import [MAX_FRAMES]"}},
      {"cancel_import", {0, 0, "cancel_import"}},
      {"save", {0, 1, "save [PATH]"}},
      {"copy_file", {2, 2, "copy_file FROM TO"}},
      {"wait_reload", {1, 2, "wait_reload FILE [MAX_FRAMES]"}},
      {"wait_stream", {0, 1, "wait_stream [MAX_FRAMES]"}},
      {"print_stats", {1, 1, "print_stats MODULE"}},
      {"preview", {0, -1, "preview [KEY=VALUE...]"}},
      {"expect", {2, 2, "expect PATH VALUE"}},
      {"expect_unsaved", {1, 1, "expect_unsaved yes|no"}},
      {"print", {0, -1, "print TEXT..."}},
      {"quit", {0, 0, "quit"}},
  };
  return table;
}

Result<double> parse_number(std::string_view text) {
  double v = 0.0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(v)) {
    return make_error(ErrorCode::kParse, fmt::format("expected a number, got \"{}\"", text));
  }
  return v;
}

Result<int> parse_count(std::string_view text, int min, int max) {
  int v = 0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (text.empty() || ec != std::errc() || ptr != end || v < min || v > max) {
    return make_error(ErrorCode::kParse, fmt::format("expected a whole number in {}..{}, got \"{}\"", min, max, text));
  }
  return v;
}

}  // namespace

std::string script_location(std::string_view source, int line) { return fmt::format("{}:{}", source, line); }

Result<std::vector<std::string>> split_words(std::string_view line) {
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    if (i >= line.size() || line[i] == '#') break;
    std::string word;
    if (line[i] == '"') {
      ++i;
      bool closed = false;
      while (i < line.size()) {
        if (line[i] == '\\' && i + 1 < line.size()) {
          word += line[i + 1];
          i += 2;
          continue;
        }
        if (line[i] == '"') {
          closed = true;
          ++i;
          break;
        }
        word += line[i++];
      }
      if (!closed) return make_error(ErrorCode::kParse, "unterminated quote");
    } else {
      while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') word += line[i++];
    }
    words.push_back(std::move(word));
  }
  return words;
}

Result<glm::dvec2> parse_point(std::string_view text) {
  const auto comma = text.find(',');
  if (comma == std::string_view::npos) {
    return make_error(ErrorCode::kParse, fmt::format("expected a world point X,Z, got \"{}\"", text));
  }
  auto x = parse_number(text.substr(0, comma));
  auto z = parse_number(text.substr(comma + 1));
  if (!x.ok() || !z.ok()) return make_error(ErrorCode::kParse, fmt::format("expected a world point X,Z, got \"{}\"", text));
  return glm::dvec2(*x, *z);
}

Result<glm::ivec2> parse_size(std::string_view text) {
  auto size = parse_render_size(text, "size");
  if (!size.ok()) return make_error(ErrorCode::kParse, size.error().message);
  return size;
}

Result<std::vector<ScriptCommand>> parse_script(std::string_view text, std::string_view source) {
  std::vector<ScriptCommand> out;
  std::vector<std::string> errors;
  int line_number = 0;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view line = text.substr(start, end - start);
    ++line_number;
    start = end + 1;
    auto fail = [&](const std::string& message) { errors.push_back(script_location(source, line_number) + ": " + message); };
    auto words = split_words(line);
    if (line.find('\0') != std::string_view::npos) {
      // A path would end at the NUL when opened: refuse rather than act on part of the line.
      fail("the line holds a NUL byte (is this a binary file?)");
    } else if (!words.ok()) {
      fail(words.error().message);
    } else if (!words->empty()) {
      ScriptCommand c;
      c.line = line_number;
      c.name = (*words)[0];
      c.args.assign(words->begin() + 1, words->end());
      const auto it = commands().find(c.name);
      if (it == commands().end()) {
        std::string known;
        for (const auto& [name, arity] : commands()) known += (known.empty() ? "" : ", ") + name;
        fail(fmt::format("unknown command \"{}\" (commands: {})", c.name, known));
      } else {
        const Arity& a = it->second;
        const int n = static_cast<int>(c.args.size());
        if (n < a.min || (a.max >= 0 && n > a.max)) {
          fail(fmt::format("{}: expected {}", c.name, a.usage));
        } else if (c.name == "stroke") {
          for (std::size_t k = 1; k < c.args.size(); ++k) {
            auto p = parse_point(c.args[k]);
            if (!p.ok()) {
              fail(fmt::format("stroke: point {}: {}", k, p.error().message));
              break;
            }
            c.points.push_back(*p);
          }
        } else if (c.name == "import_terrain" && n > 1 &&
                   (c.args[1] != "bake" || n < 3 || (n == 4 && c.args[3] != "hold"))) {
          fail("import_terrain: expected import_terrain PATH [bake OUT [hold]]");
        } else if ((c.name == "undo" || c.name == "redo" || c.name == "frames" || c.name == "wait_reload" ||
                    c.name == "wait_import" || c.name == "wait_stream") &&
                   n == (c.name == "wait_reload" ? 2 : 1)) {
          auto count = parse_count(c.args.back(), 1, 1000000);
          if (!count.ok()) fail(fmt::format("{}: {}", c.name, count.error().message));
          else c.count = *count;
        } else if (c.name == "set" && n == 1 && c.args[0].find('=') == std::string::npos) {
          fail("set: expected set PATH VALUE or set PATH=VALUE");
        } else if (c.name == "set" && n == 1) {
          const auto eq = c.args[0].find('=');
          if (eq == 0) {
            fail("set: the parameter path before '=' is empty");
          } else {
            c.args = {c.args[0].substr(0, eq), c.args[0].substr(eq + 1)};
          }
        } else if (c.name == "camera") {
          if (c.args[0] == "bookmark") {
            if (n != 2) fail("camera: expected camera bookmark NAME");
          } else if (n != 3 && n != 5 && n != 6) {
            fail("camera: expected camera X Y Z [YAW PITCH [FOV]]");
          } else {
            for (const std::string& a : c.args) {
              if (!parse_number(a).ok()) {
                fail(fmt::format("camera: expected a number, got \"{}\"", a));
                break;
              }
            }
          }
        } else if (c.name == "brush" || c.name == "preview") {
          for (const std::string& a : c.args) {
            if (a.find('=') == std::string::npos || a.front() == '=') {
              fail(fmt::format("{}: expected KEY=VALUE, got \"{}\"", c.name, a));
              break;
            }
          }
        } else if (c.name == "debug" && c.args[1] != "on" && c.args[1] != "off") {
          fail(fmt::format("debug: expected on or off, got \"{}\"", c.args[1]));
        } else if (c.name == "expect_unsaved" && c.args[0] != "yes" && c.args[0] != "no") {
          fail(fmt::format("expect_unsaved: expected yes or no, got \"{}\"", c.args[0]));
        } else if (c.name == "screenshot" && n == 2 && !parse_size(c.args[1]).ok()) {
          fail(fmt::format("screenshot: {}", parse_size(c.args[1]).error().message));
        }
        out.push_back(std::move(c));
      }
    }
    if (end >= text.size()) break;
  }
  if (!errors.empty()) {
    std::string all;
    for (const std::string& e : errors) all += (all.empty() ? "" : "\n") + e;
    return make_error(ErrorCode::kParse, std::move(all));
  }
  return out;
}

}  // namespace sylva::editor

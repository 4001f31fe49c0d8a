#include <sylva/voxel/lsystem.hpp>

#include "embedded_data.hpp"

#include <sylva/core/rng.hpp>

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <utility>

namespace sylva::voxel {

void LSystem::index_rules() {
  for (auto& v : by_letter_) v.clear();
  for (std::size_t i = 0; i < rules.size(); ++i) {
    by_letter_[static_cast<unsigned char>(rules[i].letter) & 127u].push_back(static_cast<int>(i));
  }
}

std::string LSystem::where() const { return fmt::format("{}:{}", source, line); }

namespace {

struct Token {
  std::string_view text;
  int column = 0;  // 1-based
};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }

std::vector<Token> tokens_of(std::string_view line) {
  std::vector<Token> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    if (i >= line.size()) break;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    out.push_back({line.substr(start, i - start), static_cast<int>(start) + 1});
  }
  return out;
}

std::optional<float> parse_number(std::string_view s) {
  float v = 0.0f;
  const char* first = s.data();
  if (!s.empty() && s.front() == '+') ++first;  // from_chars rejects a leading '+'
  const auto [ptr, ec] = std::from_chars(first, s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size()) return std::nullopt;
  return v;
}

bool looks_like_header(std::string_view line) {
  const auto toks = tokens_of(line);
  if (toks.size() < 2) return false;
  for (const auto& t : toks) {
    if (!parse_number(t.text)) return false;
  }
  return true;
}

class Parser {
 public:
  Parser(std::string_view text, std::string_view source) : text_(text), source_(source) {}

  Result<std::vector<LSystem>> run() {
    enum class State { kHeader, kAxiom, kRules } state = State::kHeader;
    int line_no = 0;
    std::size_t pos = 0;
    while (pos <= text_.size()) {
      const std::size_t end = text_.find('\n', pos);
      std::string_view line = text_.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos);
      pos = end == std::string_view::npos ? text_.size() + 1 : end + 1;
      ++line_no;
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      std::size_t first = 0;
      while (first < line.size() && is_space(line[first])) ++first;
      if (first == line.size()) continue;        // blank
      if (line[first] == '#') continue;          // comment on its own line
      for (std::size_t c = 0; c < line.size(); ++c) {
        const auto ch = static_cast<unsigned char>(line[c]);
        if (ch >= 127 || (ch < 32 && ch != '\t' && ch != '\v' && ch != '\f')) {
          return fail(line_no, static_cast<int>(c) + 1,
                      fmt::format("unknown symbol byte 0x{:02x}: symbols are printable ASCII", ch));
        }
      }
      switch (state) {
        case State::kHeader: {
          SYLVA_TRY(header(line, line_no));
          state = State::kAxiom;
          break;
        }
        case State::kAxiom: {
          if (const auto gt = line.find('>'); gt != std::string_view::npos) {
            return fail(line_no, static_cast<int>(gt) + 1,
                        fmt::format("missing axiom: the header on line {} must be followed by an axiom line, "
                                    "found a rule",
                                    systems_.back().line));
          }
          if (looks_like_header(line)) {
            return fail(line_no, static_cast<int>(first) + 1,
                        fmt::format("missing axiom: the header on line {} is followed by another header",
                                    systems_.back().line));
          }
          auto axiom = symbols(line, 0, line_no, "axiom");
          if (!axiom.ok()) return axiom.error();
          systems_.back().axiom = std::move(*axiom);
          state = State::kRules;
          break;
        }
        case State::kRules: {
          if (line.find('>') != std::string_view::npos) {
            SYLVA_TRY(rule(line, line_no));
          } else if (looks_like_header(line)) {
            SYLVA_TRY(header(line, line_no));
            state = State::kAxiom;
          } else {
            return fail(line_no, static_cast<int>(first) + 1,
                        "expected a rule 'letter > production' or a new header 'yaw_angle pitch_angle shrink_ratio'");
          }
          break;
        }
      }
    }
    if (state == State::kAxiom) {
      return fail(line_no, 1,
                  fmt::format("missing axiom: the header on line {} is not followed by an axiom", systems_.back().line));
    }
    if (systems_.empty()) return fail(1, 1, "no L-system: expected a header 'yaw_angle pitch_angle shrink_ratio'");
    for (auto& s : systems_) s.index_rules();
    return std::move(systems_);
  }

 private:
  Error fail(int line, int column, const std::string& what) const {
    return make_error(ErrorCode::kParse, fmt::format("{}:{}:{}: {}", source_, line, column, what));
  }

  Status header(std::string_view line, int line_no) {
    const auto toks = tokens_of(line);
    static constexpr const char* kNames[3] = {"yaw_angle", "pitch_angle", "shrink_ratio"};
    if (toks.size() != 3) {
      const int col = toks.size() > 3 ? toks[3].column : static_cast<int>(line.size()) + 1;
      return fail(line_no, col,
                  fmt::format("bad header: expected 3 numbers 'yaw_angle pitch_angle shrink_ratio', found {} field{}",
                              toks.size(), toks.size() == 1 ? "" : "s"));
    }
    float v[3];
    for (int i = 0; i < 3; ++i) {
      const auto num = parse_number(toks[static_cast<std::size_t>(i)].text);
      if (!num || !std::isfinite(*num)) {
        return fail(line_no, toks[static_cast<std::size_t>(i)].column,
                    fmt::format("bad header: {} '{}' is not a finite number", kNames[i],
                                toks[static_cast<std::size_t>(i)].text));
      }
      v[i] = *num;
    }
    for (int i = 0; i < 2; ++i) {
      if (std::abs(v[i]) > 360.0f) {
        return fail(line_no, toks[static_cast<std::size_t>(i)].column,
                    fmt::format("bad header: {} {} outside [-360, 360] degrees", kNames[i], v[i]));
      }
    }
    if (!(v[2] > 0.0f && v[2] <= 1.0f)) {
      return fail(line_no, toks[2].column, fmt::format("bad header: shrink_ratio {} outside (0, 1]", v[2]));
    }
    LSystem s;
    s.yaw_angle = v[0];
    s.pitch_angle = v[1];
    s.shrink_ratio = v[2];
    s.source = std::string(source_);
    s.line = line_no;
    systems_.push_back(std::move(s));
    return ok_status();
  }

  // Symbols of line[from..] with whitespace removed; rejects '#', '>' and unbalanced brackets.
  Result<std::string> symbols(std::string_view line, std::size_t from, int line_no, const char* what) const {
    std::string out;
    std::vector<int> open;  // columns of unmatched '['
    for (std::size_t c = from; c < line.size(); ++c) {
      const char ch = line[c];
      const int col = static_cast<int>(c) + 1;
      if (is_space(ch)) continue;
      if (ch == '#') {
        return fail(line_no, col, fmt::format("unknown symbol '#' in the {}: comments must start their own line", what));
      }
      if (ch == '>') return fail(line_no, col, fmt::format("unexpected '>' in the {}", what));
      if (ch == '[') open.push_back(col);
      if (ch == ']') {
        if (open.empty()) return fail(line_no, col, fmt::format("unbalanced ']' in the {}: no '[' to close", what));
        open.pop_back();
      }
      out.push_back(ch);
    }
    if (!open.empty()) {
      return fail(line_no, open.back(), fmt::format("unbalanced '[' in the {}: never closed", what));
    }
    return out;
  }

  Status rule(std::string_view line, int line_no) {
    const std::size_t gt = line.find('>');
    std::string_view lhs = line.substr(0, gt);
    std::vector<std::size_t> letters;
    for (std::size_t c = 0; c < lhs.size(); ++c) {
      if (!is_space(lhs[c])) letters.push_back(c);
    }
    if (letters.empty()) return fail(line_no, static_cast<int>(gt) + 1, "rule has no letter before '>'");
    if (letters.size() > 1) {
      return fail(line_no, static_cast<int>(letters[1]) + 1,
                  "rule must rewrite a single letter: 'letter > production'");
    }
    const char letter = lhs[letters[0]];
    if (letter == '[' || letter == ']') {
      return fail(line_no, static_cast<int>(letters[0]) + 1, fmt::format("'{}' cannot be rewritten", letter));
    }
    auto production = symbols(line, gt + 1, line_no, "production");
    if (!production.ok()) return production.error();
    systems_.back().rules.push_back({letter, std::move(*production), line_no});
    return ok_status();
  }

  std::string_view text_;
  std::string_view source_;
  std::vector<LSystem> systems_;
};

}  // namespace

Result<std::vector<LSystem>> parse_lsystems(std::string_view text, std::string_view source) {
  return Parser(text, source).run();
}

Result<std::vector<LSystem>> load_lsystems(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return make_error(ErrorCode::kNotFound, fmt::format("L-system file {}: cannot open", path.string()));
  std::stringstream ss;
  ss << f.rdbuf();
  if (f.bad()) return make_error(ErrorCode::kIo, fmt::format("L-system file {}: read failed", path.string()));
  return parse_lsystems(ss.str(), path.string());
}

Result<std::string> derive(const LSystem& system, int derivations, std::uint64_t salt, const ExpansionLimits& limits) {
  if (derivations < 0) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: derivation count {} is negative", system.where(), derivations));
  }
  Pcg32 rng(salt, 0x4c53u);  // stream "LS": rule choice
  std::string current = system.axiom;
  std::string next;
  if (current.size() > limits.max_symbols) {
    return make_error(ErrorCode::kLimit, fmt::format("{}: axiom longer than max_symbols={}", system.where(),
                                                     limits.max_symbols));
  }
  for (int step = 1; step <= derivations; ++step) {
    next.clear();
    for (char c : current) {
      const auto& choices = system.rules_for(c);
      const std::string* piece = nullptr;
      if (!choices.empty()) {
        const auto pick = choices.size() == 1 ? 0u : rng.next_below(static_cast<std::uint32_t>(choices.size()));
        piece = &system.rules[static_cast<std::size_t>(choices[pick])].production;
      }
      const std::size_t add = piece ? piece->size() : 1;
      if (next.size() + add > limits.max_symbols) {
        // The cap is a field of the caller's ExpansionLimits, not a scene parameter: name it as
        // such rather than a --set path that does not exist.
        return make_error(ErrorCode::kLimit,
                          fmt::format("{}: expansion exceeds max_symbols={} at derivation {} of {} "
                                      "(use fewer derivations; the cap is voxel::ExpansionLimits::max_symbols, "
                                      "not a scene parameter)",
                                      system.where(), limits.max_symbols, step, derivations));
      }
      if (piece) {
        next += *piece;
      } else {
        next.push_back(c);
      }
    }
    current.swap(next);
  }
  return current;
}

}  // namespace sylva::voxel

namespace sylva::voxel {

std::vector<std::string> builtin_lsystem_files() {
  std::vector<std::string> out;
  for (int i = 0; i < detail::kEmbeddedDataCount; ++i) {
    const std::string_view name = detail::kEmbeddedData[i].first;
    if (name.ends_with(".lsys")) out.emplace_back(name);
  }
  return out;
}

Result<std::vector<LSystem>> load_builtin_lsystems(std::string_view file_name) {
  if (file_name.ends_with(".lsys")) {
    if (const auto text = detail::embedded_file(file_name)) return parse_lsystems(*text, file_name);
  }
  std::string names;
  for (const auto& n : builtin_lsystem_files()) names += (names.empty() ? "" : ", ") + n;
  return make_error(ErrorCode::kNotFound,
                    fmt::format("no built-in L-system file '{}' (available: {})", file_name, names));
}

}  // namespace sylva::voxel

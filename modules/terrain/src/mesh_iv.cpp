// The Open Inventor 2.1 ASCII subset the seed's general-model application read (seed 002 §4: a
// terrain such as cilaos.iv): Coordinate3 { point [...] } and IndexedFaceSet { coordIndex [...] }
// anywhere in a graph of Separators and other nodes. Every other node and field is skipped by
// matching its braces and brackets. A Separator scopes the current Coordinate3 as Inventor's
// traversal state does; a face set indexes the Coordinate3 current at its place.
#include <sylva/terrain/mesh.hpp>

#include <sylva/core/atomic_file.hpp>

#include "mesh_text.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <limits>

namespace sylva::terrain {
namespace {

// Deeper nesting than any exported scene; bounds the state stack against hostile files.
constexpr std::size_t kMaxDepth = 256;

struct Token {
  enum Kind { kEnd, kWord, kNumber, kOpenBrace, kCloseBrace, kOpenBracket, kCloseBracket, kString } kind = kEnd;
  std::string_view text;
  std::size_t line = 0;
};

class Lexer {
 public:
  explicit Lexer(std::string_view text) : text_(text) {}

  Token peek() {
    Lexer copy = *this;
    return copy.next();
  }

  Token next() {
    skip_space();
    Token t;
    t.line = line_;
    if (pos_ >= text_.size()) return t;
    const char c = text_[pos_];
    const auto single = [&](Token::Kind k) {
      t.kind = k;
      t.text = text_.substr(pos_++, 1);
      return t;
    };
    if (c == '{') return single(Token::kOpenBrace);
    if (c == '}') return single(Token::kCloseBrace);
    if (c == '[') return single(Token::kOpenBracket);
    if (c == ']') return single(Token::kCloseBracket);
    if (c == '"') {
      const std::size_t b = pos_++;
      while (pos_ < text_.size() && text_[pos_] != '"') {
        if (text_[pos_] == '\\' && pos_ + 1 < text_.size()) ++pos_;
        if (text_[pos_] == '\n') ++line_;
        ++pos_;
      }
      if (pos_ < text_.size()) ++pos_;
      t.kind = Token::kString;
      t.text = text_.substr(b, pos_ - b);
      return t;
    }
    const std::size_t b = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_]) && text_[pos_] != ',' && text_[pos_] != '{' &&
           text_[pos_] != '}' && text_[pos_] != '[' && text_[pos_] != ']' && text_[pos_] != '"' && text_[pos_] != '#') {
      ++pos_;
    }
    t.text = text_.substr(b, pos_ - b);
    t.kind = (c == '-' || c == '+' || c == '.' || (c >= '0' && c <= '9')) ? Token::kNumber : Token::kWord;
    return t;
  }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == ','; }
  void skip_space() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '\n') {
        ++line_;
        ++pos_;
      } else if (is_space(c)) {
        ++pos_;
      } else if (c == '#') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else {
        break;
      }
    }
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
};

class IvParser {
 public:
  IvParser(std::string_view text, std::string_view source) : lex_(text), source_(source) {}

  Result<PolygonMesh> run(std::string_view text) {
    // The header names the format; binary Inventor and VRML are refused.
    const std::string_view first = text.substr(0, text.find('\n'));
    if (first.substr(0, 11) != "#Inventor V" || first.find("ascii") == std::string_view::npos) {
      return make_error(ErrorCode::kUnsupported,
                        fmt::format("{}:1: not an ASCII Open Inventor file (the first line must be '#Inventor V2.1 ascii')",
                                    source_));
    }
    for (Token t = lex_.next(); t.kind != Token::kEnd; t = lex_.next()) SYLVA_TRY(node_or_skip(t, 0));
    if (mesh_.face_sizes.empty()) {
      return make_error(ErrorCode::kParse, fmt::format("{}: no faces (an IndexedFaceSet with coordIndex after a Coordinate3)",
                                                       source_));
    }
    return std::move(mesh_);
  }

 private:
  Error fail(std::size_t line, const std::string& what) const {
    return Error{ErrorCode::kParse, fmt::format("{}:{}: {}", source_, line, what)};
  }

  // `t` starts a node ([DEF name] Type { ... }) at the top level or among a node's children.
  Status node_or_skip(Token t, std::size_t depth) {
    if (depth > kMaxDepth) return fail(t.line, fmt::format("nodes nested deeper than {}", kMaxDepth));
    if (t.kind == Token::kWord && (t.text == "DEF")) {
      const Token name = lex_.next();
      if (name.kind != Token::kWord) return fail(name.line, "DEF needs a name");
      t = lex_.next();
    }
    if (t.kind == Token::kWord && t.text == "USE") {
      const Token name = lex_.next();
      if (name.kind != Token::kWord) return fail(name.line, "USE needs a name");
      return {};  // instancing is not followed: each shape counts once
    }
    if (t.kind != Token::kWord) return fail(t.line, fmt::format("expected a node type, found '{}'", detail::printable(t.text)));
    const Token open = lex_.next();
    if (open.kind != Token::kOpenBrace) {
      return fail(open.line, fmt::format("expected '{{' after '{}', found '{}'", detail::printable(t.text),
                                         open.kind == Token::kEnd ? std::string("end of file") : detail::printable(open.text)));
    }
    const std::size_t saved_base = base_, saved_count = count_;
    const bool separator = t.text == "Separator" || t.text == "TransformSeparator" || t.text == "SoSeparator";
    SYLVA_TRY(body(t, depth));
    if (separator) {
      base_ = saved_base;
      count_ = saved_count;
    }
    return {};
  }

  // Fields and children up to the node's closing brace. Field names and their values other than
  // the two read here are passed over: words, numbers, strings and bracketed lists.
  Status body(const Token& type, std::size_t depth) {
    for (Token t = lex_.next();; t = lex_.next()) {
      switch (t.kind) {
        case Token::kEnd:
          return fail(t.line, fmt::format("end of file inside {} (opened at line {})", type.text, type.line));
        case Token::kCloseBrace:
          return {};
        case Token::kWord:
          if (type.text == "Coordinate3" && t.text == "point") {
            SYLVA_TRY(points());
          } else if (type.text == "IndexedFaceSet" && t.text == "coordIndex") {
            SYLVA_TRY(coord_index());
          } else if (t.text == "DEF" || t.text == "USE" || lex_.peek().kind == Token::kOpenBrace) {
            SYLVA_TRY(node_or_skip(t, depth + 1));  // a child node
          }
          break;
        case Token::kOpenBracket:
          SYLVA_TRY(list(t, 1, [](const Token&) -> Status { return {}; }));
          break;
        case Token::kNumber:
        case Token::kString:
          break;
        default:
          return fail(t.line, fmt::format("unexpected '{}' in {}", detail::printable(t.text), detail::printable(type.text)));
      }
    }
  }

  // A bracketed list (`t` is its '['), or else `single` tokens from `t` on; calls `each` with
  // every value token.
  template <class F>
  Status list(Token t, int single, F&& each) {
    if (t.kind != Token::kOpenBracket) {
      for (int i = 0; i < single; ++i, t = lex_.next()) {
        if (t.kind != Token::kNumber && t.kind != Token::kWord) return fail(t.line, fmt::format("'{}' is not a value", detail::printable(t.text)));
        SYLVA_TRY(each(t));
        if (i + 1 == single) break;
      }
      return {};
    }
    const std::size_t open = t.line;
    for (t = lex_.next(); t.kind != Token::kCloseBracket; t = lex_.next()) {
      if (t.kind == Token::kEnd) return fail(t.line, fmt::format("end of file inside the '[' list opened at line {}", open));
      if (t.kind != Token::kNumber && t.kind != Token::kWord && t.kind != Token::kString) {
        return fail(t.line, fmt::format("unexpected '{}' in the '[' list opened at line {}", detail::printable(t.text), open));
      }
      SYLVA_TRY(each(t));
    }
    return {};
  }

  Status points() {
    base_ = mesh_.positions.size();
    count_ = 0;
    glm::vec3 p{0.0f};
    int k = 0;
    std::size_t line = 0;
    SYLVA_TRY(list(lex_.next(), 3, [&](const Token& t) -> Status {
      float v = 0.0f;
      const auto r = std::from_chars(t.text.data(), t.text.data() + t.text.size(), v);
      if (t.kind != Token::kNumber || r.ec != std::errc() || r.ptr != t.text.data() + t.text.size()) {
        return fail(t.line, fmt::format("'{}' is not a coordinate", detail::printable(t.text)));
      }
      if (!std::isfinite(v)) return fail(t.line, fmt::format("coordinate '{}' is not finite", detail::printable(t.text)));
      p[k++] = v;
      line = t.line;
      if (k == 3) {
        if (mesh_.positions.size() >= std::numeric_limits<std::uint32_t>::max()) {
          return Error{ErrorCode::kLimit, fmt::format("{}:{}: more than 2^32 - 1 points", source_, t.line)};
        }
        mesh_.positions.push_back(p);
        ++count_;
        k = 0;
      }
      return {};
    }));
    if (k != 0) return fail(line, fmt::format("a point with {} coordinates (3 are needed)", k));
    return {};
  }

  Status coord_index() {
    std::uint32_t in_face = 0;
    std::size_t face_line = 0;
    const auto close = [&]() -> Status {
      if (in_face == 0) return {};
      if (in_face < 3) return fail(face_line, fmt::format("a face with {} vertices (at least 3 are needed)", in_face));
      mesh_.face_sizes.push_back(in_face);
      in_face = 0;
      return {};
    };
    SYLVA_TRY(list(lex_.next(), 1, [&](const Token& t) -> Status {
      long long idx = 0;
      const auto r = std::from_chars(t.text.data(), t.text.data() + t.text.size(), idx);
      if (t.kind != Token::kNumber || r.ec != std::errc() || r.ptr != t.text.data() + t.text.size()) {
        return fail(t.line, fmt::format("'{}' is not a vertex index", detail::printable(t.text)));
      }
      if (idx == -1) return close();
      if (idx < 0 || static_cast<unsigned long long>(idx) >= count_) {
        return fail(t.line, fmt::format("coordIndex {} is outside the {} points of the current Coordinate3", idx, count_));
      }
      if (in_face == 0) face_line = t.line;
      if (in_face == std::numeric_limits<std::uint32_t>::max() ||
          mesh_.face_indices.size() >= std::numeric_limits<std::uint32_t>::max()) {
        return Error{ErrorCode::kLimit, fmt::format("{}:{}: too many face indices", source_, t.line)};
      }
      mesh_.face_indices.push_back(static_cast<std::uint32_t>(base_ + static_cast<std::size_t>(idx)));
      ++in_face;
      return {};
    }));
    return close();  // the last face may omit its -1
  }

  Lexer lex_;
  std::string_view source_;
  PolygonMesh mesh_;
  std::size_t base_ = 0, count_ = 0;  // the current Coordinate3's first point and size
};

}  // namespace

Result<PolygonMesh> parse_iv(std::string_view text, std::string_view source) {
  IvParser parser(text, source);
  return parser.run(text);
}

Result<PolygonMesh> load_iv(const std::filesystem::path& path) {
  auto text = read_file(path);
  if (!text.ok()) return text.error();
  return parse_iv(*text, path.string());
}

}  // namespace sylva::terrain

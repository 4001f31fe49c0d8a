#include <sylva/vegetation/objt.hpp>

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/log.hpp>
#include <sylva/core/rng.hpp>
#include <sylva/vegetation/bending.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <unordered_map>
#include <vector>

namespace sylva::vegetation {
namespace {

// ---------------------------------------------------------------------------------------------
// Lexing helpers

std::string_view trim(std::string_view s) {
  const auto ws = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; };
  while (!s.empty() && ws(s.front())) s.remove_prefix(1);
  while (!s.empty() && ws(s.back())) s.remove_suffix(1);
  return s;
}

// Removes a // comment that is not inside a double-quoted string.
std::string_view strip_comment(std::string_view s) {
  bool quoted = false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '"') quoted = !quoted;
    if (!quoted && s[i] == '/' && i + 1 < s.size() && s[i + 1] == '/') return s.substr(0, i);
  }
  return s;
}

std::vector<std::string_view> split_ws(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
    std::size_t j = i;
    while (j < s.size() && s[j] != ' ' && s[j] != '\t') ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

std::optional<int> parse_int(std::string_view s) {
  int v = 0;
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size()) return std::nullopt;
  return v;
}

std::optional<std::uint32_t> parse_uint(std::string_view s) {
  std::uint32_t v = 0;
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size()) return std::nullopt;
  return v;
}

std::optional<float> parse_float(std::string_view s) {
  float v = 0.0f;
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size()) return std::nullopt;
  return v;
}

// ---------------------------------------------------------------------------------------------
// Raw records as read from the file

struct Field {
  std::vector<double> values;  // doubles hold every int32 and every float exactly
  int line = 0;
};

struct Record {
  char kind = 'B';  // 'B' or 'L'
  int id = 0;
  int line = 0;     // line of the "B <id>" header
  std::map<char, Field> fields;
};

struct FieldSpec {
  char key;
  int count;
  bool required;
  bool integer;
};

constexpr std::array<FieldSpec, 11> kBranchFields{{{'l', 1, true, true},
                                                  {'d', 1, true, false},
                                                  {'z', 3, true, false},
                                                  {'k', 3, true, false},
                                                  {'r', 3, true, false},
                                                  {'s', 3, true, false},
                                                  {'t', 3, true, false},
                                                  {'p', 1, true, true},
                                                  {'x', 1, true, false},
                                                  {'w', 2, false, false},
                                                  {'c', 2, false, false}}};
constexpr std::array<FieldSpec, 7> kLeafFields{{{'r', 3, true, false},
                                               {'s', 3, true, false},
                                               {'t', 3, true, false},
                                               {'p', 1, true, true},
                                               {'x', 1, true, false},
                                               {'w', 2, false, false},
                                               {'n', 1, false, false}}};

const FieldSpec* find_spec(char kind, char key) {
  if (kind == 'B') {
    for (const FieldSpec& f : kBranchFields)
      if (f.key == key) return &f;
  } else {
    for (const FieldSpec& f : kLeafFields)
      if (f.key == key) return &f;
  }
  return nullptr;
}

const char* kind_name(char kind) { return kind == 'B' ? "branch" : "leaf"; }

class Parser {
 public:
  Parser(std::string_view text, const ObjtReadOptions& options) : text_(text), options_(options) {}

  Result<TreeModel> run() {
    SYLVA_TRY(lex());
    return build();
  }

 private:
  Error error(int line, const std::string& what, ErrorCode code = ErrorCode::kParse) const {
    return make_error(code, fmt::format("{}:{}: {}", options_.source_name, line, what));
  }

  // A repair of a seed-valid file: a warning naming the line (objt.hpp lists the repairs).
  void warn(int line, const std::string& what) const {
    std::string text = fmt::format("{}:{}: {}", options_.source_name, line, what);
    if (options_.warnings) {
      options_.warnings->push_back(std::move(text));
    } else {
      log_warn("{}", text);
    }
  }

  Status lex() {
    int line_no = 0;
    std::optional<Record> open;     // the block being read
    bool expect_brace = false;      // header seen, waiting for "{"
    std::size_t pos = 0;
    while (pos <= text_.size()) {
      std::size_t end = text_.find('\n', pos);
      if (end == std::string_view::npos) end = text_.size();
      const std::string_view raw = text_.substr(pos, end - pos);
      pos = end + 1;
      ++line_no;
      const std::string_view line = trim(strip_comment(raw));
      if (line.empty()) {
        if (end == text_.size()) break;
        continue;
      }
      if (expect_brace) {
        if (line != "{")
          return error(line_no, fmt::format("expected '{{' to open {} {} (line {}), found '{}'", kind_name(open->kind),
                                            open->id, open->line, line));
        expect_brace = false;
        continue;
      }
      if (open) {
        if (line == "}") {
          SYLVA_TRY(finish(*open, line_no));
          records_.push_back(std::move(*open));
          open.reset();
          continue;
        }
        SYLVA_TRY(read_field(*open, line, line_no));
        continue;
      }
      // Top level: name, seed or a block header.
      const std::vector<std::string_view> tok = split_ws(line);
      if (tok[0] == "name" || (tok[0].size() > 4 && tok[0].substr(0, 4) == "name" && tok[0][4] == '=')) {
        SYLVA_TRY(read_name(line, line_no));
        continue;
      }
      if (tok[0] == "seed" || (tok[0].size() > 4 && tok[0].substr(0, 4) == "seed" && tok[0][4] == '=')) {
        SYLVA_TRY(read_seed(line, line_no));
        continue;
      }
      if (tok[0] == "B" || tok[0] == "L") {
        if (tok.size() < 2) return error(line_no, fmt::format("{} record lacks its identifier", kind_name(tok[0][0])));
        const std::optional<int> id = parse_int(tok[1]);
        if (!id) return error(line_no, fmt::format("{} identifier '{}' is not an integer", kind_name(tok[0][0]), tok[1]));
        Record r;
        r.kind = tok[0][0];
        r.id = *id;
        r.line = line_no;
        if (tok.size() == 2) {
          expect_brace = true;
        } else if (tok.size() != 3 || tok[2] != "{") {
          return error(line_no, fmt::format("expected '{{' after {} {}", kind_name(r.kind), r.id));
        }
        open = std::move(r);
        entities_seen_ = true;
        continue;
      }
      return error(line_no, fmt::format("unknown record '{}' (expected name, B, L or //)", tok[0]));
    }
    if (open) {
      return error(open->line, fmt::format("{} {} is not closed with '}}' before the end of the file",
                                           kind_name(open->kind), open->id));
    }
    return ok_status();
  }

  Status read_name(std::string_view line, int line_no) {
    if (entities_seen_) return error(line_no, "the name record must come before the first branch or leaf");
    if (have_name_) return error(line_no, "a second name record");
    const std::size_t eq = line.find('=');
    const std::size_t q0 = line.find('"');
    const std::size_t q1 = line.rfind('"');
    if (eq == std::string_view::npos || q0 == std::string_view::npos || q1 == q0 || q0 < eq ||
        !trim(line.substr(q1 + 1)).empty() || !trim(line.substr(eq + 1, q0 - eq - 1)).empty())
      return error(line_no, "expected name = \"<string>\"");
    name_ = std::string(line.substr(q0 + 1, q1 - q0 - 1));
    have_name_ = true;
    return ok_status();
  }

  Status read_seed(std::string_view line, int line_no) {
    const std::size_t eq = line.find('=');
    if (eq == std::string_view::npos) return error(line_no, "expected seed = <unsigned integer>");
    const std::optional<std::uint32_t> v = parse_uint(trim(line.substr(eq + 1)));
    if (!v) return error(line_no, fmt::format("field 'seed': '{}' is not an unsigned 32-bit integer", trim(line.substr(eq + 1))));
    seed_ = *v;
    return ok_status();
  }

  Status read_field(Record& r, std::string_view line, int line_no) {
    const std::vector<std::string_view> tok = split_ws(line);
    if (tok[0].size() != 1) {
      if (tok[0].find('}') != std::string_view::npos)
        return error(line_no, "'}' must stand on its own line");
      return error(line_no, fmt::format("{} {}: unknown field '{}'", kind_name(r.kind), r.id, tok[0]));
    }
    const char key = tok[0][0];
    const FieldSpec* spec = find_spec(r.kind, key);
    if (spec == nullptr) return error(line_no, fmt::format("{} {}: unknown field '{}'", kind_name(r.kind), r.id, key));
    if (r.fields.count(key) != 0)
      return error(line_no, fmt::format("{} {}: field '{}' appears twice (first at line {})", kind_name(r.kind), r.id, key,
                                        r.fields[key].line));
    if (static_cast<int>(tok.size()) - 1 != spec->count)
      return error(line_no, fmt::format("{} {}: field '{}' expects {} value{}, got {}", kind_name(r.kind), r.id, key,
                                        spec->count, spec->count == 1 ? "" : "s", tok.size() - 1));
    Field f;
    f.line = line_no;
    for (std::size_t i = 1; i < tok.size(); ++i) {
      if (spec->integer) {
        const std::optional<int> v = parse_int(tok[i]);
        if (!v) return error(line_no, fmt::format("{} {}: field '{}': '{}' is not an integer", kind_name(r.kind), r.id, key, tok[i]));
        f.values.push_back(static_cast<double>(*v));
      } else {
        const std::optional<float> v = parse_float(tok[i]);
        if (!v) return error(line_no, fmt::format("{} {}: field '{}': '{}' is not a number", kind_name(r.kind), r.id, key, tok[i]));
        if (!std::isfinite(*v))
          return error(line_no, fmt::format("{} {}: field '{}': '{}' is not finite", kind_name(r.kind), r.id, key, tok[i]));
        f.values.push_back(static_cast<double>(*v));
      }
    }
    r.fields.emplace(key, std::move(f));
    return ok_status();
  }

  Status finish(const Record& r, int line_no) const {
    const auto check = [&](const auto& specs) -> Status {
      for (const FieldSpec& s : specs) {
        if (s.required && r.fields.count(s.key) == 0)
          return error(r.line, fmt::format("{} {} (lines {}-{}): missing field '{}'", kind_name(r.kind), r.id, r.line,
                                           line_no, s.key));
      }
      return ok_status();
    };
    return r.kind == 'B' ? check(kBranchFields) : check(kLeafFields);
  }

  Result<TreeModel> build();

  // Branch frames need r x s = t; leaf frames (r = n, s = b) need b = t x n: both say s = t x r.
  // Frames off by more than 1e-5 are re-orthonormalised (keeping t and r's direction), with a
  // warning; zero or parallel vectors are errors.
  Status check_frame(const Record& r, BranchFrame& f) const {
    const char* what = kind_name(r.kind);
    const auto line = [&](char k) { return r.fields.at(k).line; };
    if (!(glm::length(f.t) > 1.0e-12f))
      return error(line('t'), fmt::format("{} {}: field 't': the vector is zero", what, r.id));
    if (!(glm::length(f.r) > 1.0e-12f))
      return error(line('r'), fmt::format("{} {}: field 'r': the vector is zero", what, r.id));
    constexpr float kTol = 1.0e-5f;
    const auto unit = [&](const glm::vec3& v) { return std::fabs(glm::length(v) - 1.0f) <= kTol; };
    const bool good = unit(f.r) && unit(f.s) && unit(f.t) && std::fabs(glm::dot(f.r, f.t)) <= kTol &&
                      glm::length(glm::cross(f.t, f.r) - f.s) <= 2.0f * kTol;
    if (good) return ok_status();
    const bool left_handed = glm::dot(glm::cross(f.t, f.r), f.s) < 0.0f;
    if (left_handed && options_.strict)
      return error(line('s'), fmt::format("{} {}: field 's': the frame is left-handed (s = -(t x r))", what, r.id));
    BranchFrame g = f;
    if (!orthonormalize(g))
      return error(line('r'), fmt::format("{} {}: field 'r': the vector is parallel to t", what, r.id));
    warn(r.line, left_handed ? fmt::format("{} {}: frame is left-handed; s flipped to t x r", what, r.id)
                             : fmt::format("{} {}: frame is not orthonormal; re-orthonormalised keeping t and r", what, r.id));
    f = g;
    return ok_status();
  }

  std::string_view text_;
  const ObjtReadOptions& options_;
  std::vector<Record> records_;
  std::string name_;
  bool have_name_ = false;
  bool entities_seen_ = false;
  std::uint32_t seed_ = 0;
};

}  // namespace

namespace {
Result<TreeModel> Parser::build() {
  std::vector<const Record*> branch_recs;
  std::vector<const Record*> leaf_recs;
  std::unordered_map<int, int> branch_index;  // id -> index in branch_recs
  std::unordered_map<int, int> leaf_index;
  for (const Record& r : records_) {
    auto& index = r.kind == 'B' ? branch_index : leaf_index;
    auto& recs = r.kind == 'B' ? branch_recs : leaf_recs;
    if (auto it = index.find(r.id); it != index.end())
      return error(r.line, fmt::format("{} identifier {} is used twice (first at line {})", kind_name(r.kind), r.id,
                                       recs[static_cast<std::size_t>(it->second)]->line));
    index.emplace(r.id, static_cast<int>(recs.size()));
    recs.push_back(&r);
  }
  const auto num = [](const Record& r, char key, int i = 0) { return r.fields.at(key).values[static_cast<std::size_t>(i)]; };
  const auto vec = [&](const Record& r, char key) {
    return glm::vec3(static_cast<float>(num(r, key, 0)), static_cast<float>(num(r, key, 1)),
                     static_cast<float>(num(r, key, 2)));
  };
  const auto line_of = [](const Record& r, char key) { return r.fields.at(key).line; };

  // Parent links: existence, then cycles.
  const int nb = static_cast<int>(branch_recs.size());
  std::vector<int> parent(static_cast<std::size_t>(nb), -1);
  for (int i = 0; i < nb; ++i) {
    const Record& r = *branch_recs[static_cast<std::size_t>(i)];
    const auto p = static_cast<int>(num(r, 'p'));
    if (p < 0) continue;
    const auto it = branch_index.find(p);
    if (it == branch_index.end())
      return error(line_of(r, 'p'), fmt::format("branch {}: field 'p': parent branch {} does not exist", r.id, p));
    if (it->second == i) {
      // The seed leaves the trunk's parent open; a file may name the trunk itself.
      if (options_.strict)
        return error(line_of(r, 'p'), fmt::format("branch {}: field 'p': a branch cannot be its own parent (cycle {} -> {})", r.id, r.id, r.id));
      warn(line_of(r, 'p'), fmt::format("branch {}: field 'p': the branch names itself as its parent; read as a root (level 0)", r.id));
      continue;
    }
    parent[static_cast<std::size_t>(i)] = it->second;
  }
  std::vector<int> state(static_cast<std::size_t>(nb), 0);  // 0 new, 1 on the current walk, 2 done
  for (int i = 0; i < nb; ++i) {
    std::vector<int> path;
    int j = i;
    while (j >= 0 && state[static_cast<std::size_t>(j)] == 0) {
      state[static_cast<std::size_t>(j)] = 1;
      path.push_back(j);
      j = parent[static_cast<std::size_t>(j)];
    }
    if (j >= 0 && state[static_cast<std::size_t>(j)] == 1) {
      const auto start = std::find(path.begin(), path.end(), j);
      std::string cycle;
      std::string lines;
      for (auto it = start; it != path.end(); ++it) {
        const Record& r = *branch_recs[static_cast<std::size_t>(*it)];
        cycle += fmt::format("{} -> ", r.id);
        lines += fmt::format("{}{}", lines.empty() ? "" : ", ", line_of(r, 'p'));
      }
      cycle += fmt::format("{}", branch_recs[static_cast<std::size_t>(j)]->id);
      return error(line_of(*branch_recs[static_cast<std::size_t>(j)], 'p'),
                   fmt::format("field 'p': the parent links of branches {} form a cycle (lines {})", cycle, lines));
    }
    for (int k : path) state[static_cast<std::size_t>(k)] = 2;
  }

  // Levels: roots are 0, children their parent's + 1, at most kMaxLevels levels.
  std::vector<int> level(static_cast<std::size_t>(nb), -1);
  for (int i = 0; i < nb; ++i) {
    std::vector<int> path;
    int j = i;
    while (j >= 0 && level[static_cast<std::size_t>(j)] < 0) {
      path.push_back(j);
      j = parent[static_cast<std::size_t>(j)];
    }
    int l = j >= 0 ? level[static_cast<std::size_t>(j)] : -1;
    for (auto it = path.rbegin(); it != path.rend(); ++it) level[static_cast<std::size_t>(*it)] = ++l;
  }
  for (int i = 0; i < nb; ++i) {
    const Record& r = *branch_recs[static_cast<std::size_t>(i)];
    const int expected = level[static_cast<std::size_t>(i)];
    const auto l = static_cast<int>(num(r, 'l'));
    if (l != expected) {
      const int p = parent[static_cast<std::size_t>(i)];
      const std::string what = p < 0 ? fmt::format("branch {}: field 'l': level {} but a root has level 0", r.id, l)
                                      : fmt::format("branch {}: field 'l': level {} but its parent {} has level {}", r.id, l,
                                                    branch_recs[static_cast<std::size_t>(p)]->id, expected - 1);
      if (options_.strict) return error(line_of(r, 'l'), what);
      warn(line_of(r, 'l'), fmt::format("{}; level {} used", what, expected));
    }
    if (expected >= kMaxLevels)
      return error(line_of(r, 'l'),
                   fmt::format("branch {}: level {} (from its parent chain) exceeds the supported {} levels (trunk + {})",
                               r.id, expected, kMaxLevels, kMaxLevels - 1),
                   ErrorCode::kLimit);
  }

  // Order: file order when parents come first, else a stable sort by level.
  std::vector<int> order(static_cast<std::size_t>(nb));
  for (int i = 0; i < nb; ++i) order[static_cast<std::size_t>(i)] = i;
  bool parents_first = true;
  for (int i = 0; i < nb; ++i)
    if (parent[static_cast<std::size_t>(i)] > i) parents_first = false;
  if (!parents_first)
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return level[static_cast<std::size_t>(a)] < level[static_cast<std::size_t>(b)]; });
  std::vector<int> new_index(static_cast<std::size_t>(nb));
  for (int i = 0; i < nb; ++i) new_index[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])] = i;

  TreeModel model;
  model.name = name_;
  model.seed = seed_;
  model.branches.reserve(static_cast<std::size_t>(nb));
  for (int oi = 0; oi < nb; ++oi) {
    const int i = order[static_cast<std::size_t>(oi)];
    const Record& r = *branch_recs[static_cast<std::size_t>(i)];
    Branch b;
    b.id = r.id;
    b.level = level[static_cast<std::size_t>(i)];
    b.parent = parent[static_cast<std::size_t>(i)] < 0 ? -1 : new_index[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    b.parent_x = static_cast<float>(num(r, 'x'));
    if (!(b.parent_x >= 0.0f && b.parent_x <= 1.0f))
      return error(line_of(r, 'x'), fmt::format("branch {}: field 'x': {} is outside [0, 1]", r.id, b.parent_x));
    b.length = static_cast<float>(num(r, 'd'));
    if (b.length < 0.0f) return error(line_of(r, 'd'), fmt::format("branch {}: field 'd': length {} is negative", r.id, b.length));
    b.start = vec(r, 'z');
    b.frame = {vec(r, 'r'), vec(r, 's'), vec(r, 't')};
    SYLVA_TRY(check_frame(r, b.frame));
    const glm::vec3 k = vec(r, 'k');
    const glm::vec3 expected_end = b.axis_point(1.0f);
    const float miss = glm::length(k - expected_end);
    if (!(miss <= 1.0e-3f + 0.01f * b.length)) {
      const std::string what = fmt::format("branch {}: field 'k': end point ({}, {}, {}) is {:.4g} m from z + d t = ({}, {}, {})",
                                           r.id, k.x, k.y, k.z, miss, expected_end.x, expected_end.y, expected_end.z);
      if (options_.strict) return error(line_of(r, 'k'), what);
      warn(line_of(r, 'k'), what + "; k ignored, the branch ends at z + d t");
    }
    if (r.fields.count('w') != 0) {
      b.radius_base = static_cast<float>(num(r, 'w', 0));
      b.radius_tip = static_cast<float>(num(r, 'w', 1));
      if (b.radius_base < 0.0f || b.radius_tip < 0.0f)
        return error(line_of(r, 'w'), fmt::format("branch {}: field 'w': radii {} / {} must be >= 0", r.id, b.radius_base, b.radius_tip));
    } else {
      b.radius_base = options_.default_radius_ratio * b.length;
      b.radius_tip = options_.default_taper * b.radius_base;
    }
    if (r.fields.count('c') != 0) {
      b.c2 = static_cast<float>(num(r, 'c', 0));
      b.c4 = static_cast<float>(num(r, 'c', 1));
    } else {
      const BendConstants c = bend_constants_for_taper(b.radius_base > 0.0f ? b.radius_tip / b.radius_base : 1.0f);
      b.c2 = c.c2;
      b.c4 = c.c4;
    }
    model.branches.push_back(b);
  }
  assign_bending_data(model, options_.max_length_error, /*keep_constants=*/true);

  for (const Record* rp : leaf_recs) {
    const Record& r = *rp;
    Leaf l;
    l.id = r.id;
    const auto p = static_cast<int>(num(r, 'p'));
    const auto it = branch_index.find(p);
    if (it == branch_index.end())
      return error(line_of(r, 'p'), fmt::format("leaf {}: field 'p': parent branch {} does not exist", r.id, p));
    l.parent = new_index[static_cast<std::size_t>(it->second)];
    l.parent_x = static_cast<float>(num(r, 'x'));
    if (!(l.parent_x >= 0.0f && l.parent_x <= 1.0f))
      return error(line_of(r, 'x'), fmt::format("leaf {}: field 'x': {} is outside [0, 1]", r.id, l.parent_x));
    BranchFrame f{vec(r, 'r'), vec(r, 's'), vec(r, 't')};
    SYLVA_TRY(check_frame(r, f));
    l.normal = f.r;
    l.bitangent = f.s;
    l.tangent = f.t;
    if (r.fields.count('w') != 0) {
      l.width = static_cast<float>(num(r, 'w', 0));
      l.length = static_cast<float>(num(r, 'w', 1));
      if (!(l.width > 0.0f && l.length > 0.0f))
        return error(line_of(r, 'w'), fmt::format("leaf {}: field 'w': size {} x {} must be positive", r.id, l.width, l.length));
    } else {
      l.width = options_.default_leaf_width;
      l.length = options_.default_leaf_length;
    }
    if (r.fields.count('n') != 0) {
      l.number = static_cast<float>(num(r, 'n'));
      if (!(l.number >= 0.0f && l.number < 1.0f))
        return error(line_of(r, 'n'), fmt::format("leaf {}: field 'n': {} is outside [0, 1)", r.id, l.number));
    } else {
      l.number = hash_to_unit_float(hash_u32(static_cast<std::uint32_t>(r.id), seed_, 0x6c6eu));
    }
    model.leaves.push_back(l);
  }
  if (Status s = validate(model); !s.ok())
    return make_error(ErrorCode::kParse, fmt::format("{}: {}", options_.source_name, s.error().message));
  return model;
}

}  // namespace

Result<TreeModel> parse_objt(std::string_view text, const ObjtReadOptions& options) {
  Parser parser(text, options);
  return parser.run();
}

Result<TreeModel> load_objt(const std::filesystem::path& path, ObjtReadOptions options) {
  Result<std::string> text = read_file(path);
  if (!text.ok()) return text.error();
  options.source_name = path.string();
  return parse_objt(*text, options);
}

namespace {

void append_vec(std::string& out, char key, const glm::vec3& v) {
  out += fmt::format("    {} {} {} {}\n", key, v.x, v.y, v.z);
}

}  // namespace

std::string format_objt(const TreeModel& model) {
  std::string out;
  out += "// OBJT tree (seed 000 section 4.3.1); fields w, c, n and the seed record are Sylva extensions\n";
  std::string name = model.name;
  for (char& c : name)
    if (c == '"' || c == '\n' || c == '\r') c = '\'';
  out += fmt::format("name = \"{}\"\n", name);
  out += fmt::format("seed = {}\n", model.seed);
  for (const Branch& b : model.branches) {
    out += fmt::format("B {} {{\n", b.id);
    out += fmt::format("    l {}\n", b.level);
    out += fmt::format("    d {}\n", b.length);
    append_vec(out, 'z', b.start);
    append_vec(out, 'k', b.end());
    append_vec(out, 'r', b.frame.r);
    append_vec(out, 's', b.frame.s);
    append_vec(out, 't', b.frame.t);
    out += fmt::format("    p {}\n", b.parent < 0 ? -1 : model.branches[static_cast<std::size_t>(b.parent)].id);
    out += fmt::format("    x {}\n", b.parent_x);
    out += fmt::format("    w {} {}\n", b.radius_base, b.radius_tip);
    out += fmt::format("    c {} {}\n", b.c2, b.c4);
    out += "}\n";
  }
  for (const Leaf& l : model.leaves) {
    out += fmt::format("L {} {{\n", l.id);
    append_vec(out, 'r', l.normal);
    append_vec(out, 's', l.bitangent);
    append_vec(out, 't', l.tangent);
    out += fmt::format("    p {}\n", model.branches[static_cast<std::size_t>(l.parent)].id);
    out += fmt::format("    x {}\n", l.parent_x);
    out += fmt::format("    w {} {}\n", l.width, l.length);
    out += fmt::format("    n {}\n", l.number);
    out += "}\n";
  }
  return out;
}

Status save_objt(const std::filesystem::path& path, const TreeModel& model) {
  return write_file_atomic(path, format_objt(model));
}

}  // namespace sylva::vegetation

#include <sylva/core/params.hpp>

#include "params_internal.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>

namespace sylva {

const char* to_string(Rebuild rebuild) {
  switch (rebuild) {
    case Rebuild::kNone: return "none";
    case Rebuild::kGpu: return "gpu";
    case Rebuild::kOffline: return "offline";
  }
  return "unknown";
}

const char* EnumTable::name_of(std::int64_t value) const {
  for (const auto& [v, n] : entries) {
    if (v == value) return n.c_str();
  }
  return nullptr;
}

std::string EnumTable::joined_names() const {
  std::string out;
  for (const auto& [v, n] : entries) {
    if (!out.empty()) out += ", ";
    out += n;
  }
  return out;
}

namespace detail {

void check_param_name(const char* name) {
  SYLVA_ASSERT(name != nullptr && name[0] != '\0', "a parameter name is empty");
  for (const char* c = name; *c != '\0'; ++c) {
    SYLVA_ASSERT(*c != '.' && *c != '[' && *c != ']' && *c != '=' && *c != ' ',
                 "parameter name \"{}\" contains '{}' (names are path segments)", name, *c);
  }
}

void check_unique_paths(std::span<const ParamDescriptor> params) {
  std::vector<std::string_view> paths;
  paths.reserve(params.size());
  for (const ParamDescriptor& p : params) paths.push_back(p.path);
  std::sort(paths.begin(), paths.end());
  const auto dup = std::adjacent_find(paths.begin(), paths.end());
  SYLVA_ASSERT(dup == paths.end(), "parameter \"{}\" is listed twice by visit()", dup == paths.end() ? "" : *dup);
}

}  // namespace detail

namespace params_detail {

namespace {

constexpr std::string_view kSpaces = " \t\r\n";

std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(kSpaces);
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(kSpaces);
  return s.substr(b, e - b + 1);
}

std::string quoted(std::string_view s) {
  constexpr std::size_t kMax = 60;
  if (s.size() > kMax) return fmt::format("\"{}...\"", s.substr(0, kMax));
  return fmt::format("\"{}\"", s);
}

const char* scalar_name(ParamType t) {
  switch (t) {
    case ParamType::kBool: return "bool";
    case ParamType::kInt32: return "int32";
    case ParamType::kUInt32: return "uint32";
    case ParamType::kInt64: return "int64";
    case ParamType::kUInt64: return "uint64";
    case ParamType::kFloat: return "float";
    case ParamType::kDouble: return "double";
    case ParamType::kString: return "string";
    case ParamType::kEnum: return "enum";
  }
  return "?";
}

template <class I>
Status store_integer(void* dst, const Number& n, std::string_view where) {
  using L = std::numeric_limits<I>;
  const auto range_error = [&] {
    return param_error(where, fmt::format("{} does not fit in {} ({} to {})", n.to_string(),
                                          sizeof(I) == 4 ? (L::is_signed ? "int32" : "uint32")
                                                         : (L::is_signed ? "int64" : "uint64"),
                                          L::min(), L::max()));
  };
  I value{};
  switch (n.kind) {
    case Number::Kind::kInt:
      if (n.i < static_cast<std::int64_t>(L::min()) ||
          (n.i > 0 && static_cast<std::uint64_t>(n.i) > static_cast<std::uint64_t>(L::max())))
        return range_error();
      value = static_cast<I>(n.i);
      break;
    case Number::Kind::kUInt:
      if (n.u > static_cast<std::uint64_t>(L::max())) return range_error();
      value = static_cast<I>(n.u);
      break;
    case Number::Kind::kDouble: {
      if (n.integer_overflow) return range_error();
      if (!std::isfinite(n.d)) return param_error(where, fmt::format("{} is not a finite number", n.d));
      if (std::trunc(n.d) != n.d) return param_error(where, fmt::format("expected an integer, got {}", n.d));
      // long double holds every int64/uint64 exactly on x86-64; the bounds are compared there.
      const long double d = n.d;
      if (d < static_cast<long double>(L::min()) || d > static_cast<long double>(L::max())) return range_error();
      // Beyond 2^53 a double has already been rounded (e.g. JSON's -9223372036854775809 parses
      // as -2^63), so the integer the user meant is unknown: refuse rather than guess.
      if (std::fabs(n.d) > 9007199254740992.0) {
        return param_error(where, fmt::format("{} is not exact: an integer written as a floating-point number must be "
                                              "at most 2^53 in magnitude; write all its digits",
                                              n.to_string()));
      }
      value = static_cast<I>(d);
      break;
    }
  }
  std::memcpy(dst, &value, sizeof(I));
  return {};
}

double as_double(const Number& n) {
  switch (n.kind) {
    case Number::Kind::kInt: return static_cast<double>(n.i);
    case Number::Kind::kUInt: return static_cast<double>(n.u);
    case Number::Kind::kDouble: return n.d;
  }
  return 0.0;
}

Result<Number> parse_number_text(std::string_view text, std::string_view where) {
  std::string_view s = trim(text);
  if (s.empty()) return param_error(where, "expected a number, got an empty string");
  if (s.size() > 1 && s[0] == '+' && s[1] != '-' && s[1] != '+') s.remove_prefix(1);
  const char* b = s.data();
  const char* e = s.data() + s.size();
  Number n;
  {
    std::int64_t i = 0;
    const auto r = std::from_chars(b, e, i);
    if (r.ec == std::errc() && r.ptr == e) {
      n.kind = Number::Kind::kInt;
      n.i = i;
      return n;
    }
  }
  if (s[0] != '-') {
    std::uint64_t u = 0;
    const auto r = std::from_chars(b, e, u);
    if (r.ec == std::errc() && r.ptr == e) {
      n.kind = Number::Kind::kUInt;
      n.u = u;
      return n;
    }
  }
  double d = 0.0;
  const auto r = std::from_chars(b, e, d);
  const bool integer_literal =
      std::all_of(s.begin() + (s[0] == '-' ? 1 : 0), s.end(), [](char c) { return c >= '0' && c <= '9'; }) &&
      s.size() > (s[0] == '-' ? 1u : 0u);
  if (integer_literal && r.ec == std::errc() && r.ptr == e) {
    // Digits only, yet neither int64 nor uint64 took it: beyond 64 bits.
    n.kind = Number::Kind::kDouble;
    n.d = d;
    n.integer_overflow = true;
    n.text = std::string(s);
    return n;
  }
  if (r.ptr == e && r.ec == std::errc::result_out_of_range) {
    return param_error(where, fmt::format("{} is outside the range of a double", s));
  }
  if (r.ec != std::errc() || r.ptr != e) {
    return param_error(where, fmt::format("expected a number, got {}", quoted(text)));
  }
  n.kind = Number::Kind::kDouble;
  n.d = d;
  return n;
}

// Splits "1,2,3", "[1, 2, 3]", "(1 2 3)" into its elements.
std::vector<std::string_view> split_vector_text(std::string_view text) {
  std::string_view s = trim(text);
  if (s.size() >= 2 && ((s.front() == '[' && s.back() == ']') || (s.front() == '(' && s.back() == ')'))) {
    s = trim(s.substr(1, s.size() - 2));
  }
  std::vector<std::string_view> parts;
  if (s.empty()) return parts;
  const bool commas = s.find(',') != std::string_view::npos;
  std::size_t start = 0;
  while (start <= s.size()) {
    std::size_t end = commas ? s.find(',', start) : s.find_first_of(kSpaces, start);
    if (end == std::string_view::npos) end = s.size();
    const std::string_view part = trim(s.substr(start, end - start));
    if (commas || !part.empty()) parts.push_back(part);
    start = end + 1;
  }
  return parts;
}

template <class T>
std::string format_float(T v) {
  return fmt::format("{}", v);
}

std::string format_bound(const ParamRef& ref, double bound) {
  if (ref.type == ParamType::kFloat) return format_float(static_cast<float>(bound));
  return format_float(bound);
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0u : 1u)});
      diag = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string Number::to_string() const {
  switch (kind) {
    case Kind::kInt: return fmt::format("{}", i);
    case Kind::kUInt: return fmt::format("{}", u);
    case Kind::kDouble: return integer_overflow ? text : fmt::format("{}", d);
  }
  return {};
}

Error param_error(std::string_view path, std::string_view what) {
  return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: {}", path, what));
}

Staged::Staged(const ParamRef& target) : target_(target) {
  if (target.type == ParamType::kString) {
    str_ = *static_cast<const std::string*>(target.ptr);
  } else {
    const std::size_t size = component_size(target) * target.components;
    SYLVA_ASSERT(size <= sizeof(raw_), "parameter value of {} bytes does not fit the staging buffer", size);
    std::memcpy(raw_, target.ptr, size);
  }
}

ParamRef Staged::ref() {
  ParamRef r = target_;
  r.ptr = target_.type == ParamType::kString ? static_cast<void*>(&str_) : static_cast<void*>(raw_);
  return r;
}

void Staged::commit() const {
  if (target_.type == ParamType::kString) {
    *static_cast<std::string*>(target_.ptr) = str_;
  } else {
    std::memcpy(target_.ptr, raw_, component_size(target_) * target_.components);
  }
}

std::size_t component_size(const ParamRef& ref) {
  switch (ref.type) {
    case ParamType::kBool: return sizeof(bool);
    case ParamType::kInt32: return sizeof(std::int32_t);
    case ParamType::kUInt32: return sizeof(std::uint32_t);
    case ParamType::kInt64: return sizeof(std::int64_t);
    case ParamType::kUInt64: return sizeof(std::uint64_t);
    case ParamType::kFloat: return sizeof(float);
    case ParamType::kDouble: return sizeof(double);
    case ParamType::kString: return sizeof(std::string);
    case ParamType::kEnum: return ref.enum_table->size;
  }
  return 0;
}

void* component_ptr(const ParamRef& ref, int index) {
  return static_cast<unsigned char*>(ref.ptr) + component_size(ref) * static_cast<std::size_t>(index);
}

std::string component_path(std::string_view path, const ParamRef& ref, int index) {
  if (ref.components == 1) return std::string(path);
  return fmt::format("{}[{}]", path, index);
}

Status store_number(ParamType type, void* dst, const Number& n, std::string_view where) {
  switch (type) {
    case ParamType::kInt32: return store_integer<std::int32_t>(dst, n, where);
    case ParamType::kUInt32: return store_integer<std::uint32_t>(dst, n, where);
    case ParamType::kInt64: return store_integer<std::int64_t>(dst, n, where);
    case ParamType::kUInt64: return store_integer<std::uint64_t>(dst, n, where);
    case ParamType::kFloat: {
      const double d = as_double(n);
      if (!std::isfinite(d)) return param_error(where, fmt::format("{} is not a finite number", d));
      // Doubles below FLT_MAX + half an ulp round to FLT_MAX; from there on they round to inf.
      if (std::fabs(d) >= 0x1.ffffffp+127) {
        return param_error(where, fmt::format("{} is too large for a float (largest is {})", n.to_string(),
                                              std::numeric_limits<float>::max()));
      }
      const float f = static_cast<float>(d);
      std::memcpy(dst, &f, sizeof f);
      return {};
    }
    case ParamType::kDouble: {
      const double d = as_double(n);
      if (!std::isfinite(d)) return param_error(where, fmt::format("{} is not a finite number", d));
      std::memcpy(dst, &d, sizeof d);
      return {};
    }
    case ParamType::kBool:
    case ParamType::kString:
    case ParamType::kEnum: break;
  }
  SYLVA_ASSERT(false, "store_number on a {} parameter ({})", scalar_name(type), where);
  return {};
}

Status parse_component_text(const ParamRef& ref, void* dst, std::string_view text, std::string_view where) {
  switch (ref.type) {
    case ParamType::kBool: {
      const std::string_view s = trim(text);
      bool value = false;
      if (s == "true" || s == "1" || s == "on" || s == "yes") {
        value = true;
      } else if (s == "false" || s == "0" || s == "off" || s == "no") {
        value = false;
      } else {
        return param_error(where, fmt::format("expected true or false, got {}", s.empty() ? "an empty string" : quoted(text)));
      }
      std::memcpy(dst, &value, sizeof value);
      return {};
    }
    case ParamType::kString:
      *static_cast<std::string*>(dst) = std::string(text);
      return {};
    case ParamType::kEnum: {
      return store_enum_name(ref, dst, trim(text), where);
    }
    case ParamType::kInt32:
    case ParamType::kUInt32:
    case ParamType::kInt64:
    case ParamType::kUInt64:
    case ParamType::kFloat:
    case ParamType::kDouble: {
      Result<Number> n = parse_number_text(text, where);
      if (!n.ok()) return n.error();
      return store_number(ref.type, dst, *n, where);
    }
  }
  return {};
}

Status store_enum_name(const ParamRef& ref, void* dst, std::string_view name, std::string_view where) {
  for (const auto& [value, entry_name] : ref.enum_table->entries) {
    if (entry_name == name) {
      ref.enum_table->set(dst, value);
      return {};
    }
  }
  return param_error(where, fmt::format("unknown value {}; valid values: {}", quoted(name), ref.enum_table->joined_names()));
}

Status check_value(const ParamRef& ref, const ParamInfo& info, std::string_view path) {
  for (int c = 0; c < ref.components; ++c) {
    const void* p = component_ptr(ref, c);
    const auto where = [&] { return component_path(path, ref, c); };
    const auto range = [&](auto value, auto min, auto max) -> Status {
      if (value < min) {
        return param_error(where(), fmt::format("{} is below the minimum {}", format_component(ref, c), format_bound(ref, info.min)));
      }
      if (value > max) {
        return param_error(where(), fmt::format("{} is above the maximum {}", format_component(ref, c), format_bound(ref, info.max)));
      }
      return {};
    };
    switch (ref.type) {
      case ParamType::kBool: break;
      case ParamType::kFloat: {
        const float v = *static_cast<const float*>(p);
        if (!std::isfinite(v)) return param_error(where(), fmt::format("{} is not a finite number", v));
        SYLVA_TRY(range(v, static_cast<float>(info.min), static_cast<float>(info.max)));
        break;
      }
      case ParamType::kDouble: {
        const double v = *static_cast<const double*>(p);
        if (!std::isfinite(v)) return param_error(where(), fmt::format("{} is not a finite number", v));
        SYLVA_TRY(range(v, info.min, info.max));
        break;
      }
      case ParamType::kInt32:
        SYLVA_TRY(range(static_cast<long double>(*static_cast<const std::int32_t*>(p)),
                        static_cast<long double>(info.min), static_cast<long double>(info.max)));
        break;
      case ParamType::kUInt32:
        SYLVA_TRY(range(static_cast<long double>(*static_cast<const std::uint32_t*>(p)),
                        static_cast<long double>(info.min), static_cast<long double>(info.max)));
        break;
      case ParamType::kInt64:
        SYLVA_TRY(range(static_cast<long double>(*static_cast<const std::int64_t*>(p)),
                        static_cast<long double>(info.min), static_cast<long double>(info.max)));
        break;
      case ParamType::kUInt64:
        SYLVA_TRY(range(static_cast<long double>(*static_cast<const std::uint64_t*>(p)),
                        static_cast<long double>(info.min), static_cast<long double>(info.max)));
        break;
      case ParamType::kString: {
        const double length = static_cast<double>(static_cast<const std::string*>(p)->size());
        if (length < info.min) {
          return param_error(where(), fmt::format("a string of length {} is shorter than the minimum length {}", length, info.min));
        }
        if (length > info.max) {
          return param_error(where(), fmt::format("a string of length {} is longer than the maximum length {}", length, info.max));
        }
        break;
      }
      case ParamType::kEnum: {
        const std::int64_t v = ref.enum_table->get(p);
        if (ref.enum_table->name_of(v) == nullptr) {
          return param_error(where(), fmt::format("value {} has no name; valid values: {}", v, ref.enum_table->joined_names()));
        }
        break;
      }
    }
  }
  return {};
}

std::string format_component(const ParamRef& ref, int index) {
  const void* p = component_ptr(ref, index);
  switch (ref.type) {
    case ParamType::kBool: return *static_cast<const bool*>(p) ? "true" : "false";
    case ParamType::kInt32: return fmt::format("{}", *static_cast<const std::int32_t*>(p));
    case ParamType::kUInt32: return fmt::format("{}", *static_cast<const std::uint32_t*>(p));
    case ParamType::kInt64: return fmt::format("{}", *static_cast<const std::int64_t*>(p));
    case ParamType::kUInt64: return fmt::format("{}", *static_cast<const std::uint64_t*>(p));
    case ParamType::kFloat: return format_float(*static_cast<const float*>(p));
    case ParamType::kDouble: return format_float(*static_cast<const double*>(p));
    case ParamType::kString: return *static_cast<const std::string*>(p);
    case ParamType::kEnum: {
      const std::int64_t v = ref.enum_table->get(p);
      const char* name = ref.enum_table->name_of(v);
      return name != nullptr ? std::string(name) : fmt::format("{}", v);
    }
  }
  return {};
}

std::string closest_match(std::string_view wanted, const std::vector<std::string>& candidates) {
  // Close enough to be a typo: a few edits, fewer than a third of the name.
  const std::size_t limit = std::max<std::size_t>(2, wanted.size() / 3);
  std::string best;
  std::size_t best_distance = std::numeric_limits<std::size_t>::max();
  for (const std::string& c : candidates) {
    // The distance is at least the difference in length: skipping those candidates keeps a long
    // garbage name (a hostile --set or JSON key) from costing its length times every name.
    const std::size_t length_gap = c.size() > wanted.size() ? c.size() - wanted.size() : wanted.size() - c.size();
    if (length_gap > limit) continue;
    const std::size_t d = edit_distance(wanted, c);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  return best_distance <= limit ? best : std::string();
}

}  // namespace params_detail

using namespace params_detail;

// --- ParamDescriptor ---

std::string ParamDescriptor::type_name() const {
  if (ref.components == 1) return scalar_name(ref.type);
  const char* prefix = "";
  switch (ref.type) {
    case ParamType::kFloat: prefix = ""; break;
    case ParamType::kDouble: prefix = "d"; break;
    case ParamType::kInt32: prefix = "i"; break;
    case ParamType::kUInt32: prefix = "u"; break;
    default: SYLVA_ASSERT(false, "vector of {} ({})", scalar_name(ref.type), path);
  }
  return fmt::format("{}vec{}", prefix, ref.components);
}

std::string ParamDescriptor::get_string() const {
  if (ref.components == 1) return format_component(ref, 0);
  std::string out;
  for (int c = 0; c < ref.components; ++c) {
    if (c > 0) out += ',';
    out += format_component(ref, c);
  }
  return out;
}

Status ParamDescriptor::set_string(std::string_view text) const {
  Staged staged(ref);
  const ParamRef s = staged.ref();
  if (ref.components == 1) {
    SYLVA_TRY(parse_component_text(s, s.ptr, text, path));
  } else {
    const std::vector<std::string_view> parts = split_vector_text(text);
    if (parts.size() != ref.components) {
      return param_error(path, fmt::format("expected {} numbers separated by commas, got {} in {}", int(ref.components),
                                           parts.size(), quoted(text)));
    }
    for (int c = 0; c < ref.components; ++c) {
      SYLVA_TRY(parse_component_text(s, component_ptr(s, c), parts[static_cast<std::size_t>(c)], component_path(path, ref, c)));
    }
  }
  SYLVA_TRY(check_staged(s));
  staged.commit();
  return {};
}

Status ParamDescriptor::check() const { return check_value(ref, info, path); }

Status ParamDescriptor::check_staged(const ParamRef& staged) const {
  SYLVA_ASSERT(staged.same_type(ref), "staged value of another type for {}", path);
  return check_value(staged, info, path);
}

bool ParamDescriptor::same_value(const ParamDescriptor& other) const {
  SYLVA_ASSERT(ref.same_type(other.ref), "comparing {} with {} of another type", path, other.path);
  if (ref.type == ParamType::kString) {
    return *static_cast<const std::string*>(ref.ptr) == *static_cast<const std::string*>(other.ref.ptr);
  }
  return std::memcmp(ref.ptr, other.ref.ptr, component_size(ref) * ref.components) == 0;
}

// --- operations on descriptor lists ---

Result<ParamDescriptor> find_param(std::span<const ParamDescriptor> params, std::string_view path) {
  for (const ParamDescriptor& p : params) {
    if (p.path == path) return p;
  }
  const std::string group = std::string(path) + ".";
  std::vector<std::string> members;
  for (const ParamDescriptor& p : params) {
    if (p.path.starts_with(group)) members.push_back(p.path);
  }
  const auto list = [](const std::vector<std::string>& names) {
    constexpr std::size_t kMaxListed = 20;
    std::string out;
    for (std::size_t i = 0; i < names.size() && i < kMaxListed; ++i) out += (i ? ", " : "") + names[i];
    if (names.size() > kMaxListed) out += fmt::format(", ... ({} in all)", names.size());
    return out;
  };
  if (!path.empty() && !members.empty()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{} is a group of parameters, not a parameter; it holds {}", path, list(members)));
  }
  std::vector<std::string> all;
  all.reserve(params.size());
  for (const ParamDescriptor& p : params) all.push_back(p.path);
  std::string message = fmt::format("unknown parameter \"{}\"", path);
  const std::string suggestion = closest_match(path, all);
  if (!suggestion.empty()) return make_error(ErrorCode::kNotFound, message + fmt::format("; did you mean \"{}\"?", suggestion));
  // List what the deepest existing group of the path holds, or the top-level names.
  std::string_view parent = path;
  while (true) {
    const auto dot = parent.rfind('.');
    parent = dot == std::string_view::npos ? std::string_view() : parent.substr(0, dot);
    std::vector<std::string> siblings;
    std::set<std::string> seen;
    for (const ParamDescriptor& p : params) {
      if (!parent.empty() && !p.path.starts_with(std::string(parent) + ".")) continue;
      const std::size_t start = parent.empty() ? 0 : parent.size() + 1;
      const std::size_t end = p.path.find('.', start);
      std::string child = p.path.substr(0, end);
      if (seen.insert(child).second) siblings.push_back(child);
    }
    if (!siblings.empty()) {
      return make_error(ErrorCode::kNotFound, message + fmt::format("; known {}: {}", parent.empty() ? "names" : "in " + std::string(parent), list(siblings)));
    }
    if (parent.empty()) break;
  }
  return make_error(ErrorCode::kNotFound, message + " (there are no parameters)");
}

Status set_param(std::span<const ParamDescriptor> params, std::string_view path, std::string_view text) {
  Result<ParamDescriptor> p = find_param(params, path);
  if (!p.ok()) return p.error();
  return p->set_string(text);
}

Result<std::string> get_param(std::span<const ParamDescriptor> params, std::string_view path) {
  Result<ParamDescriptor> p = find_param(params, path);
  if (!p.ok()) return p.error();
  return p->get_string();
}

std::vector<Error> param_violations(std::span<const ParamDescriptor> params) {
  std::vector<Error> out;
  for (const ParamDescriptor& p : params) {
    Status s = p.check();
    if (!s.ok()) out.push_back(s.error());
  }
  return out;
}

Status validate_params(std::span<const ParamDescriptor> params) {
  const std::vector<Error> violations = param_violations(params);
  if (violations.empty()) return {};
  std::string message;
  for (const Error& e : violations) message += (message.empty() ? "" : "\n") + e.message;
  return make_error(ErrorCode::kInvalidArgument, message);
}

Result<std::pair<std::string, std::string>> parse_param_assignment(std::string_view assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string_view::npos) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("expected path=value (for example terrain.max_pixel_error=2), got \"{}\"", assignment));
  }
  const std::string_view path = trim(assignment.substr(0, eq));
  if (path.empty()) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("missing parameter path before '=' in \"{}\"", assignment));
  }
  return std::pair<std::string, std::string>(std::string(path), std::string(assignment.substr(eq + 1)));
}

std::vector<ParamChange> diff_params(std::span<const ParamDescriptor> before, std::span<const ParamDescriptor> after) {
  SYLVA_ASSERT(before.size() == after.size(), "diff of {} and {} parameters", before.size(), after.size());
  std::vector<ParamChange> changes;
  for (std::size_t i = 0; i < before.size(); ++i) {
    SYLVA_ASSERT(before[i].path == after[i].path, "diff of {} against {}", before[i].path, after[i].path);
    if (!before[i].same_value(after[i])) changes.push_back({before[i].path, after[i].info.rebuild});
  }
  return changes;
}

Rebuild max_rebuild(std::span<const ParamChange> changes) {
  Rebuild r = Rebuild::kNone;
  for (const ParamChange& c : changes) r = std::max(r, c.rebuild);
  return r;
}

// --- ParamRegistry ---

void ParamRegistry::add_section(std::string_view name, VisitFn visit) {
  const std::string n(name);
  detail::check_param_name(n.c_str());
  SYLVA_ASSERT(!contains(name), "parameter section \"{}\" is registered twice", name);
  SYLVA_ASSERT(visit != nullptr, "parameter section \"{}\" has no visit function", name);
  sections_.push_back({n, std::move(visit)});
}

bool ParamRegistry::remove(std::string_view name) {
  const auto it = std::find_if(sections_.begin(), sections_.end(), [&](const Section& s) { return s.name == name; });
  if (it == sections_.end()) return false;
  sections_.erase(it);
  return true;
}

bool ParamRegistry::contains(std::string_view name) const {
  return std::any_of(sections_.begin(), sections_.end(), [&](const Section& s) { return s.name == name; });
}

std::vector<std::string> ParamRegistry::section_names() const {
  std::vector<std::string> names;
  for (const Section& s : sections_) names.push_back(s.name);
  return names;
}

std::vector<ParamDescriptor> ParamRegistry::describe() const {
  std::vector<ParamDescriptor> out;
  for (const Section& s : sections_) {
    ParamCollector collector(out, s.name);
    s.visit(collector);
  }
  detail::check_unique_paths(out);
  return out;
}

Result<ParamDescriptor> ParamRegistry::find(std::string_view path) const { return find_param(describe(), path); }

Status ParamRegistry::set(std::string_view path, std::string_view text) const { return set_param(describe(), path, text); }

Status ParamRegistry::set_assignment(std::string_view assignment) const {
  auto kv = parse_param_assignment(assignment);
  if (!kv.ok()) return kv.error();
  return set(kv->first, kv->second);
}

Result<std::string> ParamRegistry::get(std::string_view path) const { return get_param(describe(), path); }

Status ParamRegistry::validate() const { return validate_params(describe()); }

}  // namespace sylva

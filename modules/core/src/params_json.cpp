#include <sylva/core/params_json.hpp>

#include "params_internal.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <optional>
#include <unordered_map>
#include <unordered_set>

namespace sylva {

using json = nlohmann::json;
using namespace params_detail;

namespace {

std::string describe_json(const json& j) {
  constexpr std::size_t kMax = 60;
  const auto shorten = [](std::string s) {
    if (s.size() > kMax) s = s.substr(0, kMax) + "...";
    return s;
  };
  switch (j.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return j.get<bool>() ? "boolean true" : "boolean false";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float: return "number " + j.dump();
    case json::value_t::string: return "string " + shorten(j.dump());
    case json::value_t::array: return "array " + shorten(j.dump());
    case json::value_t::object: return "object " + shorten(j.dump());
    case json::value_t::binary:
    case json::value_t::discarded: break;
  }
  return "binary data";
}

// A float as the double of its shortest decimal ("0.1" for 0.1f) when that converts back to the
// same float bits, else the exact double: readable files and a lossless round trip.
json float_json(float f) {
  if (!std::isfinite(f)) return static_cast<double>(f);
  const std::string text = fmt::format("{}", f);
  double d = 0.0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), d);
  if (r.ec == std::errc() && std::bit_cast<std::uint32_t>(static_cast<float>(d)) == std::bit_cast<std::uint32_t>(f)) {
    return d;
  }
  return static_cast<double>(f);
}

json component_json(const ParamRef& ref, int index) {
  const void* p = component_ptr(ref, index);
  switch (ref.type) {
    case ParamType::kBool: return *static_cast<const bool*>(p);
    case ParamType::kInt32: return *static_cast<const std::int32_t*>(p);
    case ParamType::kUInt32: return *static_cast<const std::uint32_t*>(p);
    case ParamType::kInt64: return *static_cast<const std::int64_t*>(p);
    case ParamType::kUInt64: return *static_cast<const std::uint64_t*>(p);
    case ParamType::kFloat: return float_json(*static_cast<const float*>(p));
    case ParamType::kDouble: return *static_cast<const double*>(p);
    case ParamType::kString: return *static_cast<const std::string*>(p);
    case ParamType::kEnum: {
      const std::int64_t v = ref.enum_table->get(p);
      const char* name = ref.enum_table->name_of(v);
      if (name != nullptr) return name;
      return v;  // an unnamed value; loading it back reports the valid names
    }
  }
  return nullptr;
}

bool is_integer_type(ParamType t) {
  return t == ParamType::kInt32 || t == ParamType::kUInt32 || t == ParamType::kInt64 || t == ParamType::kUInt64;
}

Status parse_component_json(const ParamRef& ref, void* dst, const json& j, std::string_view where) {
  switch (ref.type) {
    case ParamType::kBool: {
      if (!j.is_boolean()) return param_error(where, fmt::format("expected true or false, got {}", describe_json(j)));
      const bool v = j.get<bool>();
      std::memcpy(dst, &v, sizeof v);
      return {};
    }
    case ParamType::kString:
      if (!j.is_string()) return param_error(where, fmt::format("expected a string, got {}", describe_json(j)));
      *static_cast<std::string*>(dst) = j.get<std::string>();
      return {};
    case ParamType::kEnum: {
      if (!j.is_string()) {
        return param_error(where, fmt::format("expected one of {} (a string), got {}", ref.enum_table->joined_names(), describe_json(j)));
      }
      return store_enum_name(ref, dst, j.get_ref<const std::string&>(), where);
    }
    case ParamType::kInt32:
    case ParamType::kUInt32:
    case ParamType::kInt64:
    case ParamType::kUInt64:
    case ParamType::kFloat:
    case ParamType::kDouble: {
      if (!j.is_number()) {
        return param_error(where, fmt::format("expected {}, got {}", is_integer_type(ref.type) ? "an integer" : "a number", describe_json(j)));
      }
      Number n;
      if (j.is_number_unsigned()) {
        n.kind = Number::Kind::kUInt;
        n.u = j.get<std::uint64_t>();
      } else if (j.is_number_integer()) {
        n.kind = Number::Kind::kInt;
        n.i = j.get<std::int64_t>();
      } else {
        n.kind = Number::Kind::kDouble;
        n.d = j.get<double>();
      }
      return store_number(ref.type, dst, n, where);
    }
  }
  return {};
}

// Parses j into the staged copy and validates it; the target is not touched.
Status stage_json(const ParamDescriptor& param, Staged& staged, const json& j) {
  const ParamRef s = staged.ref();
  if (s.components == 1) {
    SYLVA_TRY(parse_component_json(s, s.ptr, j, param.path));
  } else {
    if (!j.is_array() || j.size() != s.components) {
      return param_error(param.path, fmt::format("expected an array of {} numbers, got {}", int(s.components), describe_json(j)));
    }
    for (int c = 0; c < s.components; ++c) {
      SYLVA_TRY(parse_component_json(s, component_ptr(s, c), j[static_cast<std::size_t>(c)], component_path(param.path, s, c)));
    }
  }
  return param.check_staged(s);
}

std::string relative_path(const std::string& path, std::string_view prefix) {
  if (prefix.empty()) return path;
  SYLVA_ASSERT(path.size() > prefix.size() && path.starts_with(prefix) && path[prefix.size()] == '.',
               "parameter {} is not under the prefix {}", path, prefix);
  return path.substr(prefix.size() + 1);
}

const char* json_type_label(const json& j) {
  return j.is_object() ? "an object" : "a value";
}

}  // namespace

json param_to_json(const ParamDescriptor& param) {
  if (param.ref.components == 1) return component_json(param.ref, 0);
  json array = json::array();
  for (int c = 0; c < param.ref.components; ++c) array.push_back(component_json(param.ref, c));
  return array;
}

Status param_from_json(const ParamDescriptor& param, const json& value) {
  Staged staged(param.ref);
  SYLVA_TRY(stage_json(param, staged, value));
  staged.commit();
  return {};
}

json params_to_json(std::span<const ParamDescriptor> params, std::string_view prefix) {
  json root = json::object();
  for (const ParamDescriptor& p : params) {
    const std::string rel = relative_path(p.path, prefix);
    json* node = &root;
    std::size_t start = 0;
    for (std::size_t dot = rel.find('.'); dot != std::string::npos; dot = rel.find('.', start)) {
      node = &(*node)[rel.substr(start, dot - start)];
      start = dot + 1;
    }
    (*node)[rel.substr(start)] = param_to_json(p);
  }
  return root;
}

Status params_from_json(std::span<const ParamDescriptor> params, const json& object,
                        std::vector<std::string>& warnings, std::string_view prefix) {
  std::unordered_map<std::string, const ParamDescriptor*> leaves;
  std::unordered_map<std::string, std::vector<std::string>> children;  // group -> child names
  for (const ParamDescriptor& p : params) {
    const std::string rel = relative_path(p.path, prefix);
    leaves.emplace(rel, &p);
    std::size_t start = 0;
    std::string group;
    while (true) {
      const std::size_t dot = rel.find('.', start);
      const std::string name = rel.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
      auto& names = children[group];
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
      if (dot == std::string::npos) break;
      group = rel.substr(0, dot);
      start = dot + 1;
    }
  }
  const auto full = [&](const std::string& rel) {
    if (prefix.empty()) return rel;
    return rel.empty() ? std::string(prefix) : fmt::format("{}.{}", prefix, rel);
  };

  std::vector<std::string> errors;
  std::vector<std::pair<const ParamDescriptor*, Staged>> staged;
  // Walks the JSON object against the tree of known paths.
  const auto walk = [&](const auto& self, const json& node, const std::string& rel) -> void {
    if (!node.is_object()) {
      const std::string where = full(rel);
      errors.push_back(fmt::format("{}: expected an object, got {}", where.empty() ? "(top level)" : where, describe_json(node)));
      return;
    }
    for (auto it = node.begin(); it != node.end(); ++it) {
      const std::string& key = it.key();
      const std::string child = rel.empty() ? key : rel + "." + key;
      if (key.find('.') == std::string::npos && !key.empty()) {
        if (const auto leaf = leaves.find(child); leaf != leaves.end()) {
          Staged s(leaf->second->ref);
          Status st = stage_json(*leaf->second, s, it.value());
          if (st.ok()) {
            staged.emplace_back(leaf->second, std::move(s));
          } else {
            errors.push_back(st.error().message);
          }
          continue;
        }
        if (children.contains(child)) {
          self(self, it.value(), child);
          continue;
        }
      }
      const auto siblings = children.find(rel);
      const std::string suggestion =
          siblings == children.end() ? std::string() : closest_match(key, siblings->second);
      warnings.push_back(fmt::format("{}: unknown key ({}), ignored{}", full(child), json_type_label(it.value()),
                                     suggestion.empty() ? "" : fmt::format("; did you mean \"{}\"?", suggestion)));
    }
  };
  walk(walk, object, std::string());

  if (!errors.empty()) {
    std::string message;
    for (const std::string& e : errors) message += (message.empty() ? "" : "\n") + e;
    return make_error(ErrorCode::kInvalidArgument, message);
  }
  for (const auto& [param, value] : staged) value.commit();
  return {};
}

json params_to_json(const ParamRegistry& registry) {
  json out = params_to_json(registry.describe());
  // A registered section without parameters still appears, so a saved file lists it.
  for (const std::string& name : registry.section_names()) {
    if (!out.contains(name)) out[name] = json::object();
  }
  return out;
}

Status params_from_json(const ParamRegistry& registry, const json& object, std::vector<std::string>& warnings) {
  return params_from_json(registry.describe(), object, warnings);
}

json params_schema_json(std::span<const ParamDescriptor> params) {
  json out = json::array();
  for (const ParamDescriptor& p : params) {
    json e;
    e["path"] = p.path;
    e["type"] = p.type_name();
    e["value"] = param_to_json(p);
    if (std::isfinite(p.info.min)) e["min"] = p.info.min;
    if (std::isfinite(p.info.max)) e["max"] = p.info.max;
    if (p.info.step > 0.0) e["step"] = p.info.step;
    e["unit"] = p.info.unit;
    e["help"] = p.info.help;
    e["rebuild"] = to_string(p.info.rebuild);
    e["log_scale"] = p.info.log_scale;
    if (p.ref.type == ParamType::kEnum) {
      json names = json::array();
      for (const auto& [v, n] : p.ref.enum_table->entries) names.push_back(n);
      e["values"] = std::move(names);
    }
    out.push_back(std::move(e));
  }
  return out;
}

namespace {

// "<line>:<column>" (1-based) of byte `at` of `text`.
std::string line_column(std::string_view text, std::size_t at) {
  std::size_t line = 1;
  std::size_t column = 1;
  for (std::size_t i = 0; i < std::min(at, text.size()); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return fmt::format("{}:{}", line, column);
}

// Nesting deeper than kMaxJsonDepth, found before parsing: the parsed value and every walk over
// it recurse, so a hostile file of a few hundred KB would overflow the stack. Strings are skipped
// (brackets inside them do not nest). Returns the offset of the first too-deep bracket.
std::optional<std::size_t> too_deep_at(std::string_view text) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '"') in_string = true;
    else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::nullopt;
}

}  // namespace

Result<json> parse_json_text(std::string_view text, std::string_view source) {
  if (const auto at = too_deep_at(text)) {
    return make_error(ErrorCode::kLimit, fmt::format("{}:{}: nested deeper than {} levels", source,
                                                     line_column(text, *at), kMaxJsonDepth));
  }
  try {
    return json::parse(text.begin(), text.end());
  } catch (const json::parse_error& e) {
    // Line and column of the byte where parsing stopped (e.byte is 1-based).
    const std::string where = line_column(text, e.byte > 0 ? e.byte - 1 : 0);
    std::string reason = e.what();
    if (const auto at = reason.find("column "); at != std::string::npos) {
      if (const auto colon = reason.find(": ", at); colon != std::string::npos) reason = reason.substr(colon + 2);
    }
    return make_error(ErrorCode::kParse, fmt::format("{}:{}: {}", source, where, reason));
  } catch (const json::exception& e) {
    // Not a syntax error but a value JSON cannot hold (number overflow such as 1e400).
    std::string reason = e.what();
    if (const auto bracket = reason.find("] "); bracket != std::string::npos) reason = reason.substr(bracket + 2);
    return make_error(ErrorCode::kParse, fmt::format("{}: {}", source, reason));
  }
}

}  // namespace sylva

#pragma once
// Private helpers shared by params.cpp and params_json.cpp: staging a value of a parameter's
// own type (so a failed parse or check never touches the target), storing parsed numbers with
// exact type checks, formatting values for messages, and "did you mean" suggestions.

#include <sylva/core/params.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::params_detail {

// A parsed number before it is stored into a typed component.
struct Number {
  enum class Kind { kInt, kUInt, kDouble } kind = Kind::kInt;
  std::int64_t i = 0;
  std::uint64_t u = 0;
  double d = 0.0;
  // Set for an integer literal outside the 64-bit range: d holds its approximate value for
  // float targets, integer targets report it as not fitting, and messages echo the text.
  bool integer_overflow = false;
  std::string text;

  std::string to_string() const;
};

// A scratch copy of one parameter's value. Holds up to 32 bytes (a dvec4) or a string.
class Staged {
 public:
  explicit Staged(const ParamRef& target);
  // A ParamRef of the target's type that points at the scratch storage.
  ParamRef ref();
  // Copies the scratch value into the target.
  void commit() const;

 private:
  ParamRef target_;
  alignas(16) unsigned char raw_[32] = {};
  std::string str_;
};

std::size_t component_size(const ParamRef& ref);
void* component_ptr(const ParamRef& ref, int index);
// "path" for scalars, "path[i]" for vector components.
std::string component_path(std::string_view path, const ParamRef& ref, int index);

// Type checks (integral, fits the type, finite, fits a float) and stores into one component.
// Range checks against ParamInfo happen later, in check_value.
Status store_number(ParamType type, void* dst, const Number& number, std::string_view where);

// Stores the enum value named `name` (exact match), or names the valid values.
Status store_enum_name(const ParamRef& ref, void* dst, std::string_view name, std::string_view where);

// Text parsing of one component of `type` into dst.
Status parse_component_text(const ParamRef& ref, void* dst, std::string_view text, std::string_view where);

// Validates a value (range, finite, named enum, string length).
Status check_value(const ParamRef& ref, const ParamInfo& info, std::string_view path);

// Component i formatted as get_string() would (shortest round-trip numbers).
std::string format_component(const ParamRef& ref, int index);

// The candidate closest to `wanted` by edit distance when it is close enough, else "".
std::string closest_match(std::string_view wanted, const std::vector<std::string>& candidates);

Error param_error(std::string_view path, std::string_view what);

}  // namespace sylva::params_detail

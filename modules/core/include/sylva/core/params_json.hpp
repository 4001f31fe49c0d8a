#pragma once
// JSON load/save of settings structs, driven by their visit() (DESIGN.md §2). A struct becomes
// an object, nested structs nested objects, vectors arrays, enums their names:
//   {"max_pixel_error": 1, "criterion": "screen_space", "lod": {"morph_fraction": 0.25}}
//
// Loading is strict about what is there and lenient about what is not:
//  - a wrong type, an out-of-range or non-finite value, or an unknown enum name is an error
//    whose message starts with the full JSON path ("terrain.lod.morph_fraction: 2 is above the
//    maximum 1"); all errors are reported together, one per line;
//  - on any error nothing is written (the object keeps every previous value);
//  - a missing key keeps its current (default) value;
//  - an unknown key is not an error but a warning appended to the caller's list (with a
//    "did you mean" suggestion), so a typo is never silently dropped.
// Saving is lossless: every value loads back bit-identical (floats are written as their
// shortest round-trip decimal when that is exact, e.g. 0.1f as 0.1).

#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>

#include <nlohmann/json.hpp>

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sylva {

// One parameter's current value as JSON.
nlohmann::json param_to_json(const ParamDescriptor& param);
// Validates value for this parameter and writes it; unchanged on failure.
Status param_from_json(const ParamDescriptor& param, const nlohmann::json& value);

// The parameters as one nested object. Paths are taken relative to `prefix` (the prefix the
// descriptors were described with; "" for none).
nlohmann::json params_to_json(std::span<const ParamDescriptor> params, std::string_view prefix = {});
// Loads `object` (the JSON object at `prefix`) into the parameters; see the rules above.
Status params_from_json(std::span<const ParamDescriptor> params, const nlohmann::json& object,
                        std::vector<std::string>& warnings, std::string_view prefix = {});

template <Visitable T>
nlohmann::json params_to_json(const T& obj) {
  return params_to_json(describe_params(obj));
}
// `prefix` is where `object` sits in the whole document ("terrain"), used in messages only.
template <Visitable T>
Status params_from_json(T& obj, const nlohmann::json& object, std::vector<std::string>& warnings,
                        std::string_view prefix = {}) {
  return params_from_json(describe_params(obj, prefix), object, warnings, prefix);
}

// A registry as {"<section>": {...}, ...}; loading warns about sections that are not registered.
nlohmann::json params_to_json(const ParamRegistry& registry);
Status params_from_json(const ParamRegistry& registry, const nlohmann::json& object,
                        std::vector<std::string>& warnings);

// A description of every parameter for tools and generated docs: an array of
// {"path", "type", "value", "min", "max" (omitted when unbounded), "step", "unit", "help",
//  "rebuild", "log_scale", "values" (enum names)}.
nlohmann::json params_schema_json(std::span<const ParamDescriptor> params);

// Deepest nesting of arrays and objects that parse_json_text accepts. A scene needs about 6; the
// bound keeps a hostile file from overflowing the stack in the parser and in every walk over it.
inline constexpr int kMaxJsonDepth = 128;

// Parses JSON text without exceptions: kParse with "<source>:<line>:<column>: <reason>" for
// malformed text (including numbers JSON cannot hold, such as 1e400); kLimit with
// "<source>:<line>:<column>: nested deeper than 128 levels" before parsing a too-deep text.
Result<nlohmann::json> parse_json_text(std::string_view text, std::string_view source = "<json>");

}  // namespace sylva

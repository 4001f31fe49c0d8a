#pragma once
// Sweep specifications and their cartesian expansion (GL-free).
//
//   --sweep terrain.max_pixel_error=0.5,1,2,4 --sweep terrain.crack_fix=seams,skirts
// gives 4 x 2 = 8 settings. The first --sweep varies slowest (nested loops in the order given),
// so the settings come out in a fixed, documented order and two runs list them identically.
//
// Values are separated by commas at bracket depth 0, so vector parameters are written in
// brackets: --sweep camera.position=[0,10,0],[0,100,0]. Whitespace around values is trimmed.

#include <sylva/core/result.hpp>

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sylva::bench {

// One swept parameter: its dotted path and the values (text for ParamDescriptor::set_string).
struct SweepAxis {
  std::string path;
  std::vector<std::string> values;
};

// One path=value pair of a setting.
struct Assignment {
  std::string path;
  std::string value;
  bool operator==(const Assignment&) const = default;
};

// One combination of the sweep: one value per axis, in axis order.
struct Setting {
  std::size_t index = 0;                // 0-based position in the expansion
  std::vector<Assignment> assignments;  // one per axis

  // "terrain.max_pixel_error=2, terrain.crack_fix=seams" ("(scene as loaded)" for no axes).
  std::string label() const;
  // Short form for file names: "s003".
  std::string id() const;
};

// Parses "path=v1,v2,..." (the text after --sweep). Errors (kInvalidArgument) name the text:
// missing '=', empty path, no values, an empty value, unbalanced brackets.
Result<SweepAxis> parse_sweep(std::string_view text);

// Splits a value list at commas outside brackets; trims each value. Unbalanced brackets: error.
Result<std::vector<std::string>> split_values(std::string_view list);

// Largest number of settings a sweep may expand to (a typo like 1,2,...,1000 x 1000 stops with a
// clear message instead of running for days).
inline constexpr std::size_t kMaxSettings = 10000;

// The cartesian product, first axis slowest. No axes: one setting without assignments. The
// same path twice is an error naming it; more than kMaxSettings settings is kLimit.
Result<std::vector<Setting>> expand_sweeps(const std::vector<SweepAxis>& axes);

// Several sweeps in one run (a suite comparing two criteria on one plot): each group is expanded
// as above and the settings are concatenated with running indices. An axis with one value acts
// as a fixed assignment of its group. No groups: one setting without assignments.
Result<std::vector<Setting>> expand_sweep_groups(const std::vector<std::vector<SweepAxis>>& groups);

// Every path that some group sweeps, in order of first appearance (the CSV's columns).
std::vector<std::string> swept_paths(const std::vector<std::vector<SweepAxis>>& groups);

}  // namespace sylva::bench

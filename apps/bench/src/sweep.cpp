#include "sweep.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace sylva::bench {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

std::string Setting::label() const {
  if (assignments.empty()) return "(scene as loaded)";
  std::string out;
  for (const Assignment& a : assignments) {
    if (!out.empty()) out += ", ";
    out += a.path + "=" + a.value;
  }
  return out;
}

std::string Setting::id() const { return fmt::format("s{:03}", index); }

Result<std::vector<std::string>> split_values(std::string_view list) {
  std::vector<std::string> values;
  int depth = 0;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= list.size(); ++i) {
    const char c = i < list.size() ? list[i] : ',';
    if (c == '[') {
      ++depth;
    } else if (c == ']') {
      if (--depth < 0) {
        return make_error(ErrorCode::kInvalidArgument,
                          fmt::format("\"{}\": ']' at character {} has no matching '['", list, i + 1));
      }
    } else if (c == ',' && depth == 0) {
      values.emplace_back(trim(list.substr(start, i - start)));
      start = i + 1;
    }
  }
  if (depth != 0) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("\"{}\": a '[' is never closed", list));
  }
  return values;
}

Result<SweepAxis> parse_sweep(std::string_view text) {
  const auto eq = text.find('=');
  if (eq == std::string_view::npos) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("--sweep \"{}\": expected path=v1,v2,... such as terrain.max_pixel_error=0.5,1,2", text));
  }
  SweepAxis axis;
  axis.path = std::string(trim(text.substr(0, eq)));
  if (axis.path.empty()) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("--sweep \"{}\": the parameter path is empty", text));
  }
  const std::string_view list = trim(text.substr(eq + 1));
  if (list.empty()) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("--sweep {}: no values given", axis.path));
  }
  auto values = split_values(list);
  if (!values.ok()) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("--sweep {}: {}", axis.path, values.error().message));
  }
  for (std::size_t i = 0; i < values->size(); ++i) {
    if ((*values)[i].empty()) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("--sweep {}: value {} of \"{}\" is empty", axis.path, i + 1, list));
    }
  }
  axis.values = std::move(*values);
  return axis;
}

Result<std::vector<Setting>> expand_sweeps(const std::vector<SweepAxis>& axes) {
  std::size_t total = 1;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    for (std::size_t b = 0; b < a; ++b) {
      if (axes[a].path == axes[b].path) {
        return make_error(ErrorCode::kInvalidArgument,
                          fmt::format("--sweep {} is given twice; list all its values in one --sweep", axes[a].path));
      }
    }
    if (axes[a].values.empty()) {
      return make_error(ErrorCode::kInvalidArgument, fmt::format("--sweep {}: no values given", axes[a].path));
    }
    total *= axes[a].values.size();
    if (total > kMaxSettings) {
      return make_error(ErrorCode::kLimit, fmt::format("the sweeps expand to more than {} settings; split the run",
                                                       kMaxSettings));
    }
  }
  std::vector<Setting> settings;
  settings.reserve(total);
  std::vector<std::size_t> digit(axes.size(), 0);
  for (std::size_t n = 0; n < total; ++n) {
    Setting s;
    s.index = n;
    for (std::size_t a = 0; a < axes.size(); ++a) s.assignments.push_back({axes[a].path, axes[a].values[digit[a]]});
    settings.push_back(std::move(s));
    // Odometer increment: the last axis varies fastest.
    for (std::size_t a = axes.size(); a-- > 0;) {
      if (++digit[a] < axes[a].values.size()) break;
      digit[a] = 0;
    }
  }
  return settings;
}

Result<std::vector<Setting>> expand_sweep_groups(const std::vector<std::vector<SweepAxis>>& groups) {
  if (groups.empty()) return expand_sweeps({});
  std::vector<Setting> all;
  for (const std::vector<SweepAxis>& g : groups) {
    auto part = expand_sweeps(g);
    if (!part.ok()) return part.error();
    if (all.size() + part->size() > kMaxSettings) {
      return make_error(ErrorCode::kLimit, fmt::format("the sweeps expand to more than {} settings; split the run",
                                                       kMaxSettings));
    }
    for (Setting& s : *part) {
      s.index = all.size();
      all.push_back(std::move(s));
    }
  }
  return all;
}

std::vector<std::string> swept_paths(const std::vector<std::vector<SweepAxis>>& groups) {
  std::vector<std::string> paths;
  for (const auto& g : groups) {
    for (const SweepAxis& a : g) {
      if (std::find(paths.begin(), paths.end(), a.path) == paths.end()) paths.push_back(a.path);
    }
  }
  return paths;
}

}  // namespace sylva::bench

#pragma once
// The files of modules/voxel/data/ (grammars and the shipped species table), embedded into the
// binary at configure time by modules/voxel/CMakeLists.txt.

#include <optional>
#include <string_view>
#include <utility>

namespace sylva::voxel::detail {
extern const std::pair<std::string_view, std::string_view> kEmbeddedData[];
extern const int kEmbeddedDataCount;

// The content of an embedded file by name ("acacia.lsys"), nullopt when there is none.
inline std::optional<std::string_view> embedded_file(std::string_view name) {
  for (int i = 0; i < kEmbeddedDataCount; ++i) {
    if (kEmbeddedData[i].first == name) return kEmbeddedData[i].second;
  }
  return std::nullopt;
}
}  // namespace sylva::voxel::detail

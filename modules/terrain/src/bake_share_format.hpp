#pragma once
// Byte layout of a bake share file (bake.hpp has the contract). Offsets in bytes, little endian.
// kShHeightTile: samples per side of the ground height tiles that follow the header (uint16), and
// kShHeightOverview the stride of their overview (uint16, 0 = none; chunk_file_heights.hpp): the
// same section the chunk file holds at the same offset.

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace sylva::terrain::detail {

inline constexpr char kShareMagic[8] = {'S', 'Y', 'L', 'V', 'A', 'S', 'H', 'R'};
inline constexpr std::size_t kShareHeaderBytes = 128;
inline constexpr std::size_t kShareEntryBytes = 48;

// Header.
inline constexpr std::size_t kShVersion = 8, kShIndex = 12, kShCount = 16, kShColumns = 20, kShRows = 24,
                             kShLeafDimension = 28, kShSpacing = 32, kShOriginX = 40, kShOriginZ = 48,
                             kShFlatTolerance = 56, kShMaxMorph = 60, kShOptimize = 64, kShFirstSlot = 68,
                             kShEndSlot = 72, kShHeightTile = 76, kShHeightOverview = 78, kShDirOffset = 80, kShDirBytes = 88, kShDirChecksum = 96,
                             kShFileBytes = 104, kShHeaderChecksum = 120;
// Directory entry.
inline constexpr std::size_t kSePresent = 0, kSeError = 4, kSeMinY = 8, kSeMaxY = 12, kSeTriangles = 16,
                             kSeVertices = 20, kSeOffset = 24, kSeBytes = 32, kSeChecksum = 40;

// Slots [first, end) of share `share` of `shares`: the present chunks (ascending slots) cut into
// `shares` contiguous runs of equal count; the runs tile [0, slot_count) with no gap.
inline std::pair<std::uint32_t, std::uint32_t> share_slots(const std::vector<std::uint32_t>& present,
                                                           std::uint32_t slot_count, int share, int shares) {
  const std::size_t p = present.size();
  const std::size_t b = p * static_cast<std::size_t>(share) / static_cast<std::size_t>(shares);
  const std::size_t e = p * static_cast<std::size_t>(share + 1) / static_cast<std::size_t>(shares);
  const std::uint32_t first = share == 0 ? 0u : (b < p ? present[b] : slot_count);
  const std::uint32_t end = share + 1 == shares ? slot_count : (e < p ? present[e] : slot_count);
  return {first, end};
}

}  // namespace sylva::terrain::detail

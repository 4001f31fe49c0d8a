#pragma once
// Region files: chunks saved in groups of 8x8x8 per file "r.<x>.<y>.<z>.svr" (seed 004 streams
// objects around the player, §3.5, but never saves them; this is beyond the seed).
//
// Format v1 (little-endian):
//   "SYLVAVXR" u32 version u32 chunk_size i64 rx ry rz
//   u32 name_count { u16 length, bytes }        block names, so ids survive palette changes
//   u32 entry_count { u16 local chunk index, u16 encoding, u32 offset, u32 size, u32 crc32 }
//   u32 crc32 of everything above                 header checksum
//   payload: each chunk as runs { u16 name index, u16 run length - 1 } covering 32^3 ids
// The file size must equal header + payload exactly, so truncation is detected.
//
// Writes go to a temporary file in the same folder that is renamed over the old file, so a
// failed or interrupted save never destroys the previous region. A corrupt region (bad magic,
// version, checksum, size, run or unknown block name) is reported as kCorrupt/kNotFound naming
// the file and, for a single chunk, the chunk; the caller regenerates what it cannot read.

#include <sylva/core/result.hpp>
#include <sylva/voxel/block.hpp>
#include <sylva/voxel/chunk.hpp>
#include <sylva/voxel/coords.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace sylva::voxel {

inline constexpr int kRegionShift = 3;
inline constexpr int kRegionSize = 1 << kRegionShift;  // chunks per region edge
inline constexpr std::uint32_t kRegionVersion = 1;

struct RegionCoord {
  std::int64_t x = 0, y = 0, z = 0;
  bool operator==(const RegionCoord&) const = default;
  auto operator<=>(const RegionCoord&) const = default;
};
constexpr RegionCoord region_of(const ChunkCoord& c) {
  return {c.x >> kRegionShift, c.y >> kRegionShift, c.z >> kRegionShift};
}
std::string region_file_name(const RegionCoord& r);

// IEEE 802.3 CRC-32 (the zlib polynomial).
std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0);

// One decoded region: the chunks that read back, and the ones that failed their checksum.
struct RegionContents {
  RegionCoord coord;
  std::map<ChunkCoord, Chunk> chunks;
  std::map<ChunkCoord, Error> bad_chunks;
};

// Encodes a region (all chunks must belong to `r`, asserted) to bytes.
std::vector<std::uint8_t> encode_region(const RegionCoord& r, const BlockPalette& palette,
                                        std::span<const std::pair<ChunkCoord, const Chunk*>> chunks);
// Decodes bytes; `source` names the file in messages. A damaged header fails as a whole;
// damaged chunk payloads land in bad_chunks.
Result<RegionContents> decode_region(std::span<const std::uint8_t> bytes, const BlockPalette& palette,
                                     const std::string& source);

Result<RegionContents> read_region_file(const std::filesystem::path& path, const BlockPalette& palette);
Status write_region_file(const std::filesystem::path& path, const RegionCoord& r, const BlockPalette& palette,
                         std::span<const std::pair<ChunkCoord, const Chunk*>> chunks);

// A folder of region files with a small LRU cache of decoded regions (a streamed world visits
// regions one after another; the cache never holds more than `cache_regions` of them).
class RegionStore {
 public:
  RegionStore(std::filesystem::path folder, const BlockPalette& palette, std::size_t cache_regions = 8);

  // nullopt when the chunk was never saved; kCorrupt/kNotFound when its region or payload is
  // damaged (the message names the file and chunk; the caller regenerates the chunk).
  Result<std::optional<Chunk>> load(const ChunkCoord& c);

  // Saves the given chunks, merging them into their regions' existing chunks (unreadable old
  // contents are replaced, with a warning). Every region file is written atomically.
  Status save(std::span<const std::pair<ChunkCoord, const Chunk*>> chunks);

  const std::filesystem::path& folder() const { return folder_; }
  std::filesystem::path path_of(const RegionCoord& r) const { return folder_ / region_file_name(r); }

  // Forgets cached regions (after files changed on disk behind the store's back).
  void clear_cache() { cache_.clear(); }
  std::size_t cached_regions() const { return cache_.size(); }

 private:
  struct CacheEntry {
    std::shared_ptr<RegionContents> contents;  // null when the file does not exist
    std::optional<Error> error;                // whole-file failure
    std::uint64_t last_use = 0;
  };
  const CacheEntry& region(const RegionCoord& r);

  std::filesystem::path folder_;
  const BlockPalette* palette_;
  std::map<RegionCoord, CacheEntry> cache_;
  std::size_t cache_limit_ = 8;
  std::uint64_t use_clock_ = 0;
};

}  // namespace sylva::voxel

// Voxel region files (modules/voxel region.cpp decode_region). Every input is decoded as given
// (magic, version, size and checksum checks) and again with its checksums recomputed, so mutated
// headers and runs reach the decoder behind the CRCs. What decodes must encode and decode back.
#include "support/fuzz_support.hpp"

#include <sylva/voxel/region.hpp>

namespace {

using sylva::fuzz::load;
using sylva::fuzz::store;
using sylva::voxel::crc32;

// Walks the header layout of region.hpp and rewrites every chunk CRC and the header CRC.
// Returns false when the header is too short to walk.
bool repair_checksums(std::vector<std::uint8_t>& b) {
  std::size_t pos = 40;  // magic, version, chunk size, region x y z
  if (b.size() < pos + 4) return false;
  const std::uint32_t names = load<std::uint32_t>(b, pos);
  pos += 4;
  for (std::uint32_t i = 0; i < names && i <= 65536; ++i) {
    if (b.size() < pos + 2) return false;
    pos += 2 + (b[pos] | (b[pos + 1] << 8));
  }
  if (b.size() < pos + 4) return false;
  const std::uint32_t entries = std::min<std::uint32_t>(load<std::uint32_t>(b, pos), 512);
  pos += 4;
  const std::size_t table = pos;
  const std::size_t header_end = table + std::size_t{16} * entries;
  if (b.size() < header_end + 4) return false;
  const std::size_t payload = header_end + 4;
  for (std::size_t e = table; e < header_end; e += 16) {
    const std::size_t offset = load<std::uint32_t>(b, e + 4), size = load<std::uint32_t>(b, e + 8);
    if (payload + offset + size <= b.size()) {
      store<std::uint32_t>(b, e + 12, crc32(std::span<const std::uint8_t>(b).subspan(payload + offset, size)));
    }
  }
  store<std::uint32_t>(b, header_end, crc32(std::span<const std::uint8_t>(b).first(header_end)));
  return true;
}

void decode(std::span<const std::uint8_t> bytes) {
  using namespace sylva::voxel;
  const BlockPalette& palette = BlockPalette::standard();
  auto region = decode_region(bytes, palette, "fuzz.svr");
  if (!region.ok()) {
    sylva::fuzz::require_message(region.error());
    return;
  }
  std::vector<std::pair<ChunkCoord, const Chunk*>> chunks;
  for (const auto& [coord, chunk] : region->chunks) chunks.emplace_back(coord, &chunk);
  const std::vector<std::uint8_t> encoded = encode_region(region->coord, palette, chunks);
  auto again = decode_region(encoded, palette, "encoded.svr");
  sylva::fuzz::require(again.ok() && again->bad_chunks.empty() && again->chunks.size() == region->chunks.size(),
                       "a decoded region does not encode and decode back");
  for (const auto& [coord, chunk] : region->chunks) {
    std::vector<BlockId> before(kChunkVolume), after(kChunkVolume);
    chunk.copy_to(before);
    again->chunks.at(coord).copy_to(after);
    sylva::fuzz::require(before == after, "a chunk changed through encode and decode");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  decode({data, size});
  std::vector<std::uint8_t> repaired(data, data + size);
  if (repair_checksums(repaired)) decode(repaired);
  return 0;
}

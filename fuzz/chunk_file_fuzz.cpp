// Terrain chunk files (modules/terrain chunk_file.cpp): the bytes are written to a temporary file
// (ChunkFile opens a path), opened, and every present chunk read. Each input is tried as given
// and with its FNV checksums and size field recomputed, so mutations reach the directory and
// mesh decoding behind them.
#include "support/fuzz_support.hpp"

#include <sylva/terrain/chunk_file.hpp>

namespace {

constexpr std::size_t kHeaderBytes = 128;  // chunk_file.hpp layout
constexpr std::size_t kEntryBytes = 64;

using sylva::fuzz::load;
using sylva::fuzz::store;

// Rewrites the blob checksums of the directory entries, the directory checksum, the file size
// and the header checksum. Returns false when there is no header to repair.
bool repair_checksums(std::vector<std::uint8_t>& b) {
  using sylva::terrain::fnv1a64;
  const std::size_t size = b.size();
  if (size < kHeaderBytes) return false;
  const std::uint64_t dir_offset = load<std::uint64_t>(b, 80), dir_bytes = load<std::uint64_t>(b, 88);
  if (dir_offset <= size && dir_bytes <= size - dir_offset) {
    for (std::uint64_t e = dir_offset; e + kEntryBytes <= dir_offset + dir_bytes; e += kEntryBytes) {
      const std::uint64_t offset = load<std::uint64_t>(b, e + 40), bytes = load<std::uint64_t>(b, e + 48);
      if (offset <= size && bytes <= size - offset) store<std::uint64_t>(b, e + 56, fnv1a64(b.data() + offset, bytes));
    }
    store<std::uint64_t>(b, 96, fnv1a64(b.data() + dir_offset, dir_bytes));
  }
  store<std::uint64_t>(b, 104, size);
  store<std::uint64_t>(b, 120, fnv1a64(b.data(), 120));
  return true;
}

void open_and_read(std::span<const std::uint8_t> bytes) {
  using sylva::terrain::ChunkFile;
  auto file = ChunkFile::open(sylva::fuzz::write_temp_file(bytes, ".chunks"));
  if (!file.ok()) {
    sylva::fuzz::require_message(file.error());
    return;
  }
  const ChunkFile& f = **file;
  const std::uint32_t count = static_cast<std::uint32_t>(std::min<std::size_t>(f.tree().chunk_count(), 1024));
  for (std::uint32_t i = 0; i < count; ++i) {
    if (!f.tree().chunk(i).present) continue;
    (void)f.mesh_bytes(i);
    auto mesh = f.read_chunk(i);
    if (!mesh.ok()) sylva::fuzz::require_message(mesh.error());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  open_and_read({data, size});
  std::vector<std::uint8_t> repaired(data, data + size);
  if (repair_checksums(repaired)) open_and_read(repaired);
  return 0;
}

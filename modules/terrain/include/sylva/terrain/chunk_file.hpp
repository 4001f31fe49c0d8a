#pragma once
// The built chunk tree on disk, for out-of-core terrains (seed 002 future work: "swap unneeded
// terrain parts to disk").
//
// Layout (little endian): a 128-byte header (magic "SYLVACHK", version, field geometry, tree
// settings, directory offset and size, total file size, FNV-1a 64 checksums of the directory and
// of the header itself), then every chunk's mesh blob, then the directory: one 64-byte entry per
// chunk slot (presence, key, errors, bounds, counts, blob offset, size and checksum). Opening
// reads and verifies the header and directory only; chunk blobs are read and verified on demand.
// A truncated or corrupt file gives a clear error naming the file and what is wrong (and the
// chunk, for a blob), never a crash.

#include <sylva/core/result.hpp>
#include <sylva/terrain/chunk_tree.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>

namespace sylva::terrain {

inline constexpr std::uint32_t kChunkFileVersion = 1;

// Writes the tree (which must hold its meshes) through a temporary file and a rename.
Status save_chunk_file(const std::filesystem::path& path, const ChunkTree& tree);

class ChunkFile {
 public:
  // Verifies header, directory and file size. Errors: kNotFound, kIo, kCorrupt (bad magic,
  // checksum, truncation, inconsistent sizes), kUnsupported (another version).
  static Result<std::shared_ptr<ChunkFile>> open(const std::filesystem::path& path);

  // The tree's metadata (errors, bounds, counts, geometry) without meshes: what selection needs.
  const ChunkTree& tree() const { return tree_; }
  const std::filesystem::path& path() const { return path_; }

  // Reads, verifies and decodes one chunk's mesh. Thread-safe. Errors (kCorrupt/kIo) name the
  // file and the chunk.
  Result<ChunkMesh> read_chunk(std::uint32_t index) const;
  // Bytes the decoded mesh of a chunk occupies in memory (for memory budgets).
  std::size_t mesh_bytes(std::uint32_t index) const;

 private:
  struct Entry {
    std::uint64_t offset = 0, bytes = 0, checksum = 0;
    std::uint32_t vertices = 0, indices = 0;
  };
  std::filesystem::path path_;
  ChunkTree tree_;
  std::vector<Entry> entries_;
  mutable std::mutex mutex_;
  mutable std::ifstream in_;
};

// FNV-1a 64 of a byte range (exposed for tests that corrupt files on purpose).
std::uint64_t fnv1a64(const void* data, std::size_t bytes, std::uint64_t seed = 0xcbf29ce484222325ull);

}  // namespace sylva::terrain

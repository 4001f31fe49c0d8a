#pragma once
// The built chunk tree on disk, for out-of-core terrains (seed 002 future work: "swap unneeded
// terrain parts to disk").
//
// Layout (little endian): a 128-byte header (magic "SYLVACHK", version, field geometry, tree
// settings, directory offset and size, total file size, a 64-bit tag (0 unless the writer set one;
// the tree cache stores its key there, tree_cache.hpp), FNV-1a 64 checksums of the directory and
// of the header itself), then every chunk's mesh blob, then the directory: one 64-byte entry per
// chunk slot (presence, key, errors, bounds, counts, blob offset, size and checksum). Opening
// reads and verifies the header and directory only; chunk blobs are read and verified on demand.
// A truncated or corrupt file gives a clear error naming the file and what is wrong (and the
// chunk, for a blob), never a crash.

#include <sylva/core/hash.hpp>
#include <sylva/core/height_field.hpp>
#include <sylva/core/result.hpp>
#include <sylva/terrain/chunk_tree.hpp>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>

namespace sylva::terrain {

// 2: the ground heights after the header; 3: with an overview of them (chunk_file_heights.hpp).
// Version 2 files are still read (their section is version 3's without an overview).
inline constexpr std::uint32_t kChunkFileVersion = 3;

// A field with more samples than this gets an overview in its height section: every 2nd, 4th, ...
// sample, at most this many (4097^2: 64 MiB; 16385^2 -> every 4th sample), which is what a scene
// reads as its ground (scene/baked_ground.hpp) instead of every tile of the field.
inline constexpr std::uint64_t kHeightOverviewMaxSamples = std::uint64_t{4097} * 4097;

// Rows of ground heights for a writer: fill `out` with the `width` samples of row z from x0 on
// [m]. Called tile by tile (256^2); an error stops the writing and is returned.
using HeightRows = std::function<Status(int z, int x0, int width, float* out)>;

// Writes the tree (which must hold its meshes) through a temporary file and a rename. `tag` goes
// into the header (ChunkFile::tag()). `ground`: the field the tree was built from, stored as the
// ground height section (its columns and rows must equal the tree's, asserted); nullptr = none
// (the tree cache, which keeps its field elsewhere). `overview_max_samples`: the ground's
// overview limit (height_overview_stride; tests use small ones).
Status save_chunk_file(const std::filesystem::path& path, const ChunkTree& tree, std::uint64_t tag = 0,
                       const HeightField* ground = nullptr,
                       std::uint64_t overview_max_samples = kHeightOverviewMaxSamples);

// The overview stride of a columns x rows field's height section: the smallest power of two
// giving at most `max_samples` samples, 0 (no overview) when the field itself has no more.
std::uint32_t height_overview_stride(int columns, int rows, std::uint64_t max_samples = kHeightOverviewMaxSamples);

// Writes a chunk file chunk by chunk, so a tree too big for memory can be saved (bake.hpp): blobs
// go to a temporary file beside the target as they come, the directory and header at finish(),
// then fsync + rename. Nothing appears at the target unless finish() succeeds; an unfinished
// writer (error, cancellation, destruction) removes its temporary. For the same chunks the bytes
// equal save_chunk_file's (which uses it).
class ChunkFileWriter {
 public:
  // `layout`: the tree's geometry, settings and chunk slots (ChunkTreeBuilder::layout or a built
  // tree). Errors: kIo naming `path` (missing folder, read-only target, cannot create).
  // `overwrite`: instead of a new temporary, write over this existing file of ours (beside
  // `path`), which becomes the temporary: blobs added must then lie where the file already holds
  // blobs of the same sizes in the same order (the bake's one-process share, bake.hpp).
  // `heights`: the file gets a ground height section of the layout's field size: written by
  // write_heights() before the first add(), or, with `overwrite`, already in that file;
  // `overview_stride`: its overview (height_overview_stride; 0 = none).
  static Result<std::unique_ptr<ChunkFileWriter>> create(const std::filesystem::path& path, const ChunkTree& layout,
                                                         const std::filesystem::path& overwrite = {},
                                                         bool heights = false, std::uint32_t overview_stride = 0);
  ~ChunkFileWriter();
  ChunkFileWriter(const ChunkFileWriter&) = delete;
  ChunkFileWriter& operator=(const ChunkFileWriter&) = delete;

  // Slot `index` (strictly increasing over the calls; skipped slots stay absent): its metadata
  // (present, error, error_bound, min/max y, counts) and, when present, its mesh or encoded blob.
  // Errors: kIo naming the file (disk full); the temporary is then removed.
  Status add(std::uint32_t index, const Chunk& chunk, const ChunkMesh& mesh);
  Status add(std::uint32_t index, const Chunk& chunk, std::string_view blob);
  // The same with the blob's fnv1a64 computed by the caller (on another thread).
  Status add(std::uint32_t index, const Chunk& chunk, std::string_view blob, std::uint64_t checksum);
  // The ground height section (create() with heights, no overwrite; once, before add()).
  // Errors: the row source's, kIo naming the file; the temporary is then removed.
  Status write_heights(const HeightRows& rows);
  // The header's tag (default 0), written at finish().
  void set_tag(std::uint64_t tag);
  // Directory, header, fsync, rename over the target. Errors: kIo naming the file.
  Status finish();
  // Stops and removes the temporary (no-op once finished).
  void abandon();

 private:
  ChunkFileWriter() = default;
  Status write_failed();
  std::filesystem::path path_, temp_;
  std::ofstream out_;
  std::string header_, directory_;
  std::uint64_t offset_ = 128;
  std::int64_t last_ = -1;
  bool heights_pending_ = false;
  bool done_ = false;
};

class ChunkFile {
 public:
  // Verifies header, directory and file size. Errors: kNotFound, kIo, kCorrupt (bad magic,
  // checksum, truncation, inconsistent sizes), kUnsupported (another version).
  static Result<std::shared_ptr<ChunkFile>> open(const std::filesystem::path& path);

  // The tree's metadata (errors, bounds, counts, geometry) without meshes: what selection needs.
  const ChunkTree& tree() const { return tree_; }
  const std::filesystem::path& path() const { return path_; }
  // The header's tag: what the writer stored there (0 for a bake or a plain save_chunk_file).
  std::uint64_t tag() const { return tag_; }

  // Whether the file holds the ground heights (version 2 files written with them: every bake).
  bool has_heights() const { return height_tile_ != 0; }
  // The stride of the heights' overview, 0 = none (a field of at most kHeightOverviewMaxSamples,
  // or a version-2 file).
  std::uint32_t height_overview() const { return height_overview_; }
  std::uint32_t version() const { return version_; }
  // The ground: every `stride`-th sample (stride >= 1) of the baked field in x and z, from sample
  // (0, 0), placed like the tree (origin, spacing x stride). Reads the overview's tiles when
  // stride is a multiple of its stride, else the field's; each tile verified, on every thread.
  // Errors: kInvalidArgument without heights, kCorrupt naming the file and the tile (checksum,
  // truncation).
  Result<HeightField> read_heights(int stride = 1) const;
  // Bytes of height tiles read so far by read_heights (a statistic: the overview's worth).
  std::uint64_t height_bytes_read() const { return height_bytes_read_; }
  // The smallest power-of-two stride whose ground has at most `max_samples` samples.
  int height_stride(std::uint64_t max_samples) const;

  // Reads, verifies and decodes one chunk's mesh. Thread-safe. Errors (kCorrupt/kIo) name the
  // file and the chunk.
  Result<ChunkMesh> read_chunk(std::uint32_t index) const;
  // Bytes the decoded mesh of a chunk occupies in memory (for memory budgets).
  std::size_t mesh_bytes(std::uint32_t index) const;

  // The whole tree with every chunk's mesh, equal to the ChunkTree::build that wrote the file
  // (vertices, indices, edges, errors, bounds, nodes; the report has the levels, no times). The
  // file stores leaf_dimension, flat_tolerance and max_morph_fraction: they must equal
  // `settings`' (else kInvalidArgument naming the parameter and both values); the rest
  // (optimize_vertex_cache, threads, max_build_bytes) is taken from `settings`, keep_meshes is
  // true. Chunks are read in slot order and verified and decoded on settings.threads threads.
  // Errors: as read_chunk (the first bad chunk, named), kCancelled.
  Result<ChunkTree> read_tree(const ChunkTreeSettings& settings, const BuildControl& control = {}) const;

 private:
  struct Entry {
    std::uint64_t offset = 0, bytes = 0, checksum = 0;
    std::uint32_t vertices = 0, indices = 0;
  };
  std::filesystem::path path_;
  std::uint64_t tag_ = 0;
  std::uint32_t height_tile_ = 0;
  std::uint32_t height_overview_ = 0;
  std::uint32_t version_ = 0;
  mutable std::atomic<std::uint64_t> height_bytes_read_{0};
  std::vector<std::uint64_t> height_table_;  // per-tile checksums
  ChunkTree tree_;
  std::vector<Entry> entries_;
  mutable std::mutex mutex_;
  mutable std::ifstream in_;
};

// FNV-1a 64 of a byte range (core/hash.hpp; tests that corrupt files on purpose recompute it).
using sylva::fnv1a64;

}  // namespace sylva::terrain

#pragma once
// Baking a terrain's chunk tree into a chunk file without holding the tree in memory (issue 15;
// seed 002 future work, "swap unneeded terrain parts to disk"; DESIGN.md §2: long work shows
// progress and can be cancelled). The engine behind `sylva-bake terrain`.
//
// How. ChunkTreeBuilder::prepare computes the padded height grid and the RTIN error grid once
// (4 + 4 bytes per root-grid point); chunks are then meshed in batches on every thread and their
// blobs streamed to disk in slot order, so only one batch of meshes is in memory at a time. A
// vertex's morph_error is the error bound of the coarser chunks holding it, and a bound depends
// on every descendant's measured error (seed 002 §2.2 after Ulrich: "a child halves the error"),
// so blobs are first written with morph_error = 0 into a *share* file (one per process with
// `--tiles I/N`, or one temporary), and merge_bake_shares computes the bounds from the shares'
// directories and copies the blobs in slot order into the chunk file, patching morph_error.
// Result: byte for byte save_chunk_file(ChunkTree::build(field)), for any number of shares
// (tested: one process and three, against the in-memory build).
//
// Share file ("SYLVASHR", little endian): 128-byte header (version, share I of N, field geometry,
// tree settings, slot range, directory place, height tile size, FNV-1a 64 checksums of directory
// and header), the ground height section (every share holds the whole field's, as the chunk file
// does: chunk_file.hpp), the share's blobs, a 48-byte directory entry per slot of its range. The
// merge copies share 0's heights tile by tile, verified, after checking that every share's
// height table is the same. Shares are written through a
// temporary and a rename: a killed bake leaves no share and no chunk file, only nothing.
//
// Failure: every error names the file (and the chunk or share); nothing is left at the target
// unless the whole file was written (temporary + fsync + rename, core/atomic_file.hpp).

#include <sylva/core/height_field.hpp>
#include <sylva/core/result.hpp>
#include <sylva/terrain/chunk_file.hpp>
#include <sylva/terrain/chunk_tree.hpp>

#include <cstdint>
#include <filesystem>
#include <vector>

namespace sylva::terrain {

// 2: the ground heights after the header; 3: with their overview (chunk_file.hpp).
inline constexpr std::uint32_t kBakeShareVersion = 3;

struct BakeOptions {
  ChunkTreeSettings tree;        // keep_meshes is ignored: a bake always writes the meshes
  int share = 0;                 // this process bakes share `share` of `shares`: [0, shares)
  int shares = 1;                // 1..1024; shares split the present chunks into contiguous runs
  // Meshes held at once while baking, at most about this many bytes (at least one chunk per
  // thread): the "memory budget" on top of the grids (8 bytes per root-grid point).
  std::size_t batch_bytes = std::size_t{64} << 20;
  // A field with more samples gets an overview of its ground heights (chunk_file.hpp); the shares
  // of one bake must agree (merge checks their height tables).
  std::uint64_t overview_max_samples = kHeightOverviewMaxSamples;
  BuildControl control;          // progress in [0, 1] and cancellation (checked between chunks)
};

struct BakeReport {
  double prepare_ms = 0.0;       // height and error grids
  double meshes_ms = 0.0;        // meshing and writing the share(s)
  double merge_ms = 0.0;         // bounds and the copy into the chunk file
  std::uint64_t chunks = 0;      // present chunks written
  std::uint64_t triangles = 0;
  std::uint64_t bytes = 0;       // size of the file written [B]
};

// Bakes share options.share of options.shares into `share_file`. The field is taken by value
// and released as soon as it is in the height grid (std::move a big one in: for a (2^k+1)^2
// field the bake then holds 8 bytes per sample, not 12). Errors: invalid options or field (as
// ChunkTree::build), kIo naming the file (cannot write, disk full), kCancelled.
Result<BakeReport> bake_share(HeightField field, const std::filesystem::path& share_file,
                              const BakeOptions& options);

// Joins the shares 0..N-1 of one bake (any order on the command line) into the chunk file `out`.
// Errors name the share file (and chunk): kNotFound, kCorrupt (bad magic, checksum, truncation),
// kUnsupported (another version), kInvalidArgument (shares of different bakes, missing or
// repeated shares), kIo, kCancelled.
Result<BakeReport> merge_bake_shares(const std::vector<std::filesystem::path>& shares,
                                     const std::filesystem::path& out, const BuildControl& control = {});

// One process: bake_share(0 of 1) into a temporary beside `out`, then merge_bake_shares.
Result<BakeReport> bake_chunk_file(HeightField field, const std::filesystem::path& out,
                                   const BakeOptions& options);

}  // namespace sylva::terrain

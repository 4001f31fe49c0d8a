#pragma once
// The chunk-tree cache (issue 15: a scene names the raw source, "baked on first use into a cache
// file keyed by the source's content hash and the tree settings, so the second launch reopens it
// without rebuilding"; DESIGN.md §2: long work is cached by content hash).
//
// A cache file is a chunk file (chunk_file.hpp) named after its key, with the key in the header's
// tag. Key: FNV-1a 64 of the cache version, the chunk file version, the field's geometry (columns,
// rows, spacing, origin), the settings that change the tree (leaf_dimension, flat_tolerance,
// max_morph_fraction, keep_meshes, optimize_vertex_cache) and every sample's bytes. threads and
// max_build_bytes are left out: they never change the tree (chunk_tree_test), so changing them
// must not throw a cache away. An edited field (the editor's height painting) has another key.
//
// Failure is never an error of the caller: a missing file is a miss; a damaged, truncated,
// foreign or mismatched one is a warning naming the file and why, a rebuild and a replacement; a
// write that fails (read-only folder, full disk) is a warning. Writes go through a temporary and
// a rename (core/atomic_file.hpp), so a killed launch leaves no half file under a cache name.

#include <sylva/core/height_field.hpp>
#include <sylva/core/result.hpp>
#include <sylva/terrain/chunk_tree.hpp>
#include <sylva/terrain/settings.hpp>

#include <cstdint>
#include <filesystem>
#include <string>

namespace sylva::terrain {

// Raise when ChunkTree::build gives other output for the same input (the chunk file format may
// stay the same while every cached tree becomes stale).
inline constexpr std::uint32_t kTreeCacheVersion = 1;

enum class TreeCacheOutcome : std::uint8_t {
  kOff,   // no folder, keep_meshes off, or the field is below min_samples: built, not cached
  kHit,   // loaded from the cache
  kMiss,  // built, then written to the cache (or the write failed with a warning)
};
// "off", "hit", "miss" (the terrain module's `tree_cache` statistic).
const char* to_string(TreeCacheOutcome outcome);

// The key above. Reads every sample once (~0.1 s per 4097^2 field on this machine).
std::uint64_t chunk_tree_cache_key(const HeightField& field, const ChunkTreeSettings& settings);

// "<directory>/terrain-<key as 16 hex digits>.sylvaterrain".
std::filesystem::path chunk_tree_cache_file(const std::filesystem::path& directory, std::uint64_t key);

// The folder of a TreeCacheSettings::directory value: "" = none (empty path), "auto" =
// <temp>/sylva-terrain-cache (empty when there is no temp folder), a relative path is taken
// relative to `base` (the scene file's folder), an absolute one as it is.
std::filesystem::path resolve_tree_cache_directory(const std::string& setting, const std::filesystem::path& base);

// Opens a cache file and reads the whole tree, refusing one that was not made from this field and
// these settings. Errors: kNotFound; kCorrupt / kUnsupported naming the file (and chunk);
// kInvalidArgument naming the file and what differs (the key, the field's size, spacing or
// origin, a tree setting); kCancelled.
Result<ChunkTree> load_cached_chunk_tree(const std::filesystem::path& file, const HeightField& field,
                                         const ChunkTreeSettings& settings, std::uint64_t key,
                                         const BuildControl& control = {});

// Creates the folder, writes the tree (with meshes) with `key` as its tag atomically, then deletes
// the least recently used cache files beyond `max_files`. Errors: kIo naming the file.
Status save_cached_chunk_tree(const std::filesystem::path& file, const ChunkTree& tree, std::uint64_t key,
                              int max_files);

struct CachedChunkTree {
  ChunkTree tree;
  TreeCacheOutcome cache = TreeCacheOutcome::kOff;
  std::filesystem::path file;  // the cache file (empty when off)
  double key_ms = 0.0;         // hashing the field
  double load_ms = 0.0;        // reading the cache file (a hit, or a rejected file)
  double build_ms = 0.0;       // ChunkTree::build (a miss or off)
  double save_ms = 0.0;        // writing the cache file (a miss)
};

// The tree of `field`: from the cache when `cache` names a folder, the settings keep meshes and
// the field has at least cache.min_samples samples and a valid file exists; else built by
// ChunkTree::build and, when cached, written. Errors: only ChunkTree::build's (the cache's own
// failures are warnings, see above).
Result<CachedChunkTree> build_or_load_chunk_tree(const HeightField& field, const ChunkTreeSettings& settings,
                                                 const TreeCacheSettings& cache, const std::filesystem::path& base,
                                                 const BuildControl& control = {});

}  // namespace sylva::terrain

// The chunk-tree cache (tree_cache.hpp, issue 15): the key changes with every sample and every
// setting that changes the tree and with nothing else; a cached tree equals the built one (and
// edits on it equal edits on a built one); mismatched, truncated and foreign files are refused
// by name and rebuilt; a folder that cannot be written is a warning, never an error.
#include <sylva/terrain/chunk_file.hpp>
#include <sylva/terrain/tree_cache.hpp>

#include "support/terrain_test_support.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <chrono>
#include <cstring>
#include <fstream>

namespace sylva::terrain {
namespace {

using namespace testing;
namespace fs = std::filesystem;

ChunkTreeSettings small_settings() {
  ChunkTreeSettings s;
  s.leaf_dimension = 17;
  s.threads = 2;
  return s;
}

const HeightField& field() {
  static const HeightField f = fbm_field(129, 97, 2.0, 80.0f, 17);
  return f;
}

// Every chunk's metadata, mesh and selection node bit-exact.
void expect_same_tree(const ChunkTree& a, const ChunkTree& b) {
  ASSERT_EQ(a.chunk_count(), b.chunk_count());
  ASSERT_EQ(a.levels(), b.levels());
  EXPECT_EQ(a.field_columns(), b.field_columns());
  EXPECT_EQ(a.field_rows(), b.field_rows());
  EXPECT_TRUE(b.has_meshes());
  for (std::uint32_t i = 0; i < a.chunk_count(); ++i) {
    const Chunk &x = a.chunk(i), &y = b.chunk(i);
    ASSERT_EQ(x.present, y.present) << i;
    EXPECT_EQ(x.error, y.error) << i;
    EXPECT_EQ(x.error_bound, y.error_bound) << i;
    EXPECT_EQ(x.min_y, y.min_y) << i;
    EXPECT_EQ(x.max_y, y.max_y) << i;
    EXPECT_EQ(x.triangle_count, y.triangle_count) << i;
    EXPECT_TRUE(same_bytes(x.mesh.vertices, y.mesh.vertices)) << "chunk " << i;
    EXPECT_EQ(x.mesh.indices, y.mesh.indices) << i;
    EXPECT_EQ(x.mesh.edges, y.mesh.edges) << i;
    const ChunkNode &m = a.nodes()[i], &n = b.nodes()[i];
    EXPECT_TRUE(m.lo == n.lo && m.hi == n.hi && m.error_bound == n.error_bound && m.parent_bound == n.parent_bound &&
                m.x == n.x && m.z == n.z && m.level == n.level && m.present == n.present)
        << "node " << i;
  }
  ASSERT_EQ(a.report().levels.size(), b.report().levels.size());
  for (std::size_t l = 0; l < a.report().levels.size(); ++l) {
    EXPECT_EQ(a.report().levels[l].triangles, b.report().levels[l].triangles);
    EXPECT_EQ(a.report().levels[l].max_error, b.report().levels[l].max_error);
  }
}

struct TempDir {
  fs::path path = unique_temp("tree_cache");
  TempDir() { fs::remove_all(path); }
  ~TempDir() { fs::remove_all(path); }
  std::size_t files() const {
    std::size_t n = 0;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(path, ec)) n += e.is_regular_file() ? 1 : 0;
    return n;
  }
};

TreeCacheSettings cache_in(const fs::path& dir) {
  TreeCacheSettings c;
  c.directory = dir.string();
  c.min_samples = 0;
  return c;
}

TEST(TreeCacheKey, StableForTheSameInputAndChangedByEverySampleAndSetting) {
  const ChunkTreeSettings s = small_settings();
  const std::uint64_t key = chunk_tree_cache_key(field(), s);
  HeightField copy = field();
  EXPECT_EQ(chunk_tree_cache_key(copy, s), key) << "same samples, same key";
  // Settings that never change the tree keep the key (a new thread count reuses the cache).
  ChunkTreeSettings same = s;
  same.threads = 7;
  same.max_build_bytes = 1e8;
  EXPECT_EQ(chunk_tree_cache_key(field(), same), key);

  // One sample, one ulp: another key, wherever the sample is.
  for (std::size_t i : {std::size_t{0}, copy.samples().size() / 2, copy.samples().size() - 1}) {
    HeightField edited = field();
    edited.samples()[i] = std::nextafter(edited.samples()[i], 1e9f);
    EXPECT_NE(chunk_tree_cache_key(edited, s), key) << "sample " << i;
  }
  // Geometry.
  EXPECT_NE(chunk_tree_cache_key(fbm_field(129, 97, 2.5, 80.0f, 17), s), key) << "spacing";
  EXPECT_NE(chunk_tree_cache_key(fbm_field(129, 97, 2.0, 80.0f, 17, {1.0, 0.0}), s), key) << "origin x";
  EXPECT_NE(chunk_tree_cache_key(fbm_field(129, 97, 2.0, 80.0f, 17, {0.0, -3.0}), s), key) << "origin z";
  // The same samples read as 97 x 129 instead of 129 x 97.
  HeightField transposed(97, 129, 2.0);
  transposed.samples() = field().samples();
  EXPECT_NE(chunk_tree_cache_key(transposed, s), key) << "columns and rows";
  // Every setting that changes the tree.
  ChunkTreeSettings t = s;
  t.leaf_dimension = 33;
  EXPECT_NE(chunk_tree_cache_key(field(), t), key) << "leaf_dimension";
  t = s;
  t.flat_tolerance = 0.03f;
  EXPECT_NE(chunk_tree_cache_key(field(), t), key) << "flat_tolerance";
  t = s;
  t.max_morph_fraction = 0.4f;
  EXPECT_NE(chunk_tree_cache_key(field(), t), key) << "max_morph_fraction";
  t = s;
  t.optimize_vertex_cache = false;
  EXPECT_NE(chunk_tree_cache_key(field(), t), key) << "optimize_vertex_cache";
  t = s;
  t.keep_meshes = false;
  EXPECT_NE(chunk_tree_cache_key(field(), t), key) << "keep_meshes";
  EXPECT_NE(chunk_tree_cache_file("/a", key), chunk_tree_cache_file("/a", key + 1));
}

TEST(TreeCacheDirectory, AutoEmptyRelativeAndAbsolute) {
  EXPECT_TRUE(resolve_tree_cache_directory("", "/scenes").empty());
  EXPECT_EQ(resolve_tree_cache_directory("auto", "/scenes").filename(), "sylva-terrain-cache");
  EXPECT_EQ(resolve_tree_cache_directory("cache", "/scenes"), fs::path("/scenes/cache"));
  EXPECT_EQ(resolve_tree_cache_directory("/tmp/x", "/scenes"), fs::path("/tmp/x"));
}

TEST(TreeCacheLoad, EqualsTheBuildAndRefusesMismatchedFiles) {
  TempDir dir;
  const ChunkTreeSettings s = small_settings();
  const ChunkTree built = ChunkTree::build(field(), s).value();
  const std::uint64_t key = chunk_tree_cache_key(field(), s);
  const fs::path file = chunk_tree_cache_file(dir.path, key);
  ASSERT_TRUE(save_cached_chunk_tree(file, built, key, 4).ok());
  EXPECT_EQ(ChunkFile::open(file).value()->tag(), key);

  Result<ChunkTree> loaded = load_cached_chunk_tree(file, field(), s, key);
  ASSERT_TRUE(loaded.ok()) << loaded.error().describe();
  expect_same_tree(built, *loaded);
  EXPECT_EQ(loaded->settings().threads, 2) << "unstored settings come from the caller";

  // Another key (another field or settings): refused, naming the file and the key.
  Result<ChunkTree> other = load_cached_chunk_tree(file, field(), s, key ^ 1);
  ASSERT_FALSE(other.ok());
  EXPECT_EQ(other.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(other.error().message.find(file.string()), std::string::npos) << other.error().message;
  EXPECT_NE(other.error().message.find("key"), std::string::npos) << other.error().message;
  // The same key (a collision, or a renamed file) with a field of another size or place.
  const HeightField wider = fbm_field(130, 97, 2.0, 80.0f, 17);
  Result<ChunkTree> size = load_cached_chunk_tree(file, wider, s, key);
  ASSERT_FALSE(size.ok());
  EXPECT_NE(size.error().message.find("129 x 97"), std::string::npos) << size.error().message;
  const HeightField moved = fbm_field(129, 97, 2.0, 80.0f, 17, {5.0, 0.0});
  EXPECT_FALSE(load_cached_chunk_tree(file, moved, s, key).ok());
  // ... or other stored tree settings: refused naming the parameter.
  ChunkTreeSettings t = s;
  t.flat_tolerance = 0.5f;
  Result<ChunkTree> setting = load_cached_chunk_tree(file, field(), t, key);
  ASSERT_FALSE(setting.ok());
  EXPECT_NE(setting.error().message.find("flat_tolerance"), std::string::npos) << setting.error().message;
  t = s;
  t.leaf_dimension = 33;
  setting = load_cached_chunk_tree(file, field(), t, key);
  ASSERT_FALSE(setting.ok());
  EXPECT_NE(setting.error().message.find("leaf_dimension"), std::string::npos) << setting.error().message;

  // A chunk file without the tag (a plain save or a bake) is not a cache of this key.
  const fs::path plain = dir.path / "plain.sylvaterrain";
  ASSERT_TRUE(save_chunk_file(plain, built).ok());
  EXPECT_FALSE(load_cached_chunk_tree(plain, field(), s, key).ok());
}

TEST(TreeCacheLoad, EditsOnALoadedTreeEqualEditsOnABuiltTree) {
  TempDir dir;
  const ChunkTreeSettings s = small_settings();
  ChunkTree built = ChunkTree::build(field(), s).value();
  const std::uint64_t key = chunk_tree_cache_key(field(), s);
  const fs::path file = chunk_tree_cache_file(dir.path, key);
  ASSERT_TRUE(save_cached_chunk_tree(file, built, key, 4).ok());
  ChunkTree loaded = load_cached_chunk_tree(file, field(), s, key).value();
  HeightField edited = field();
  for (int z = 40; z < 50; ++z)
    for (int x = 60; x < 75; ++x) edited.samples()[static_cast<std::size_t>(z) * 129 + x] += 6.0f;
  ASSERT_TRUE(built.rebuild_region(edited, 60, 40, 75, 50).ok());
  Result<RegionRebuild> r = loaded.rebuild_region(edited, 60, 40, 75, 50);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  EXPECT_GT(r->rebuilt.size(), 0u);
  expect_same_tree(built, loaded);
}

TEST(TreeCacheBuildOrLoad, MissWritesOneFileThenHitsWithTheSameTree) {
  TempDir dir;
  const ChunkTreeSettings s = small_settings();
  Result<CachedChunkTree> first = build_or_load_chunk_tree(field(), s, cache_in(dir.path), {});
  ASSERT_TRUE(first.ok()) << first.error().describe();
  EXPECT_EQ(first->cache, TreeCacheOutcome::kMiss);
  EXPECT_STREQ(to_string(first->cache), "miss");
  EXPECT_EQ(dir.files(), 1u);
  EXPECT_TRUE(fs::exists(first->file));
  Result<CachedChunkTree> second = build_or_load_chunk_tree(field(), s, cache_in(dir.path), {});
  ASSERT_TRUE(second.ok());
  EXPECT_EQ(second->cache, TreeCacheOutcome::kHit);
  EXPECT_EQ(second->build_ms, 0.0) << "a hit builds nothing";
  expect_same_tree(first->tree, second->tree);
  EXPECT_EQ(dir.files(), 1u);

  // Off: no folder, a field below min_samples, or no meshes to cache.
  TreeCacheSettings off = cache_in(dir.path);
  off.directory = "";
  EXPECT_EQ(build_or_load_chunk_tree(field(), s, off, {})->cache, TreeCacheOutcome::kOff);
  TreeCacheSettings big = cache_in(dir.path);
  big.min_samples = 129 * 97 + 1;
  EXPECT_EQ(build_or_load_chunk_tree(field(), s, big, {})->cache, TreeCacheOutcome::kOff);
  big.min_samples = 129 * 97;
  EXPECT_EQ(build_or_load_chunk_tree(field(), s, big, {})->cache, TreeCacheOutcome::kHit);
  ChunkTreeSettings no_meshes = s;
  no_meshes.keep_meshes = false;
  EXPECT_EQ(build_or_load_chunk_tree(field(), no_meshes, cache_in(dir.path), {})->cache, TreeCacheOutcome::kOff);
  EXPECT_EQ(dir.files(), 1u) << "nothing written when off";
}

TEST(TreeCacheBuildOrLoad, TruncatedOrJunkFileIsRebuiltAndReplaced) {
  TempDir dir;
  const ChunkTreeSettings s = small_settings();
  const ChunkTree reference = ChunkTree::build(field(), s).value();
  const fs::path file = build_or_load_chunk_tree(field(), s, cache_in(dir.path), {})->file;
  const auto full = fs::file_size(file);
  for (std::uintmax_t size : {full / 2, std::uintmax_t{100}, std::uintmax_t{0}, full - 1}) {
    fs::resize_file(file, size);
    Result<CachedChunkTree> r = build_or_load_chunk_tree(field(), s, cache_in(dir.path), {});
    ASSERT_TRUE(r.ok()) << r.error().describe();
    EXPECT_EQ(r->cache, TreeCacheOutcome::kMiss) << "truncated to " << size;
    expect_same_tree(reference, r->tree);
    EXPECT_EQ(fs::file_size(file), full) << "replaced by a whole file";
    EXPECT_EQ(build_or_load_chunk_tree(field(), s, cache_in(dir.path), {})->cache, TreeCacheOutcome::kHit);
  }
  // A damaged chunk blob (the directory and header intact): refused at its checksum, rebuilt.
  {
    std::fstream f(file, std::ios::binary | std::ios::in | std::ios::out);
    f.seekp(static_cast<std::streamoff>(full / 3));
    f.put('\x5a').put('\xa5').put('\x11');
  }
  Result<CachedChunkTree> r = build_or_load_chunk_tree(field(), s, cache_in(dir.path), {});
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->cache, TreeCacheOutcome::kMiss);
  expect_same_tree(reference, r->tree);
  EXPECT_EQ(dir.files(), 1u) << "no temporaries left";
}

TEST(TreeCacheBuildOrLoad, UnwritableFolderIsAWarningAndOldFilesArePruned) {
  TempDir dir;
  fs::create_directories(dir.path);
  const ChunkTreeSettings s = small_settings();
  // The "folder" is a file: the write fails, the tree is still built.
  const fs::path blocker = dir.path / "not_a_folder";
  std::ofstream(blocker) << "x";
  Result<CachedChunkTree> r = build_or_load_chunk_tree(field(), s, cache_in(blocker), {});
  ASSERT_TRUE(r.ok()) << r.error().describe();
  EXPECT_EQ(r->cache, TreeCacheOutcome::kMiss);
  EXPECT_GT(r->tree.chunk_count(), 0u);

  // Three trees with max_files = 2: the least recently used goes.
  const fs::path cache = dir.path / "cache";
  TreeCacheSettings c = cache_in(cache);
  c.max_files = 2;
  std::vector<fs::path> files;
  for (float tolerance : {0.01f, 0.02f, 0.03f}) {
    ChunkTreeSettings t = s;
    t.flat_tolerance = tolerance;
    files.push_back(build_or_load_chunk_tree(field(), t, c, {})->file);
    // Modification times one second apart (file systems with coarse timestamps).
    fs::last_write_time(files.back(), fs::file_time_type::clock::now() - std::chrono::seconds(10 - static_cast<int>(files.size())));
  }
  EXPECT_FALSE(fs::exists(files[0]));
  EXPECT_TRUE(fs::exists(files[1]));
  EXPECT_TRUE(fs::exists(files[2]));

  // Temporaries of killed writes: removed by the next write once older than an hour; a younger one
  // (another launch writing now) stays.
  const fs::path old_temp = cache / ".terrain-0123456789abcdef.99999-1.tmp.sylvaterrain";
  const fs::path new_temp = cache / ".terrain-0123456789abcdef.99998-1.tmp.sylvaterrain";
  std::ofstream(old_temp) << "half";
  std::ofstream(new_temp) << "half";
  fs::last_write_time(old_temp, fs::file_time_type::clock::now() - std::chrono::hours(2));
  ChunkTreeSettings t = s;
  t.flat_tolerance = 0.04f;
  ASSERT_EQ(build_or_load_chunk_tree(field(), t, c, {})->cache, TreeCacheOutcome::kMiss);
  EXPECT_FALSE(fs::exists(old_temp));
  EXPECT_TRUE(fs::exists(new_temp));
}

}  // namespace
}  // namespace sylva::terrain

#include <sylva/terrain/tree_cache.hpp>

#include <sylva/core/log.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/terrain/chunk_file.hpp>

#include <sylva/core/cache_directory.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <vector>

namespace sylva::terrain {
namespace {

constexpr const char* kPrefix = "terrain-";
constexpr const char* kExtension = ".sylvaterrain";

template <class T>
std::uint64_t hash_value(const T& v, std::uint64_t h) {
  return fnv1a64(&v, sizeof(T), h);
}

// Deletes the least recently used (oldest modification time: a hit touches its file) cache files
// beyond `keep`, and temporaries of writes killed more than an hour ago (SIGKILL or a power cut
// leaves ".terrain-<key>.<pid>-<n>.tmp.sylvaterrain", up to a GB at 4097^2; a younger one may be
// another launch's write in progress). Best effort: a file that cannot be removed stays.
void prune(const std::filesystem::path& directory, int keep) {
  std::error_code ec;
  const auto stale = std::filesystem::file_time_type::clock::now() - std::chrono::hours(1);
  std::vector<std::pair<std::filesystem::file_time_type, std::filesystem::path>> files;
  for (const auto& entry : std::filesystem::directory_iterator(directory, ec)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != kExtension) continue;
    const std::filesystem::file_time_type time = entry.last_write_time(ec);
    if (name.starts_with(std::string(".") + kPrefix) && name.find(".tmp") != std::string::npos) {
      if (!ec && time < stale) std::filesystem::remove(entry.path(), ec);
      continue;
    }
    if (name.starts_with(kPrefix)) files.emplace_back(time, entry.path());
  }
  if (files.size() <= static_cast<std::size_t>(std::max(keep, 1))) return;
  std::sort(files.begin(), files.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t i = static_cast<std::size_t>(std::max(keep, 1)); i < files.size(); ++i) {
    if (std::filesystem::remove(files[i].second, ec)) log_info("terrain: removed old tree cache {}", files[i].second.string());
  }
}

}  // namespace

const char* to_string(TreeCacheOutcome outcome) {
  switch (outcome) {
    case TreeCacheOutcome::kHit: return "hit";
    case TreeCacheOutcome::kMiss: return "miss";
    case TreeCacheOutcome::kOff: break;
  }
  return "off";
}

std::uint64_t chunk_tree_cache_key(const HeightField& field, const ChunkTreeSettings& s) {
  std::uint64_t h = hash_value(kTreeCacheVersion, 0xcbf29ce484222325ull);
  h = hash_value(kChunkFileVersion, h);
  h = hash_value(static_cast<std::int32_t>(field.columns()), h);
  h = hash_value(static_cast<std::int32_t>(field.rows()), h);
  h = hash_value(field.spacing(), h);
  h = hash_value(field.origin().x, h);
  h = hash_value(field.origin().y, h);
  h = hash_value(static_cast<std::int32_t>(s.leaf_dimension), h);
  h = hash_value(s.flat_tolerance, h);
  h = hash_value(s.max_morph_fraction, h);
  h = hash_value(static_cast<std::uint8_t>(s.keep_meshes), h);
  h = hash_value(static_cast<std::uint8_t>(s.optimize_vertex_cache), h);
  const std::vector<float>& samples = field.samples();
  return fnv1a64(samples.data(), samples.size() * sizeof(float), h);
}

std::filesystem::path chunk_tree_cache_file(const std::filesystem::path& directory, std::uint64_t key) {
  return directory / fmt::format("{}{:016x}{}", kPrefix, key, kExtension);
}

std::filesystem::path resolve_tree_cache_directory(const std::string& setting, const std::filesystem::path& base) {
  return resolve_cache_directory(setting, "sylva-terrain-cache", base);
}

Result<ChunkTree> load_cached_chunk_tree(const std::filesystem::path& file, const HeightField& field,
                                         const ChunkTreeSettings& settings, std::uint64_t key,
                                         const BuildControl& control) {
  Result<std::shared_ptr<ChunkFile>> opened = ChunkFile::open(file);
  if (!opened.ok()) return opened.error();
  const ChunkFile& f = **opened;
  const std::string name = file.string();
  if (f.tag() != key) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: made from another field or other tree settings (key {:016x}, expected {:016x})",
                                  name, f.tag(), key));
  }
  // The key covers these too; checked apart so a colliding key can never give a tree of another
  // size (the renderer indexes the field with the tree's layout).
  const ChunkTree& t = f.tree();
  if (t.field_columns() != field.columns() || t.field_rows() != field.rows() || t.spacing() != field.spacing() ||
      t.origin() != field.origin()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: made from a {} x {} field with spacing {} m at ({}, {}), not {} x {} with {} m at ({}, {})",
                                  name, t.field_columns(), t.field_rows(), t.spacing(), t.origin().x, t.origin().y,
                                  field.columns(), field.rows(), field.spacing(), field.origin().x, field.origin().y));
  }
  return f.read_tree(settings, control);
}

Status save_cached_chunk_tree(const std::filesystem::path& file, const ChunkTree& tree, std::uint64_t key, int max_files) {
  std::error_code ec;
  std::filesystem::create_directories(file.parent_path(), ec);
  if (ec) return make_error(ErrorCode::kIo, fmt::format("{}: cannot create the folder: {}", file.parent_path().string(), ec.message()));
  SYLVA_TRY(save_chunk_file(file, tree, key));
  prune(file.parent_path(), max_files);
  return {};
}

Result<CachedChunkTree> build_or_load_chunk_tree(const HeightField& field, const ChunkTreeSettings& settings,
                                                 const TreeCacheSettings& cache, const std::filesystem::path& base,
                                                 const BuildControl& control) {
  CachedChunkTree out;
  const std::filesystem::path directory = resolve_tree_cache_directory(cache.directory, base);
  // The seed's hq tessellations are built in memory only (chunk files hold RTIN trees).
  const bool use = !directory.empty() && settings.keep_meshes && settings.tessellation == Tessellation::kRtin &&
                   field.samples().size() >= static_cast<std::size_t>(std::max(cache.min_samples, 0));
  std::uint64_t key = 0;
  if (use) {
    Stopwatch watch;
    key = chunk_tree_cache_key(field, settings);
    out.file = chunk_tree_cache_file(directory, key);
    out.key_ms = watch.lap_ms();
    std::error_code ec;
    if (std::filesystem::exists(out.file, ec)) {
      Result<ChunkTree> loaded = load_cached_chunk_tree(out.file, field, settings, key, control);
      out.load_ms = watch.lap_ms();
      if (loaded.ok()) {
        out.tree = std::move(*loaded);
        out.cache = TreeCacheOutcome::kHit;
        // Most recently used: what prune() keeps.
        std::filesystem::last_write_time(out.file, std::filesystem::file_time_type::clock::now(), ec);
        log_info("terrain: chunk tree loaded from the cache {} in {:.0f} ms", out.file.string(), out.load_ms);
        return out;
      }
      if (loaded.error().code == ErrorCode::kCancelled) return loaded.error();
      log_warn("terrain: rejected the chunk-tree cache, rebuilding: {}", loaded.error().message);
    }
  }
  Stopwatch watch;
  Result<ChunkTree> built = ChunkTree::build(field, settings, control);
  if (!built.ok()) return built.error();
  out.tree = std::move(*built);
  out.build_ms = watch.lap_ms();
  if (!use) return out;
  out.cache = TreeCacheOutcome::kMiss;
  const Status saved = save_cached_chunk_tree(out.file, out.tree, key, cache.max_files);
  out.save_ms = watch.lap_ms();
  if (!saved.ok()) {
    log_warn("terrain: could not write the chunk-tree cache (the next launch rebuilds): {}", saved.error().message);
  } else {
    log_info("terrain: chunk tree built in {:.0f} ms, cached in {} ({:.0f} ms)", out.build_ms, out.file.string(),
             out.save_ms);
  }
  return out;
}

}  // namespace sylva::terrain

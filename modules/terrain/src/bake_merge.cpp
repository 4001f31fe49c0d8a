// merge_bake_shares: joins the share files of one bake into the chunk file (bake.hpp), computing
// the error bounds from the shares' directories and patching every vertex's morph_error.
#include <sylva/terrain/bake.hpp>
#include <sylva/terrain/chunk_file.hpp>

#include "bake_share_format.hpp"
#include "chunk_blob.hpp"
#include "chunk_file_heights.hpp"
#include "bake_merge.hpp"
#include "chunk_build.hpp"
#include "parallel.hpp"

#include <sylva/core/assert.hpp>
#include <sylva/core/timer.hpp>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>

namespace sylva::terrain {

using detail::get_le;
using detail::put_le;

namespace {

struct Share {
  std::filesystem::path path;
  std::string header, directory;
  std::uint32_t index = 0, count = 0, first = 0, end = 0;
  detail::HeightTiles tiles;
  std::vector<std::uint64_t> height_table;  // verified per-tile checksums of the ground heights
  std::unique_ptr<std::ifstream> in;
  std::string name() const { return path.string(); }
};

Result<Share> open_share(const std::filesystem::path& path) {
  Share s;
  s.path = path;
  const std::string name = path.string();
  auto corrupt = [&](const std::string& what) {
    return make_error(ErrorCode::kCorrupt, fmt::format("{}: {}", name, what));
  };
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    return make_error(ErrorCode::kNotFound, fmt::format("{}: bake share not found", name));
  }
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) return make_error(ErrorCode::kIo, fmt::format("{}: cannot read its size", name));
  s.in = std::make_unique<std::ifstream>(path, std::ios::binary);
  if (!*s.in) return make_error(ErrorCode::kIo, fmt::format("{}: cannot open", name));
  if (size < detail::kShareHeaderBytes) return corrupt(fmt::format("truncated: {} bytes, not a bake share", size));
  s.header.assign(detail::kShareHeaderBytes, '\0');
  s.in->read(s.header.data(), static_cast<std::streamsize>(s.header.size()));
  const char* h = s.header.data();
  if (!*s.in || std::memcmp(h, detail::kShareMagic, 8) != 0) return corrupt("not a Sylva bake share (bad magic)");
  const auto version = get_le<std::uint32_t>(h, detail::kShVersion);
  if (version != kBakeShareVersion) {
    return make_error(ErrorCode::kUnsupported, fmt::format("{}: bake share version {}, this build reads version {}",
                                                           name, version, kBakeShareVersion));
  }
  if (get_le<std::uint64_t>(h, detail::kShHeaderChecksum) != fnv1a64(h, detail::kShHeaderChecksum)) {
    return corrupt("header checksum mismatch");
  }
  const auto file_bytes = get_le<std::uint64_t>(h, detail::kShFileBytes);
  if (file_bytes != size) {
    return corrupt(fmt::format("{}: {} bytes but the header says {}", size < file_bytes ? "truncated" : "wrong size",
                               size, file_bytes));
  }
  s.index = get_le<std::uint32_t>(h, detail::kShIndex);
  s.count = get_le<std::uint32_t>(h, detail::kShCount);
  s.first = get_le<std::uint32_t>(h, detail::kShFirstSlot);
  s.end = get_le<std::uint32_t>(h, detail::kShEndSlot);
  const auto dir_offset = get_le<std::uint64_t>(h, detail::kShDirOffset);
  const auto dir_bytes = get_le<std::uint64_t>(h, detail::kShDirBytes);
  s.tiles = detail::HeightTiles{get_le<std::int32_t>(h, detail::kShColumns), get_le<std::int32_t>(h, detail::kShRows),
                                 get_le<std::uint16_t>(h, detail::kShHeightTile),
                                 get_le<std::uint16_t>(h, detail::kShHeightOverview)};
  if (s.tiles.tile != detail::kHeightTileSamples || s.tiles.columns < 1 || s.tiles.rows < 1 ||
      (s.tiles.overview != 0 && (s.tiles.overview < 2 || (s.tiles.overview & (s.tiles.overview - 1)) != 0))) {
    return corrupt(fmt::format("implausible ground height layout ({} x {} samples, tiles of {}, overview stride {})",
                               s.tiles.columns, s.tiles.rows, s.tiles.tile, s.tiles.overview));
  }
  if (s.first > s.end || dir_bytes != static_cast<std::uint64_t>(s.end - s.first) * detail::kShareEntryBytes ||
      dir_bytes > size || dir_offset != size - dir_bytes || s.index >= s.count ||
      dir_offset < detail::kShareHeaderBytes + s.tiles.section_bytes()) {
    return corrupt("inconsistent header (share index, slot range or directory)");
  }
  s.directory.assign(dir_bytes, '\0');
  s.in->seekg(static_cast<std::streamoff>(dir_offset));
  s.in->read(s.directory.data(), static_cast<std::streamsize>(dir_bytes));
  if (!*s.in) return corrupt("cannot read the directory");
  if (get_le<std::uint64_t>(h, detail::kShDirChecksum) != fnv1a64(s.directory.data(), s.directory.size())) {
    return corrupt("directory checksum mismatch");
  }
  auto table = detail::read_height_table(*s.in, detail::kShareHeaderBytes, s.tiles, name);
  if (!table) return table.error();
  s.height_table = std::move(*table);
  return s;
}

// The shares, sorted by index, must be exactly 0..N-1 of one bake whose slot ranges tile the tree.
Status check_shares(const std::vector<Share>& shares, std::uint32_t slot_count) {
  const Share& a = shares.front();
  // Bytes [kShColumns, kShFirstSlot) hold the field geometry and tree settings.
  for (const Share& s : shares) {
    if (s.count != shares.size()) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: share {} of {}, but {} share file(s) were given", s.name(), s.index, s.count,
                                    shares.size()));
    }
    if (std::memcmp(s.header.data() + detail::kShColumns, a.header.data() + detail::kShColumns,
                    detail::kShFirstSlot - detail::kShColumns) != 0) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: baked from another field or with other terrain.tree settings than {}",
                                    s.name(), a.name()));
    }
    if (s.tiles.overview != a.tiles.overview) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: its ground overview has stride {}, {}'s {}: baked with another overview limit",
                                    s.name(), s.tiles.overview, a.name(), a.tiles.overview));
    }
    if (s.height_table != a.height_table) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: its ground heights differ from {}'s: baked from another field", s.name(), a.name()));
    }
  }
  for (std::size_t i = 0; i < shares.size(); ++i) {
    const Share& s = shares[i];
    if (s.index != i) {
      return make_error(ErrorCode::kInvalidArgument,
                        i > 0 && shares[i - 1].index == s.index
                            ? fmt::format("{}: share {} given twice (also {})", s.name(), s.index, shares[i - 1].name())
                            : fmt::format("share {} of {} is missing (given from {} on)", i, shares.size(), s.name()));
    }
    const std::uint32_t expected_first = i == 0 ? 0u : shares[i - 1].end;
    const std::uint32_t expected_end = i + 1 == shares.size() ? slot_count : s.end;
    if (s.first != expected_first || s.end != expected_end) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: its chunk slots [{}, {}) do not continue the other shares' (expected [{}, {}) "
                                    "of {})", s.name(), s.first, s.end, expected_first, expected_end, slot_count));
    }
  }
  return ok_status();
}

}  // namespace

Result<BakeReport> merge_bake_shares(const std::vector<std::filesystem::path>& paths, const std::filesystem::path& out,
                                     const BuildControl& control) {
  return detail::merge_shares(paths, out, control, false);
}

Result<BakeReport> detail::merge_shares(const std::vector<std::filesystem::path>& paths, const std::filesystem::path& out,
                                        const BuildControl& control, bool in_place) {
  Stopwatch watch;
  if (paths.empty()) return make_error(ErrorCode::kInvalidArgument, "bake merge: no share files given");
  std::vector<Share> shares;
  for (const auto& p : paths) {
    Result<Share> s = open_share(p);
    if (!s) return s.error();
    shares.push_back(std::move(s.value()));
  }
  std::sort(shares.begin(), shares.end(), [](const Share& a, const Share& b) { return a.index < b.index; });

  const char* h = shares.front().header.data();
  ChunkTreeSettings settings;
  settings.leaf_dimension = static_cast<int>(get_le<std::uint32_t>(h, detail::kShLeafDimension));
  settings.flat_tolerance = get_le<float>(h, detail::kShFlatTolerance);
  settings.max_morph_fraction = get_le<float>(h, detail::kShMaxMorph);
  settings.optimize_vertex_cache = get_le<std::uint8_t>(h, detail::kShOptimize) != 0;
  settings.max_build_bytes = 1e12;  // the grids were held by the bakes, not here
  const int columns = get_le<std::int32_t>(h, detail::kShColumns), rows = get_le<std::int32_t>(h, detail::kShRows);
  const double spacing = get_le<double>(h, detail::kShSpacing);
  const glm::dvec2 origin(get_le<double>(h, detail::kShOriginX), get_le<double>(h, detail::kShOriginZ));
  if (columns < 1 || rows < 1 || !(spacing > 0.0) || !std::isfinite(spacing) || !std::isfinite(origin.x) ||
      !std::isfinite(origin.y)) {
    return make_error(ErrorCode::kCorrupt, fmt::format("{}: implausible field geometry ({} x {} samples, spacing {})",
                                                       shares.front().name(), columns, rows, spacing));
  }
  Result<ChunkTree> laid = ChunkTreeBuilder::layout(columns, rows, spacing, origin, settings);
  if (!laid) {
    return make_error(laid.error().code, fmt::format("{}: {}", shares.front().name(), laid.error().message));
  }
  ChunkTree& tree = laid.value();
  const auto slot_count = static_cast<std::uint32_t>(tree.chunk_count());
  SYLVA_TRY(check_shares(shares, slot_count));

  // Metadata of every chunk from the directories, then the bounds (ChunkTree::build's order).
  for (const Share& s : shares) {
    for (std::uint32_t i = s.first; i < s.end; ++i) {
      const char* e = s.directory.data() + static_cast<std::size_t>(i - s.first) * detail::kShareEntryBytes;
      Chunk& c = ChunkTreeBuilder::chunk(tree, i);
      if ((get_le<std::uint8_t>(e, detail::kSePresent) != 0) != c.present) {
        return make_error(ErrorCode::kCorrupt, fmt::format("{}: chunk {} (level {} at {}, {}) has the wrong presence",
                                                           s.name(), i, c.key.level, c.key.x, c.key.z));
      }
      if (!c.present) continue;
      c.error = get_le<float>(e, detail::kSeError);
      c.min_y = get_le<float>(e, detail::kSeMinY);
      c.max_y = get_le<float>(e, detail::kSeMaxY);
      c.triangle_count = get_le<std::uint32_t>(e, detail::kSeTriangles);
      c.vertex_count = get_le<std::uint32_t>(e, detail::kSeVertices);
    }
  }
  ChunkTreeBuilder::finish(tree);

  // In place: a single share's blobs already sit at the chunk file's offsets (both headers are
  // 128 bytes, blobs in slot order), so they are patched where they are; each batch is read
  // before it is overwritten, and the larger chunk-file directory replaces the share's.
  SYLVA_ASSERT(!in_place || shares.size() == 1, "in-place merge of {} shares", shares.size());
  Result<std::unique_ptr<ChunkFileWriter>> writer =
      ChunkFileWriter::create(out, tree, in_place ? shares.front().path : std::filesystem::path(), true,
                              shares.front().tiles.overview);
  if (!writer) return writer.error();
  if (!in_place) {
    // Every share holds the same heights (check_shares); share 0's field is copied tile by tile
    // and the overview made from it again (the same bytes: the same samples).
    const Share& s = shares.front();
    SYLVA_TRY((*writer)->write_heights(
        detail::HeightTileRows(*s.in, detail::kShareHeaderBytes, s.tiles, s.height_table, s.name())));
  }
  BakeReport report;
  // Batches of blobs: read in slot order, verified and patched on every thread, written in slot
  // order (the output does not depend on the thread count).
  struct Item {
    const Share* share;
    std::uint32_t slot;
    std::string blob, error;
    std::uint64_t checksum = 0;
  };
  std::vector<Item> batch;
  std::size_t batch_bytes = 0;
  const int threads = detail::resolve_threads(0);
  const std::uint32_t levels = static_cast<std::uint32_t>(tree.levels());

  // Verifies one blob against its share's directory and patches morph_error, the only field the
  // bounds decide; an error names the share file and the chunk.
  auto patch = [&](Item& it) {
    const Chunk& c = tree.chunk(it.slot);
    const char* e = it.share->directory.data() + static_cast<std::size_t>(it.slot - it.share->first) * detail::kShareEntryBytes;
    auto corrupt = [&](const std::string& what) {
      it.error = fmt::format("{}: chunk {} (level {} at {}, {}): {}", it.share->name(), it.slot, c.key.level, c.key.x,
                             c.key.z, what);
    };
    std::string& blob = it.blob;
    // In place, the share is this process's own temporary, written without blob checksums
    // (bake_merge.hpp); shares from other processes are verified.
    if (!in_place && fnv1a64(blob.data(), blob.size()) != get_le<std::uint64_t>(e, detail::kSeChecksum)) {
      return corrupt("checksum mismatch");
    }
    const auto nv = get_le<std::uint32_t>(blob.data(), 0);
    if (nv != c.vertex_count || 24 + static_cast<std::uint64_t>(nv) * detail::kChunkVertexBytes > blob.size()) {
      return corrupt("its vertex count does not match its size");
    }
    const std::uint32_t size = tree.chunk_size(c.key.level);
    const std::uint64_t x0 = std::uint64_t{c.key.x} * size, z0 = std::uint64_t{c.key.z} * size;
    for (std::uint32_t k = 0; k < nv; ++k) {
      const std::size_t at = 24 + static_cast<std::size_t>(k) * detail::kChunkVertexBytes;
      ChunkVertex v;
      v.gx = get_le<std::uint32_t>(blob.data(), at);
      v.gz = get_le<std::uint32_t>(blob.data(), at + 4);
      v.intro_level = get_le<std::uint8_t>(blob.data(), at + 20);
      if (v.intro_level > c.key.level || v.intro_level >= levels || v.gx < x0 || v.gx > x0 + size || v.gz < z0 ||
          v.gz > z0 + size) {
        return corrupt(fmt::format("vertex {} at ({}, {}) of level {} lies outside the chunk", k, v.gx, v.gz,
                                   v.intro_level));
      }
      put_le(blob, at + detail::kMorphErrorOffset, ChunkTreeBuilder::morph_error(tree, v));
    }
    it.checksum = fnv1a64(blob.data(), blob.size());
  };
  auto flush = [&]() -> Status {
    const bool finished = detail::parallel_for(batch.size(), threads, [&](std::size_t k) { patch(batch[k]); },
                                               control.cancel);
    if (!finished) {
      return make_error(ErrorCode::kCancelled, fmt::format("{}: bake cancelled; nothing was written", out.string()));
    }
    for (Item& it : batch) {
      if (!it.error.empty()) return make_error(ErrorCode::kCorrupt, it.error);
      const Chunk& c = tree.chunk(it.slot);
      SYLVA_TRY((*writer)->add(it.slot, c, std::string_view(it.blob), it.checksum));
      ++report.chunks;
      report.triangles += c.triangle_count;
    }
    if (control.progress && !batch.empty()) {
      control.progress(static_cast<float>(batch.back().slot) / static_cast<float>(slot_count));
    }
    batch.clear();
    batch_bytes = 0;
    return ok_status();
  };
  for (const Share& s : shares) {
    const std::uint64_t dir_offset = get_le<std::uint64_t>(s.header.data(), detail::kShDirOffset);
    for (std::uint32_t i = s.first; i < s.end; ++i) {
      const Chunk& c = tree.chunk(i);
      if (!c.present) continue;
      const char* e = s.directory.data() + static_cast<std::size_t>(i - s.first) * detail::kShareEntryBytes;
      const auto offset = get_le<std::uint64_t>(e, detail::kSeOffset), bytes = get_le<std::uint64_t>(e, detail::kSeBytes);
      auto corrupt = [&](const std::string& what) {
        return make_error(ErrorCode::kCorrupt, fmt::format("{}: chunk {} (level {} at {}, {}): {}", s.name(), i,
                                                           c.key.level, c.key.x, c.key.z, what));
      };
      if (offset < detail::kShareHeaderBytes + s.tiles.section_bytes() || bytes > dir_offset || offset > dir_offset - bytes || bytes < 24) {
        return corrupt("points outside the data");
      }
      Item& it = batch.emplace_back(Item{&s, i, std::string(bytes, '\0'), {}, 0});
      s.in->seekg(static_cast<std::streamoff>(offset));
      s.in->read(it.blob.data(), static_cast<std::streamsize>(bytes));
      if (!*s.in) return corrupt("cannot read its data (file changed or truncated)");
      batch_bytes += bytes;
      if (batch_bytes >= (std::size_t{64} << 20)) SYLVA_TRY(flush());
    }
  }
  SYLVA_TRY(flush());
  SYLVA_TRY((*writer)->finish());
  std::error_code ec;
  report.bytes = std::filesystem::file_size(out, ec);
  report.merge_ms = watch.elapsed_ms();
  if (control.progress) control.progress(1.0f);
  return report;
}

}  // namespace sylva::terrain

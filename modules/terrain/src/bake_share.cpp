// bake_share: meshes one share of the chunk slots (bake.hpp) and streams the blobs to a share file.
#include <sylva/terrain/bake.hpp>
#include <sylva/terrain/chunk_file.hpp>

#include "bake_merge.hpp"
#include "bake_share_format.hpp"
#include "chunk_blob.hpp"
#include "chunk_file_heights.hpp"
#include "chunk_build.hpp"
#include "parallel.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/timer.hpp>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <string>

namespace sylva::terrain {

using detail::put_le;

namespace {

// Removes the temporary share unless released (error, cancellation, exception).
struct TempGuard {
  std::filesystem::path path;
  ~TempGuard() {
    if (path.empty()) return;
    std::error_code ec;
    std::filesystem::remove(path, ec);
  }
};

Status check_options(const BakeOptions& o) {
  if (o.shares < 1 || o.shares > 1024) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("bake: --tiles N = {} is not in 1..1024", o.shares));
  }
  if (o.share < 0 || o.share >= o.shares) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("bake: --tiles {}/{}: the share index must be in 0..{}", o.share, o.shares, o.shares - 1));
  }
  if (o.tree.tessellation != Tessellation::kRtin) {
    return make_error(ErrorCode::kInvalidArgument,
                      "bake: chunk files hold RTIN trees; terrain.tree.tessellation = hq0/hq1/hq2 is built in memory only");
  }
  return ok_status();
}

}  // namespace

Result<BakeReport> bake_share(HeightField field, const std::filesystem::path& share_file,
                              const BakeOptions& options) {
  return detail::bake_share(std::move(field), share_file, options, true);
}

Result<BakeReport> detail::bake_share(HeightField field, const std::filesystem::path& share_file,
                                      const BakeOptions& options, bool blob_checksums) {
  SYLVA_TRY(check_options(options));
  BakeReport report;
  Stopwatch watch;
  ChunkTreeSettings settings = options.tree;
  settings.keep_meshes = true;
  auto prepared = ChunkTreeBuilder::prepare(std::move(field), settings, options.control);
  if (!prepared) return prepared.error();
  const detail::TreeGrids& grids = *prepared.value();
  const ChunkTree& layout = grids.tree;
  report.prepare_ms = watch.lap_ms();

  const auto [first, end] = detail::share_slots(grids.present, static_cast<std::uint32_t>(layout.chunk_count()),
                                                options.share, options.shares);
  std::vector<std::uint32_t> mine;
  for (std::uint32_t i : grids.present)
    if (i >= first && i < end) mine.push_back(i);

  SYLVA_TRY(check_replaceable(share_file));
  TempGuard temp{temp_path_beside(share_file)};
  std::ofstream out(temp.path, std::ios::binary | std::ios::trunc);
  const std::string name = share_file.string();
  if (!out) return make_error(ErrorCode::kIo, fmt::format("{}: cannot create a file in this folder", name));
  auto write_failed = [&] {
    return make_error(ErrorCode::kIo, fmt::format("{}: writing failed (disk full?); no share was written", name));
  };
  std::string header(detail::kShareHeaderBytes, '\0');
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  std::string directory(static_cast<std::size_t>(end - first) * detail::kShareEntryBytes, '\0');
  // The ground heights: the field's samples, which are the padded grid's [0, columns) x [0, rows).
  const detail::HeightTiles tiles{layout.field_columns(), layout.field_rows(), detail::kHeightTileSamples,
                                  height_overview_stride(layout.field_columns(), layout.field_rows(),
                                                         options.overview_max_samples)};
  SYLVA_TRY(detail::write_height_section(out, tiles, [&](int z, int x0, int width, float* row) {
    const float* src = grids.heights.h.data() + static_cast<std::size_t>(z) * static_cast<std::size_t>(grids.heights.n + 1);
    std::memcpy(row, src + x0, static_cast<std::size_t>(width) * sizeof(float));
    return ok_status();
  }, name));
  std::uint64_t offset = detail::kShareHeaderBytes + tiles.section_bytes();

  // Batches of chunks meshed on every thread, then written in slot order: the file does not
  // depend on the thread count or timing, and only one batch of meshes is in memory.
  const int threads = detail::resolve_threads(settings.threads);
  const std::size_t dim = static_cast<std::size_t>(settings.leaf_dimension);
  const std::size_t chunk_bytes = 100 * dim * dim;  // mesh + blob of a full chunk, roughly
  const std::size_t batch = std::max<std::size_t>(static_cast<std::size_t>(threads), options.batch_bytes / chunk_bytes);
  std::vector<Chunk> chunks;
  std::vector<std::string> blobs;
  std::vector<std::uint64_t> sums;
  for (std::size_t b = 0; b < mine.size(); b += batch) {
    const std::size_t count = std::min(batch, mine.size() - b);
    chunks.assign(count, Chunk{});
    blobs.assign(count, std::string());
    sums.assign(count, 0);
    const bool finished = detail::parallel_for(count, threads, [&](std::size_t k) {
      Chunk& c = chunks[k];
      c = layout.chunk(mine[b + k]);
      ChunkTreeBuilder::build_chunk(grids, c);
      blobs[k] = detail::encode_chunk_mesh(c.mesh);
      if (blob_checksums) sums[k] = fnv1a64(blobs[k].data(), blobs[k].size());
      c.mesh = ChunkMesh{};
    }, options.control.cancel);
    if (!finished) return make_error(ErrorCode::kCancelled, fmt::format("{}: bake cancelled; no share was written", name));
    for (std::size_t k = 0; k < count; ++k) {
      const Chunk& c = chunks[k];
      const std::string& blob = blobs[k];
      const std::size_t at = static_cast<std::size_t>(mine[b + k] - first) * detail::kShareEntryBytes;
      put_le(directory, at + detail::kSePresent, std::uint8_t{1});
      put_le(directory, at + detail::kSeError, c.error);
      put_le(directory, at + detail::kSeMinY, c.min_y);
      put_le(directory, at + detail::kSeMaxY, c.max_y);
      put_le(directory, at + detail::kSeTriangles, c.triangle_count);
      put_le(directory, at + detail::kSeVertices, c.vertex_count);
      put_le(directory, at + detail::kSeOffset, offset);
      put_le(directory, at + detail::kSeBytes, static_cast<std::uint64_t>(blob.size()));
      put_le(directory, at + detail::kSeChecksum, sums[k]);
      out.write(blob.data(), static_cast<std::streamsize>(blob.size()));
      offset += blob.size();
      report.triangles += c.triangle_count;
    }
    if (!out) return write_failed();
    report.chunks += count;
    if (options.control.progress) {
      options.control.progress(static_cast<float>(b + count) / static_cast<float>(std::max<std::size_t>(mine.size(), 1)));
    }
  }

  const std::uint64_t dir_offset = offset;
  out.write(directory.data(), static_cast<std::streamsize>(directory.size()));
  std::memcpy(header.data(), detail::kShareMagic, 8);
  put_le(header, detail::kShVersion, kBakeShareVersion);
  put_le(header, detail::kShIndex, static_cast<std::uint32_t>(options.share));
  put_le(header, detail::kShCount, static_cast<std::uint32_t>(options.shares));
  put_le(header, detail::kShColumns, static_cast<std::int32_t>(layout.field_columns()));
  put_le(header, detail::kShRows, static_cast<std::int32_t>(layout.field_rows()));
  put_le(header, detail::kShLeafDimension, static_cast<std::uint32_t>(settings.leaf_dimension));
  put_le(header, detail::kShSpacing, layout.spacing());
  put_le(header, detail::kShOriginX, layout.origin().x);
  put_le(header, detail::kShOriginZ, layout.origin().y);
  put_le(header, detail::kShFlatTolerance, settings.flat_tolerance);
  put_le(header, detail::kShMaxMorph, settings.max_morph_fraction);
  put_le(header, detail::kShOptimize, static_cast<std::uint8_t>(settings.optimize_vertex_cache ? 1 : 0));
  put_le(header, detail::kShFirstSlot, first);
  put_le(header, detail::kShEndSlot, end);
  put_le(header, detail::kShHeightTile, static_cast<std::uint16_t>(tiles.tile));
  put_le(header, detail::kShHeightOverview, static_cast<std::uint16_t>(tiles.overview));
  put_le(header, detail::kShDirOffset, dir_offset);
  put_le(header, detail::kShDirBytes, static_cast<std::uint64_t>(directory.size()));
  put_le(header, detail::kShDirChecksum, fnv1a64(directory.data(), directory.size()));
  put_le(header, detail::kShFileBytes, dir_offset + directory.size());
  put_le(header, detail::kShHeaderChecksum, fnv1a64(header.data(), detail::kShHeaderChecksum));
  out.seekp(0);
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  out.close();
  if (!out) return write_failed();
  SYLVA_TRY(replace_with_temp(temp.path, share_file));
  temp.path.clear();
  report.bytes = dir_offset + directory.size();
  report.meshes_ms = watch.lap_ms();
  return report;
}

}  // namespace sylva::terrain

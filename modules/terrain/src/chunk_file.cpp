#include <sylva/terrain/chunk_file.hpp>

#include "chunk_blob.hpp"
#include "chunk_file_heights.hpp"
#include "parallel.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/assert.hpp>
#include <sylva/core/log.hpp>

#include <atomic>
#include <cmath>
#include <cstring>
#include <optional>

namespace sylva::terrain {

namespace {

constexpr char kMagic[8] = {'S', 'Y', 'L', 'V', 'A', 'C', 'H', 'K'};
constexpr std::size_t kHeaderBytes = 128;
constexpr std::size_t kEntryBytes = 64;
using detail::get_le;
using detail::put_le;
constexpr std::size_t kHeightTileAt = 76;      // header: uint16 samples per height tile side, 0 = no heights
constexpr std::size_t kHeightOverviewAt = 78;  // header: uint16 overview stride, 0 = none (version 2: always)

detail::HeightTiles height_tiles(const ChunkTree& t, std::uint32_t tile, std::uint32_t overview) {
  return detail::HeightTiles{t.field_columns(), t.field_rows(), tile, tile == 0 ? 0u : overview};
}

}  // namespace

Result<std::unique_ptr<ChunkFileWriter>> ChunkFileWriter::create(const std::filesystem::path& path,
                                                                 const ChunkTree& layout,
                                                                 const std::filesystem::path& overwrite,
                                                                 bool heights, std::uint32_t overview_stride) {
  SYLVA_TRY(check_replaceable(path));
  if (layout.settings().tessellation != Tessellation::kRtin) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: chunk files hold RTIN trees; terrain.tree.tessellation = hq0/hq1/hq2 is built in "
                                  "memory only", path.string()));
  }
  std::unique_ptr<ChunkFileWriter> w(new ChunkFileWriter());
  w->path_ = path;
  w->header_.assign(kHeaderBytes, '\0');
  if (overwrite.empty()) {
    w->temp_ = temp_path_beside(path);
    w->out_.open(w->temp_, std::ios::binary | std::ios::trunc);
    if (!w->out_) return make_error(ErrorCode::kIo, fmt::format("{}: cannot create a file in this folder", path.string()));
    w->out_.write(w->header_.data(), static_cast<std::streamsize>(kHeaderBytes));
  } else {
    w->temp_ = overwrite;
    w->out_.open(w->temp_, std::ios::binary | std::ios::in | std::ios::out);  // no truncation
    if (!w->out_) return make_error(ErrorCode::kIo, fmt::format("{}: cannot reopen {}", path.string(), overwrite.string()));
  }
  SYLVA_ASSERT(overview_stride == 0 || (overview_stride >= 2 && overview_stride <= 0x8000 &&
                                        (overview_stride & (overview_stride - 1)) == 0),
               "ChunkFileWriter: overview stride {}", overview_stride);
  const detail::HeightTiles tiles = height_tiles(layout, heights ? detail::kHeightTileSamples : 0, overview_stride);
  w->offset_ = kHeaderBytes + tiles.section_bytes();
  w->heights_pending_ = heights && overwrite.empty();
  // In place, the share's section already lies where this file wants it (bake_merge.cpp).
  if (!overwrite.empty()) w->out_.seekp(static_cast<std::streamoff>(w->offset_));
  std::string& header = w->header_;
  std::memcpy(header.data(), kMagic, 8);
  put_le(header, 8, kChunkFileVersion);
  put_le(header, 12, static_cast<std::uint32_t>(kHeaderBytes));
  put_le(header, 16, static_cast<std::uint32_t>(layout.levels()));
  put_le(header, 20, layout.leaf_intervals());
  put_le(header, 24, layout.root_intervals());
  put_le(header, 28, static_cast<std::int32_t>(layout.field_columns()));
  put_le(header, 32, static_cast<std::int32_t>(layout.field_rows()));
  put_le(header, 36, static_cast<std::uint32_t>(layout.chunk_count()));
  put_le(header, 40, layout.spacing());
  put_le(header, 48, layout.origin().x);
  put_le(header, 56, layout.origin().y);
  put_le(header, 64, layout.settings().flat_tolerance);
  put_le(header, 68, layout.settings().max_morph_fraction);
  put_le(header, 72, static_cast<std::uint32_t>(layout.settings().leaf_dimension));
  put_le(header, kHeightTileAt, static_cast<std::uint16_t>(tiles.tile));
  put_le(header, kHeightOverviewAt, static_cast<std::uint16_t>(tiles.overview));
  w->directory_.assign(layout.chunk_count() * kEntryBytes, '\0');
  for (std::uint32_t i = 0; i < layout.chunk_count(); ++i) {
    const ChunkKey& k = layout.chunk(i).key;
    const std::size_t at = static_cast<std::size_t>(i) * kEntryBytes;
    put_le(w->directory_, at + 1, static_cast<std::uint8_t>(k.level));
    put_le(w->directory_, at + 4, k.x);
    put_le(w->directory_, at + 8, k.z);
  }
  return w;
}

ChunkFileWriter::~ChunkFileWriter() { abandon(); }

void ChunkFileWriter::abandon() {
  if (done_) return;
  done_ = true;
  if (out_.is_open()) out_.close();
  std::error_code ec;
  std::filesystem::remove(temp_, ec);
}

Status ChunkFileWriter::write_failed() {
  abandon();
  return make_error(ErrorCode::kIo, fmt::format("{}: writing failed (disk full?); the old file is untouched", path_.string()));
}

Status ChunkFileWriter::add(std::uint32_t index, const Chunk& c, std::string_view blob) {
  return add(index, c, blob, c.present ? fnv1a64(blob.data(), blob.size()) : 0);
}

Status ChunkFileWriter::write_heights(const HeightRows& rows) {
  SYLVA_ASSERT(heights_pending_ && !done_, "write_heights: not announced to create() or already written");
  heights_pending_ = false;
  const detail::HeightTiles tiles{get_le<std::int32_t>(header_.data(), 28), get_le<std::int32_t>(header_.data(), 32),
                                  get_le<std::uint16_t>(header_.data(), kHeightTileAt),
                                  get_le<std::uint16_t>(header_.data(), kHeightOverviewAt)};
  Status written = detail::write_height_section(out_, tiles, rows, path_.string());
  if (!written.ok()) abandon();
  return written;
}

Status ChunkFileWriter::add(std::uint32_t index, const Chunk& c, std::string_view blob, std::uint64_t checksum) {
  SYLVA_ASSERT(!heights_pending_, "ChunkFileWriter: write_heights() must come before the chunks");
  SYLVA_ASSERT(!done_ && static_cast<std::int64_t>(index) > last_ && index < directory_.size() / kEntryBytes,
               "chunk {} after {} ({} slots, finished {})", index, last_, directory_.size() / kEntryBytes, done_);
  last_ = index;
  const std::size_t at = static_cast<std::size_t>(index) * kEntryBytes;
  put_le(directory_, at, static_cast<std::uint8_t>(c.present ? 1 : 0));
  put_le(directory_, at + 12, c.error);
  put_le(directory_, at + 16, c.error_bound);
  put_le(directory_, at + 20, c.min_y);
  put_le(directory_, at + 24, c.max_y);
  put_le(directory_, at + 28, c.triangle_count);
  put_le(directory_, at + 32, c.vertex_count);
  if (!c.present) return ok_status();
  out_.write(blob.data(), static_cast<std::streamsize>(blob.size()));
  if (!out_) return write_failed();
  put_le(directory_, at + 40, offset_);
  put_le(directory_, at + 48, static_cast<std::uint64_t>(blob.size()));
  put_le(directory_, at + 56, checksum);
  offset_ += blob.size();
  return ok_status();
}

Status ChunkFileWriter::add(std::uint32_t index, const Chunk& chunk, const ChunkMesh& mesh) {
  return add(index, chunk, chunk.present ? std::string_view(detail::encode_chunk_mesh(mesh)) : std::string_view());
}

void ChunkFileWriter::set_tag(std::uint64_t tag) { put_le(header_, 112, tag); }

Status ChunkFileWriter::finish() {
  SYLVA_ASSERT(!done_, "ChunkFileWriter::finish called twice");
  const std::uint64_t directory_offset = offset_;
  out_.write(directory_.data(), static_cast<std::streamsize>(directory_.size()));
  const std::uint64_t file_bytes = directory_offset + directory_.size();
  put_le(header_, 80, directory_offset);
  put_le(header_, 88, static_cast<std::uint64_t>(directory_.size()));
  put_le(header_, 96, fnv1a64(directory_.data(), directory_.size()));
  put_le(header_, 104, file_bytes);
  put_le(header_, 120, fnv1a64(header_.data(), 120));
  out_.seekp(0);
  out_.write(header_.data(), static_cast<std::streamsize>(header_.size()));
  out_.close();
  if (!out_) return write_failed();
  done_ = true;
  return replace_with_temp(temp_, path_);
}

std::uint32_t height_overview_stride(int columns, int rows, std::uint64_t max_samples) {
  const int stride = detail::stride_for(columns, rows, max_samples);
  return stride == 1 ? 0u : static_cast<std::uint32_t>(stride);
}

Status save_chunk_file(const std::filesystem::path& path, const ChunkTree& tree, std::uint64_t tag,
                       const HeightField* ground, std::uint64_t overview_max_samples) {
  if (!tree.has_meshes()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: the chunk tree was built without meshes (keep_meshes = false)", path.string()));
  }
  Result<std::unique_ptr<ChunkFileWriter>> writer = ChunkFileWriter::create(
      path, tree, {}, ground != nullptr,
      height_overview_stride(tree.field_columns(), tree.field_rows(), overview_max_samples));
  if (!writer) return writer.error();
  (*writer)->set_tag(tag);
  if (ground != nullptr) {
    SYLVA_ASSERT(ground->columns() == tree.field_columns() && ground->rows() == tree.field_rows(),
                 "save_chunk_file: ground {}x{} for a tree of {}x{}", ground->columns(), ground->rows(),
                 tree.field_columns(), tree.field_rows());
    SYLVA_TRY((*writer)->write_heights([&](int z, int x0, int width, float* out) {
      for (int x = 0; x < width; ++x) out[x] = ground->sample(x0 + x, z);
      return ok_status();
    }));
  }
  for (std::uint32_t i = 0; i < tree.chunk_count(); ++i) SYLVA_TRY((*writer)->add(i, tree.chunk(i), tree.chunk(i).mesh));
  return (*writer)->finish();
}

Result<std::shared_ptr<ChunkFile>> ChunkFile::open(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    return make_error(ErrorCode::kNotFound, fmt::format("{}: chunk file not found", name));
  }
  auto file = std::make_shared<ChunkFile>();
  file->path_ = path;
  file->in_.open(path, std::ios::binary);
  if (!file->in_) return make_error(ErrorCode::kIo, fmt::format("{}: cannot open", name));
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) return make_error(ErrorCode::kIo, fmt::format("{}: cannot read its size", name));
  auto corrupt = [&](const std::string& what) { return make_error(ErrorCode::kCorrupt, fmt::format("{}: {}", name, what)); };
  if (size < kHeaderBytes) return corrupt(fmt::format("truncated: {} bytes, the header alone needs {}", size, kHeaderBytes));
  std::string header(kHeaderBytes, '\0');
  file->in_.read(header.data(), static_cast<std::streamsize>(kHeaderBytes));
  if (!file->in_) return corrupt("cannot read the header");
  if (std::memcmp(header.data(), kMagic, 8) != 0) return corrupt("not a Sylva chunk file (bad magic)");
  const auto version = get_le<std::uint32_t>(header.data(), 8);
  // Version 2 is version 3 without the heights' overview (the header's overview stride is 0).
  if (version != kChunkFileVersion && version != 2) {
    return make_error(ErrorCode::kUnsupported,
                      fmt::format("{}: chunk file version {}, this build reads versions 2 (which adds the ground "
                                  "heights) and {}: re-bake it with `sylva-bake terrain`", name, version,
                                  kChunkFileVersion));
  }
  file->version_ = version;
  if (get_le<std::uint64_t>(header.data(), 120) != fnv1a64(header.data(), 120)) return corrupt("header checksum mismatch");
  const auto file_bytes = get_le<std::uint64_t>(header.data(), 104);
  if (file_bytes != size) {
    return corrupt(fmt::format("{}: {} bytes but the header says {}", size < file_bytes ? "truncated" : "wrong size",
                               size, file_bytes));
  }
  file->tag_ = get_le<std::uint64_t>(header.data(), 112);
  ChunkTree& t = file->tree_;
  t.levels_ = static_cast<int>(get_le<std::uint32_t>(header.data(), 16));
  t.n_ = get_le<std::uint32_t>(header.data(), 20);
  t.root_n_ = get_le<std::uint32_t>(header.data(), 24);
  t.columns_ = get_le<std::int32_t>(header.data(), 28);
  t.rows_ = get_le<std::int32_t>(header.data(), 32);
  const auto count = get_le<std::uint32_t>(header.data(), 36);
  t.spacing_ = get_le<double>(header.data(), 40);
  t.origin_ = glm::dvec2(get_le<double>(header.data(), 48), get_le<double>(header.data(), 56));
  t.settings_.flat_tolerance = get_le<float>(header.data(), 64);
  t.settings_.max_morph_fraction = get_le<float>(header.data(), 68);
  t.settings_.leaf_dimension = static_cast<int>(get_le<std::uint32_t>(header.data(), 72));
  t.settings_.keep_meshes = false;
  std::uint64_t expected_count = 0;
  if (t.levels_ < 1 || t.levels_ > 24) return corrupt(fmt::format("implausible level count {}", t.levels_));
  for (int l = 0; l < t.levels_; ++l) expected_count += (1ull << l) * (1ull << l);
  if (count != expected_count || t.n_ < 2 || (std::uint64_t{t.n_} << (t.levels_ - 1)) != t.root_n_) {
    return corrupt(fmt::format("inconsistent tree layout ({} chunks for {} levels)", count, t.levels_));
  }
  // The geometry every later computation trusts: a field the root grid covers, a finite placement.
  if ((t.n_ & (t.n_ - 1)) != 0 || t.settings_.leaf_dimension != static_cast<int>(t.n_ + 1) || t.columns_ < 1 ||
      t.rows_ < 1 || static_cast<std::uint32_t>(t.columns_) > t.root_n_ + 1 ||
      static_cast<std::uint32_t>(t.rows_) > t.root_n_ + 1 || !(t.spacing_ > 0.0) || !std::isfinite(t.spacing_) ||
      !std::isfinite(t.origin_.x) || !std::isfinite(t.origin_.y)) {
    return corrupt(fmt::format("implausible field geometry ({} x {} samples, spacing {}, leaf dimension {})", t.columns_,
                               t.rows_, t.spacing_, t.settings_.leaf_dimension));
  }
  file->height_tile_ = get_le<std::uint16_t>(header.data(), kHeightTileAt);
  file->height_overview_ = get_le<std::uint16_t>(header.data(), kHeightOverviewAt);
  if ((file->height_tile_ != 0 && file->height_tile_ != detail::kHeightTileSamples) ||
      (file->height_overview_ != 0 && (file->height_tile_ == 0 || file->height_overview_ < 2 ||
                                       (file->height_overview_ & (file->height_overview_ - 1)) != 0))) {
    return corrupt(fmt::format("implausible height tiles ({} samples, overview stride {})", file->height_tile_,
                               file->height_overview_));
  }
  const detail::HeightTiles tiles = height_tiles(t, file->height_tile_, file->height_overview_);
  const std::uint64_t data_start = kHeaderBytes + tiles.section_bytes();
  const auto dir_offset = get_le<std::uint64_t>(header.data(), 80);
  const auto dir_bytes = get_le<std::uint64_t>(header.data(), 88);
  if (dir_bytes != static_cast<std::uint64_t>(count) * kEntryBytes || dir_bytes > size ||
      dir_offset != size - dir_bytes || dir_offset < data_start) {
    return corrupt("the directory does not fit the file");
  }
  if (tiles.tile != 0) {
    auto table = detail::read_height_table(file->in_, kHeaderBytes, tiles, name);
    if (!table) return table.error();
    file->height_table_ = std::move(*table);
  }
  std::string dir(dir_bytes, '\0');
  file->in_.seekg(static_cast<std::streamoff>(dir_offset));
  file->in_.read(dir.data(), static_cast<std::streamsize>(dir_bytes));
  if (!file->in_) return corrupt("cannot read the directory");
  if (get_le<std::uint64_t>(header.data(), 96) != fnv1a64(dir.data(), dir.size())) return corrupt("directory checksum mismatch");

  std::uint32_t offset = 0;
  for (int l = 0; l < t.levels_; ++l) {
    t.level_offset_.push_back(offset);
    offset += (1u << l) * (1u << l);
  }
  t.chunks_.resize(count);
  file->entries_.resize(count);
  int level = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    const char* e = dir.data() + static_cast<std::size_t>(i) * kEntryBytes;
    Chunk& c = t.chunks_[i];
    c.present = get_le<std::uint8_t>(e, 0) != 0;
    c.key = ChunkKey{get_le<std::uint8_t>(e, 1), get_le<std::uint32_t>(e, 4), get_le<std::uint32_t>(e, 8)};
    // The key is implied by the slot (levels in order, rows of chunks x fastest); one that is not
    // would index outside the tree.
    if (level + 1 < t.levels_ && i >= t.level_offset_[static_cast<std::size_t>(level) + 1]) ++level;
    const std::uint32_t local = i - t.level_offset_[static_cast<std::size_t>(level)], side = 1u << level;
    if (c.key != ChunkKey{level, local % side, local / side}) {
      return corrupt(fmt::format("chunk {} is labelled level {} at {}, {} but its slot is level {} at {}, {}", i,
                                 c.key.level, c.key.x, c.key.z, level, local % side, local / side));
    }
    c.error = get_le<float>(e, 12);
    c.error_bound = get_le<float>(e, 16);
    c.min_y = get_le<float>(e, 20);
    c.max_y = get_le<float>(e, 24);
    c.triangle_count = get_le<std::uint32_t>(e, 28);
    c.vertex_count = get_le<std::uint32_t>(e, 32);
    Entry& en = file->entries_[i];
    en.offset = get_le<std::uint64_t>(e, 40);
    en.bytes = get_le<std::uint64_t>(e, 48);
    en.checksum = get_le<std::uint64_t>(e, 56);
    en.vertices = c.vertex_count;
    en.indices = c.triangle_count * 3;
    if (c.present && (en.offset < data_start || en.bytes > dir_offset || en.offset > dir_offset - en.bytes ||
                      en.bytes < 24)) {
      return corrupt(fmt::format("chunk {} (level {} at {}, {}) points outside the data", i, c.key.level, c.key.x, c.key.z));
    }
  }
  t.compute_nodes();
  return file;
}

int ChunkFile::height_stride(std::uint64_t max_samples) const {
  return detail::stride_for(tree_.field_columns(), tree_.field_rows(), max_samples);
}

Result<HeightField> ChunkFile::read_heights(int stride) const {
  SYLVA_ASSERT(stride >= 1, "read_heights: stride {}", stride);
  if (!has_heights()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: holds no ground heights (a tree cache file): re-bake it with `sylva-bake terrain`",
                                  path_.string()));
  }
  const detail::HeightTiles tiles = height_tiles(tree_, height_tile_, height_overview_);
  const int columns = (tiles.columns - 1) / stride + 1, rows = (tiles.rows - 1) / stride + 1;
  HeightField field(columns, rows, tree_.spacing() * stride, tree_.origin());
  // The overview when it holds every sample wanted: the same samples, 1/overview^2 of the bytes.
  const bool from_overview = tiles.overview != 0 && stride % static_cast<int>(tiles.overview) == 0;
  const detail::HeightTiles::Grid grid = from_overview ? tiles.overview_grid() : tiles.field_grid();
  const int sub = stride / grid.stride;  // every sub-th sample of the grid read
  // Tiles read in file order under the stream's lock, verified and copied on every thread (the
  // checksum is most of the time); each tile writes its own samples of the field.
  const std::uint32_t count = grid.tiles_x * grid.tiles_z;
  std::vector<std::optional<Error>> failed(count);
  std::atomic<bool> bad{false};
  detail::parallel_for(count, detail::resolve_threads(0), [&](std::size_t i) {
    if (bad.load(std::memory_order_relaxed)) return;
    const auto t = grid.first + static_cast<std::uint32_t>(i);
    std::vector<float> tile;
    Status status = ok_status();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      status = detail::read_height_tile_bytes(in_, kHeaderBytes, tiles, t, path_.string(), tile);
    }
    height_bytes_read_ += tile.size() * sizeof(float);
    if (status.ok()) status = detail::verify_height_tile(tiles, height_table_, t, path_.string(), tile);
    if (!status.ok()) {
      failed[i] = status.error();
      bad = true;
      return;
    }
    detail::copy_strided(tile, tiles.rect(t), sub, field.samples().data(), columns, rows);
  }, nullptr, 1);
  for (const std::optional<Error>& e : failed)
    if (e) return *e;  // the first in file order of the bad tiles found
  field.update_range();
  return field;
}

std::size_t ChunkFile::mesh_bytes(std::uint32_t index) const {
  const Entry& e = entries_[index];
  return static_cast<std::size_t>(e.vertices) * sizeof(ChunkVertex) + static_cast<std::size_t>(e.indices) * 4 +
         static_cast<std::size_t>(e.bytes);  // edges and bookkeeping, bounded by the blob size
}

Result<ChunkMesh> ChunkFile::read_chunk(std::uint32_t index) const {
  if (index >= entries_.size() || !tree_.chunk(index).present) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: chunk {} is not in the file", path_.string(), index));
  }
  const Entry& e = entries_[index];
  const ChunkKey& k = tree_.chunk(index).key;
  auto corrupt = [&](const std::string& what) {
    return make_error(ErrorCode::kCorrupt, fmt::format("{}: chunk {} (level {} at {}, {}): {}", path_.string(), index,
                                                       k.level, k.x, k.z, what));
  };
  std::string blob(e.bytes, '\0');
  {
    std::lock_guard<std::mutex> lock(mutex_);
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(e.offset));
    in_.read(blob.data(), static_cast<std::streamsize>(e.bytes));
    if (!in_) return corrupt("cannot read its data (file changed or truncated)");
  }
  if (fnv1a64(blob.data(), blob.size()) != e.checksum) return corrupt("checksum mismatch");
  ChunkMesh m;
  const std::string wrong = detail::decode_chunk_mesh(blob, e.vertices, e.indices, m);
  if (!wrong.empty()) return corrupt(wrong);
  return m;
}

Result<ChunkTree> ChunkFile::read_tree(const ChunkTreeSettings& settings, const BuildControl& control) const {
  const ChunkTreeSettings& stored = tree_.settings();
  auto differs = [&](const char* name, double file, double wanted) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: built with terrain.tree.{} = {}, not {}",
                                                               path_.string(), name, file, wanted));
  };
  if (stored.leaf_dimension != settings.leaf_dimension)
    return differs("leaf_dimension", stored.leaf_dimension, settings.leaf_dimension);
  if (stored.flat_tolerance != settings.flat_tolerance)
    return differs("flat_tolerance", stored.flat_tolerance, settings.flat_tolerance);
  if (stored.max_morph_fraction != settings.max_morph_fraction)
    return differs("max_morph_fraction", stored.max_morph_fraction, settings.max_morph_fraction);
  ChunkTree tree = tree_;  // metadata, layout and selection nodes
  tree.settings_ = settings;
  tree.settings_.keep_meshes = true;
  // read_chunk serialises the reads (slot order: the file's order) and verifies and decodes
  // outside its lock, so the checksums and decoding run on every thread.
  std::vector<std::optional<Error>> failed(tree.chunks_.size());
  std::atomic<bool> bad{false};
  std::atomic<std::size_t> done{0};
  const bool finished = detail::parallel_for(
      tree.chunks_.size(), detail::resolve_threads(settings.threads),
      [&](std::size_t i) {
        Chunk& c = tree.chunks_[i];
        if (!c.present || bad.load(std::memory_order_relaxed)) return;
        Result<ChunkMesh> mesh = read_chunk(static_cast<std::uint32_t>(i));
        if (!mesh.ok()) {
          failed[i] = mesh.error();
          bad = true;
          return;
        }
        c.mesh = std::move(*mesh);
        const std::size_t n = done.fetch_add(1) + 1;
        if (control.progress && n % 64 == 0) control.progress(static_cast<float>(n) / static_cast<float>(tree.chunks_.size()));
      },
      control.cancel, 16);
  if (bad) {
    for (const std::optional<Error>& e : failed)
      if (e) return *e;
  }
  if (!finished) return make_error(ErrorCode::kCancelled, fmt::format("{}: reading cancelled", path_.string()));
  tree.report_ = BuildReport{};
  tree.report_.threads = detail::resolve_threads(settings.threads);
  tree.fill_level_report();
  if (control.progress) control.progress(1.0f);
  return tree;
}

}  // namespace sylva::terrain

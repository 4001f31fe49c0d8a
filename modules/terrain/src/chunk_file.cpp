#include <sylva/terrain/chunk_file.hpp>

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/log.hpp>

#include <cmath>
#include <cstring>

namespace sylva::terrain {

std::uint64_t fnv1a64(const void* data, std::size_t bytes, std::uint64_t seed) {
  const auto* p = static_cast<const unsigned char*>(data);
  std::uint64_t h = seed;
  for (std::size_t i = 0; i < bytes; ++i) {
    h ^= p[i];
    h *= 0x100000001b3ull;
  }
  return h;
}

namespace {

constexpr char kMagic[8] = {'S', 'Y', 'L', 'V', 'A', 'C', 'H', 'K'};
constexpr std::size_t kHeaderBytes = 128;
constexpr std::size_t kEntryBytes = 64;
constexpr std::size_t kVertexBytes = 24;

template <class T>
void put(std::string& out, std::size_t at, const T& v) {
  std::memcpy(out.data() + at, &v, sizeof(T));
}
template <class T>
T get(const char* in, std::size_t at) {
  T v;
  std::memcpy(&v, in + at, sizeof(T));
  return v;
}

std::string encode_mesh(const ChunkMesh& m) {
  std::size_t edge_total = 0;
  for (const auto& e : m.edges) edge_total += e.size();
  std::string out(24 + m.vertices.size() * kVertexBytes + (m.indices.size() + edge_total) * 4, '\0');
  std::size_t at = 0;
  put(out, at, static_cast<std::uint32_t>(m.vertices.size()));
  put(out, at + 4, static_cast<std::uint32_t>(m.indices.size()));
  for (int e = 0; e < 4; ++e) put(out, at + 8 + 4 * static_cast<std::size_t>(e), static_cast<std::uint32_t>(m.edges[static_cast<std::size_t>(e)].size()));
  at = 24;
  for (const ChunkVertex& v : m.vertices) {
    put(out, at, v.gx);
    put(out, at + 4, v.gz);
    put(out, at + 8, v.height);
    put(out, at + 12, v.morph_target);
    put(out, at + 16, v.morph_error);
    put(out, at + 20, v.intro_level);
    put(out, at + 21, v.outside);
    at += kVertexBytes;
  }
  std::memcpy(out.data() + at, m.indices.data(), m.indices.size() * 4);
  at += m.indices.size() * 4;
  for (const auto& e : m.edges) {
    std::memcpy(out.data() + at, e.data(), e.size() * 4);
    at += e.size() * 4;
  }
  return out;
}

}  // namespace

Status save_chunk_file(const std::filesystem::path& path, const ChunkTree& tree) {
  if (!tree.has_meshes()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: the chunk tree was built without meshes (keep_meshes = false)", path.string()));
  }
  SYLVA_TRY(check_replaceable(path));
  const std::filesystem::path temp = temp_path_beside(path);
  std::ofstream out(temp, std::ios::binary | std::ios::trunc);
  if (!out) return make_error(ErrorCode::kIo, fmt::format("{}: cannot create a file in this folder", path.string()));
  std::string header(kHeaderBytes, '\0');
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  std::string directory(tree.chunk_count() * kEntryBytes, '\0');
  std::uint64_t offset = kHeaderBytes;
  for (std::uint32_t i = 0; i < tree.chunk_count(); ++i) {
    const Chunk& c = tree.chunk(i);
    const std::size_t at = static_cast<std::size_t>(i) * kEntryBytes;
    put(directory, at, static_cast<std::uint8_t>(c.present ? 1 : 0));
    put(directory, at + 1, static_cast<std::uint8_t>(c.key.level));
    put(directory, at + 4, c.key.x);
    put(directory, at + 8, c.key.z);
    put(directory, at + 12, c.error);
    put(directory, at + 16, c.error_bound);
    put(directory, at + 20, c.min_y);
    put(directory, at + 24, c.max_y);
    put(directory, at + 28, c.triangle_count);
    put(directory, at + 32, c.vertex_count);
    if (!c.present) continue;
    const std::string blob = encode_mesh(c.mesh);
    out.write(blob.data(), static_cast<std::streamsize>(blob.size()));
    put(directory, at + 40, offset);
    put(directory, at + 48, static_cast<std::uint64_t>(blob.size()));
    put(directory, at + 56, fnv1a64(blob.data(), blob.size()));
    offset += blob.size();
  }
  const std::uint64_t directory_offset = offset;
  out.write(directory.data(), static_cast<std::streamsize>(directory.size()));
  const std::uint64_t file_bytes = directory_offset + directory.size();

  std::memcpy(header.data(), kMagic, 8);
  put(header, 8, kChunkFileVersion);
  put(header, 12, static_cast<std::uint32_t>(kHeaderBytes));
  put(header, 16, static_cast<std::uint32_t>(tree.levels()));
  put(header, 20, tree.leaf_intervals());
  put(header, 24, tree.root_intervals());
  put(header, 28, static_cast<std::int32_t>(tree.field_columns()));
  put(header, 32, static_cast<std::int32_t>(tree.field_rows()));
  put(header, 36, static_cast<std::uint32_t>(tree.chunk_count()));
  put(header, 40, tree.spacing());
  put(header, 48, tree.origin().x);
  put(header, 56, tree.origin().y);
  put(header, 64, tree.settings().flat_tolerance);
  put(header, 68, tree.settings().max_morph_fraction);
  put(header, 72, static_cast<std::uint32_t>(tree.settings().leaf_dimension));
  put(header, 80, directory_offset);
  put(header, 88, static_cast<std::uint64_t>(directory.size()));
  put(header, 96, fnv1a64(directory.data(), directory.size()));
  put(header, 104, file_bytes);
  put(header, 120, fnv1a64(header.data(), 120));
  out.seekp(0);
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  out.close();
  if (!out) {
    std::error_code ec;
    std::filesystem::remove(temp, ec);
    return make_error(ErrorCode::kIo, fmt::format("{}: writing failed (disk full?); the old file is untouched", path.string()));
  }
  return replace_with_temp(temp, path);
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
  const auto version = get<std::uint32_t>(header.data(), 8);
  if (version != kChunkFileVersion) {
    return make_error(ErrorCode::kUnsupported, fmt::format("{}: chunk file version {}, this build reads version {}",
                                                           name, version, kChunkFileVersion));
  }
  if (get<std::uint64_t>(header.data(), 120) != fnv1a64(header.data(), 120)) return corrupt("header checksum mismatch");
  const auto file_bytes = get<std::uint64_t>(header.data(), 104);
  if (file_bytes != size) {
    return corrupt(fmt::format("{}: {} bytes but the header says {}", size < file_bytes ? "truncated" : "wrong size",
                               size, file_bytes));
  }
  ChunkTree& t = file->tree_;
  t.levels_ = static_cast<int>(get<std::uint32_t>(header.data(), 16));
  t.n_ = get<std::uint32_t>(header.data(), 20);
  t.root_n_ = get<std::uint32_t>(header.data(), 24);
  t.columns_ = get<std::int32_t>(header.data(), 28);
  t.rows_ = get<std::int32_t>(header.data(), 32);
  const auto count = get<std::uint32_t>(header.data(), 36);
  t.spacing_ = get<double>(header.data(), 40);
  t.origin_ = glm::dvec2(get<double>(header.data(), 48), get<double>(header.data(), 56));
  t.settings_.flat_tolerance = get<float>(header.data(), 64);
  t.settings_.max_morph_fraction = get<float>(header.data(), 68);
  t.settings_.leaf_dimension = static_cast<int>(get<std::uint32_t>(header.data(), 72));
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
  const auto dir_offset = get<std::uint64_t>(header.data(), 80);
  const auto dir_bytes = get<std::uint64_t>(header.data(), 88);
  if (dir_bytes != static_cast<std::uint64_t>(count) * kEntryBytes || dir_bytes > size ||
      dir_offset != size - dir_bytes) {
    return corrupt("the directory does not fit the file");
  }
  std::string dir(dir_bytes, '\0');
  file->in_.seekg(static_cast<std::streamoff>(dir_offset));
  file->in_.read(dir.data(), static_cast<std::streamsize>(dir_bytes));
  if (!file->in_) return corrupt("cannot read the directory");
  if (get<std::uint64_t>(header.data(), 96) != fnv1a64(dir.data(), dir.size())) return corrupt("directory checksum mismatch");

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
    c.present = get<std::uint8_t>(e, 0) != 0;
    c.key = ChunkKey{get<std::uint8_t>(e, 1), get<std::uint32_t>(e, 4), get<std::uint32_t>(e, 8)};
    // The key is implied by the slot (levels in order, rows of chunks x fastest); one that is not
    // would index outside the tree.
    if (level + 1 < t.levels_ && i >= t.level_offset_[static_cast<std::size_t>(level) + 1]) ++level;
    const std::uint32_t local = i - t.level_offset_[static_cast<std::size_t>(level)], side = 1u << level;
    if (c.key != ChunkKey{level, local % side, local / side}) {
      return corrupt(fmt::format("chunk {} is labelled level {} at {}, {} but its slot is level {} at {}, {}", i,
                                 c.key.level, c.key.x, c.key.z, level, local % side, local / side));
    }
    c.error = get<float>(e, 12);
    c.error_bound = get<float>(e, 16);
    c.min_y = get<float>(e, 20);
    c.max_y = get<float>(e, 24);
    c.triangle_count = get<std::uint32_t>(e, 28);
    c.vertex_count = get<std::uint32_t>(e, 32);
    Entry& en = file->entries_[i];
    en.offset = get<std::uint64_t>(e, 40);
    en.bytes = get<std::uint64_t>(e, 48);
    en.checksum = get<std::uint64_t>(e, 56);
    en.vertices = c.vertex_count;
    en.indices = c.triangle_count * 3;
    if (c.present && (en.offset < kHeaderBytes || en.bytes > dir_offset || en.offset > dir_offset - en.bytes ||
                      en.bytes < 24)) {
      return corrupt(fmt::format("chunk {} (level {} at {}, {}) points outside the data", i, c.key.level, c.key.x, c.key.z));
    }
  }
  t.compute_nodes();
  return file;
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
  const auto nv = get<std::uint32_t>(blob.data(), 0), ni = get<std::uint32_t>(blob.data(), 4);
  std::uint64_t edge_total = 0;
  std::uint32_t ne[4];
  for (int q = 0; q < 4; ++q) {
    ne[q] = get<std::uint32_t>(blob.data(), 8 + 4 * static_cast<std::size_t>(q));
    edge_total += ne[q];
  }
  if (24 + static_cast<std::uint64_t>(nv) * kVertexBytes + (static_cast<std::uint64_t>(ni) + edge_total) * 4 != e.bytes ||
      nv != e.vertices || ni != e.indices) {
    return corrupt("its counts do not match its size");
  }
  m.vertices.resize(nv);
  std::size_t at = 24;
  for (ChunkVertex& v : m.vertices) {
    v.gx = get<std::uint32_t>(blob.data(), at);
    v.gz = get<std::uint32_t>(blob.data(), at + 4);
    v.height = get<float>(blob.data(), at + 8);
    v.morph_target = get<float>(blob.data(), at + 12);
    v.morph_error = get<float>(blob.data(), at + 16);
    v.intro_level = get<std::uint8_t>(blob.data(), at + 20);
    v.outside = get<std::uint8_t>(blob.data(), at + 21);
    at += kVertexBytes;
  }
  m.indices.resize(ni);
  std::memcpy(m.indices.data(), blob.data() + at, static_cast<std::size_t>(ni) * 4);
  at += static_cast<std::size_t>(ni) * 4;
  for (int q = 0; q < 4; ++q) {
    m.edges[static_cast<std::size_t>(q)].resize(ne[q]);
    std::memcpy(m.edges[static_cast<std::size_t>(q)].data(), blob.data() + at, static_cast<std::size_t>(ne[q]) * 4);
    at += static_cast<std::size_t>(ne[q]) * 4;
  }
  for (std::uint32_t i : m.indices)
    if (i >= nv) return corrupt(fmt::format("index {} beyond its {} vertices", i, nv));
  for (const auto& edge : m.edges)
    for (std::uint32_t i : edge)
      if (i >= nv) return corrupt(fmt::format("edge vertex {} beyond its {} vertices", i, nv));
  return m;
}

}  // namespace sylva::terrain

#include <sylva/voxel/region.hpp>

#include <sylva/core/assert.hpp>
#include <sylva/core/atomic_file.hpp>
#include <sylva/core/log.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <fstream>
#include <limits>

namespace sylva::voxel {

namespace {

constexpr char kMagic[8] = {'S', 'Y', 'L', 'V', 'A', 'V', 'X', 'R'};
constexpr std::uint16_t kEncodingRuns = 1;

std::array<std::uint32_t, 256> make_crc_table() {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    t[i] = c;
  }
  return t;
}

class Writer {
 public:
  void u16(std::uint16_t v) { put(&v, 2); }
  void u32(std::uint32_t v) { put(&v, 4); }
  void i64(std::int64_t v) { put(&v, 8); }
  void bytes(const void* p, std::size_t n) { put(p, n); }
  std::vector<std::uint8_t>& data() { return out_; }
  void patch_u32(std::size_t at, std::uint32_t v) { std::memcpy(out_.data() + at, &v, 4); }

 private:
  void put(const void* p, std::size_t n) {
    static_assert(std::endian::native == std::endian::little, "region files assume a little-endian host");
    const auto* b = static_cast<const std::uint8_t*>(p);
    out_.insert(out_.end(), b, b + n);
  }
  std::vector<std::uint8_t> out_;
};

class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> b) : b_(b) {}
  bool u16(std::uint16_t& v) { return get(&v, 2); }
  bool u32(std::uint32_t& v) { return get(&v, 4); }
  bool i64(std::int64_t& v) { return get(&v, 8); }
  bool bytes(void* p, std::size_t n) { return get(p, n); }
  std::size_t pos() const { return pos_; }

 private:
  bool get(void* p, std::size_t n) {
    if (pos_ + n > b_.size()) return false;
    std::memcpy(p, b_.data() + pos_, n);
    pos_ += n;
    return true;
  }
  std::span<const std::uint8_t> b_;
  std::size_t pos_ = 0;
};

int chunk_slot(const ChunkCoord& c) {
  const int lx = static_cast<int>(c.x & (kRegionSize - 1));
  const int ly = static_cast<int>(c.y & (kRegionSize - 1));
  const int lz = static_cast<int>(c.z & (kRegionSize - 1));
  return lx + kRegionSize * (lz + kRegionSize * ly);
}

ChunkCoord slot_chunk(const RegionCoord& r, int slot) {
  const int lx = slot % kRegionSize;
  const int lz = (slot / kRegionSize) % kRegionSize;
  const int ly = slot / (kRegionSize * kRegionSize);
  return {r.x * kRegionSize + lx, r.y * kRegionSize + ly, r.z * kRegionSize + lz};
}

std::string chunk_name(const ChunkCoord& c) { return fmt::format("chunk ({}, {}, {})", c.x, c.y, c.z); }

// Whether every block of a region has an int64 position: (r * blocks per region edge) + the
// last block must not overflow. A file read from disk may claim any coordinate, and without
// this check slot_chunk() and chunk_origin() would overflow (undefined) for |r| >= 2^60.
constexpr std::int64_t kRegionBlocks = std::int64_t{kRegionSize} * kChunkSize;
bool region_axis_in_world(std::int64_t r) {
  std::int64_t first = 0, last = 0;
  return !__builtin_mul_overflow(r, kRegionBlocks, &first) && !__builtin_add_overflow(first, kRegionBlocks - 1, &last);
}

}  // namespace

std::string region_file_name(const RegionCoord& r) { return fmt::format("r.{}.{}.{}.svr", r.x, r.y, r.z); }

std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc) {
  static const auto table = make_crc_table();
  crc = ~crc;
  for (std::uint8_t b : bytes) crc = table[(crc ^ b) & 0xffu] ^ (crc >> 8);
  return ~crc;
}

std::vector<std::uint8_t> encode_region(const RegionCoord& r, const BlockPalette& palette,
                                        std::span<const std::pair<ChunkCoord, const Chunk*>> chunks) {
  // Name table: palette ids used by any chunk, in first-use order.
  std::vector<int> name_of_id(palette.size(), -1);
  std::vector<BlockId> names;
  std::vector<std::vector<std::uint8_t>> payloads;
  std::vector<int> slots;
  std::vector<BlockId> ids(kChunkVolume);
  for (const auto& [coord, chunk] : chunks) {
    SYLVA_ASSERT(region_of(coord) == r, "{} is not in region ({}, {}, {})", chunk_name(coord), r.x, r.y, r.z);
    chunk->copy_to(ids);
    Writer w;
    std::size_t i = 0;
    while (i < ids.size()) {
      const BlockId id = ids[i];
      std::size_t run = 1;
      while (i + run < ids.size() && ids[i + run] == id && run < 65536) ++run;
      if (name_of_id[id] < 0) {
        name_of_id[id] = static_cast<int>(names.size());
        names.push_back(id);
      }
      w.u16(static_cast<std::uint16_t>(name_of_id[id]));
      w.u16(static_cast<std::uint16_t>(run - 1));
      i += run;
    }
    payloads.push_back(std::move(w.data()));
    slots.push_back(chunk_slot(coord));
  }
  Writer h;
  h.bytes(kMagic, sizeof kMagic);
  h.u32(kRegionVersion);
  h.u32(static_cast<std::uint32_t>(kChunkSize));
  h.i64(r.x);
  h.i64(r.y);
  h.i64(r.z);
  h.u32(static_cast<std::uint32_t>(names.size()));
  for (BlockId id : names) {
    const std::string& name = palette[id].name;
    h.u16(static_cast<std::uint16_t>(name.size()));
    h.bytes(name.data(), name.size());
  }
  h.u32(static_cast<std::uint32_t>(payloads.size()));
  std::uint32_t offset = 0;
  for (std::size_t k = 0; k < payloads.size(); ++k) {
    h.u16(static_cast<std::uint16_t>(slots[k]));
    h.u16(kEncodingRuns);
    h.u32(offset);
    h.u32(static_cast<std::uint32_t>(payloads[k].size()));
    h.u32(crc32(payloads[k]));
    offset += static_cast<std::uint32_t>(payloads[k].size());
  }
  h.u32(crc32(h.data()));
  auto& out = h.data();
  for (const auto& p : payloads) out.insert(out.end(), p.begin(), p.end());
  return std::move(out);
}

Result<RegionContents> decode_region(std::span<const std::uint8_t> bytes, const BlockPalette& palette,
                                     const std::string& source) {
  auto corrupt = [&source](const std::string& what) {
    return make_error(ErrorCode::kCorrupt, fmt::format("region file {}: {}", source, what));
  };
  Reader in(bytes);
  char magic[8];
  if (!in.bytes(magic, 8) || std::memcmp(magic, kMagic, 8) != 0) return corrupt("not a Sylva region file (bad magic)");
  std::uint32_t version = 0, chunk_size = 0;
  if (!in.u32(version)) return corrupt("truncated header");
  if (version != kRegionVersion) {
    return make_error(ErrorCode::kUnsupported,
                      fmt::format("region file {}: version {} (this build reads {})", source, version, kRegionVersion));
  }
  if (!in.u32(chunk_size)) return corrupt("truncated header");
  if (chunk_size != static_cast<std::uint32_t>(kChunkSize)) {
    return corrupt(fmt::format("chunk size {} (expected {})", chunk_size, kChunkSize));
  }
  RegionContents out;
  if (!in.i64(out.coord.x) || !in.i64(out.coord.y) || !in.i64(out.coord.z)) return corrupt("truncated header");
  if (!region_axis_in_world(out.coord.x) || !region_axis_in_world(out.coord.y) || !region_axis_in_world(out.coord.z)) {
    return corrupt(fmt::format("region coordinate ({}, {}, {}) is outside the world (each axis within {}..{})",
                               out.coord.x, out.coord.y, out.coord.z,
                               std::numeric_limits<std::int64_t>::min() / kRegionBlocks,
                               std::numeric_limits<std::int64_t>::max() / kRegionBlocks));
  }
  std::uint32_t name_count = 0;
  if (!in.u32(name_count) || name_count > 65536) return corrupt("bad block-name count");
  std::vector<std::string> names(name_count);
  for (auto& name : names) {
    std::uint16_t len = 0;
    if (!in.u16(len) || len > 256) return corrupt("bad block-name table");
    name.resize(len);
    if (!in.bytes(name.data(), len)) return corrupt("truncated block-name table");
  }
  std::uint32_t entry_count = 0;
  if (!in.u32(entry_count) || entry_count > static_cast<std::uint32_t>(kRegionSize * kRegionSize * kRegionSize)) {
    return corrupt("bad chunk count");
  }
  struct Entry {
    std::uint16_t slot, encoding;
    std::uint32_t offset, size, crc;
  };
  std::vector<Entry> entries(entry_count);
  for (auto& e : entries) {
    if (!in.u16(e.slot) || !in.u16(e.encoding) || !in.u32(e.offset) || !in.u32(e.size) || !in.u32(e.crc)) {
      return corrupt("truncated chunk table");
    }
  }
  const std::size_t header_end = in.pos();
  std::uint32_t header_crc = 0;
  if (!in.u32(header_crc)) return corrupt("truncated header checksum");
  if (crc32(bytes.first(header_end)) != header_crc) return corrupt("header checksum mismatch");
  const std::size_t payload_start = in.pos();
  std::uint64_t payload_size = 0;
  for (const auto& e : entries) payload_size += e.size;
  if (bytes.size() != payload_start + payload_size) {
    return corrupt(fmt::format("size {} bytes, header says {} (truncated or padded)", bytes.size(),
                               payload_start + payload_size));
  }
  // Names resolve against the current palette; a missing one makes only chunks using it bad.
  std::vector<int> name_ids(names.size(), -1);
  for (std::size_t k = 0; k < names.size(); ++k) {
    auto id = palette.find(names[k]);
    if (id.ok()) name_ids[k] = *id;
  }
  for (const auto& e : entries) {
    if (e.slot >= kRegionSize * kRegionSize * kRegionSize) return corrupt(fmt::format("chunk slot {} out of range", e.slot));
    const ChunkCoord cc = slot_chunk(out.coord, e.slot);
    if (static_cast<std::uint64_t>(e.offset) + e.size > payload_size) {
      return corrupt(fmt::format("{} payload outside the file", chunk_name(cc)));
    }
    const auto payload = bytes.subspan(payload_start + e.offset, e.size);
    auto bad = [&](ErrorCode code, const std::string& what) {
      out.bad_chunks.emplace(cc, make_error(code, fmt::format("region file {}: {}: {}", source, chunk_name(cc), what)));
    };
    if (crc32(payload) != e.crc) {
      bad(ErrorCode::kCorrupt, "checksum mismatch");
      continue;
    }
    if (e.encoding != kEncodingRuns) {
      bad(ErrorCode::kUnsupported, fmt::format("unknown encoding {}", e.encoding));
      continue;
    }
    Chunk chunk;
    auto dense = chunk.dense();
    Reader pr(payload);
    std::size_t filled = 0;
    bool ok = true;
    std::string problem;
    while (filled < dense.size()) {
      std::uint16_t name = 0, run = 0;
      if (!pr.u16(name) || !pr.u16(run)) {
        ok = false;
        problem = "runs end before 32768 blocks";
        break;
      }
      if (name >= names.size()) {
        ok = false;
        problem = fmt::format("block-name index {} outside table of {}", name, names.size());
        break;
      }
      if (name_ids[name] < 0) {
        bad(ErrorCode::kNotFound, fmt::format("block '{}' is not in the palette", names[name]));
        ok = false;
        break;
      }
      const std::size_t len = static_cast<std::size_t>(run) + 1;
      if (filled + len > dense.size()) {
        ok = false;
        problem = "runs exceed 32768 blocks";
        break;
      }
      std::fill(dense.begin() + static_cast<std::ptrdiff_t>(filled),
                dense.begin() + static_cast<std::ptrdiff_t>(filled + len), static_cast<BlockId>(name_ids[name]));
      filled += len;
    }
    if (ok && pr.pos() != payload.size()) {
      ok = false;
      problem = "trailing bytes after the runs";
    }
    if (!ok) {
      if (!problem.empty()) bad(ErrorCode::kCorrupt, problem);
      continue;
    }
    chunk.compact();
    out.chunks.emplace(cc, std::move(chunk));
  }
  return out;
}

Result<RegionContents> read_region_file(const std::filesystem::path& path, const BlockPalette& palette) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return make_error(ErrorCode::kNotFound, fmt::format("region file {}: cannot open", path.string()));
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (f.bad()) return make_error(ErrorCode::kIo, fmt::format("region file {}: read failed", path.string()));
  return decode_region(bytes, palette, path.string());
}

Status write_region_file(const std::filesystem::path& path, const RegionCoord& r, const BlockPalette& palette,
                         std::span<const std::pair<ChunkCoord, const Chunk*>> chunks) {
  const std::vector<std::uint8_t> bytes = encode_region(r, palette, chunks);
  std::error_code ec;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
  Status written = write_file_atomic(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  if (!written.ok()) return make_error(written.error().code, "region file " + written.error().message);
  return ok_status();
}

RegionStore::RegionStore(std::filesystem::path folder, const BlockPalette& palette, std::size_t cache_regions)
    : folder_(std::move(folder)), palette_(&palette), cache_limit_(std::max<std::size_t>(1, cache_regions)) {}

const RegionStore::CacheEntry& RegionStore::region(const RegionCoord& r) {
  auto it = cache_.find(r);
  if (it != cache_.end()) {
    it->second.last_use = ++use_clock_;
    return it->second;
  }
  // Evict the least recently used region before adding one.
  while (cache_.size() >= cache_limit_) {
    auto oldest = cache_.begin();
    for (auto e = cache_.begin(); e != cache_.end(); ++e) {
      if (e->second.last_use < oldest->second.last_use) oldest = e;
    }
    cache_.erase(oldest);
  }
  CacheEntry entry;
  entry.last_use = ++use_clock_;
  const auto path = path_of(r);
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) {
    auto contents = read_region_file(path, *palette_);
    if (contents.ok()) {
      if (contents->coord != r) {
        entry.error = make_error(ErrorCode::kCorrupt,
                                 fmt::format("region file {}: holds region ({}, {}, {})", path.string(),
                                             contents->coord.x, contents->coord.y, contents->coord.z));
      } else {
        entry.contents = std::make_shared<RegionContents>(std::move(*contents));
      }
    } else {
      entry.error = contents.error();
    }
    if (entry.error) log_warn("voxel: {} (its chunks will be regenerated)", entry.error->message);
  }
  return cache_.emplace(r, std::move(entry)).first->second;
}

Result<std::optional<Chunk>> RegionStore::load(const ChunkCoord& c) {
  const CacheEntry& e = region(region_of(c));
  if (e.error) return *e.error;
  if (!e.contents) return std::optional<Chunk>{};
  if (auto bad = e.contents->bad_chunks.find(c); bad != e.contents->bad_chunks.end()) return bad->second;
  auto it = e.contents->chunks.find(c);
  if (it == e.contents->chunks.end()) return std::optional<Chunk>{};
  return std::optional<Chunk>{it->second};
}

Status RegionStore::save(std::span<const std::pair<ChunkCoord, const Chunk*>> chunks) {
  std::map<RegionCoord, std::vector<std::pair<ChunkCoord, const Chunk*>>> by_region;
  for (const auto& entry : chunks) by_region[region_of(entry.first)].push_back(entry);
  for (auto& [r, updates] : by_region) {
    // Keep the region's other chunks (those that still read back).
    const CacheEntry& old = region(r);
    std::map<ChunkCoord, const Chunk*> merged;
    if (old.contents) {
      for (const auto& [cc, chunk] : old.contents->chunks) merged[cc] = &chunk;
    } else if (old.error) {
      log_warn("voxel: replacing unreadable region {}", path_of(r).string());
    }
    for (const auto& [cc, chunk] : updates) merged[cc] = chunk;
    std::vector<std::pair<ChunkCoord, const Chunk*>> list(merged.begin(), merged.end());
    const Status st = write_region_file(path_of(r), r, *palette_, list);
    if (!st.ok()) return st;
    // Re-read lazily: copies of the chunks must not dangle into the old cache entry.
    cache_.erase(r);
  }
  return ok_status();
}

}  // namespace sylva::voxel

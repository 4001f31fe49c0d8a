// The ground height section of chunk files and bake shares (chunk_file_heights.hpp).
#include "chunk_file_heights.hpp"

#include <sylva/core/hash.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <istream>
#include <ostream>

namespace sylva::terrain::detail {

static_assert(std::endian::native == std::endian::little, "height tiles are stored as little-endian float32");

HeightTiles::Rect HeightTiles::rect(std::uint32_t t) const {
  const std::uint32_t tx = t % tiles_x(), tz = t / tiles_x();
  Rect r;
  r.x0 = static_cast<int>(tx * tile);
  r.z0 = static_cast<int>(tz * tile);
  r.width = std::min(static_cast<int>(tile), columns - r.x0);
  r.height = std::min(static_cast<int>(tile), rows - r.z0);
  return r;
}

std::uint64_t HeightTiles::tile_offset(std::uint32_t t) const {
  const Rect r = rect(t);
  // Every tile row above holds `tile` full rows of the field; this row's tiles to the left hold
  // r.height rows of `tile` samples each.
  return table_bytes() + 4 * (std::uint64_t{static_cast<std::uint32_t>(r.z0)} * static_cast<std::uint32_t>(columns) +
                              std::uint64_t{static_cast<std::uint32_t>(r.x0)} * static_cast<std::uint32_t>(r.height));
}

std::string HeightTiles::describe(std::uint32_t t) const {
  const Rect r = rect(t);
  return fmt::format("height tile {} (samples x {}..{}, z {}..{})", t, r.x0, r.x0 + r.width - 1, r.z0,
                     r.z0 + r.height - 1);
}

Status write_height_section(std::ostream& out, const HeightTiles& layout, const HeightRowSource& rows,
                            const std::string& out_name) {
  if (layout.tile == 0) return ok_status();
  const std::streamoff start = out.tellp();
  std::vector<std::uint64_t> table(layout.count() + 1, 0);
  out.write(reinterpret_cast<const char*>(table.data()), static_cast<std::streamsize>(table.size() * 8));
  std::vector<float> samples;
  for (std::uint32_t t = 0; t < layout.count(); ++t) {
    const HeightTiles::Rect r = layout.rect(t);
    samples.resize(static_cast<std::size_t>(r.width) * static_cast<std::size_t>(r.height));
    for (int z = 0; z < r.height; ++z) {
      SYLVA_TRY(rows(r.z0 + z, r.x0, r.width, samples.data() + static_cast<std::size_t>(z) * static_cast<std::size_t>(r.width)));
    }
    const std::size_t bytes = samples.size() * sizeof(float);
    table[t] = fnv1a64(samples.data(), bytes);
    out.write(reinterpret_cast<const char*>(samples.data()), static_cast<std::streamsize>(bytes));
  }
  table.back() = fnv1a64(table.data(), std::size_t{layout.count()} * 8);
  const std::streamoff end = out.tellp();
  out.seekp(start);
  out.write(reinterpret_cast<const char*>(table.data()), static_cast<std::streamsize>(table.size() * 8));
  out.seekp(end);
  if (!out) return make_error(ErrorCode::kIo, fmt::format("{}: writing the ground heights failed (disk full?)", out_name));
  return ok_status();
}

Result<std::vector<std::uint64_t>> read_height_table(std::istream& in, std::uint64_t at, const HeightTiles& layout,
                                                     const std::string& file) {
  std::vector<std::uint64_t> table(layout.count() + 1, 0);
  in.clear();
  in.seekg(static_cast<std::streamoff>(at));
  in.read(reinterpret_cast<char*>(table.data()), static_cast<std::streamsize>(table.size() * 8));
  if (!in) return make_error(ErrorCode::kCorrupt, fmt::format("{}: cannot read the height tile table", file));
  if (table.back() != fnv1a64(table.data(), std::size_t{layout.count()} * 8)) {
    return make_error(ErrorCode::kCorrupt, fmt::format("{}: height tile table checksum mismatch", file));
  }
  table.pop_back();
  return table;
}

Status read_height_tile_bytes(std::istream& in, std::uint64_t at, const HeightTiles& layout, std::uint32_t t,
                              const std::string& file, std::vector<float>& out) {
  const HeightTiles::Rect r = layout.rect(t);
  out.resize(static_cast<std::size_t>(r.width) * static_cast<std::size_t>(r.height));
  in.clear();
  in.seekg(static_cast<std::streamoff>(at + layout.tile_offset(t)));
  in.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(out.size() * sizeof(float)));
  if (!in) {
    return make_error(ErrorCode::kCorrupt, fmt::format("{}: {}: cannot read it (file changed or truncated)", file,
                                                       layout.describe(t)));
  }
  return ok_status();
}

Status verify_height_tile(const HeightTiles& layout, const std::vector<std::uint64_t>& table, std::uint32_t t,
                          const std::string& file, const std::vector<float>& samples) {
  if (fnv1a64(samples.data(), samples.size() * sizeof(float)) != table[t]) {
    return make_error(ErrorCode::kCorrupt, fmt::format("{}: {}: checksum mismatch", file, layout.describe(t)));
  }
  return ok_status();
}

Status read_height_tile(std::istream& in, std::uint64_t at, const HeightTiles& layout,
                        const std::vector<std::uint64_t>& table, std::uint32_t t, const std::string& file,
                        std::vector<float>& out) {
  SYLVA_TRY(read_height_tile_bytes(in, at, layout, t, file, out));
  return verify_height_tile(layout, table, t, file, out);
}

Status HeightTileRows::operator()(int z, int x0, int width, float* out) {
  const std::uint32_t t = static_cast<std::uint32_t>(z) / layout_.tile * layout_.tiles_x() +
                          static_cast<std::uint32_t>(x0) / layout_.tile;
  if (loaded_ != static_cast<std::int64_t>(t)) {
    SYLVA_TRY(read_height_tile(in_, at_, layout_, table_, t, file_, tile_));
    loaded_ = t;
  }
  const HeightTiles::Rect r = layout_.rect(t);
  std::memcpy(out, tile_.data() + static_cast<std::size_t>(z - r.z0) * static_cast<std::size_t>(r.width) + (x0 - r.x0),
              static_cast<std::size_t>(width) * sizeof(float));
  return ok_status();
}

}  // namespace sylva::terrain::detail

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

int stride_for(int columns, int rows, std::uint64_t max_samples) {
  auto samples = [&](int s) {
    return std::uint64_t{static_cast<std::uint32_t>((columns - 1) / s + 1)} * static_cast<std::uint32_t>((rows - 1) / s + 1);
  };
  int stride = 1;
  while (samples(stride) > std::max<std::uint64_t>(max_samples, 1) && stride < (1 << 20)) stride *= 2;
  return stride;
}

HeightTiles::Grid HeightTiles::field_grid() const {
  Grid g;
  g.columns = columns;
  g.rows = rows;
  if (tile == 0) return g;
  g.tiles_x = (static_cast<std::uint32_t>(columns) + tile - 1) / tile;
  g.tiles_z = (static_cast<std::uint32_t>(rows) + tile - 1) / tile;
  return g;
}

HeightTiles::Grid HeightTiles::overview_grid() const {
  Grid g;
  if (tile == 0 || overview == 0) return g;
  const Grid field = field_grid();
  g.stride = static_cast<int>(overview);
  g.columns = (columns - 1) / g.stride + 1;
  g.rows = (rows - 1) / g.stride + 1;
  g.first = field.tiles_x * field.tiles_z;
  g.tiles_x = (static_cast<std::uint32_t>(g.columns) + tile - 1) / tile;
  g.tiles_z = (static_cast<std::uint32_t>(g.rows) + tile - 1) / tile;
  g.offset = std::uint64_t{static_cast<std::uint32_t>(columns)} * static_cast<std::uint32_t>(rows) * 4;
  return g;
}

std::uint64_t HeightTiles::section_bytes() const {
  if (tile == 0) return 0;
  const Grid o = overview_grid();
  return table_bytes() + std::uint64_t{static_cast<std::uint32_t>(columns)} * static_cast<std::uint32_t>(rows) * 4 +
         std::uint64_t{static_cast<std::uint32_t>(o.columns)} * static_cast<std::uint32_t>(o.rows) * 4;
}

HeightTiles::Rect HeightTiles::rect(std::uint32_t t) const {
  const Grid g = grid_of(t);
  const std::uint32_t local = t - g.first, tx = local % g.tiles_x, tz = local / g.tiles_x;
  Rect r;
  r.x0 = static_cast<int>(tx * tile);
  r.z0 = static_cast<int>(tz * tile);
  r.width = std::min(static_cast<int>(tile), g.columns - r.x0);
  r.height = std::min(static_cast<int>(tile), g.rows - r.z0);
  return r;
}

std::uint64_t HeightTiles::tile_offset(std::uint32_t t) const {
  const Grid g = grid_of(t);
  const Rect r = rect(t);
  // Every tile row above holds `tile` full rows of the grid; this row's tiles to the left hold
  // r.height rows of `tile` samples each.
  return table_bytes() + g.offset +
         4 * (std::uint64_t{static_cast<std::uint32_t>(r.z0)} * static_cast<std::uint32_t>(g.columns) +
              std::uint64_t{static_cast<std::uint32_t>(r.x0)} * static_cast<std::uint32_t>(r.height));
}

std::string HeightTiles::describe(std::uint32_t t) const {
  const Grid g = grid_of(t);
  const Rect r = rect(t);
  const int s = g.stride;
  if (s == 1) {
    return fmt::format("height tile {} (samples x {}..{}, z {}..{})", t, r.x0, r.x0 + r.width - 1, r.z0,
                       r.z0 + r.height - 1);
  }
  return fmt::format("overview tile {} (every {}{} sample; samples x {}..{}, z {}..{})", t, s, s == 2 ? "nd" : "th", r.x0 * s,
                     (r.x0 + r.width - 1) * s, r.z0 * s, (r.z0 + r.height - 1) * s);
}

void copy_strided(const std::vector<float>& tile, const HeightTiles::Rect& r, int sub, float* out, int out_columns,
                  int out_rows) {
  const int fx = (r.x0 + sub - 1) / sub * sub, fz = (r.z0 + sub - 1) / sub * sub;
  for (int z = fz; z < r.z0 + r.height && z / sub < out_rows; z += sub) {
    for (int x = fx; x < r.x0 + r.width && x / sub < out_columns; x += sub) {
      out[static_cast<std::size_t>(z / sub) * static_cast<std::size_t>(out_columns) + static_cast<std::size_t>(x / sub)] =
          tile[static_cast<std::size_t>(z - r.z0) * static_cast<std::size_t>(r.width) + static_cast<std::size_t>(x - r.x0)];
    }
  }
}

Status write_height_section(std::ostream& out, const HeightTiles& layout, const HeightRowSource& rows,
                            const std::string& out_name) {
  if (layout.tile == 0) return ok_status();
  const std::streamoff start = out.tellp();
  std::vector<std::uint64_t> table(layout.count() + 1, 0);
  out.write(reinterpret_cast<const char*>(table.data()), static_cast<std::streamsize>(table.size() * 8));
  std::vector<float> samples;
  const HeightTiles::Grid overview = layout.overview_grid();
  std::vector<float> coarse(static_cast<std::size_t>(overview.columns) * static_cast<std::size_t>(overview.rows));
  for (std::uint32_t t = 0; t < layout.count(); ++t) {
    const HeightTiles::Rect r = layout.rect(t);
    samples.resize(static_cast<std::size_t>(r.width) * static_cast<std::size_t>(r.height));
    if (t < layout.field_count()) {
      for (int z = 0; z < r.height; ++z) {
        SYLVA_TRY(rows(r.z0 + z, r.x0, r.width, samples.data() + static_cast<std::size_t>(z) * static_cast<std::size_t>(r.width)));
      }
      if (!coarse.empty()) copy_strided(samples, r, overview.stride, coarse.data(), overview.columns, overview.rows);
    } else {
      for (int z = 0; z < r.height; ++z) {
        std::memcpy(samples.data() + static_cast<std::size_t>(z) * static_cast<std::size_t>(r.width),
                    coarse.data() + static_cast<std::size_t>(r.z0 + z) * static_cast<std::size_t>(overview.columns) +
                        static_cast<std::size_t>(r.x0),
                    static_cast<std::size_t>(r.width) * sizeof(float));
      }
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
  const std::uint32_t t = static_cast<std::uint32_t>(z) / layout_.tile * layout_.field_grid().tiles_x +
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

// The edit layer of a baked terrain (edit_layer.hpp).
#include <sylva/terrain/edit_layer.hpp>

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/hash.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

namespace sylva::terrain {
namespace {

constexpr char kMagic[8] = {'S', 'Y', 'L', 'V', 'A', 'E', 'D', 'T'};
constexpr std::size_t kHeaderBytes = 40;
constexpr std::size_t kTileHeaderBytes = 24;

int tiles_per_side(int samples) { return (samples + kEditLayerTile - 1) / kEditLayerTile; }

// The samples a tile covers: x0, z0, width, height.
struct TileRect {
  int x0 = 0, z0 = 0, w = 0, h = 0;
};
TileRect tile_rect(std::uint32_t index, int columns, int rows) {
  const int per_row = tiles_per_side(columns);
  TileRect r;
  r.x0 = static_cast<int>(index % static_cast<std::uint32_t>(per_row)) * kEditLayerTile;
  r.z0 = static_cast<int>(index / static_cast<std::uint32_t>(per_row)) * kEditLayerTile;
  r.w = std::min(kEditLayerTile, columns - r.x0);
  r.h = std::min(kEditLayerTile, rows - r.z0);
  return r;
}

std::vector<float> tile_samples(const std::vector<float>& field, int columns, const TileRect& r) {
  std::vector<float> out(static_cast<std::size_t>(r.w) * static_cast<std::size_t>(r.h));
  for (int z = 0; z < r.h; ++z) {
    const float* row = field.data() + static_cast<std::size_t>(r.z0 + z) * static_cast<std::size_t>(columns) + r.x0;
    std::copy(row, row + r.w, out.begin() + static_cast<std::ptrdiff_t>(z) * r.w);
  }
  return out;
}

std::uint64_t checksum_of(const std::vector<float>& v) { return fnv1a64(v.data(), v.size() * sizeof(float)); }

std::uint64_t tile_checksum(std::uint32_t index, const std::vector<float>& heights) {
  return fnv1a64(heights.data(), heights.size() * sizeof(float), fnv1a64(&index, sizeof(index)));
}

template <class T>
void put(std::string& out, T v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}
template <class T>
T get(const std::string& in, std::size_t at) {
  T v;
  std::memcpy(&v, in.data() + at, sizeof(T));
  return v;
}

std::string tile_name(std::uint32_t index, int columns) {
  const int per_row = tiles_per_side(std::max(columns, 1));
  return fmt::format("tile ({}, {})", index % static_cast<std::uint32_t>(per_row),
                     index / static_cast<std::uint32_t>(per_row));
}

}  // namespace

EditLayer diff_edit_layer(const std::vector<float>& baked, const std::vector<float>& painted, int columns, int rows) {
  EditLayer layer;
  layer.columns = columns;
  layer.rows = rows;
  const std::uint32_t count = static_cast<std::uint32_t>(tiles_per_side(columns) * tiles_per_side(rows));
  for (std::uint32_t t = 0; t < count; ++t) {
    const TileRect r = tile_rect(t, columns, rows);
    std::vector<float> before = tile_samples(baked, columns, r);
    std::vector<float> after = tile_samples(painted, columns, r);
    if (std::memcmp(before.data(), after.data(), before.size() * sizeof(float)) == 0) continue;
    layer.tiles.push_back(EditLayerTile{t, checksum_of(before), std::move(after)});
  }
  return layer;
}

Status apply_edit_layer(const EditLayer& layer, std::vector<float>& samples, int columns, int rows,
                        const std::filesystem::path& file) {
  if (layer.columns != columns || layer.rows != rows) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: the edits are for a {}x{} field, the baked terrain has {}x{} samples",
                                  file.string(), layer.columns, layer.rows, columns, rows));
  }
  for (const EditLayerTile& tile : layer.tiles) {
    const TileRect r = tile_rect(tile.index, columns, rows);
    if (checksum_of(tile_samples(samples, columns, r)) != tile.baked_checksum) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: {}: the baked heights under it are not the ones it was painted over (was "
                                    "the chunk file re-baked?)",
                                    file.string(), tile_name(tile.index, columns)));
    }
  }
  for (const EditLayerTile& tile : layer.tiles) {
    const TileRect r = tile_rect(tile.index, columns, rows);
    for (int z = 0; z < r.h; ++z) {
      const float* src = tile.heights.data() + static_cast<std::size_t>(z) * static_cast<std::size_t>(r.w);
      std::copy(src, src + r.w,
                samples.begin() + static_cast<std::ptrdiff_t>((r.z0 + z) * static_cast<std::size_t>(columns) + r.x0));
    }
  }
  return ok_status();
}

std::vector<SampleRect> changed_rects(const std::vector<float>& baked, const std::vector<float>& painted, int columns,
                                      int rows) {
  std::vector<SampleRect> rects;
  const std::uint32_t count = static_cast<std::uint32_t>(tiles_per_side(columns) * tiles_per_side(rows));
  for (std::uint32_t t = 0; t < count; ++t) {
    const TileRect r = tile_rect(t, columns, rows);
    SampleRect box{r.x0 + r.w, r.z0 + r.h, r.x0, r.z0};  // empty
    for (int z = r.z0; z < r.z0 + r.h; ++z) {
      for (int x = r.x0; x < r.x0 + r.w; ++x) {
        const std::size_t i = static_cast<std::size_t>(z) * static_cast<std::size_t>(columns) + static_cast<std::size_t>(x);
        if (std::memcmp(&baked[i], &painted[i], sizeof(float)) == 0) continue;
        box = {std::min(box.x0, x), std::min(box.z0, z), std::max(box.x1, x + 1), std::max(box.z1, z + 1)};
      }
    }
    if (box.x0 < box.x1) rects.push_back(box);
  }
  return rects;
}

std::string encode_edit_layer(const EditLayer& layer) {
  std::string out(kMagic, sizeof(kMagic));
  put(out, kEditLayerVersion);
  put(out, static_cast<std::uint32_t>(kEditLayerTile));
  put(out, static_cast<std::uint32_t>(layer.columns));
  put(out, static_cast<std::uint32_t>(layer.rows));
  put(out, static_cast<std::uint32_t>(layer.tiles.size()));
  put(out, std::uint32_t{0});
  put(out, fnv1a64(out.data(), out.size()));
  for (const EditLayerTile& tile : layer.tiles) {
    put(out, tile.index);
    put(out, std::uint32_t{0});
    put(out, tile.baked_checksum);
    put(out, tile_checksum(tile.index, tile.heights));
    out.append(reinterpret_cast<const char*>(tile.heights.data()), tile.heights.size() * sizeof(float));
  }
  return out;
}

Result<EditLayer> read_edit_layer(const std::filesystem::path& file) {
  auto bytes = read_file(file);
  if (!bytes.ok()) return bytes.error();
  const std::string& in = *bytes;
  const std::string name = file.string();
  auto corrupt = [&](const std::string& what) { return make_error(ErrorCode::kCorrupt, fmt::format("{}: {}", name, what)); };
  if (in.size() < kHeaderBytes || std::memcmp(in.data(), kMagic, sizeof(kMagic)) != 0) {
    return corrupt("not a Sylva edit layer (bad magic or shorter than its header)");
  }
  if (get<std::uint64_t>(in, 32) != fnv1a64(in.data(), 32)) return corrupt("header checksum mismatch");
  const auto version = get<std::uint32_t>(in, 8), tile = get<std::uint32_t>(in, 12);
  if (version != kEditLayerVersion || tile != static_cast<std::uint32_t>(kEditLayerTile)) {
    return make_error(ErrorCode::kUnsupported,
                      fmt::format("{}: edit layer version {} with {}^2 tiles; this program reads version {} with {}^2",
                                  name, version, tile, kEditLayerVersion, kEditLayerTile));
  }
  EditLayer layer;
  layer.columns = static_cast<int>(get<std::uint32_t>(in, 16));
  layer.rows = static_cast<int>(get<std::uint32_t>(in, 20));
  const std::uint32_t count = get<std::uint32_t>(in, 24);
  if (layer.columns < 1 || layer.rows < 1 || layer.columns > 65536 || layer.rows > 65536) {
    return corrupt(fmt::format("field size {}x{} out of range", layer.columns, layer.rows));
  }
  const std::uint64_t tiles = static_cast<std::uint64_t>(tiles_per_side(layer.columns)) * tiles_per_side(layer.rows);
  if (count > tiles) return corrupt(fmt::format("{} tiles for a field of {}", count, tiles));
  std::size_t at = kHeaderBytes;
  for (std::uint32_t k = 0; k < count; ++k) {
    if (in.size() - at < kTileHeaderBytes) return corrupt(fmt::format("truncated at tile {} of {}", k + 1, count));
    EditLayerTile t;
    t.index = get<std::uint32_t>(in, at);
    if (t.index >= tiles || (!layer.tiles.empty() && t.index <= layer.tiles.back().index)) {
      return corrupt(fmt::format("tile {} of {}: index {} out of order or range", k + 1, count, t.index));
    }
    t.baked_checksum = get<std::uint64_t>(in, at + 8);
    const std::uint64_t checksum = get<std::uint64_t>(in, at + 16);
    const TileRect r = tile_rect(t.index, layer.columns, layer.rows);
    const std::size_t n = static_cast<std::size_t>(r.w) * static_cast<std::size_t>(r.h);
    at += kTileHeaderBytes;
    if (in.size() - at < n * sizeof(float)) return corrupt(fmt::format("{}: truncated", tile_name(t.index, layer.columns)));
    t.heights.resize(n);
    std::memcpy(t.heights.data(), in.data() + at, n * sizeof(float));
    at += n * sizeof(float);
    if (tile_checksum(t.index, t.heights) != checksum) {
      return corrupt(fmt::format("{}: checksum mismatch (the file is damaged)", tile_name(t.index, layer.columns)));
    }
    layer.tiles.push_back(std::move(t));
  }
  if (at != in.size()) return corrupt(fmt::format("{} bytes after the last tile", in.size() - at));
  return layer;
}

}  // namespace sylva::terrain

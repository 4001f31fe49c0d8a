// The exact field of a baked terrain painted through its every-n-th-sample ground
// (decimated_ground_edits.hpp).
#include <sylva/terrain/chunk_file.hpp>
#include <sylva/terrain/decimated_ground_edits.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace sylva::terrain {

Result<std::unique_ptr<DecimatedGroundEdits>> DecimatedGroundEdits::open(const ChunkFile& file, int stride) {
  if (stride < 2) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: a ground of every {}th sample is the field itself", file.path().string(), stride));
  }
  auto field = file.read_heights(1);
  if (!field.ok()) return field.error();
  return std::unique_ptr<DecimatedGroundEdits>(new DecimatedGroundEdits(std::move(*field), stride));
}

DecimatedGroundEdits::DecimatedGroundEdits(HeightField baked, int stride) : painted_(std::move(baked)), stride_(stride) {}

std::uint32_t DecimatedGroundEdits::tile_of(int x, int z) const {
  const int per_row = (painted_.columns() + kEditLayerTile - 1) / kEditLayerTile;
  return static_cast<std::uint32_t>((z / kEditLayerTile) * per_row + x / kEditLayerTile);
}

float DecimatedGroundEdits::baked(int x, int z) const {
  const auto tile = baked_tiles_.find(tile_of(x, z));
  if (tile == baked_tiles_.end()) return painted_.sample(x, z);  // never written: still the file's
  const int tx = x / kEditLayerTile * kEditLayerTile, tz = z / kEditLayerTile * kEditLayerTile;
  const int width = std::min(kEditLayerTile, painted_.columns() - tx);
  return tile->second[static_cast<std::size_t>(z - tz) * width + static_cast<std::size_t>(x - tx)];
}

void DecimatedGroundEdits::keep_baked_tiles(const SampleRect& r) {
  for (int tz = r.z0 / kEditLayerTile * kEditLayerTile; tz < r.z1; tz += kEditLayerTile) {
    for (int tx = r.x0 / kEditLayerTile * kEditLayerTile; tx < r.x1; tx += kEditLayerTile) {
      auto [tile, added] = baked_tiles_.try_emplace(tile_of(tx, tz));
      if (!added) continue;
      const int width = std::min(kEditLayerTile, painted_.columns() - tx);
      const int height = std::min(kEditLayerTile, painted_.rows() - tz);
      tile->second.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
      for (int z = 0; z < height; ++z)
        for (int x = 0; x < width; ++x)
          tile->second[static_cast<std::size_t>(z) * width + static_cast<std::size_t>(x)] = painted_.sample(tx + x, tz + z);
    }
  }
}

std::size_t DecimatedGroundEdits::bytes() const {
  std::size_t n = painted_.samples().size();
  for (const auto& [index, tile] : baked_tiles_) n += tile.size();
  return n * sizeof(float);
}

std::vector<float> DecimatedGroundEdits::baked_ground() const {
  const int gc = ground_columns(), gr = ground_rows();
  std::vector<float> out(static_cast<std::size_t>(gc) * static_cast<std::size_t>(gr));
  for (int j = 0; j < gr; ++j)
    for (int i = 0; i < gc; ++i) out[static_cast<std::size_t>(j) * gc + i] = baked(i * stride_, j * stride_);
  return out;
}

Result<SampleRect> DecimatedGroundEdits::apply(const std::vector<float>& ground, SampleRect rect) {
  const int gc = ground_columns(), gr = ground_rows(), fc = painted_.columns(), fr = painted_.rows();
  if (ground.size() != static_cast<std::size_t>(gc) * static_cast<std::size_t>(gr)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("terrain: the painted ground has {} samples, every {}th sample of the baked {}x{} "
                                  "field is {}x{}: it cannot be painted",
                                  ground.size(), stride_, fc, fr, gc, gr));
  }
  rect = {std::max(rect.x0, 0), std::max(rect.z0, 0), std::min(rect.x1, gc), std::min(rect.z1, gr)};
  if (rect.x0 >= rect.x1 || rect.z0 >= rect.z1) return SampleRect{};
  for (int j = rect.z0; j < rect.z1; ++j) {
    for (int i = rect.x0; i < rect.x1; ++i) {
      if (!std::isfinite(ground[static_cast<std::size_t>(j) * gc + i])) {
        return make_error(ErrorCode::kInvalidArgument,
                          fmt::format("terrain: the painted ground has a NaN/Inf sample at column {} row {}", i, j));
      }
    }
  }
  const int s = stride_;
  const auto node = [&](int i, int j) { return ground[static_cast<std::size_t>(j) * gc + static_cast<std::size_t>(i)]; };
  const auto unpainted = [&](int i, int j) {
    return std::bit_cast<std::uint32_t>(node(i, j)) == std::bit_cast<std::uint32_t>(baked(i * s, j * s));
  };
  const auto delta = [&](int i, int j) { return static_cast<double>(node(i, j)) - baked(i * s, j * s); };
  // A ground sample reaches the exact samples of the cells around it; the last ground row and
  // column also reach the samples beyond them (a field whose size is not a multiple of the stride).
  const SampleRect out{std::max((rect.x0 - 1) * s + 1, 0), std::max((rect.z0 - 1) * s + 1, 0),
                       rect.x1 >= gc ? fc : std::min(rect.x1 * s, fc), rect.z1 >= gr ? fr : std::min(rect.z1 * s, fr)};
  keep_baked_tiles(out);  // before the first write: the file's samples of the tiles it touches
  for (int z = out.z0; z < out.z1; ++z) {
    const int j0 = std::min(z / s, gr - 1), j1 = std::min(j0 + 1, gr - 1);
    const double fz = static_cast<double>(z - j0 * s) / s;
    for (int x = out.x0; x < out.x1; ++x) {
      const int i0 = std::min(x / s, gc - 1), i1 = std::min(i0 + 1, gc - 1);
      float& h = painted_.sample(x, z);
      if (unpainted(i0, j0) && unpainted(i1, j0) && unpainted(i0, j1) && unpainted(i1, j1)) {
        h = baked(x, z);
      } else if (x == i0 * s && z == j0 * s) {
        h = node(i0, j0);
      } else {
        const double fx = static_cast<double>(x - i0 * s) / s;
        const double d = (1.0 - fz) * ((1.0 - fx) * delta(i0, j0) + fx * delta(i1, j0)) +
                         fz * ((1.0 - fx) * delta(i0, j1) + fx * delta(i1, j1));
        h = static_cast<float>(baked(x, z) + d);
      }
    }
  }
  // No update_range: a whole-field pass per stroke; the edit path reads samples, not the range.
  return out;
}

}  // namespace sylva::terrain

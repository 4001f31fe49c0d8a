#pragma once
// Splicing freshly generated tiles into a tiled set (issue 16's tile-local regeneration): the
// blades of regenerate_tiles and the far field's clumps both keep generate_*'s order (z, then x)
// so that a spliced set equals a full regeneration bit for bit.
#include <sylva/grass/generator.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace sylva::grass::detail {

template <class T>
struct MergedTiles {
  std::vector<T> items;
  std::vector<GrassTile> tiles;  // `first` indexes items
  std::uint32_t first_changed = 0;  // items before it are the old set's (at the same index)
};

// The old set's tiles outside `range`, and the fresh ones (every tile of `range` that holds any
// item), in (z, x) order. Tile `first`s of the old set index old_items, those of the fresh set
// fresh_items.
template <class T>
MergedTiles<T> merge_tiles(std::span<const T> old_items, std::span<const GrassTile> old_tiles, std::span<const T> fresh_items,
                           std::span<const GrassTile> fresh_tiles, const TileRange& range) {
  const auto before = [](const TileKey& a, const TileKey& b) { return a.z != b.z ? a.z < b.z : a.x < b.x; };
  const auto inside = [&range](const TileKey& k) { return k.x >= range.x0 && k.x < range.x1 && k.z >= range.z0 && k.z < range.z1; };
  const TileKey first_key{static_cast<std::int32_t>(range.x0), 0, static_cast<std::int32_t>(range.z0)};
  const auto unchanged = static_cast<std::uint32_t>(old_items.size());
  MergedTiles<T> out;
  out.first_changed = unchanged;
  out.items.reserve(old_items.size() + fresh_items.size());
  out.tiles.reserve(old_tiles.size() + fresh_tiles.size());
  std::size_t i = 0, j = 0;
  while (i < old_tiles.size() || j < fresh_tiles.size()) {
    if (i < old_tiles.size() && inside(old_tiles[i].key)) {
      ++i;
      continue;
    }
    const bool take_old = j == fresh_tiles.size() || (i < old_tiles.size() && before(old_tiles[i].key, fresh_tiles[j].key));
    GrassTile t = take_old ? old_tiles[i++] : fresh_tiles[j++];
    const T* src = (take_old ? old_items.data() : fresh_items.data()) + t.first;
    if (out.first_changed == unchanged && !before(t.key, first_key)) out.first_changed = static_cast<std::uint32_t>(out.items.size());
    t.first = static_cast<std::uint32_t>(out.items.size());
    out.items.insert(out.items.end(), src, src + t.count);
    out.tiles.push_back(t);
  }
  return out;
}

}  // namespace sylva::grass::detail

#pragma once
// The edit layer of a baked terrain (issue 15, "painting a streamed terrain: strokes go into a
// sparse edit layer of tiles saved next to the scene"): the painted ground heights of the 256^2
// tiles where the painted field differs from the heights baked into the chunk file.
//
// Absolute heights, not deltas over the baked ones: a delta added back in float is not always
// the painted float (a + (b - a) != b in general), while the brush, undo and the bake all work
// on absolute samples, so absolute tiles give the painted field back bit for bit. Each tile also
// records the FNV-1a 64 of the baked heights it was painted over, so a chunk file re-baked from
// another source is noticed instead of silently mixing two fields.
//
// File (little endian, one file per scene, written atomically by the scene's save):
//   header 40 bytes: magic "SYLVAEDT", version u32 (kEditLayerVersion), tile size u32 (256),
//                    field columns u32, rows u32, tile count u32, reserved u32 (0),
//                    FNV-1a 64 of the 32 bytes before it;
//   per tile, ascending index (tile row * tiles per row + tile column):
//                    index u32, reserved u32 (0), baked checksum u64, checksum u64 (FNV-1a 64 of
//                    the index and the heights), heights f32 (the tile's width x height samples,
//                    row by row; edge tiles are clipped to the field).

#include <sylva/core/result.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace sylva::terrain {

inline constexpr std::uint32_t kEditLayerVersion = 1;
inline constexpr int kEditLayerTile = 256;  // samples per tile side (the chunk file's height tiles)

// Field samples [x0, x1) x [z0, z1) (columns, rows; x1/z1 exclusive).
struct SampleRect {
  int x0 = 0, z0 = 0, x1 = 0, z1 = 0;
};

struct EditLayerTile {
  std::uint32_t index = 0;            // tile row * tiles per row + tile column
  std::uint64_t baked_checksum = 0;   // FNV-1a 64 of the baked heights under the tile
  std::vector<float> heights;         // painted heights [m], the tile's samples row by row
};

struct EditLayer {
  int columns = 0, rows = 0;          // the field's samples
  std::vector<EditLayerTile> tiles;   // ascending index; empty = nothing painted
};

// The tiles where `painted` differs from `baked` in any bit (both columns x rows samples, row by
// row). Painting then undoing everything gives an empty layer.
EditLayer diff_edit_layer(const std::vector<float>& baked, const std::vector<float>& painted, int columns, int rows);

// Writes the layer over `samples` (the baked heights, columns x rows). Errors (nothing written
// then), naming `file` and the tile (column, row): another field size (kInvalidArgument), a tile
// whose baked heights are not the ones it was painted over (kInvalidArgument: the chunk file was
// re-baked), a tile out of range (kCorrupt).
Status apply_edit_layer(const EditLayer& layer, std::vector<float>& samples, int columns, int rows,
                        const std::filesystem::path& file);

// Per 256^2 tile, the bounding rectangle of the samples where `painted` differs from `baked` in
// any bit (what a streamed terrain rebuilds when it opens painted).
std::vector<SampleRect> changed_rects(const std::vector<float>& baked, const std::vector<float>& painted, int columns,
                                      int rows);

std::string encode_edit_layer(const EditLayer& layer);
// Errors name the file (and the tile): kNotFound, kIo, kCorrupt (bad magic, header checksum,
// truncation, tile checksum, tiles out of order or range, trailing bytes), kUnsupported (another
// version or tile size).
Result<EditLayer> read_edit_layer(const std::filesystem::path& file);

}  // namespace sylva::terrain

#pragma once
// The ground height section of chunk files (version 2) and bake shares (issue 15: "a baked file
// carries its ground"): the source field's samples, exact float32, in square tiles so a reader
// loads only the tiles it needs (a 16385^2 file holds 1 GiB of heights; opening it reads none).
//
// Layout, right after the 128-byte header of either file (so a one-process bake's share already
// holds it where the chunk file wants it, bake.hpp): a table of FNV-1a 64 checksums, one per tile
// (tiles row-major, x fastest), the FNV-1a 64 of that table, then the tiles, each its samples
// row-major as little-endian float32. Tiles are `tile` samples square except in the last tile
// column and row. The tile size is in the file's header (0 = no section).

#include <sylva/core/result.hpp>

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace sylva::terrain::detail {

inline constexpr std::uint32_t kHeightTileSamples = 256;  // 256 KiB per full tile

struct HeightTiles {
  int columns = 0, rows = 0;  // field samples
  std::uint32_t tile = 0;     // samples per tile side; 0 = no section

  struct Rect {
    int x0 = 0, z0 = 0, width = 0, height = 0;
  };
  std::uint32_t tiles_x() const { return tile == 0 ? 0u : (static_cast<std::uint32_t>(columns) + tile - 1) / tile; }
  std::uint32_t tiles_z() const { return tile == 0 ? 0u : (static_cast<std::uint32_t>(rows) + tile - 1) / tile; }
  std::uint32_t count() const { return tiles_x() * tiles_z(); }
  Rect rect(std::uint32_t t) const;
  std::uint64_t table_bytes() const { return tile == 0 ? 0 : std::uint64_t{count()} * 8 + 8; }
  // From the start of the section.
  std::uint64_t tile_offset(std::uint32_t t) const;
  std::uint64_t section_bytes() const {
    return tile == 0 ? 0 : table_bytes() + std::uint64_t{static_cast<std::uint32_t>(columns)} * static_cast<std::uint32_t>(rows) * 4;
  }
  // "height tile 3 (samples x 256..511, z 0..255)" for error messages.
  std::string describe(std::uint32_t t) const;
};

// Fills `out` (width floats) with the heights of row z, samples x0 .. x0 + width - 1; rows are
// asked for tile by tile (chunk_file.hpp, HeightRows). An error stops the writing.
using HeightRowSource = std::function<Status(int z, int x0, int width, float* out)>;

// Writes the section at the stream's put position (the table last, by seeking back) and leaves
// the position at its end. Errors: the row source's, kIo naming `out_name` (disk full).
Status write_height_section(std::ostream& out, const HeightTiles& layout, const HeightRowSource& rows,
                            const std::string& out_name);

// Reads and verifies the table of a section starting at `at`. Errors (kCorrupt) name `file`.
Result<std::vector<std::uint64_t>> read_height_table(std::istream& in, std::uint64_t at, const HeightTiles& layout,
                                                     const std::string& file);

// Reads tile `t` of the section at `at` into `out` (width x height floats) and verifies it
// against `table`. Errors (kCorrupt) name `file` and the tile.
Status read_height_tile(std::istream& in, std::uint64_t at, const HeightTiles& layout,
                        const std::vector<std::uint64_t>& table, std::uint32_t t, const std::string& file,
                        std::vector<float>& out);
// The two halves of read_height_tile, so a caller can read under its lock and verify outside it.
Status read_height_tile_bytes(std::istream& in, std::uint64_t at, const HeightTiles& layout, std::uint32_t t,
                              const std::string& file, std::vector<float>& out);
Status verify_height_tile(const HeightTiles& layout, const std::vector<std::uint64_t>& table, std::uint32_t t,
                          const std::string& file, const std::vector<float>& samples);

// Rows served from the verified tiles of a section (the merge copies a share's section through
// it): one tile in memory, each tile read once when rows are asked for tile by tile.
class HeightTileRows {
 public:
  HeightTileRows(std::istream& in, std::uint64_t at, HeightTiles layout, std::vector<std::uint64_t> table,
                 std::string file)
      : in_(in), at_(at), layout_(layout), table_(std::move(table)), file_(std::move(file)) {}
  Status operator()(int z, int x0, int width, float* out);

 private:
  std::istream& in_;
  std::uint64_t at_;
  HeightTiles layout_;
  std::vector<std::uint64_t> table_;
  std::string file_;
  std::int64_t loaded_ = -1;
  std::vector<float> tile_;
};

}  // namespace sylva::terrain::detail

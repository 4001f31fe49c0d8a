#pragma once
// The ground height section of chunk files (version 2) and bake shares (issue 15: "a baked file
// carries its ground"): the source field's samples, exact float32, in square tiles so a reader
// loads only the tiles it needs (a 16385^2 file holds 1 GiB of heights; opening it reads none).
//
// Layout, right after the 128-byte header of either file (so a one-process bake's share already
// holds it where the chunk file wants it, bake.hpp): a table of FNV-1a 64 checksums, one per tile,
// the FNV-1a 64 of that table, then the field's tiles, then (version 3) the overview's tiles.
// Tiles are row-major (x fastest), each its samples row-major as little-endian float32, `tile`
// samples square except in the last tile column and row of their grid. The overview is the
// field's samples at (x, z) = multiples of `overview` (its grid is (columns - 1) / overview + 1
// wide), so a reader wanting a coarse ground reads 1/overview^2 of the bytes. The header holds the
// tile size (uint16, 0 = no section) and the overview stride (uint16 after it, 0 = none: fields
// at most kHeightOverviewMaxSamples, and version-2 files, whose layout is otherwise the same).

#include <sylva/core/result.hpp>

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace sylva::terrain::detail {

inline constexpr std::uint32_t kHeightTileSamples = 256;  // 256 KiB per full tile

// The smallest power-of-two stride s whose grid of every s-th sample of a columns x rows field
// has at most max_samples samples (1 when the field itself fits).
int stride_for(int columns, int rows, std::uint64_t max_samples);

struct HeightTiles {
  int columns = 0, rows = 0;  // field samples
  std::uint32_t tile = 0;     // samples per tile side; 0 = no section
  std::uint32_t overview = 0; // the overview's stride (>= 2), 0 = no overview

  struct Rect {
    int x0 = 0, z0 = 0, width = 0, height = 0;  // in the samples of the tile's grid
  };
  // The grid a tile belongs to: the field's (stride 1, tiles [0, field_count())) or the overview's
  // (tiles [field_count(), count())).
  struct Grid {
    int columns = 0, rows = 0, stride = 1;
    std::uint32_t first = 0, tiles_x = 0, tiles_z = 0;
    std::uint64_t offset = 0;  // of its first tile, from the start of the section
  };
  Grid field_grid() const;
  Grid overview_grid() const;  // empty (no tiles) without an overview
  Grid grid_of(std::uint32_t t) const { return t < field_count() ? field_grid() : overview_grid(); }
  std::uint32_t field_count() const { return field_grid().tiles_x * field_grid().tiles_z; }
  std::uint32_t count() const { return field_count() + overview_grid().tiles_x * overview_grid().tiles_z; }
  Rect rect(std::uint32_t t) const;
  std::uint64_t table_bytes() const { return tile == 0 ? 0 : std::uint64_t{count()} * 8 + 8; }
  // From the start of the section.
  std::uint64_t tile_offset(std::uint32_t t) const;
  std::uint64_t section_bytes() const;
  // "height tile 3 (samples x 256..511, z 0..255)" or "overview tile 70 (every 4th sample;
  // samples x 1024..2044, z 0..1020)" for error messages.
  std::string describe(std::uint32_t t) const;
};

// Fills `out` (width floats) with the heights of row z, samples x0 .. x0 + width - 1; rows are
// asked for tile by tile (chunk_file.hpp, HeightRows). An error stops the writing.
using HeightRowSource = std::function<Status(int z, int x0, int width, float* out)>;

// Copies the samples of `tile` (the section's tile t, rect r of its grid) that lie on the grid of
// every `sub`-th sample into `out` (an out_columns x out_rows grid of every sub-th sample of the
// tile's grid), skipping samples beyond it.
void copy_strided(const std::vector<float>& tile, const HeightTiles::Rect& r, int sub, float* out, int out_columns,
                  int out_rows);

// Writes the section at the stream's put position (the table last, by seeking back) and leaves
// the position at its end. The overview's samples are kept while the field's tiles are written
// (4 bytes per overview sample, at most 64 MiB) and written after them. Errors: the row source's, kIo naming `out_name` (disk full).
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

// Rows of the field served from the verified tiles of a section (the merge copies a share's
// section through it; write_height_section makes the overview again): one tile in memory, each tile read once when rows are asked for tile by tile.
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

#pragma once
// Painting a baked terrain whose ground is every n-th sample (issue 15, "painting a streamed
// terrain works", fields above the scene's ground limit, e.g. 8193^2 or 16385^2): the scene's
// ground (grass, trees, camera clamp, the brush) is the file's heights every `stride`-th sample
// (scene/src/baked_ground.hpp), so a brush stroke edits those coarse samples; the chunks must be
// rebuilt from the field's exact samples. This class holds the exact field painted the same way:
//
//   exact(x, z) = baked(x, z)                    where the four ground samples around it are
//                                                 unpainted (bit-equal to the baked samples under them)
//               = ground(i, j)                    on a ground sample (x = i * stride, z = j * stride)
//               = baked(x, z) + bilinear(delta)   elsewhere, delta = ground - baked at the ground samples
//
// so the fine relief under a stroke is kept and raised with it, the painted exact field sampled at
// the stride IS the painted ground (the ground needs no update: grass and the camera stand on the
// same heights the chunks are built from), and each sample is a function of the baked heights and
// the ground alone: a stroke undone (the ground's old samples back) gives the baked samples back
// bit for bit, and reopening a scene from its saved ground (the edit layer of the coarse ground)
// gives the same exact field bit for bit.
//
// Cost: the exact heights are read from the chunk file's height tiles once, at the first stroke (or
// when a scene opens with painted tiles), never before: the painted field, 4 bytes per sample
// (256 MiB at 8193^2, 1 GiB at 16385^2), plus the baked samples of the 256^2 tiles strokes have
// written (256 KiB each); the streamer's edit grids add 8 bytes per root-grid point
// (stream_edits.hpp). Per stroke: the stroke's exact samples only.

#include <sylva/core/height_field.hpp>
#include <sylva/core/result.hpp>
#include <sylva/terrain/edit_layer.hpp>

#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

namespace sylva::terrain {

class ChunkFile;

class DecimatedGroundEdits {
 public:
  // Reads every height sample of `file` (its ground height section). `stride` >= 2: the ground's
  // step in field samples. Errors: the file's own (naming it and the tile), kInvalidArgument for a
  // stride below 2 or a file without heights.
  static Result<std::unique_ptr<DecimatedGroundEdits>> open(const ChunkFile& file, int stride);

  int stride() const { return stride_; }
  // The ground's samples per row and column: (field - 1) / stride + 1.
  int ground_columns() const { return (painted_.columns() - 1) / stride_ + 1; }
  int ground_rows() const { return (painted_.rows() - 1) / stride_ + 1; }

  // Brings the exact field up to `ground` (the painted ground, ground_columns() x ground_rows()
  // samples row by row) within the ground samples `rect` (x1/z1 exclusive, clamped). Returns the
  // exact samples rewritten (empty when `rect` is): what ChunkStreamer::apply_height_edit needs.
  // Errors (kInvalidArgument, the field unchanged): a ground of another size, a NaN/Inf ground
  // sample in `rect` (named by column and row).
  Result<SampleRect> apply(const std::vector<float>& ground, SampleRect rect);

  // The painted exact field (the file's size, spacing and origin; its min/max_height stay the
  // baked field's: recomputing them is a whole-field pass, and the edit path does not read them).
  const HeightField& field() const { return painted_; }
  // Bytes held: the painted field plus the baked tiles kept.
  std::size_t bytes() const;
  // The baked ground: the file's heights every stride-th sample (what the ground is unpainted).
  std::vector<float> baked_ground() const;

 private:
  DecimatedGroundEdits(HeightField baked, int stride);

  // Chunk file sample (x, z) as baked: kept per 256^2 tile the strokes have written, the painted
  // field elsewhere (never written there).
  float baked(int x, int z) const;
  std::uint32_t tile_of(int x, int z) const;
  void keep_baked_tiles(const SampleRect& samples);

  std::unordered_map<std::uint32_t, std::vector<float>> baked_tiles_;  // tile index -> its baked samples
  HeightField painted_;
  int stride_ = 2;
};

}  // namespace sylva::terrain

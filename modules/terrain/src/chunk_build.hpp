#pragma once
// The steps of ChunkTree::build, split so the out-of-core bake (bake.hpp) runs the very same code
// chunk by chunk and writes a file byte-identical to save_chunk_file(ChunkTree::build(...)):
//   prepare()      validation, tree layout, padded height grid, RTIN error grid, active rule;
//   build_chunk()  one chunk's mesh, measured error and height range (morph_error left 0: it needs
//                  every chunk's error bound, seed 002 §2.2 "a child halves the error");
//   finish()       monotone error bounds, level report, selection nodes of a tree whose chunks
//                  carry their metadata (the bake's merge fills it from the shares' directories).
// A chunk reads only the grids (heights of its square for the measurement, errors and heights
// along the RTIN descent for its vertices and morph targets), never another chunk, which is why
// chunks can be built in any order, on any thread or in another process.

#include "rtin.hpp"

#include <sylva/terrain/chunk_tree.hpp>

#include <memory>

namespace sylva::terrain {

namespace detail {
// What chunk meshes are computed from. Held by unique_ptr: `rule` points into `errors`.
struct TreeGrids {
  ChunkTree tree;                      // layout: geometry, settings, chunk slots; no meshes
  HeightGrid heights;                  // (N+1)^2 padded heights [m]
  ErrorGrid errors;                    // RTIN vertex errors [m]
  ActiveRule rule;                     // per-level vertex sets
  std::vector<std::uint32_t> present;  // present chunk slots, ascending
};
}  // namespace detail

class ChunkTreeBuilder {
 public:
  static Result<ChunkTree> build(const HeightField& field, const ChunkTreeSettings& settings,
                                 const BuildControl& control);
  // Errors as ChunkTree::build (invalid settings or field, kLimit, kCancelled). Consumes the
  // field: it is released once its samples are in the padded grid (moved there when the field is
  // exactly the root grid), before the error grid is allocated.
  static Result<std::unique_ptr<detail::TreeGrids>> prepare(HeightField&& field, const ChunkTreeSettings& settings,
                                                            const BuildControl& control);
  // The empty tree of a field of columns x rows samples: levels, chunk slots with keys and
  // presence (no metadata). Errors: invalid settings, kLimit (grid above max_build_bytes).
  static Result<ChunkTree> layout(int columns, int rows, double spacing, glm::dvec2 origin,
                                  const ChunkTreeSettings& settings);
  // Fills `chunk` (a copy of slot chunk.key's layout entry) with mesh, error and height range.
  // The mesh is kept (and vertex-cache ordered) per grids.tree.settings(); morph_error is 0.
  static void build_chunk(const detail::TreeGrids& grids, Chunk& chunk);
  // Error bounds, level report and nodes from the chunks' measured errors (meshes untouched).
  static void finish(ChunkTree& tree);
  static float morph_error(const ChunkTree& tree, const ChunkVertex& v) { return tree.morph_error_of(v); }
  static Chunk& chunk(ChunkTree& tree, std::uint32_t index) { return tree.chunks_[index]; }
};

}  // namespace sylva::terrain

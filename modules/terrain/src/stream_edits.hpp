#pragma once
// Height edits of a streamed (baked) terrain (issue 15, "painting a streamed terrain works: the
// chunks they reach are rebuilt from source + layer"). The chunk file stays as baked; this
// overlay holds what the edited field changes, and the ChunkStreamer consults it for every chunk
// it makes resident:
//  - rebuilt chunks: the chunks ChunkTree::rebuild_region would re-triangulate (square grown by
//    half a chunk meets the edit, at every level, up to the root), built from the edited field by
//    the bake's own code (ChunkTreeBuilder::prepare + build_chunk, chunk_build.hpp), so a rebuilt
//    chunk equals the chunk ChunkTree::build of the edited field gives, bit for bit, and its
//    same-level neighbours from the file share its edges exactly as in a bake;
//  - the tree's metadata (measured errors, monotone error bounds, height ranges, selection nodes)
//    recomputed from the rebuilt chunks' errors, so the certified error holds for the edited field;
//  - every other chunk read from the file gets its morph data recomputed on load (morph_target
//    from the edited field's coarser surface, morph_error from the new bounds) and its height
//    range refreshed: the in-memory path updates exactly these fields (rebuild_region "updated").
// Together a resident chunk always equals ChunkTree::build(edited field)'s chunk. Undo is a second
// edit back to the old heights, so its chunks equal the file's again.
// Cost per edit: the padded height and RTIN error grids of the whole field (as rebuild_region,
// O(samples)), the rebuilt chunks (each measured over its square: the root's square is the field),
// O(chunks) for bounds and nodes; memory: the grids (8 bytes per root-grid point) while edits
// exist. Only RTIN trees (the bake's default) can be edited.
//
// The overlay keeps no mesh (issue 15, "rebuilt chunk meshes count against the streaming
// budget"): an edit hands its rebuilt meshes to the streamer, which keeps the resident ones
// within terrain.stream.budget_mb like the file's and drops the others; a rebuilt chunk asked for
// again is built again by the loader thread from the published RebuildSource (the same grids and
// code: the same bytes), then patched like a file chunk.

#include "chunk_build.hpp"

#include <sylva/core/height_field.hpp>
#include <sylva/core/result.hpp>
#include <sylva/terrain/streaming.hpp>

#include <memory>
#include <unordered_map>
#include <vector>

namespace sylva::terrain::detail {

// What the chunks rebuilt by edits are made from, immutable once published (the loader thread
// builds an evicted rebuilt chunk again from it while the main thread paints on).
struct RebuildSource {
  std::shared_ptr<const TreeGrids> grids;  // of the edited field
  std::vector<std::uint8_t> rebuilt;       // per chunk slot: rebuilt by some edit so far
  std::uint64_t generation = 0;            // the edit it belongs to (1, 2, ...)

  bool is_rebuilt(std::uint32_t index) const { return index < rebuilt.size() && rebuilt[index] != 0; }
  // Chunk `index`'s mesh as the edit built it, before StreamEdits::resolve patches its morph data.
  ChunkMesh build(std::uint32_t index) const;
};

// Meshes rebuilt by one edit, final (patched), by chunk index.
using RebuiltMeshes = std::unordered_map<std::uint32_t, std::shared_ptr<const ChunkMesh>>;

class StreamEdits {
 public:
  // Starts from the file's tree metadata (copied).
  explicit StreamEdits(const ChunkTree& file_tree);

  // The samples in `rects` (x1/z1 exclusive) of `field` (the whole edited field, of the file's
  // size, spacing and origin) changed. Errors (kInvalidArgument): another grid, a non-RTIN tree,
  // NaN/Inf samples; the overlay is unchanged on error. `rebuilt`: the chunks re-triangulated;
  // `meshes` receives their meshes (the caller keeps what it holds resident, drops the rest).
  Result<RegionRebuild> apply(const HeightField& field, const std::vector<SampleRect>& rects, RebuiltMeshes& meshes);

  // The tree with the edited field's errors, bounds and (for resolved chunks) height ranges.
  const ChunkTree& tree() const { return tree_; }
  // Chunk `index` under the edits: `mesh` (the file's chunk, or for a rebuilt chunk the current
  // source()'s build of it) with its morph data recomputed. Updates the chunk's height range in
  // tree(); call refresh_nodes() after a batch.
  std::shared_ptr<const ChunkMesh> resolve(std::uint32_t index, std::shared_ptr<const ChunkMesh> mesh);
  bool rebuilt(std::uint32_t index) const { return source_ && source_->is_rebuilt(index); }
  std::size_t rebuilt_count() const { return rebuilt_count_; }
  // The latest edit's source (null before the first edit) and its generation (0 before).
  std::shared_ptr<const RebuildSource> source() const { return source_; }
  std::uint64_t generation() const { return source_ ? source_->generation : 0; }
  // Recomputes the selection nodes from the chunks' metadata (O(chunks)).
  void refresh_nodes();

 private:
  void patch(std::uint32_t index, ChunkMesh& mesh);

  ChunkTree tree_;                                // metadata only (no meshes)
  std::shared_ptr<const RebuildSource> source_;   // null before the first edit
  std::size_t rebuilt_count_ = 0;
};

}  // namespace sylva::terrain::detail

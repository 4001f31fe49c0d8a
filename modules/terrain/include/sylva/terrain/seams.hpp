#pragma once
// Seams between drawn chunks of different LOD (seed 002 §3.2-3.3, rebuilt so that any LOD
// difference is crack-free by construction).
//
// Why they are needed: a coarser chunk's edge holds a subset of the finer chunk's edge vertices
// (every level's vertex set contains the coarser level's), so the fine side has T-junctions: its
// extra vertices lie inside a coarse edge segment. Both sides compute every shared point
// bit-identically (vertex_position.hpp), so only these T-junctions can open gaps.
//
// The seam (built by the finer side, as in the seed): for each coarse edge segment [u, w] and the
// fine vertices u = f0, f1, ..., fm = w between, the fan of triangles (u, f(i+1), f(i)) for
// i = 1..m-1. It is a zero-width strip in x/z that exactly fills the vertical gap between the fine
// polyline and the coarse segment: its boundary is the fine polyline (reversed, cancelling the
// fine chunk's boundary edges) plus the coarse segment (cancelling the coarse chunk's), so the
// drawn surface has no boundary edge between chunks for any LOD difference, in any morph state.
// (The seed's one-cell-wide strip inset into the fine chunk needs interpolated vertices when
// 2^dLOD exceeds the chunk dimension; the fan does not.) A seam depends only on the fine chunk,
// the edge and the coarse chunk, so it is cached until that neighbour changes (seed §3.3).

#include <sylva/terrain/chunk_tree.hpp>
#include <sylva/terrain/selection.hpp>

#include <cstdint>
#include <functional>
#include <list>
#include <unordered_map>
#include <vector>

namespace sylva::terrain {

struct Seam {
  // Triangles. An index below the fine chunk's vertex_count refers to its vertices; index
  // vertex_count + k refers to extra_vertices[k].
  std::vector<std::uint32_t> indices;
  // Coarse vertices the fine chunk does not hold (the anchor of a segment starting before the
  // fine chunk's edge): at most one per seam.
  std::vector<ChunkVertex> extra_vertices;
};

// Where chunk meshes come from: the tree itself (built with keep_meshes) or a ChunkStreamer.
// Returns nullptr when the mesh is not available.
using MeshSource = std::function<const ChunkMesh*(std::uint32_t chunk)>;
// The tree's own meshes (asserts they were kept).
MeshSource tree_meshes(const ChunkTree& tree);

// Builds the seam of chunk `fine` along edge `e` towards the coarser chunk `coarse` (which must be
// the coarser chunk across that edge). Both meshes must be available from `meshes`.
Seam build_seam(const ChunkTree& tree, const MeshSource& meshes, std::uint32_t fine, Edge e, std::uint32_t coarse);
inline Seam build_seam(const ChunkTree& tree, std::uint32_t fine, Edge e, std::uint32_t coarse) {
  return build_seam(tree, tree_meshes(tree), fine, e, coarse);
}

// Seams keyed by (fine chunk, edge, coarse level), least recently used dropped first.
class SeamCache {
 public:
  explicit SeamCache(std::size_t capacity = 4096) : capacity_(capacity) {}
  const Seam& get(const ChunkTree& tree, const MeshSource& meshes, std::uint32_t fine, Edge e, std::uint32_t coarse);
  const Seam& get(const ChunkTree& tree, std::uint32_t fine, Edge e, std::uint32_t coarse) {
    return get(tree, tree_meshes(tree), fine, e, coarse);
  }
  // Drops the seams whose fine or coarse chunk is in `chunks` (after ChunkTree::rebuild_region
  // changed their meshes); returns how many were dropped.
  std::size_t invalidate(const std::vector<std::uint32_t>& chunks);
  void clear();
  std::size_t size() const { return map_.size(); }
  std::uint64_t builds() const { return builds_; }
  std::uint64_t hits() const { return hits_; }

 private:
  struct Entry {
    Seam seam;
    std::list<std::uint64_t>::iterator lru;
    std::uint32_t fine = 0, coarse = 0;  // chunk indices, for invalidate()
  };
  std::size_t capacity_;
  std::unordered_map<std::uint64_t, Entry> map_;
  std::list<std::uint64_t> lru_;
  std::uint64_t builds_ = 0, hits_ = 0;
};

}  // namespace sylva::terrain

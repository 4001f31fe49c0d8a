#pragma once
// CPU assembly of everything a selection draws (chunk bodies, seams or skirts) with the exact
// per-vertex positions of vertex_position.hpp. The GL renderer uploads the same pieces; tests
// and the error measurement use this directly (crack test, projected-error test).

#include <sylva/terrain/chunk_tree.hpp>
#include <sylva/terrain/seams.hpp>
#include <sylva/terrain/selection.hpp>
#include <sylva/terrain/vertex_position.hpp>

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace sylva::terrain {

enum class PieceKind : std::uint8_t { kBody = 0, kSeam = 1, kSkirt = 2 };

struct FrameMesh {
  std::vector<glm::vec3> positions;     // camera-relative, three per triangle
  std::vector<std::uint32_t> chunk;     // drawn chunk index of each triangle
  std::vector<PieceKind> kind;          // of each triangle
  std::uint64_t triangles() const { return chunk.size(); }
};

// Skirt depth below a chunk edge [m]: the chunk's own deviation plus the largest deviation of its
// neighbours across that edge (SelectedChunk::neighbour_error), so the skirt always spans the gap.
float skirt_depth(const ChunkTree& tree, const SelectedChunk& s, Edge e);

// crack_fix decides between seams and skirts. Every drawn chunk's mesh must be available from
// `meshes` (the tree's own when omitted).
FrameMesh assemble_frame(const ChunkTree& tree, const MeshSource& meshes, const Selection& selection,
                         const VertexFrame& frame, CrackFix crack_fix, SeamCache& seams);
inline FrameMesh assemble_frame(const ChunkTree& tree, const Selection& selection, const VertexFrame& frame,
                                CrackFix crack_fix, SeamCache& seams) {
  return assemble_frame(tree, tree_meshes(tree), selection, frame, crack_fix, seams);
}

}  // namespace sylva::terrain

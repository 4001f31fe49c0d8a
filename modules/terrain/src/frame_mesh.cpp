#include <sylva/terrain/frame_mesh.hpp>

#include <sylva/core/assert.hpp>

namespace sylva::terrain {

float skirt_depth(const ChunkTree& tree, const SelectedChunk& s, Edge e) {
  const Chunk& c = tree.chunk(s.index);
  const float own = c.key.level > 0 ? tree.chunk(tree.parent_index(s.index)).error_bound : c.error_bound;
  // A small floor so that a skirt on exactly flat ground still closes rounding gaps.
  const float floor = 0.01f * static_cast<float>(tree.spacing());
  return own + s.neighbour_error[static_cast<std::size_t>(e)] + floor;
}

FrameMesh assemble_frame(const ChunkTree& tree, const MeshSource& meshes, const Selection& selection,
                         const VertexFrame& frame, CrackFix crack_fix, SeamCache& seams) {
  FrameMesh out;
  std::vector<glm::vec3> pos;
  for (const SelectedChunk& s : selection.chunks) {
    const ChunkMesh* mp = meshes(s.index);
    SYLVA_ASSERT(mp != nullptr, "drawn chunk {} has no mesh loaded", s.index);
    struct View {
      const ChunkMesh& mesh;
      std::uint32_t vertex_count;
    } c{*mp, static_cast<std::uint32_t>(mp->vertices.size())};
    pos.resize(c.mesh.vertices.size());
    for (std::size_t i = 0; i < pos.size(); ++i) pos[i] = vertex_position(frame, c.mesh.vertices[i]);
    for (std::size_t i = 0; i < c.mesh.indices.size(); i += 3) {
      for (int k = 0; k < 3; ++k) out.positions.push_back(pos[c.mesh.indices[i + static_cast<std::size_t>(k)]]);
      out.chunk.push_back(s.index);
      out.kind.push_back(PieceKind::kBody);
    }
    for (int e = 0; e < 4; ++e) {
      const Edge edge = static_cast<Edge>(e);
      if (crack_fix == CrackFix::kSeams) {
        const std::uint32_t coarse = s.coarser_neighbour[static_cast<std::size_t>(e)];
        if (coarse == kNoChunk) continue;
        const Seam& seam = seams.get(tree, meshes, s.index, edge, coarse);
        for (std::size_t i = 0; i < seam.indices.size(); i += 3) {
          for (int k = 0; k < 3; ++k) {
            const std::uint32_t vi = seam.indices[i + static_cast<std::size_t>(k)];
            out.positions.push_back(vi < c.vertex_count ? pos[vi]
                                                        : vertex_position(frame, seam.extra_vertices[vi - c.vertex_count]));
          }
          out.chunk.push_back(s.index);
          out.kind.push_back(PieceKind::kSeam);
        }
      } else if (crack_fix == CrackFix::kSkirts) {
        const float depth = skirt_depth(tree, s, edge);
        const std::vector<std::uint32_t>& ev = c.mesh.edges[static_cast<std::size_t>(e)];
        const bool increasing = (edge == kWest || edge == kNorth);
        for (std::size_t i = 0; i + 1 < ev.size(); ++i) {
          // Walk in boundary direction so the skirt faces outwards.
          const std::uint32_t a = increasing ? ev[i] : ev[ev.size() - 1 - i];
          const std::uint32_t b = increasing ? ev[i + 1] : ev[ev.size() - 2 - i];
          const glm::vec3 pa = pos[a], pb = pos[b];
          const glm::vec3 qa = pa - glm::vec3(0, depth, 0), qb = pb - glm::vec3(0, depth, 0);
          const glm::vec3 tris[6] = {pb, pa, qa, pb, qa, qb};
          for (const glm::vec3& p : tris) out.positions.push_back(p);
          for (int k = 0; k < 2; ++k) {
            out.chunk.push_back(s.index);
            out.kind.push_back(PieceKind::kSkirt);
          }
        }
      }
    }
  }
  return out;
}

}  // namespace sylva::terrain

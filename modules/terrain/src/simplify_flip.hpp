#pragma once
// Bounded edge-flip repair after the pass-wise QEM's collapses (issue 18, README "vs
// meshoptimizer 1.2"). A half-edge collapse places every reduced vertex well (its quadric is
// small there), but the quadrics see vertices, not the inside of triangles: on a height field the
// diagonal of two large triangles can run across a valley or a ridge that neither corner's
// planes reach, and that spot is the mesh's worst-case (Hausdorff) error. The repair looks only
// at the edges whose midpoint is worst by the merged quadrics, and flips one only when the
// original surface around it, measured exactly, says the flip brings the surface closer.

#include "quadric.hpp"
#include "simplify_mesh_ops.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace sylva::terrain::detail {

constexpr std::uint32_t kNoVertex = 0xFFFFFFFFu;

// The reducer's state the repair reads, all indexed by the reducer's local vertex ids.
struct FlipInputs {
  std::span<const glm::vec3> positions;
  std::span<const glm::vec3> normals;     // area-weighted original surface normal per vertex
  std::span<const Quadric> quadrics;      // merged plane quadric of each reduced vertex
  std::span<const double> weights;        // sum of the plane weights in each quadric
  // The original vertices each reduced vertex absorbed, as a chain starting at the vertex itself:
  // absorbed_next[v] is the next one, kNoVertex ends it.
  std::span<const std::uint32_t> absorbed_next;
  // Fans of the input mesh (build_fans of the original triangles).
  std::span<const std::uint32_t> original_offset;
  std::span<const Corner> original_fans;
};

// Work arrays, reused across calls by the caller (no allocation once they have grown).
struct FlipScratch {
  // Fans of the reduced mesh, only for the candidates' vertices (a, b, c): slot_of maps such a
  // vertex to its slot (kNoVertex otherwise; reset after each call), offset / fans are the slots'
  // corners in CSR form, touching the triangles that hold a slot vertex.
  std::vector<std::uint32_t> slot_of;
  std::vector<std::uint32_t> offset;
  std::vector<Corner> fans;
  std::vector<std::uint32_t> touching;
  struct Candidate {
    double cost;
    std::uint32_t a, b, c;                  // triangle (a, b, c) holding the edge a -> b
  };
  std::vector<Candidate> candidates;
  std::vector<std::uint32_t> flip_of;       // vertex -> accepted flip touching it, else kNoVertex
  std::vector<std::uint32_t> flips;         // a, b, c, d per accepted flip
  std::vector<std::uint32_t> nearby;        // original triangles near a candidate, 3 ids each
  std::vector<std::uint32_t> absorbed_mark; // vertex -> stamp of the candidate that absorbed it
  std::uint32_t stamp = 0;
};

// Candidates: the max(8, triangles / 500) interior edges (a, b) with the highest merged-quadric
// cost at their midpoint, (Q_a + Q_b)(mid) / (w_a + w_b), highest first. Edge (a, b) with
// triangles (a, b, c) and (b, a, d) becomes (c, d) when
//  * a, b, c, d take part in no other flip of this call, (a, b) has exactly those two triangles
//    and (c, d) is no edge yet (the surface stays manifold);
//  * the new triangles (a, d, c) and (d, b, c) are not degenerate, turn by at most ~70 degrees
//    against both old ones and face the original surface (the collapse tests);
//  * the diagonal's midpoint cost drops, (Q_c + Q_d)(mid_cd) / (w_c + w_d) < the edge's cost;
//  * exactly, against the original triangles around the original vertices a, b, c, d absorbed:
//    the largest distance from the points the flip moves (the two inner third points of the
//    diagonal and the two centroids) to them is smaller after than before, and no absorbed
//    original vertex whose distance to the pair changes ends farther from the new pair than the
//    farthest such one was from the old (both directions of the Hausdorff distance the README
//    measures).
// Vertex positions and the open boundary are untouched, so locked vertices and segment borders
// stay bit-identical. Deterministic. Rewrites `tris` (3 local ids each; nv vertices) in place and
// returns the number of flips.
std::size_t flip_worst_edges(const FlipInputs& in, std::vector<std::uint32_t>& tris, std::size_t nv,
                             FlipScratch& scratch);

}  // namespace sylva::terrain::detail

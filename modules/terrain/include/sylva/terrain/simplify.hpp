#pragma once
// Triangle reduction with locked vertices (seed 002 §4.2-4.3) and its measured error.
//
// All functions take the full position array and a triangle list indexing it; the result is a
// triangle list over the same positions. The reducers only ever merge a vertex into one of its
// neighbours (half-edge collapse; the pass-wise QEM also flips a few interior edges at the end),
// so the result's vertices are a subset of the input's and a locked vertex keeps its exact
// position: segment borders stay bit-identical.

#include <glm/glm.hpp>

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace sylva::terrain {

struct SimplifyStats {
  std::size_t collapses = 0;
  std::size_t rejected = 0;  // collapses refused by the validity tests (QEM)
  std::size_t passes = 0;    // seed and pass-wise QEM reducers: passes over the mesh
  std::size_t flips = 0;     // pass-wise QEM: edges flipped by its final repair
};

// Garland-Heckbert quadric error metric (area-weighted plane quadrics), cheapest collapse first.
// A collapse is refused when it would remove a locked vertex, break the link condition (making
// the surface non-manifold or closing a hole), flip a triangle or make one degenerate, turn a
// triangle's normal by more than ~70 degrees, or leave a triangle facing against the original
// surface normals at its corners. Stops at target_triangles or when nothing is left.
std::vector<std::uint32_t> simplify_qem(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices,
                                        std::span<const std::uint8_t> locked, std::size_t target_triangles,
                                        SimplifyStats* stats = nullptr);

// The same collapse rules evaluated in passes (seed §4.3's structure with QEM costs), the model
// tree's default: every free vertex proposes its cheapest collapse, the proposals are walked in
// cost order and each valid one whose source and target took no part in an earlier collapse of
// the pass is applied; validity is tested on the current mesh, so the guarantees are the queue's.
// Faster than meshoptimizer 0.18's meshopt_simplify on the benchmark segments, at a lower
// error than the queue (bench/simplify_bench.cpp, README Results). Vertices on an open boundary
// are treated as locked. After the passes, a bounded repair flips up to max(8, triangles / 500)
// interior edges whose midpoint lies worst, each only when the original surface around it,
// measured exactly, comes closer (src/simplify_flip.hpp; stats->flips counts them): the edge
// between two large triangles can cross a valley that no vertex quadric sees. Reuses per-thread work arrays (no allocation but the result once they
// have grown); deterministic.
std::vector<std::uint32_t> simplify_qem_passes(std::span<const glm::vec3> positions,
                                               std::span<const std::uint32_t> indices,
                                               std::span<const std::uint8_t> locked, std::size_t target_triangles,
                                               SimplifyStats* stats = nullptr);

// The seed's reduction (§4.3), faithfully: per triangle its shortest edge (first vertex deleted,
// second kept, in triangle order), sorted by length; a vertex may be deleted when it is not a
// border vertex, not deleted and nothing was merged into it, and its target is not deleted; then
// triangles holding a deleted vertex and its target vanish, the others are re-linked, and
// collinear or repeated-vertex triangles are removed (the seed's clean-up, with the robust
// test of its errata). Passes repeat until target_triangles is reached or a pass removes
// nothing. No validity tests: it can fold triangles and open holes, as the seed reports.
std::vector<std::uint32_t> simplify_shortest_edge(std::span<const glm::vec3> positions,
                                                  std::span<const std::uint32_t> indices,
                                                  std::span<const std::uint8_t> locked, std::size_t target_triangles,
                                                  SimplifyStats* stats = nullptr);

struct HausdorffDistance {
  double original_to_reduced = 0.0;  // max over points of the original of the distance to the reduced
  double reduced_to_original = 0.0;  // max over points of the reduced of the distance to the original
  double max() const { return original_to_reduced > reduced_to_original ? original_to_reduced : reduced_to_original; }
};

// Measured (sampled) Hausdorff distances [m]. Points: every vertex and triangle centroid, plus a
// barycentric grid of spacing `sample_spacing` on each triangle longer than that (0 = the mean
// original edge length), so large reduced triangles are sampled as densely as the original.
HausdorffDistance hausdorff_distance(std::span<const glm::vec3> positions, std::span<const std::uint32_t> original,
                                     std::span<const std::uint32_t> reduced, double sample_spacing = 0.0);

}  // namespace sylva::terrain

// The pass-wise QEM's edge-flip repair (src/simplify_flip.hpp) on the case it exists for: two
// reduced triangles whose shared diagonal runs across a ridge of the original surface. The other
// diagonal lies on the ridge, so the flip must happen and bring the measured (Hausdorff) error
// down; where the diagonal already follows the ridge, or the surface is flat, nothing moves.
#include <sylva/terrain/mesh.hpp>
#include <sylva/terrain/simplify.hpp>

#include "../src/simplify_flip.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace sylva::terrain {
namespace {

using detail::kNoVertex;

// A (n + 1)^2 grid over [0, 2]^2 in x-z whose height is a ridge (or valley) of height `height`
// along the line x + z = 2 (`along_cd`) or x = z, triangulated with the ridge on grid edges, and
// the state the reducer would hand the repair after collapsing it to its four corners a = (0, 0),
// b = (2, 2), c = (2, 0), d = (0, 2), reduced to (a, b, c), (b, a, d): each vertex's plane quadric
// and normal, every vertex absorbed by its nearest corner.
struct RidgeCase {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> original;
  std::vector<detail::Quadric> quadrics;
  std::vector<double> weights;
  std::vector<glm::vec3> normals;
  std::vector<std::uint32_t> absorbed_next;
  std::vector<std::uint32_t> original_offset;
  std::vector<detail::Corner> original_fans;
  std::uint32_t a = 0, b = 0, c = 0, d = 0;

  RidgeCase(float height, bool along_cd, int n = 8) {
    const auto id = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const float x = 2.0f * static_cast<float>(i) / static_cast<float>(n);
        const float z = 2.0f * static_cast<float>(j) / static_cast<float>(n);
        const float off = along_cd ? std::abs(x + z - 2.0f) : std::abs(x - z);
        positions.emplace_back(x, height * (1.0f - 0.5f * off), z);
      }
    // Counter-clockwise seen from +y; cells split along the ridge's direction.
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::uint32_t p00 = id(i, j), p10 = id(i + 1, j), p01 = id(i, j + 1), p11 = id(i + 1, j + 1);
        if (along_cd)
          original.insert(original.end(), {p00, p01, p10, p10, p01, p11});
        else
          original.insert(original.end(), {p00, p01, p11, p00, p11, p10});
      }
    a = id(0, 0), b = id(n, n), c = id(n, 0), d = id(0, n);
    const std::size_t nv = positions.size();
    quadrics.assign(nv, {});
    weights.assign(nv, 0.0);
    std::vector<glm::dvec3> normal_sum(nv, glm::dvec3(0.0));
    for (std::size_t t = 0; t < original.size(); t += 3) {
      const glm::dvec3 p0(positions[original[t]]), p1(positions[original[t + 1]]), p2(positions[original[t + 2]]);
      const glm::dvec3 nn = glm::cross(p1 - p0, p2 - p0);
      const double len = glm::length(nn);
      for (std::size_t k = 0; k < 3; ++k) {
        quadrics[original[t + k]].add_plane(nn / len, -glm::dot(nn / len, p0), std::sqrt(0.5 * len));
        weights[original[t + k]] += std::sqrt(0.5 * len);
        normal_sum[original[t + k]] += nn;
      }
    }
    for (const glm::dvec3& s : normal_sum) normals.emplace_back(s);
    detail::build_fans(original, nv, original_offset, original_fans);
    // Absorption: chains from each corner through the vertices nearest to it, quadrics merged.
    absorbed_next.assign(nv, kNoVertex);
    std::uint32_t last[4] = {a, b, c, d};
    for (std::uint32_t v = 0; v < nv; ++v) {
      if (v == a || v == b || v == c || v == d) continue;
      int best = 0;
      float best_d = 1e30f;
      for (int k = 0; k < 4; ++k) {
        const glm::vec3 e = positions[v] - positions[(k == 0 ? a : k == 1 ? b : k == 2 ? c : d)];
        if (glm::dot(e, e) < best_d) best_d = glm::dot(e, e), best = k;
      }
      const std::uint32_t corner = best == 0 ? a : best == 1 ? b : best == 2 ? c : d;
      absorbed_next[last[best]] = v;
      last[best] = v;
      quadrics[corner] += quadrics[v];
      weights[corner] += weights[v];
    }
  }

  detail::FlipInputs inputs() const {
    return {positions, normals, quadrics, weights, absorbed_next, original_offset, original_fans};
  }
  std::vector<std::uint32_t> reduced() const { return {a, b, c, b, a, d}; }
};

TEST(SimplifyFlip, DiagonalAcrossARidgeIsFlippedAndTheErrorDrops) {
  const RidgeCase ridge(1.0f, true);
  std::vector<std::uint32_t> tris = ridge.reduced();
  const double before = hausdorff_distance(ridge.positions, ridge.original, tris).max();
  detail::FlipScratch scratch;
  EXPECT_EQ(detail::flip_worst_edges(ridge.inputs(), tris, ridge.positions.size(), scratch), 1u);
  // (a, b, c), (b, a, d) -> (a, d, c), (d, b, c): same winding, the diagonal now c-d.
  EXPECT_EQ(tris, (std::vector<std::uint32_t>{ridge.a, ridge.d, ridge.c, ridge.d, ridge.b, ridge.c}));
  const double after = hausdorff_distance(ridge.positions, ridge.original, tris).max();
  EXPECT_GT(before, 0.8);  // the old diagonal's midpoint lies 1 m below the ridge line, 0.82 m from its faces
  EXPECT_LT(after, 1e-4 * before);
  const MeshCheck check = check_mesh(ridge.positions, tris);
  EXPECT_EQ(check.degenerate, 0u);
  EXPECT_EQ(check.non_manifold, 0u);
  EXPECT_EQ(count_flipped(ridge.positions, ridge.original, tris), 0u);
}

TEST(SimplifyFlip, DiagonalAlongTheRidgeOrOnAFlatSurfaceStays) {
  for (const RidgeCase& surface : {RidgeCase(1.0f, false), RidgeCase(-1.0f, false), RidgeCase(0.0f, true)}) {
    std::vector<std::uint32_t> tris = surface.reduced();
    detail::FlipScratch scratch;
    EXPECT_EQ(detail::flip_worst_edges(surface.inputs(), tris, surface.positions.size(), scratch), 0u);
    EXPECT_EQ(tris, surface.reduced());
  }
}

TEST(SimplifyFlip, OpenEdgesAreNeverFlipped) {
  // One triangle alone: its edges are all open.
  const RidgeCase ridge(1.0f, true);
  std::vector<std::uint32_t> tris = {ridge.a, ridge.b, ridge.c};
  detail::FlipScratch scratch;
  EXPECT_EQ(detail::flip_worst_edges(ridge.inputs(), tris, ridge.positions.size(), scratch), 0u);
  EXPECT_EQ(tris, (std::vector<std::uint32_t>{ridge.a, ridge.b, ridge.c}));
}

}  // namespace
}  // namespace sylva::terrain

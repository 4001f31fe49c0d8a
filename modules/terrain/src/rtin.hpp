#pragma once
// Right-triangulated irregular network (RTIN) on the square root grid of N x N intervals
// (N a power of two). A triangle is (a, b, c): hypotenuse a-b, right angle at c. Splitting it at
// the hypotenuse midpoint m gives (c, a, m) and (b, c, m). The root square is split along its
// main diagonal (0,0)-(N,N); a square of the quadtree is split along the diagonal that points to
// its parent's centre, i.e. along the main diagonal when its column + row is even.
//
// Vertex errors (after Evans, Kirkpatrick and Townsend's RTIN, as popularised by "Martini"):
// err(p) = max(|h(p) - mean of its hypotenuse ends|, err of the points that split p's two
// triangles' children). So err never increases from a point to its descendants, and the set
// {p : err(p) > eps} is closed under ancestry: triangulating "split while the midpoint is
// active" gives a conforming mesh, identical on both sides of any shared edge.

#include <cstdint>
#include <cstdlib>
#include <vector>

namespace sylva::terrain::detail {

struct Pt {
  std::int32_t x = 0, z = 0;
  bool operator==(const Pt&) const = default;
};
inline Pt midpoint(Pt a, Pt b) { return {(a.x + b.x) / 2, (a.z + b.z) / 2}; }

struct Tri {
  Pt a, b, c;  // hypotenuse a-b, apex c
};

// Twice the signed area in the x/z plane with the sign of the triangle normal's y component:
// > 0 means up-facing (counter-clockwise seen from above, the GL front face of a terrain seen
// from above with y up).
inline std::int64_t area2(Pt p0, Pt p1, Pt p2) {
  return static_cast<std::int64_t>(p1.z - p0.z) * (p2.x - p0.x) -
         static_cast<std::int64_t>(p1.x - p0.x) * (p2.z - p0.z);
}

// The two root triangles of the quadtree square [x0, x0+size] x [z0, z0+size] whose column and
// row at its level are (cx, cz).
inline void square_triangles(std::int32_t x0, std::int32_t z0, std::int32_t size, std::uint32_t cx,
                             std::uint32_t cz, Tri out[2]) {
  const std::int32_t x1 = x0 + size, z1 = z0 + size;
  if (((cx + cz) & 1u) == 0u) {  // main diagonal (x0,z0)-(x1,z1)
    out[0] = Tri{{x0, z0}, {x1, z1}, {x1, z0}};
    out[1] = Tri{{x1, z1}, {x0, z0}, {x0, z1}};
  } else {  // anti diagonal (x1,z0)-(x0,z1)
    out[0] = Tri{{x1, z0}, {x0, z1}, {x1, z1}};
    out[1] = Tri{{x0, z1}, {x1, z0}, {x0, z0}};
  }
}

// Height grid of (N+1)^2 points: the field with clamped padding, stored densely for speed.
struct HeightGrid {
  std::int32_t n = 0;  // N
  std::vector<float> h;
  float at(std::int32_t x, std::int32_t z) const {
    return h[static_cast<std::size_t>(z) * static_cast<std::size_t>(n + 1) + static_cast<std::size_t>(x)];
  }
  float at(Pt p) const { return at(p.x, p.z); }
};

// Vertex errors over the root grid. Only points with both coordinates even are stored (a quarter
// of the grid: 1 byte per root-grid point, not 4; the bake's peak memory, bake.hpp): a point with
// an odd coordinate is split only by the finest pass (t = 2), has no children, and its error is
// its own deviation from its hypotenuse ends (a centre's also its four side neighbours'), so at()
// computes it from the heights, with the same float operations the pass would have done.
struct ErrorGrid {
  std::int32_t n = 0;
  const HeightGrid* heights = nullptr;  // outlives the grid (both live in TreeGrids or a scope)
  std::vector<float> even;              // errors of (2i, 2j), (n/2 + 1)^2 of them
  float at(Pt p) const {
    if (((p.x | p.z) & 1) == 0) {
      return even[static_cast<std::size_t>(p.z / 2) * static_cast<std::size_t>(n / 2 + 1) + static_cast<std::size_t>(p.x / 2)];
    }
    return finest(p);
  }
  float finest(Pt p) const;  // a point with an odd coordinate (pass t = 2)
};

// Computes ErrorGrid from the heights, finest triangles first, rows in parallel.
ErrorGrid compute_errors(const HeightGrid& heights, int threads);

// After the heights of the root-grid points [x0, x1] x [z0, z1] (inclusive) changed in
// *errors.heights, recomputes the stored errors that can depend on them (those within 2 t of the
// rectangle on pass t), leaving `errors` bit-identical to compute_errors of the new heights
// (issue 15: a paint stroke's cost follows the stroke, not the field). Returns the count of
// stored error cells recomputed: about the rectangle grown by 2 t per pass (area / 4 in all) plus a few per
// coarse pass that reaches the border (log2 n of them), not the field's (n / 2 + 1)^2.
std::int64_t update_errors(ErrorGrid& errors, std::int32_t x0, std::int32_t z0, std::int32_t x1, std::int32_t z1);

// Whether a point belongs to a level's vertex set: it lies on the level's grid and is either
// forced (on the half-chunk grid, which keeps every chunk split down to its four quadrants so
// that the next level's chunks nest inside it) or its error exceeds the level's tolerance.
struct ActiveRule {
  const ErrorGrid* errors = nullptr;
  int levels = 1;
  std::int32_t leaf_n = 2;  // leaf_dimension - 1
  std::vector<float> eps;    // per level [m]

  std::int32_t step(int level) const { return std::int32_t{1} << (levels - 1 - level); }
  bool active(Pt p, int level) const {
    const std::int32_t s = step(level);
    if ((p.x & (s - 1)) != 0 || (p.z & (s - 1)) != 0) return false;
    const std::int32_t fs = leaf_n * s / 2;
    if (p.x % fs == 0 && p.z % fs == 0) return true;
    return errors->at(p) > eps[static_cast<std::size_t>(level)];
  }
  // Coarsest level containing p (levels when none does).
  int intro_level(Pt p) const {
    for (int l = 0; l < levels; ++l)
      if (active(p, l)) return l;
    return levels;
  }
};

// Height of a level's (unmorphed) surface at grid point p: descends the bintree from the root
// square while the midpoint is active at `level`, then interpolates in the leaf triangle. A pure
// function of (level, p): every caller gets the same float.
double level_surface_height(const ActiveRule& rule, const HeightGrid& heights, int level, Pt p);

}  // namespace sylva::terrain::detail

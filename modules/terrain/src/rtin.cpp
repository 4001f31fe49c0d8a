#include "rtin.hpp"

#include "parallel.hpp"

#include <algorithm>
#include <cmath>

namespace sylva::terrain::detail {
namespace {

// A midpoint's own error: computed in double, where the mean of two floats is exact, so the error
// is the true one.
float own_error(float hm, float ha, float hb) {
  return static_cast<float>(std::fabs(static_cast<double>(hm) - 0.5 * (static_cast<double>(ha) + hb)));
}

// Passes t = 4, 8, ..., n: they write only points with both coordinates even (ErrorGrid::even);
// the finest pass (t = 2) is ErrorGrid::finest, evaluated where it is read.
struct ErrorPass {
  const HeightGrid& hg;
  ErrorGrid& eg;
  std::int32_t n;

  float h(std::int32_t x, std::int32_t z) const { return hg.at(x, z); }
  void set(std::int32_t x, std::int32_t z, float err) const {
    eg.even[static_cast<std::size_t>(z / 2) * static_cast<std::size_t>(n / 2 + 1) + static_cast<std::size_t>(x / 2)] = err;
  }
  float e(std::int32_t x, std::int32_t z) const { return eg.at(Pt{x, z}); }
  float e_or0(std::int32_t x, std::int32_t z) const {
    if (x < 0 || z < 0 || x > n || z > n) return 0.0f;
    return e(x, z);
  }

  // The first x >= lo with x = offset mod t (offset < t).
  static std::int32_t first(std::int32_t offset, std::int32_t t, std::int32_t lo) {
    if (lo <= offset) return offset;
    return offset + (lo - offset + t - 1) / t * t;
  }

  // Side midpoints of cells of size t on row z, columns [lo, hi].
  std::int64_t sides(std::int32_t t, std::int32_t z, std::int32_t lo, std::int32_t hi) const {
    std::int64_t count = 0;
    const std::int32_t half = t / 2, quarter = t / 4;
    if (z % t == 0) {  // horizontal sides: x = t/2 mod t
      for (std::int32_t x = first(half, t, lo); x <= std::min(n, hi); x += t) {
        float err = own_error(h(x, z), h(x - half, z), h(x + half, z));
        err = std::max({err, e_or0(x - quarter, z - quarter), e_or0(x + quarter, z - quarter),
                        e_or0(x - quarter, z + quarter), e_or0(x + quarter, z + quarter)});
        set(x, z, err);
        ++count;
      }
    } else if (z % t == half) {  // vertical sides: x = 0 mod t
      for (std::int32_t x = first(0, t, lo); x <= std::min(n, hi); x += t) {
        float err = own_error(h(x, z), h(x, z - half), h(x, z + half));
        err = std::max({err, e_or0(x - quarter, z - quarter), e_or0(x + quarter, z - quarter),
                        e_or0(x - quarter, z + quarter), e_or0(x + quarter, z + quarter)});
        set(x, z, err);
        ++count;
      }
    }
    return count;
  }

  // Cell centres of cells of size t on row z (z = t/2 mod t), columns [lo, hi].
  std::int64_t centres(std::int32_t t, std::int32_t z, std::int32_t lo, std::int32_t hi) const {
    std::int64_t count = 0;
    const std::int32_t half = t / 2;
    const std::int32_t cz = (z - half) / t;
    for (std::int32_t x = first(half, t, lo); x <= std::min(n, hi); x += t) {
      const std::int32_t cx = (x - half) / t;
      float ha, hb;
      if (((cx + cz) & 1) == 0) {
        ha = h(x - half, z - half);
        hb = h(x + half, z + half);
      } else {
        ha = h(x + half, z - half);
        hb = h(x - half, z + half);
      }
      float err = own_error(h(x, z), ha, hb);
      err = std::max({err, e(x - half, z), e(x + half, z), e(x, z - half), e(x, z + half)});
      set(x, z, err);
      ++count;
    }
    return count;
  }
};

}  // namespace

float ErrorGrid::finest(Pt p) const {
  const HeightGrid& hg = *heights;
  const std::int32_t x = p.x, z = p.z;
  if ((z & 1) == 0) return own_error(hg.at(x, z), hg.at(x - 1, z), hg.at(x + 1, z));  // horizontal side
  if ((x & 1) == 0) return own_error(hg.at(x, z), hg.at(x, z - 1), hg.at(x, z + 1));  // vertical side
  // Centre of the 2x2 cell (cx, cz): the diagonal alternates with the cell's parity.
  const std::int32_t cx = (x - 1) / 2, cz = (z - 1) / 2;
  const bool main_diagonal = ((cx + cz) & 1) == 0;
  const float ha = main_diagonal ? hg.at(x - 1, z - 1) : hg.at(x + 1, z - 1);
  const float hb = main_diagonal ? hg.at(x + 1, z + 1) : hg.at(x - 1, z + 1);
  const float err = own_error(hg.at(x, z), ha, hb);
  return std::max({err, finest({x - 1, z}), finest({x + 1, z}), finest({x, z - 1}), finest({x, z + 1})});
}

ErrorGrid compute_errors(const HeightGrid& heights, int threads) {
  ErrorGrid eg;
  eg.n = heights.n;
  eg.heights = &heights;
  const std::size_t side = static_cast<std::size_t>(heights.n / 2) + 1;
  eg.even.assign(side * side, 0.0f);
  ErrorPass pass{heights, eg, heights.n};
  for (std::int32_t t = 4; t <= heights.n; t *= 2) {
    // Rows of side midpoints: z multiple of t/2. Each row writes only its own points and reads
    // the finer pass, so rows are independent.
    const std::size_t side_rows = static_cast<std::size_t>(heights.n / (t / 2)) + 1;
    parallel_for(side_rows, threads, [&](std::size_t r) { (void)pass.sides(t, static_cast<std::int32_t>(r) * (t / 2), 0, heights.n); },
                 nullptr, 16);
    const std::size_t centre_rows = static_cast<std::size_t>(heights.n / t);
    parallel_for(centre_rows, threads,
                 [&](std::size_t r) { (void)pass.centres(t, t / 2 + static_cast<std::int32_t>(r) * t, 0, heights.n); }, nullptr, 16);
  }
  return eg;
}

std::int64_t update_errors(ErrorGrid& errors, std::int32_t x0, std::int32_t z0, std::int32_t x1, std::int32_t z1) {
  const std::int32_t n = errors.n;
  ErrorPass pass{*errors.heights, errors, n};
  std::int64_t recomputed = 0;
  for (std::int32_t t = 4; t <= n; t *= 2) {
    // A pass-t point reads heights and finer errors within 1.5 t - 1 of itself (the recursion
    // t/2 + t/4 + ...: see the header): every point farther than 2 t from the changed heights
    // keeps its value, and every nearer one is recomputed with the same float operations in the
    // same pass order as compute_errors, so the grid stays bit-identical.
    const std::int32_t lo_x = std::max(x0 - 2 * t, 0), hi_x = std::min(x1 + 2 * t, n);
    const std::int32_t lo_z = std::max(z0 - 2 * t, 0), hi_z = std::min(z1 + 2 * t, n);
    const std::int32_t half = t / 2;
    for (std::int32_t z = ErrorPass::first(0, half, lo_z); z <= hi_z; z += half) recomputed += pass.sides(t, z, lo_x, hi_x);
    for (std::int32_t z = ErrorPass::first(half, t, lo_z); z <= hi_z; z += t) recomputed += pass.centres(t, z, lo_x, hi_x);
  }
  return recomputed;
}

double level_surface_height(const ActiveRule& rule, const HeightGrid& heights, int level, Pt p) {
  const std::int32_t n = heights.n;
  Tri t = (p.x >= p.z) ? Tri{{0, 0}, {n, n}, {n, 0}} : Tri{{n, n}, {0, 0}, {0, n}};
  for (;;) {
    const Pt m = midpoint(t.a, t.b);
    if ((t.a.x - t.b.x) % 2 != 0 || (t.a.z - t.b.z) % 2 != 0) break;  // unit triangle
    if (!rule.active(m, level)) break;
    // The split line runs from c to m; the child (c, a, m) holds the a side (ties go there).
    const std::int64_t side_p = area2(t.c, m, p);
    const std::int64_t side_a = area2(t.c, m, t.a);
    if (side_p == 0 || (side_p > 0) == (side_a > 0)) {
      t = Tri{t.c, t.a, m};
    } else {
      t = Tri{t.b, t.c, m};
    }
  }
  if (p == t.a) return heights.at(t.a);
  if (p == t.b) return heights.at(t.b);
  if (p == t.c) return heights.at(t.c);
  const double total = static_cast<double>(area2(t.a, t.b, t.c));
  const double wa = static_cast<double>(area2(p, t.b, t.c)) / total;
  const double wb = static_cast<double>(area2(t.a, p, t.c)) / total;
  const double wc = 1.0 - wa - wb;
  return wa * heights.at(t.a) + wb * heights.at(t.b) + wc * heights.at(t.c);
}

}  // namespace sylva::terrain::detail

#include "grid_tessellation.hpp"

#include <sylva/core/assert.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::terrain::detail {
namespace {

// Corner heights of a grid square: 00 = (x0, z0), 10 = (x1, z0), 11 = (x1, z1), 01 = (x0, z1).
struct Square {
  double h00, h10, h11, h01;
  bool main_diagonal(Tessellation t) const {
    // hq1: the diagonal whose ends differ less (seed 002 §3.3 method B, the extraction's [Inference]).
    return t != Tessellation::kHq1 || std::fabs(h00 - h11) <= std::fabs(h10 - h01);
  }
  // Rounded to the float the centre vertex stores, so the measured error is the drawn mesh's.
  double centre() const { return static_cast<float>(0.25 * (h00 + h10 + h11 + h01)); }
};

Square square_at(const HeightGrid& hg, std::int32_t x, std::int32_t z, std::int32_t s) {
  return {hg.at(x, z), hg.at(x + s, z), hg.at(x + s, z + s), hg.at(x, z + s)};
}

// The square's surface at (u, v) in [0, 1]^2 (u along x, v along z): barycentric weights of the
// triangle holding the point (§3.3 methods A/B: 2 triangles, C: 4 around the centre).
double square_height(const Square& q, Tessellation t, double u, double v) {
  if (t == Tessellation::kHq2) {
    const double c = q.centre();
    if (v <= u && v <= 1.0 - u) return q.h00 * (1.0 - u - v) + q.h10 * (u - v) + c * 2.0 * v;          // south
    if (u >= v && u >= 1.0 - v) return q.h10 * (u - v) + q.h11 * (u + v - 1.0) + c * 2.0 * (1.0 - u);  // east
    if (v >= u && v >= 1.0 - u) return q.h01 * (v - u) + q.h11 * (u + v - 1.0) + c * 2.0 * (1.0 - v);  // north
    return q.h00 * (1.0 - u - v) + q.h01 * (v - u) + c * 2.0 * u;                                       // west
  }
  if (q.main_diagonal(t)) {
    if (u >= v) return q.h00 * (1.0 - u) + q.h10 * (u - v) + q.h11 * v;
    return q.h00 * (1.0 - v) + q.h01 * (v - u) + q.h11 * u;
  }
  if (u + v <= 1.0) return q.h00 * (1.0 - u - v) + q.h10 * u + q.h01 * v;
  return q.h11 * (u + v - 1.0) + q.h10 * (1.0 - v) + q.h01 * (1.0 - u);
}

}  // namespace

double grid_surface_height(const HeightGrid& hg, Tessellation t, std::int32_t step, double px, double pz) {
  SYLVA_ASSERT(t != Tessellation::kRtin && step > 0 && step <= hg.n, "tessellation {} step {} (N = {})",
               static_cast<int>(t), step, hg.n);
  const double s = step;
  const std::int32_t x = std::clamp(static_cast<std::int32_t>(std::floor(px / s)) * step, 0, hg.n - step);
  const std::int32_t z = std::clamp(static_cast<std::int32_t>(std::floor(pz / s)) * step, 0, hg.n - step);
  return square_height(square_at(hg, x, z, step), t, (px - x) / s, (pz - z) / s);
}

double build_grid_chunk(const GridChunkInput& in, ChunkMesh& mesh) {
  const HeightGrid& hg = *in.heights;
  const Tessellation t = in.tessellation;
  SYLVA_ASSERT(t != Tessellation::kRtin && in.size > 0, "tessellation {} chunk size {}", static_cast<int>(t), in.size);
  const std::int32_t s = std::int32_t{1} << (in.levels - 1 - in.level);
  const std::int32_t cells = in.size / s;
  auto step_of = [&](int l) { return std::int32_t{1} << (in.levels - 1 - l); };

  // Corners first (row by row), then the hq2 centres: vertex index = position in these grids.
  const std::size_t side = static_cast<std::size_t>(cells) + 1;
  mesh.vertices.reserve(side * side + (t == Tessellation::kHq2 ? static_cast<std::size_t>(cells) * cells : 0));
  for (std::int32_t j = 0; j <= cells; ++j) {
    for (std::int32_t i = 0; i <= cells; ++i) {
      const std::int32_t x = in.x0 + i * s, z = in.z0 + j * s;
      ChunkVertex v;
      v.gx = static_cast<std::uint32_t>(x);
      v.gz = static_cast<std::uint32_t>(z);
      v.height = hg.at(x, z);
      v.outside = (x > in.columns - 1 || z > in.rows - 1) ? 1 : 0;
      int intro = 0;
      while (intro < in.level && ((x % step_of(intro)) != 0 || (z % step_of(intro)) != 0)) ++intro;
      v.intro_level = static_cast<std::uint8_t>(intro);
      v.morph_target = intro == 0 ? v.height
                                  : static_cast<float>(grid_surface_height(hg, t, step_of(intro - 1), x, z));
      mesh.vertices.push_back(v);
    }
  }
  auto corner = [&](std::int32_t i, std::int32_t j) { return static_cast<std::uint32_t>(j * (cells + 1) + i); };
  double max_err = 0.0;
  for (std::int32_t j = 0; j < cells; ++j) {
    for (std::int32_t i = 0; i < cells; ++i) {
      const std::int32_t x = in.x0 + i * s, z = in.z0 + j * s;
      const Square q = square_at(hg, x, z, s);
      const std::uint32_t c00 = corner(i, j), c10 = corner(i + 1, j), c11 = corner(i + 1, j + 1),
                          c01 = corner(i, j + 1);
      // Up-facing (rtin.hpp area2 > 0) orders, (x, z) corners 00 -> 10 -> 11 -> 01.
      if (t == Tessellation::kHq2) {
        ChunkVertex v;
        const double cx = x + 0.5 * s, cz = z + 0.5 * s;
        v.gx = static_cast<std::uint32_t>(s > 1 ? x + s / 2 : x);
        v.gz = static_cast<std::uint32_t>(s > 1 ? z + s / 2 : z);
        v.centre = s > 1 ? 0 : 1;  // a leaf square's centre is half a sample off the grid
        v.height = static_cast<float>(q.centre());
        v.outside = (cx > in.columns - 1 || cz > in.rows - 1) ? 1 : 0;
        v.intro_level = static_cast<std::uint8_t>(in.level);
        v.morph_target = in.level == 0 ? v.height
                                       : static_cast<float>(grid_surface_height(hg, t, step_of(in.level - 1), cx, cz));
        const auto c = static_cast<std::uint32_t>(mesh.vertices.size());
        mesh.vertices.push_back(v);
        mesh.indices.insert(mesh.indices.end(), {c00, c, c10, c10, c, c11, c11, c, c01, c01, c, c00});
      } else if (q.main_diagonal(t)) {
        mesh.indices.insert(mesh.indices.end(), {c00, c11, c10, c00, c01, c11});
      } else {
        mesh.indices.insert(mesh.indices.end(), {c00, c01, c10, c10, c01, c11});
      }
      // Measured error over the field samples of the square (padding samples do not count).
      const std::int32_t xe = std::min(x + s, in.columns - 1), ze = std::min(z + s, in.rows - 1);
      for (std::int32_t fz = z; fz <= ze; ++fz) {
        for (std::int32_t fx = x; fx <= xe; ++fx) {
          const double h = square_height(q, t, static_cast<double>(fx - x) / s, static_cast<double>(fz - z) / s);
          max_err = std::max(max_err, std::fabs(h - static_cast<double>(hg.at(fx, fz))));
        }
      }
    }
  }
  return max_err;
}

}  // namespace sylva::terrain::detail

// Nodata fill for elevation rasters (contract in <sylva/core/elevation_raster.hpp>).
#include <sylva/core/assert.hpp>
#include <sylva/core/elevation_raster.hpp>

#include <cstddef>
#include <vector>

namespace sylva {

std::size_t fill_nodata(std::vector<float>& values, const std::vector<std::uint8_t>& valid, int columns, int rows) {
  const std::size_t n = static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows);
  SYLVA_ASSERT(columns > 0 && rows > 0 && values.size() == n && valid.size() == n,
               "fill_nodata: {}x{} grid, {} values, {} flags", columns, rows, values.size(), valid.size());
  // Breadth-first flood from every valid sample at once: each hole sample takes the value of the
  // neighbour that reached it first, so it carries the value of a nearest valid sample (in
  // 8-neighbour steps). O(n), unlike repeated neighbour averaging, which needs one pass over the
  // whole grid per sample of hole radius.
  std::vector<std::size_t> queue;
  queue.reserve(n);
  std::vector<std::uint8_t> known = valid;
  std::vector<std::size_t> holes;
  for (std::size_t k = 0; k < n; ++k) {
    if (valid[k]) queue.push_back(k);
  }
  SYLVA_ASSERT(!queue.empty(), "fill_nodata: no valid sample in {}x{}", columns, rows);
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::size_t k = queue[head];
    const int i = static_cast<int>(k % static_cast<std::size_t>(columns));
    const int j = static_cast<int>(k / static_cast<std::size_t>(columns));
    for (int dj = -1; dj <= 1; ++dj) {
      for (int di = -1; di <= 1; ++di) {
        const int x = i + di, z = j + dj;
        if (x < 0 || z < 0 || x >= columns || z >= rows) continue;
        const std::size_t m = static_cast<std::size_t>(z) * static_cast<std::size_t>(columns) + static_cast<std::size_t>(x);
        if (known[m]) continue;
        known[m] = 1;
        values[m] = values[k];
        queue.push_back(m);
        holes.push_back(m);
      }
    }
  }
  // The flood leaves flat Voronoi terraces with steps where two nearest samples meet; a few 3x3
  // means over the filled samples only round them off. Valid samples are never changed.
  std::vector<float> next(holes.size());
  for (int pass = 0; pass < kFillSmoothingPasses && !holes.empty(); ++pass) {
    for (std::size_t h = 0; h < holes.size(); ++h) {
      const std::size_t k = holes[h];
      const int i = static_cast<int>(k % static_cast<std::size_t>(columns));
      const int j = static_cast<int>(k / static_cast<std::size_t>(columns));
      double sum = 0.0;
      int count = 0;
      for (int dj = -1; dj <= 1; ++dj) {
        for (int di = -1; di <= 1; ++di) {
          const int x = i + di, z = j + dj;
          if (x < 0 || z < 0 || x >= columns || z >= rows) continue;
          sum += values[static_cast<std::size_t>(z) * static_cast<std::size_t>(columns) + static_cast<std::size_t>(x)];
          ++count;
        }
      }
      next[h] = static_cast<float>(sum / count);
    }
    for (std::size_t h = 0; h < holes.size(); ++h) values[holes[h]] = next[h];
  }
  return holes.size();
}

}  // namespace sylva

// Nodata fill for elevation rasters (contract in <sylva/core/elevation_raster.hpp>).
#include <sylva/core/assert.hpp>
#include <sylva/core/elevation_raster.hpp>

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

namespace sylva {
namespace {

// A valid sample with an invalid one among its 8 neighbours.
bool beside_a_hole(const std::vector<std::uint8_t>& valid, std::size_t k, int columns, int rows) {
  const int i = static_cast<int>(k % static_cast<std::size_t>(columns));
  const int j = static_cast<int>(k / static_cast<std::size_t>(columns));
  for (int z = std::max(j - 1, 0); z <= std::min(j + 1, rows - 1); ++z) {
    for (int x = std::max(i - 1, 0); x <= std::min(i + 1, columns - 1); ++x) {
      if (!valid[static_cast<std::size_t>(z) * static_cast<std::size_t>(columns) + static_cast<std::size_t>(x)]) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace

std::size_t fill_nodata(std::vector<float>& values, const std::vector<std::uint8_t>& valid, int columns, int rows) {
  const std::size_t n = static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows);
  SYLVA_ASSERT(columns > 0 && rows > 0 && values.size() == n && valid.size() == n,
               "fill_nodata: {}x{} grid, {} values, {} flags", columns, rows, values.size(), valid.size());
  // Breadth-first flood from every valid sample at once: each hole sample takes the value of the
  // neighbour that reached it first, so it carries the value of a nearest valid sample (in
  // 8-neighbour steps). O(n), unlike repeated neighbour averaging, which needs one pass over the
  // whole grid per sample of hole radius. Only valid samples beside a hole are queued: the others
  // have no unknown neighbour, so taking them out of the queue changes nothing (same order, same
  // result) and the queue holds the holes and their borders instead of 8 bytes per sample.
  std::vector<std::uint8_t> known = valid;
  std::vector<std::size_t> queue;
  bool any_valid = false;
  for (std::size_t k = 0; k < n; ++k) {
    if (!valid[k]) continue;
    any_valid = true;
    if (beside_a_hole(valid, k, columns, rows)) queue.push_back(k);
  }
  SYLVA_ASSERT(any_valid, "fill_nodata: no valid sample in {}x{}", columns, rows);
  const std::size_t seeds = queue.size();
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
      }
    }
  }
  known = {};
  // The holes, in the order the flood reached them.
  const std::span<const std::size_t> holes(queue.data() + seeds, queue.size() - seeds);
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

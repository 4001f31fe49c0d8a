#include <sylva/terrain/selection.hpp>

#include <sylva/core/timer.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace sylva::terrain {

namespace {

// Squared horizontal distance from the eye to the middle of a chunk's box [m^2].
double centre_distance2(const ChunkNode& node, const glm::dvec3& eye) {
  const double dx = 0.5 * (node.lo.x + node.hi.x) - eye.x;
  const double dz = 0.5 * (node.lo.z + node.hi.z) - eye.z;
  return dx * dx + dz * dz;
}

}  // namespace

LodSelector::LodSelector(const ChunkTree& tree) : tree_(&tree), state_(tree.chunk_count(), kUnseen) {}

bool LodSelector::accept(std::uint32_t index, const LodView& view, const LodSettings& settings, double* rho) const {
  const ChunkNode& c = tree_->nodes()[index];
  *rho = 0.0;
  if (c.level + 1 >= tree_->levels()) return true;  // leaves are the finest there is
  if (settings.criterion == LodCriterion::kBruteForce) {
    // Seed 002 Tab. 3.1's unoptimised rendering: refine to the leaves everywhere.
    *rho = 1e30;
    return false;
  }
  if (settings.criterion == LodCriterion::kSeedDistance) {
    // Seed 002 §2.3: chunk_error = vertex spacing of the chunk, d = distance to its centre.
    const double chunk_error = static_cast<double>(tree_->step(c.level)) * tree_->spacing();
    const double d = glm::length(view.position - 0.5 * (c.lo + c.hi));
    *rho = chunk_error * static_cast<double>(settings.lod_distance) / std::max(d, 1e-9);
    return chunk_error * static_cast<double>(settings.lod_distance) <= d;
  }
  if (c.error_bound <= 0.0f) return true;
  const double delta = static_cast<double>(c.error_bound);
  // The drawn point lies in the box, the field point may lie up to delta outside it, so the
  // vertical error segment is at least D - delta away: rho = K * delta / (D - delta) <= tau,
  // written without dividing by a distance that may be 0 or negative.
  const double d = view.distance_to_box(c.lo, c.hi) - delta;
  *rho = d > 0.0 ? view.k * delta / d : 1e30;
  return d > 0.0 && view.k * delta <= static_cast<double>(settings.max_pixel_error) * d;
}

const Selection& LodSelector::select(const LodView& view, const LodSettings& settings, const Residency* residency) {
  Stopwatch watch;
  // Incremental reset: only the chunks the last frame touched.
  for (std::uint32_t i : touched_) state_[i] = kUnseen;
  touched_.clear();
  Selection& sel = selection_;
  sel.chunks.clear();
  sel.stats = SelectionStats{};
  sel.stats.chunks_per_level.assign(static_cast<std::size_t>(tree_->levels()), 0);
  sel.morph = settings.criterion == LodCriterion::kScreenSpaceError && settings.morph_fraction > 0.0f;
  // Brute force draws the leaves, whose error is the finest the tree has (0 for exact leaves).
  sel.bound_certified = settings.criterion == LodCriterion::kBruteForce ||
                        (settings.criterion == LodCriterion::kScreenSpaceError &&
                         (!sel.morph || settings.morph_fraction <= tree_->settings().max_morph_fraction + 1e-6f));

  const std::vector<ChunkNode>& nodes = tree_->nodes();
  stack_.clear();
  if (tree_->chunk_count() > 0 && nodes[0].present) {
    if (residency == nullptr || residency->resident(0)) {
      stack_.emplace_back(0u, std::uint8_t{0x3F});
    } else {
      residency->request(0, 1e30);
    }
  }
  while (!stack_.empty()) {
    const auto [i, parent_mask] = stack_.back();
    stack_.pop_back();
    touched_.push_back(i);
    ++sel.stats.visited;
    const ChunkNode& node = nodes[i];
    // Plane masks: a box wholly inside a frustum plane passes that plane for all its children.
    std::uint8_t mask = parent_mask;
    if (settings.frustum_cull && mask != 0 && !view.box_visible(node.lo, node.hi, mask)) {
      state_[i] = kCulled;
      ++sel.stats.culled;
      continue;
    }
    double rho = 0.0;
    bool draw = accept(i, view, settings, &rho);
    std::array<std::uint32_t, 4> children{};
    if (!draw) {
      // Children of (x, z) at level l are (2x + a, 2z + b) at level l + 1, stored row by row.
      const std::uint32_t side = 2u << node.level;
      const std::uint32_t base = tree_->level_offset(node.level + 1) + 2 * node.z * side + 2 * node.x;
      children = {base, base + 1, base + side, base + side + 1};
    }
    if (!draw && residency != nullptr) {
      // Refine only into resident children; otherwise draw this chunk and ask for them.
      bool all = true;
      for (std::uint32_t ci : children) {
        if (!nodes[ci].present || residency->resident(ci)) continue;
        all = false;
        residency->request(ci, rho);
      }
      if (!all) {
        draw = true;
        ++sel.stats.substituted;
      }
    }
    if (draw) {
      state_[i] = kDrawn;
      SelectedChunk s;
      s.index = i;
      sel.chunks.push_back(s);
      continue;
    }
    state_[i] = kRefined;
    // Nearest child on top of the stack: the chunks come out front to back, so a software
    // rasteriser's early depth test rejects the hidden ground behind nearer hills before shading.
    std::array<double, 4> far{};
    for (std::size_t k = 0; k < 4; ++k) far[k] = centre_distance2(nodes[children[k]], view.position);
    std::array<std::size_t, 4> order{0, 1, 2, 3};
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return far[a] > far[b]; });
    for (std::size_t k : order) {
      const std::uint32_t ci = children[k];
      if (nodes[ci].present) stack_.emplace_back(ci, mask);
    }
  }

  // Neighbours. The same-level chunk across an edge tells the case by its state: drawn (same
  // level), refined (finer neighbours), or unseen, in which case the drawn coarser neighbour is
  // the first drawn ancestor (a culled or absent ancestor means nothing is drawn there). This
  // walks up at most the LOD difference instead of down from the root.
  const bool skirts = settings.crack_fix == CrackFix::kSkirts;
  for (SelectedChunk& s : sel.chunks) {
    const ChunkNode& c = nodes[s.index];
    const int level = c.level;
    ++sel.stats.chunks_per_level[static_cast<std::size_t>(level)];
    sel.stats.triangles += tree_->chunk(s.index).triangle_count;
    const std::int64_t side = std::int64_t{1} << level;
    for (int e = 0; e < 4; ++e) {
      std::int64_t nx = c.x, nz = c.z;
      switch (e) {
        case kWest: --nx; break;
        case kEast: ++nx; break;
        case kSouth: --nz; break;
        default: ++nz; break;
      }
      float worst = 0.0f;
      if (nx >= 0 && nz >= 0 && nx < side && nz < side) {
        std::uint32_t j = tree_->level_offset(level) + static_cast<std::uint32_t>(nz * side + nx);
        const std::uint8_t st = state_[j];
        if (st == kDrawn) {
          // A drawn chunk deviates from the field by at most its parent's bound (its own error,
          // or, while morphing, the parent surface it moves to).
          worst = nodes[j].parent_bound;
        } else if (st == kRefined) {
          // Finer neighbours: the largest level difference and, for skirts, their deviation,
          // probed at the middle of the edge (and at both ends for skirts).
          const std::int64_t size = tree_->chunk_size(level);
          const std::int64_t x0 = static_cast<std::int64_t>(c.x) * size, z0 = static_cast<std::int64_t>(c.z) * size;
          const std::array<std::int64_t, 3> along{size / 2, 0, size - 1};
          const std::size_t probes = skirts ? 3 : 1;
          for (std::size_t k = 0; k < probes; ++k) {
            std::int64_t cx = 0, cz = 0;
            switch (e) {
              case kWest: cx = x0 - 1; cz = z0 + along[k]; break;
              case kEast: cx = x0 + size; cz = z0 + along[k]; break;
              case kSouth: cx = x0 + along[k]; cz = z0 - 1; break;
              default: cx = x0 + along[k]; cz = z0 + size; break;
            }
            const std::uint32_t other = drawn_chunk_at_cell(cx, cz);
            if (other == kNoChunk) continue;
            worst = std::max(worst, nodes[other].parent_bound);
            if (k == 0) {
              sel.stats.max_level_difference = std::max(sel.stats.max_level_difference, nodes[other].level - level);
            }
          }
        } else if (st == kUnseen) {
          // Walk up to the drawn coarser chunk (also across absent padding chunks).
          std::uint32_t ax = static_cast<std::uint32_t>(nx), az = static_cast<std::uint32_t>(nz);
          for (int l = level - 1; l >= 0; --l) {
            ax >>= 1;
            az >>= 1;
            j = tree_->level_offset(l) + az * (1u << l) + ax;
            const std::uint8_t sa = state_[j];
            if (sa == kUnseen) continue;
            if (sa == kDrawn) {
              worst = nodes[j].parent_bound;
              s.coarser_neighbour[static_cast<std::size_t>(e)] = j;
              sel.stats.max_level_difference = std::max(sel.stats.max_level_difference, level - l);
            }
            break;
          }
        }
      }
      s.neighbour_error[static_cast<std::size_t>(e)] = worst;
    }
  }
  sel.stats.chunks = static_cast<std::uint32_t>(sel.chunks.size());
  sel.stats.cpu_ms = watch.elapsed_ms();
  return sel;
}

std::uint32_t LodSelector::drawn_chunk_at_cell(std::int64_t cx, std::int64_t cz) const {
  const std::int64_t n = tree_->root_intervals();
  if (cx < 0 || cz < 0 || cx >= n || cz >= n) return kNoChunk;
  if (tree_->chunk_count() == 0) return kNoChunk;
  // Descend level by level: the chunk holding the cell at level l is (cx, cz) >> (levels-1-l) in
  // units of the leaf size.
  const int levels = tree_->levels();
  const std::int64_t leaf = tree_->chunk_size(levels - 1);
  const std::int64_t lx = cx / leaf, lz = cz / leaf;
  for (int l = 0; l < levels; ++l) {
    const int shift = levels - 1 - l;
    const std::uint32_t side = 1u << l;
    const std::uint32_t i = tree_->level_offset(l) + static_cast<std::uint32_t>(lz >> shift) * side +
                            static_cast<std::uint32_t>(lx >> shift);
    const std::uint8_t st = state_[i];
    if (st == kDrawn) return i;
    if (st != kRefined) return kNoChunk;
  }
  return kNoChunk;
}

}  // namespace sylva::terrain

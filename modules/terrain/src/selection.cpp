#include <sylva/terrain/selection.hpp>

#include <sylva/core/timer.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace sylva::terrain {

LodSelector::LodSelector(const ChunkTree& tree) : tree_(&tree), state_(tree.chunk_count(), kUnseen) {}

bool LodSelector::accept(std::uint32_t index, const LodView& view, const LodSettings& settings, double* rho) const {
  const Chunk& c = tree_->chunk(index);
  *rho = 0.0;
  if (c.key.level + 1 >= tree_->levels()) return true;  // leaves are the finest there is
  glm::dvec3 lo, hi;
  tree_->chunk_bounds(index, lo, hi);
  if (settings.criterion == LodCriterion::kSeedDistance) {
    // Seed 002 §2.3: chunk_error = vertex spacing of the chunk, d = distance to its centre.
    const double chunk_error = static_cast<double>(tree_->step(c.key.level)) * tree_->spacing();
    const double d = glm::length(view.position - 0.5 * (lo + hi));
    *rho = chunk_error * static_cast<double>(settings.lod_distance) / std::max(d, 1e-9);
    return chunk_error * static_cast<double>(settings.lod_distance) <= d;
  }
  if (c.error_bound <= 0.0f) return true;
  const double delta = static_cast<double>(c.error_bound);
  // The drawn point lies in the box, the field point may lie up to delta outside it, so the
  // vertical error segment is at least D - delta away: rho = K * delta / (D - delta) <= tau,
  // written without dividing by a distance that may be 0 or negative.
  const double d = view.distance_to_box(lo, hi) - delta;
  *rho = d > 0.0 ? view.k * delta / d : 1e30;
  return d > 0.0 && view.k * delta <= static_cast<double>(settings.max_pixel_error) * d;
}

const Selection& LodSelector::select(const LodView& view, const LodSettings& settings, const Residency* residency) {
  Stopwatch watch;
  for (std::uint32_t i : touched_) state_[i] = kUnseen;
  touched_.clear();
  Selection& sel = selection_;
  sel.chunks.clear();
  sel.stats = SelectionStats{};
  sel.stats.chunks_per_level.assign(static_cast<std::size_t>(tree_->levels()), 0);
  sel.morph = settings.criterion == LodCriterion::kScreenSpaceError && settings.morph_fraction > 0.0f;
  sel.bound_certified = settings.criterion == LodCriterion::kScreenSpaceError &&
                        (!sel.morph || settings.morph_fraction <= tree_->settings().max_morph_fraction + 1e-6f);

  stack_.clear();
  if (tree_->chunk_count() > 0 && tree_->chunk(0).present) {
    if (residency == nullptr || residency->resident(0)) {
      stack_.push_back(0);
    } else {
      residency->request(0, 1e30);
    }
  }
  while (!stack_.empty()) {
    const std::uint32_t i = stack_.back();
    stack_.pop_back();
    touched_.push_back(i);
    ++sel.stats.visited;
    if (settings.frustum_cull) {
      glm::dvec3 lo, hi;
      tree_->chunk_bounds(i, lo, hi);
      if (!view.box_visible(lo, hi)) {
        state_[i] = kCulled;
        ++sel.stats.culled;
        continue;
      }
    }
    double rho = 0.0;
    bool draw = accept(i, view, settings, &rho);
    const auto children = draw ? std::array<std::uint32_t, 4>{} : tree_->child_indices(i);
    if (!draw && residency != nullptr) {
      // Refine only into resident children; otherwise draw this chunk and ask for them.
      bool all = true;
      for (std::uint32_t ci : children) {
        if (!tree_->chunk(ci).present || residency->resident(ci)) continue;
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
    for (int k = 3; k >= 0; --k) {
      const std::uint32_t ci = children[static_cast<std::size_t>(k)];
      if (tree_->chunk(ci).present) stack_.push_back(ci);
    }
  }

  // Neighbours: a coarser drawn neighbour covers the whole shared edge, so probing the cell just
  // across the middle of the edge finds it. Finer neighbours are found the same way for the
  // skirt depth (largest error along the edge is approximated by the probe and both ends).
  for (SelectedChunk& s : sel.chunks) {
    const Chunk& c = tree_->chunk(s.index);
    const int level = c.key.level;
    const std::int64_t size = tree_->chunk_size(level);
    const std::int64_t x0 = static_cast<std::int64_t>(c.key.x) * size, z0 = static_cast<std::int64_t>(c.key.z) * size;
    ++sel.stats.chunks_per_level[static_cast<std::size_t>(level)];
    sel.stats.triangles += c.triangle_count;
    for (int e = 0; e < 4; ++e) {
      std::array<std::int64_t, 3> along{size / 2, 0, size - 1};
      float worst = 0.0f;
      for (std::size_t k = 0; k < along.size(); ++k) {
        std::int64_t cx = 0, cz = 0;
        switch (e) {
          case kWest: cx = x0 - 1; cz = z0 + along[k]; break;
          case kEast: cx = x0 + size; cz = z0 + along[k]; break;
          case kSouth: cx = x0 + along[k]; cz = z0 - 1; break;
          default: cx = x0 + along[k]; cz = z0 + size; break;
        }
        const std::uint32_t other = drawn_chunk_at_cell(cx, cz);
        if (other == kNoChunk) continue;
        const Chunk& oc = tree_->chunk(other);
        // A drawn chunk deviates from the field by at most its parent's bound (its own error,
        // or, while morphing, the parent surface it moves to).
        const float deviation =
            oc.key.level > 0 ? tree_->chunk(tree_->parent_index(other)).error_bound : oc.error_bound;
        worst = std::max(worst, deviation);
        if (k == 0) {
          const int diff = std::abs(oc.key.level - level);
          sel.stats.max_level_difference = std::max(sel.stats.max_level_difference, diff);
          if (oc.key.level < level) s.coarser_neighbour[static_cast<std::size_t>(e)] = other;
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
  std::uint32_t i = 0;
  for (;;) {
    const std::uint8_t st = state_[i];
    if (st == kDrawn) return i;
    if (st != kRefined) return kNoChunk;
    const Chunk& c = tree_->chunk(i);
    const std::int64_t half = tree_->chunk_size(c.key.level) / 2;
    const std::int64_t x0 = static_cast<std::int64_t>(c.key.x) * 2 * half, z0 = static_cast<std::int64_t>(c.key.z) * 2 * half;
    const int qx = cx >= x0 + half ? 1 : 0, qz = cz >= z0 + half ? 1 : 0;
    i = tree_->child_indices(i)[static_cast<std::size_t>(qz * 2 + qx)];
  }
}

}  // namespace sylva::terrain

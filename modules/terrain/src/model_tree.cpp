#include <sylva/terrain/model_tree.hpp>

#include "parallel.hpp"

#include <sylva/core/assert.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/terrain/simplify.hpp>

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <unordered_map>

namespace sylva::terrain {

std::uint32_t ModelTree::index(int level, std::uint32_t x, std::uint32_t z) const {
  SYLVA_ASSERT(level >= 0 && level < levels_, "level={} levels={}", level, levels_);
  const std::uint32_t side = 1u << level;
  SYLVA_ASSERT(x < side && z < side, "segment ({}, {}) outside level {}", x, z, level);
  return level_offset_[static_cast<std::size_t>(level)] + z * side + x;
}

std::array<std::uint32_t, 4> ModelTree::child_indices(std::uint32_t i) const {
  const ChunkKey& k = segments_[i].key;
  SYLVA_ASSERT(k.level + 1 < levels_, "segment at level {} has no children", k.level);
  return {index(k.level + 1, 2 * k.x, 2 * k.z), index(k.level + 1, 2 * k.x + 1, 2 * k.z),
          index(k.level + 1, 2 * k.x, 2 * k.z + 1), index(k.level + 1, 2 * k.x + 1, 2 * k.z + 1)};
}

Result<ModelTree> ModelTree::build(const TriangleMesh& mesh, const ModelTreeSettings& settings,
                                   const BuildControl& control) {
  Stopwatch total;
  SYLVA_TRY(validate_params(settings, "terrain.model"));
  if (mesh.indices.empty() || mesh.indices.size() % 3 != 0) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("terrain.model: the mesh has {} indices (needs a non-zero multiple of 3)",
                                  mesh.indices.size()));
  }
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
    if (mesh.indices[i] >= mesh.positions.size()) {
      return make_error(ErrorCode::kInvalidArgument, fmt::format("terrain.model: index {} of triangle {} is {}, "
                                                                 "beyond the {} vertices", i % 3, i / 3,
                                                                 mesh.indices[i], mesh.positions.size()));
    }
  }
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      return make_error(ErrorCode::kInvalidArgument, fmt::format("terrain.model: vertex {} is not finite", i));
    }
  }
  ModelTree tree;
  tree.settings_ = settings;
  tree.levels_ = settings.levels;
  tree.positions_ = mesh.positions;
  const int threads = detail::resolve_threads(settings.threads);
  tree.report_.threads = threads;
  const int L = settings.levels;

  // Root square over the used vertices.
  glm::dvec2 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (std::uint32_t i : mesh.indices) {
    lo = glm::min(lo, glm::dvec2(mesh.positions[i].x, mesh.positions[i].z));
    hi = glm::max(hi, glm::dvec2(mesh.positions[i].x, mesh.positions[i].z));
  }
  tree.root_origin_ = lo;
  tree.root_size_ = std::max({hi.x - lo.x, hi.y - lo.y, 1e-6});
  const std::uint32_t leaf_side = 1u << (L - 1);
  const double leaf_size = tree.root_size_ / leaf_side;
  // Half-open leaf cell of a ground-plane point; the root's far edges belong to the last cell.
  auto cell_of = [&](double x, double z) {
    const auto c = [&](double v, double o) {
      const double f = std::floor((v - o) / leaf_size);
      return static_cast<std::uint32_t>(std::clamp(f, 0.0, static_cast<double>(leaf_side - 1)));
    };
    return glm::uvec2(c(x, lo.x), c(z, lo.y));
  };
  const std::size_t nt = mesh.triangle_count();
  std::vector<glm::uvec2> tri_cell(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                    c = mesh.positions[mesh.indices[3 * t + 2]];
    // Seed §4.1: the centroid in the ground plane decides the segment.
    tri_cell[t] = cell_of((static_cast<double>(a.x) + b.x + c.x) / 3.0, (static_cast<double>(a.z) + b.z + c.z) / 3.0);
  }
  std::vector<glm::uvec2> vert_cell(mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) vert_cell[v] = cell_of(mesh.positions[v].x, mesh.positions[v].z);
  std::vector<std::uint8_t> mesh_boundary(mesh.positions.size(), 0);
  if (settings.lock_mesh_boundary) {
    for (const auto& [a, b] : boundary_edges(mesh.indices)) mesh_boundary[a] = mesh_boundary[b] = 1;
  }

  std::uint32_t offset = 0;
  for (int l = 0; l < L; ++l) {
    tree.level_offset_.push_back(offset);
    offset += (1u << l) * (1u << l);
  }
  tree.segments_.resize(offset);
  std::vector<std::vector<std::uint32_t>> members(offset), locked(offset);
  for (int l = 0; l < L; ++l) {
    const int shift = L - 1 - l;
    for (std::uint32_t z = 0; z < (1u << l); ++z)
      for (std::uint32_t x = 0; x < (1u << l); ++x) tree.segments_[tree.index(l, x, z)].key = ChunkKey{l, x, z};
    for (std::uint32_t t = 0; t < nt; ++t) {
      const glm::uvec2 tc = tri_cell[t] >> static_cast<std::uint32_t>(shift);
      const std::uint32_t s = tree.index(l, tc.x, tc.y);
      members[s].push_back(t);
      // Seed §4.2: a vertex of a member triangle outside the segment (cases 1 and 2a), and a
      // vertex inside a segment used by a triangle of another segment (case 2b), are border
      // vertices.
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = mesh.indices[3 * t + static_cast<std::size_t>(k)];
        const glm::uvec2 vc = vert_cell[v] >> static_cast<std::uint32_t>(shift);
        if (vc != tc) {
          locked[s].push_back(v);
          locked[tree.index(l, vc.x, vc.y)].push_back(v);
        }
        if (mesh_boundary[v]) locked[s].push_back(v);
      }
    }
  }

  // Reduce every segment from the original triangles.
  std::mutex report_mutex;
  tree.report_.levels.resize(static_cast<std::size_t>(L));
  std::vector<std::uint32_t> order(offset);
  for (std::uint32_t i = 0; i < offset; ++i) order[i] = i;
  std::atomic<std::size_t> done{0};
  const bool finished = detail::parallel_for(order.size(), threads, [&](std::size_t oi) {
    const std::uint32_t si = order[oi];
    Segment& seg = tree.segments_[si];
    std::vector<std::uint32_t>& lk = locked[si];
    std::sort(lk.begin(), lk.end());
    lk.erase(std::unique(lk.begin(), lk.end()), lk.end());
    seg.locked_vertices = static_cast<std::uint32_t>(lk.size());
    seg.original_triangles = static_cast<std::uint32_t>(members[si].size());
    seg.present = !members[si].empty();
    if (!seg.present) return;
    std::vector<std::uint32_t> original;
    original.reserve(members[si].size() * 3);
    for (std::uint32_t t : members[si])
      for (int k = 0; k < 3; ++k) original.push_back(mesh.indices[3 * t + static_cast<std::size_t>(k)]);
    const int depth = L - 1 - seg.key.level;
    Stopwatch watch;
    if (depth == 0) {
      seg.indices = original;  // maximum detail (§4.4: leaves are not reduced)
    } else {
      thread_local std::vector<std::uint8_t> flags;
      flags.assign(tree.positions_.size(), 0);
      for (std::uint32_t v : lk) flags[v] = 1;
      const auto reduce = [&](const std::vector<std::uint32_t>& in, std::size_t target) {
        return settings.reducer == Reducer::kQem ? simplify_qem_passes(tree.positions_, in, flags, target)
                                                 : simplify_shortest_edge(tree.positions_, in, flags, target);
      };
      if (settings.reduce_per_pass > 0.0f) {
        // The seed's -reduce: `depth` passes, each removing that share of what is left.
        seg.indices = original;
        const double keep = 1.0 - static_cast<double>(settings.reduce_per_pass);
        for (int pass = 0; pass < depth; ++pass) {
          const std::size_t before = seg.indices.size() / 3;
          seg.indices = reduce(seg.indices, static_cast<std::size_t>(std::ceil(keep * static_cast<double>(before))));
          if (seg.indices.size() / 3 == before) break;  // nothing removable is left
        }
      } else {
        const double keep = std::pow(static_cast<double>(settings.keep_per_level), depth);
        seg.indices = reduce(original, static_cast<std::size_t>(std::ceil(keep * static_cast<double>(members[si].size()))));
      }
    }
    const double reduce_ms = watch.lap_ms();
    if (depth > 0) seg.error = static_cast<float>(hausdorff_distance(tree.positions_, original, seg.indices).max());
    const double measure_ms = watch.lap_ms();
    // Checks: the outline must be the original one (no holes), no degenerate/non-manifold
    // triangles, none flipped against the original surface.
    const MeshCheck check = check_mesh(tree.positions_, seg.indices);
    const std::size_t holes = boundary_edges(seg.indices) != boundary_edges(original) ? 1 : 0;
    const std::size_t flipped = count_flipped(tree.positions_, original, seg.indices);
    if (settings.optimize_vertex_cache && !seg.indices.empty()) {
      std::unordered_map<std::uint32_t, std::uint32_t> local;
      std::vector<std::uint32_t> global, li(seg.indices.size());
      for (std::size_t i = 0; i < seg.indices.size(); ++i) {
        auto [it, inserted] = local.try_emplace(seg.indices[i], static_cast<std::uint32_t>(global.size()));
        if (inserted) global.push_back(seg.indices[i]);
        li[i] = it->second;
      }
      std::vector<std::uint32_t> out(li.size());
      meshopt_optimizeVertexCache(out.data(), li.data(), li.size(), global.size());
      for (std::size_t i = 0; i < out.size(); ++i) seg.indices[i] = global[out[i]];
    }
    glm::vec3 blo(std::numeric_limits<float>::max()), bhi(-std::numeric_limits<float>::max());
    for (std::uint32_t v : seg.indices) {
      blo = glm::min(blo, tree.positions_[v]);
      bhi = glm::max(bhi, tree.positions_[v]);
    }
    seg.lo = blo;
    seg.hi = bhi;
    {
      std::lock_guard<std::mutex> lock(report_mutex);
      ModelLevelReport& r = tree.report_.levels[static_cast<std::size_t>(seg.key.level)];
      r.level = seg.key.level;
      ++r.segments;
      r.original_triangles += seg.original_triangles;
      r.triangles += seg.triangle_count();
      r.max_error = std::max(r.max_error, seg.error);
      r.reduce_ms += reduce_ms;
      r.measure_ms += measure_ms;
      tree.report_.holes += holes;
      tree.report_.degenerate += check.degenerate;
      tree.report_.non_manifold += check.non_manifold;
      tree.report_.flipped += flipped;
      const std::size_t d = ++done;
      if (control.progress) control.progress(static_cast<float>(d) / static_cast<float>(order.size()));
    }
  }, control.cancel);
  if (!finished) return make_error(ErrorCode::kCancelled, "terrain.model: build cancelled");
  for (int l = 0; l < L; ++l) tree.report_.levels[static_cast<std::size_t>(l)].level = l;

  // Monotone bounds, finest first.
  for (int l = L - 1; l >= 0; --l) {
    for (std::uint32_t i = tree.level_offset_[static_cast<std::size_t>(l)];
         i < tree.level_offset_[static_cast<std::size_t>(l)] + (1u << l) * (1u << l); ++i) {
      Segment& s = tree.segments_[i];
      float b = s.error;
      if (l + 1 < L)
        for (std::uint32_t c : tree.child_indices(i)) b = std::max(b, tree.segments_[c].error_bound);
      s.error_bound = b;
    }
  }
  tree.report_.total_ms = total.elapsed_ms();
  return tree;
}

ModelSelection select_segments(const ModelTree& tree, const LodView& view, const LodSettings& settings,
                               ModelSelection* unculled) {
  Stopwatch watch;
  ModelSelection sel;
  if (unculled != nullptr) *unculled = ModelSelection{};
  // A segment is in view while it and every ancestor pass the frustum test. With `unculled`, the
  // traversal goes on below a culled segment (its LOD decisions do not depend on the frustum),
  // feeding `unculled` only.
  struct Entry {
    std::uint32_t segment;
    bool in_view;
  };
  std::vector<Entry> stack;
  if (tree.segment_count() > 0 && tree.segment(0).present) stack.push_back({0, true});
  while (!stack.empty()) {
    const auto [i, parent_in_view] = stack.back();
    stack.pop_back();
    const Segment& s = tree.segment(i);
    const glm::dvec3 lo(s.lo), hi(s.hi);
    bool in_view = parent_in_view;
    const glm::dvec3 margin(s.error_bound);
    if (in_view && settings.frustum_cull && !view.box_visible(lo - margin, hi + margin)) {
      ++sel.culled;
      in_view = false;
    }
    if (!in_view && unculled == nullptr) continue;
    bool accept = s.key.level + 1 >= tree.levels() || s.error_bound <= 0.0f;
    if (!accept) {
      const double delta = s.error_bound;
      const double d = view.distance_to_box(lo, hi) - delta;
      accept = d > 0.0 && view.k * delta <= static_cast<double>(settings.max_pixel_error) * d;
    }
    if (accept) {
      if (in_view) {
        sel.segments.push_back(i);
        sel.triangles += s.triangle_count();
      }
      if (unculled != nullptr) {
        unculled->segments.push_back(i);
        unculled->triangles += s.triangle_count();
      }
      continue;
    }
    const auto children = tree.child_indices(i);
    for (int k = 3; k >= 0; --k) {
      const std::uint32_t c = children[static_cast<std::size_t>(k)];
      if (tree.segment(c).present) stack.push_back({c, in_view});
    }
  }
  sel.cpu_ms = watch.elapsed_ms();
  if (unculled != nullptr) unculled->cpu_ms = sel.cpu_ms;
  return sel;
}

}  // namespace sylva::terrain

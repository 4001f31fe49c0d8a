#include <sylva/terrain/simplify.hpp>

#include "quadric.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace sylva::terrain {

namespace {

using detail::Quadric;

struct Candidate {
  float cost;
  std::uint32_t v, u;  // collapse v into u
};

}  // namespace

// Same collapse rules as simplify_qem (simplify_qem.cpp), organised in passes like the seed's
// reduction (§4.3) instead of a priority queue: each pass computes the best collapse of every
// edge, keeps the cheapest as many as are still needed, and walks them in cost order accepting
// every valid collapse whose neighbourhood no earlier collapse of the pass touched (so all the
// checks of a pass see the pass-start mesh, as the seed's flags do). Vertices on an open
// boundary are treated as locked.
std::vector<std::uint32_t> simplify_qem_passes(std::span<const glm::vec3> positions,
                                               std::span<const std::uint32_t> indices,
                                               std::span<const std::uint8_t> locked_in,
                                               std::size_t target_triangles, SimplifyStats* stats) {
  // Compact the used vertices (a reused global-size map, reset after).
  thread_local std::vector<std::uint32_t> local_of;
  if (local_of.size() < positions.size()) local_of.assign(positions.size(), 0xFFFFFFFFu);
  std::vector<std::uint32_t> global;
  global.reserve(indices.size() / 2);
  std::vector<std::array<std::uint32_t, 3>> tris(indices.size() / 3);
  for (std::size_t t = 0; t < tris.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t g = indices[3 * t + static_cast<std::size_t>(k)];
      if (local_of[g] == 0xFFFFFFFFu) {
        local_of[g] = static_cast<std::uint32_t>(global.size());
        global.push_back(g);
      }
      tris[t][static_cast<std::size_t>(k)] = local_of[g];
    }
  }
  for (std::uint32_t g : global) local_of[g] = 0xFFFFFFFFu;
  const std::size_t nv = global.size();
  std::vector<glm::dvec3> pos(nv);
  std::vector<std::uint8_t> locked(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    pos[i] = glm::dvec3(positions[global[i]]);
    locked[i] = locked_in[global[i]];
  }
  std::vector<Quadric> q(nv);
  std::vector<glm::dvec3> surface_normal(nv, glm::dvec3(0.0));
  for (const auto& tr : tris) {
    const glm::dvec3 n = glm::cross(pos[tr[1]] - pos[tr[0]], pos[tr[2]] - pos[tr[0]]);
    const double len = glm::length(n);
    if (len > 0.0) {
      const glm::dvec3 nn = n / len;
      const double d = -glm::dot(nn, pos[tr[0]]);
      for (std::uint32_t v : tr) q[v].add_plane(nn, d, 0.5 * len);
    }
    for (std::uint32_t v : tr) surface_normal[v] += n;
  }

  SimplifyStats st;
  std::vector<std::uint32_t> offset(nv + 1), adj, fill(nv), mark(nv, 0), remap(nv);
  std::vector<std::uint8_t> touched(nv);
  std::vector<Candidate> cand;
  std::uint32_t mark_id = 0;
  const double cos_limit = 0.35;
  // Open-boundary vertices (an edge used once) are locked. Computed once: with locked boundary
  // vertices and the link condition, collapses never create or remove boundary edges.
  {
    std::vector<std::uint64_t> half(3 * tris.size()), twin(3 * tris.size());
    for (std::size_t t = 0; t < tris.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const std::uint64_t a = tris[t][static_cast<std::size_t>(k)], b = tris[t][static_cast<std::size_t>((k + 1) % 3)];
        half[3 * t + static_cast<std::size_t>(k)] = (a << 32) | b;
        twin[3 * t + static_cast<std::size_t>(k)] = (b << 32) | a;
      }
    std::sort(half.begin(), half.end());
    for (std::uint64_t e : twin) {
      if (std::binary_search(half.begin(), half.end(), e)) continue;
      locked[static_cast<std::size_t>(e >> 32)] = 1;  // e is b->a of an unmatched a->b
      locked[static_cast<std::size_t>(e & 0xFFFFFFFFu)] = 1;
    }
  }
  while (tris.size() > target_triangles) {
    ++st.passes;
    // Vertex -> triangle adjacency of the current mesh (CSR).
    std::fill(offset.begin(), offset.end(), 0u);
    for (const auto& tr : tris)
      for (std::uint32_t v : tr) ++offset[v + 1];
    for (std::size_t i = 0; i < nv; ++i) offset[i + 1] += offset[i];
    adj.resize(offset[nv]);
    std::copy(offset.begin(), offset.end() - 1, fill.begin());
    for (std::uint32_t t = 0; t < tris.size(); ++t)
      for (std::uint32_t v : tris[t]) adj[fill[v]++] = t;
    // Best collapse of every edge (each interior edge once: from the half-edge with a < b).
    cand.clear();
    for (const auto& tr : tris) {
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = tr[static_cast<std::size_t>(k)], b = tr[static_cast<std::size_t>((k + 1) % 3)];
        if (a > b) continue;
        const bool free_a = !locked[a], free_b = !locked[b];
        if (!free_a && !free_b) continue;
        const double ca = free_a ? q[a].error_sum(q[b], pos[b]) : 1e300;  // a into b
        const double cb = free_b ? q[b].error_sum(q[a], pos[a]) : 1e300;  // b into a
        if (ca <= cb) {
          cand.push_back({static_cast<float>(std::max(ca, 0.0)), a, b});
        } else {
          cand.push_back({static_cast<float>(std::max(cb, 0.0)), b, a});
        }
      }
    }
    if (cand.empty()) break;
    // Only the cheapest candidates compete in this pass (a collapse removes about two triangles).
    const std::size_t needed = (tris.size() - target_triangles + 1) / 2;
    // Three times as many candidates as collapses still needed: the touched rule blocks many, so
    // this fills a pass with the next cheapest independent collapses and halves the pass count.
    const std::size_t keep = std::min(cand.size(), std::max<std::size_t>(3 * needed, 64));
    auto by_cost = [](const Candidate& x, const Candidate& y) { return x.cost < y.cost; };
    if (keep < cand.size()) std::nth_element(cand.begin(), cand.begin() + static_cast<std::ptrdiff_t>(keep), cand.end(), by_cost);
    cand.resize(keep);
    std::sort(cand.begin(), cand.end(), by_cost);

    std::fill(touched.begin(), touched.end(), std::uint8_t{0});
    for (std::size_t i = 0; i < nv; ++i) remap[i] = static_cast<std::uint32_t>(i);
    std::size_t removed = 0, accepted = 0;
    for (const Candidate& c : cand) {
      if (tris.size() - removed <= target_triangles) break;
      const std::uint32_t v = c.v, u = c.u;
      if (touched[v] || touched[u]) continue;
      // Link condition: common neighbours == triangles on the edge.
      ++mark_id;
      std::size_t shared = 0;
      for (std::uint32_t i = offset[v]; i < offset[v + 1]; ++i) {
        const auto& tr = tris[adj[i]];
        if (tr[0] == u || tr[1] == u || tr[2] == u) ++shared;
        for (std::uint32_t w : tr)
          if (w != v) mark[w] = mark_id;
      }
      std::size_t common = 0;
      ++mark_id;  // count each common neighbour once
      for (std::uint32_t i = offset[u]; i < offset[u + 1]; ++i) {
        for (std::uint32_t w : tris[adj[i]]) {
          if (w == u || mark[w] != mark_id - 1) continue;
          mark[w] = mark_id;
          ++common;
        }
      }
      if (shared == 0 || common != shared) {
        ++st.rejected;
        continue;
      }
      bool ok = true;
      for (std::uint32_t i = offset[v]; i < offset[v + 1] && ok; ++i) {
        const auto& tr = tris[adj[i]];
        if (tr[0] == u || tr[1] == u || tr[2] == u) continue;
        glm::dvec3 p[3], r[3];
        glm::dvec3 ref(0.0);
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t w = tr[static_cast<std::size_t>(k)];
          p[k] = pos[w];
          r[k] = w == v ? pos[u] : p[k];
          ref += surface_normal[w == v ? u : w];
        }
        const glm::dvec3 n0 = glm::cross(p[1] - p[0], p[2] - p[0]);
        const glm::dvec3 e1 = r[1] - r[0], e2 = r[2] - r[0];
        const glm::dvec3 n1 = glm::cross(e1, e2);
        const double l1 = glm::dot(n1, n1);
        if (l1 <= 1e-10 * glm::dot(e1, e1) * glm::dot(e2, e2)) ok = false;
        else if (glm::dot(n0, n1) <= cos_limit * std::sqrt(glm::dot(n0, n0) * l1)) ok = false;
        else if (glm::dot(n1, ref) <= 0.0) ok = false;
      }
      if (!ok) {
        ++st.rejected;
        continue;
      }
      touched[v] = touched[u] = 1;
      for (std::uint32_t i = offset[v]; i < offset[v + 1]; ++i)
        for (std::uint32_t w : tris[adj[i]]) touched[w] = 1;
      remap[v] = u;
      q[u] += q[v];
      removed += shared;
      ++accepted;
    }
    if (accepted == 0) break;
    st.collapses += accepted;
    std::size_t out = 0;
    for (std::size_t t = 0; t < tris.size(); ++t) {
      std::array<std::uint32_t, 3> tr{remap[tris[t][0]], remap[tris[t][1]], remap[tris[t][2]]};
      if (tr[0] == tr[1] || tr[1] == tr[2] || tr[0] == tr[2]) continue;
      tris[out++] = tr;
    }
    tris.resize(out);
  }
  if (stats) *stats = st;
  std::vector<std::uint32_t> result;
  result.reserve(tris.size() * 3);
  for (const auto& tr : tris)
    for (std::uint32_t v : tr) result.push_back(global[v]);
  return result;
}

}  // namespace sylva::terrain

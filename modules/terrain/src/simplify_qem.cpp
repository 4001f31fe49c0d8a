#include <sylva/terrain/simplify.hpp>

#include "quadric.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <queue>
#include <unordered_map>

namespace sylva::terrain {

namespace {

using detail::Quadric;

struct Candidate {
  double cost;
  std::uint32_t v, u;        // collapse v into u
  std::uint32_t sv, su;      // stamps at push time
  bool operator<(const Candidate& o) const { return cost > o.cost; }  // min-heap
};

}  // namespace

std::vector<std::uint32_t> simplify_qem(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices,
                                        std::span<const std::uint8_t> locked_in, std::size_t target_triangles,
                                        SimplifyStats* stats) {
  // Compact the used vertices to local ids.
  std::unordered_map<std::uint32_t, std::uint32_t> local_of;
  std::vector<std::uint32_t> global;
  local_of.reserve(indices.size());
  std::vector<std::array<std::uint32_t, 3>> tris(indices.size() / 3);
  for (std::size_t t = 0; t < tris.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t g = indices[3 * t + static_cast<std::size_t>(k)];
      auto [it, inserted] = local_of.try_emplace(g, static_cast<std::uint32_t>(global.size()));
      if (inserted) global.push_back(g);
      tris[t][static_cast<std::size_t>(k)] = it->second;
    }
  }
  const std::size_t nv = global.size();
  std::vector<glm::dvec3> pos(nv);
  std::vector<std::uint8_t> locked(nv), dead_v(nv, 0);
  for (std::size_t i = 0; i < nv; ++i) {
    pos[i] = glm::dvec3(positions[global[i]]);
    locked[i] = locked_in[global[i]];
  }
  std::vector<Quadric> q(nv);
  // Area-weighted normals of the original surface at each vertex: a collapse may not leave a
  // triangle facing against the original surface around its corners.
  std::vector<glm::dvec3> surface_normal(nv, glm::dvec3(0.0));
  std::vector<std::vector<std::uint32_t>> vt(nv);
  std::vector<std::uint8_t> dead_t(tris.size(), 0);
  std::size_t alive = tris.size();
  for (std::uint32_t t = 0; t < tris.size(); ++t) {
    const auto& tr = tris[t];
    const glm::dvec3 n = glm::cross(pos[tr[1]] - pos[tr[0]], pos[tr[2]] - pos[tr[0]]);
    const double len = glm::length(n);
    if (len > 0.0) {
      const glm::dvec3 nn = n / len;
      const double d = -glm::dot(nn, pos[tr[0]]);
      for (std::uint32_t v : tr) q[v].add_plane(nn, d, 0.5 * len);
    }
    for (std::uint32_t v : tr) {
      vt[v].push_back(t);
      surface_normal[v] += n;
    }
  }
  std::vector<std::uint32_t> stamp(nv, 0);
  std::priority_queue<Candidate> heap;
  auto push = [&](std::uint32_t v, std::uint32_t u) {
    if (locked[v] || dead_v[v] || dead_v[u]) return;
    Quadric s = q[v];
    s += q[u];
    heap.push(Candidate{std::max(0.0, s.error(pos[u])), v, u, stamp[v], stamp[u]});
  };
  for (const auto& tr : tris) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = tr[static_cast<std::size_t>(k)], b = tr[static_cast<std::size_t>((k + 1) % 3)];
      push(a, b);
      push(b, a);
    }
  }

  std::vector<std::uint32_t> mark(nv, 0);
  std::uint32_t mark_id = 0;
  std::vector<std::uint32_t> nbr_v, nbr_u;
  SimplifyStats st;
  auto neighbours = [&](std::uint32_t v, std::vector<std::uint32_t>& out) {
    out.clear();
    for (std::uint32_t t : vt[v]) {
      if (dead_t[t]) continue;
      for (std::uint32_t w : tris[t])
        if (w != v) out.push_back(w);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  };
  const double cos_limit = 0.35;  // refuse normals turning by more than ~70 degrees

  while (alive > target_triangles && !heap.empty()) {
    const Candidate c = heap.top();
    heap.pop();
    if (dead_v[c.v] || dead_v[c.u] || stamp[c.v] != c.sv || stamp[c.u] != c.su) continue;
    const std::uint32_t v = c.v, u = c.u;
    // Link condition: the common neighbours of v and u are exactly the apexes of the triangles
    // on the edge v-u.
    std::size_t shared_tris = 0;
    for (std::uint32_t t : vt[v]) {
      if (dead_t[t]) continue;
      const auto& tr = tris[t];
      if (tr[0] == u || tr[1] == u || tr[2] == u) ++shared_tris;
    }
    if (shared_tris == 0) continue;  // no longer an edge
    neighbours(v, nbr_v);
    neighbours(u, nbr_u);
    ++mark_id;
    for (std::uint32_t w : nbr_v) mark[w] = mark_id;
    std::size_t common = 0;
    for (std::uint32_t w : nbr_u) common += mark[w] == mark_id;
    if (common != shared_tris) {
      ++st.rejected;
      continue;
    }
    // Geometry: no flip, no degenerate, no large normal change.
    bool ok = true;
    for (std::uint32_t t : vt[v]) {
      if (dead_t[t]) continue;
      const auto& tr = tris[t];
      if (tr[0] == u || tr[1] == u || tr[2] == u) continue;
      glm::dvec3 p[3], r[3];
      for (int k = 0; k < 3; ++k) {
        p[k] = pos[tr[static_cast<std::size_t>(k)]];
        r[k] = tr[static_cast<std::size_t>(k)] == v ? pos[u] : p[k];
      }
      const glm::dvec3 n0 = glm::cross(p[1] - p[0], p[2] - p[0]);
      const glm::dvec3 e1 = r[1] - r[0], e2 = r[2] - r[0];
      const glm::dvec3 n1 = glm::cross(e1, e2);
      const double l1 = glm::dot(n1, n1);
      if (l1 <= 1e-10 * glm::dot(e1, e1) * glm::dot(e2, e2)) { ok = false; break; }
      const double l0 = glm::dot(n0, n0);
      if (glm::dot(n0, n1) <= cos_limit * std::sqrt(l0 * l1)) { ok = false; break; }
      glm::dvec3 ref(0.0);
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t w = tr[static_cast<std::size_t>(k)] == v ? u : tr[static_cast<std::size_t>(k)];
        ref += surface_normal[w];
      }
      if (glm::dot(n1, ref) <= 0.0) { ok = false; break; }
    }
    if (!ok) {
      ++st.rejected;
      continue;
    }
    // Apply.
    for (std::uint32_t t : vt[v]) {
      if (dead_t[t]) continue;
      auto& tr = tris[t];
      if (tr[0] == u || tr[1] == u || tr[2] == u) {
        dead_t[t] = 1;
        --alive;
      } else {
        for (auto& w : tr)
          if (w == v) w = u;
        vt[u].push_back(t);
      }
    }
    dead_v[v] = 1;
    vt[v].clear();
    q[u] += q[v];
    ++stamp[u];
    ++st.collapses;
    // Drop dead triangles from u's list now and then to keep it short.
    if (vt[u].size() > 32) {
      vt[u].erase(std::remove_if(vt[u].begin(), vt[u].end(), [&](std::uint32_t t) { return dead_t[t] != 0; }),
                  vt[u].end());
    }
    neighbours(u, nbr_u);
    for (std::uint32_t w : nbr_u) {
      push(u, w);
      push(w, u);
    }
  }
  if (stats) *stats = st;
  std::vector<std::uint32_t> out;
  out.reserve(alive * 3);
  for (std::size_t t = 0; t < tris.size(); ++t) {
    if (dead_t[t]) continue;
    for (std::uint32_t v : tris[t]) out.push_back(global[v]);
  }
  return out;
}

}  // namespace sylva::terrain

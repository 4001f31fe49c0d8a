#include <sylva/terrain/simplify.hpp>

#include "quadric.hpp"
#include "simplify_flip.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <utility>

namespace sylva::terrain {

namespace {

using detail::build_fans;
using detail::Corner;
using detail::kCosLimit;
using detail::Quadric;

constexpr std::uint32_t kNone = 0xFFFFFFFFu;
// A pass stops past kGoalFactor x the cost of the goal-th proposal (once a sixth of the goal is
// done). Measured against meshoptimizer 1.2 on the bunny, armadillo, dragon and terrain segments at
// 25 % and 5 % (README "vs meshoptimizer 1.2"): 1.3 / 1.5 / 2.0 cost passes or error; 1.4 kept
// the dragon's passes at the bunny's.
constexpr float kGoalFactor = 1.4f;
// A vertex whose target is taken or whose collapse is invalid proposes its next best target at
// most this often per pass: 1 left the dragon a pass behind the bunny, 4 gained nothing.
constexpr std::uint8_t kRetries = 2;

// Work arrays reused by every call on a thread (a model tree reduces thousands of segments; the
// benchmark 16 per iteration), so a call allocates only its result once they have grown.
struct Scratch {
  std::vector<std::uint32_t> local_of;  // global vertex -> local id, kNone outside a call
  std::vector<std::uint32_t> global;    // local -> global
  std::vector<std::uint32_t> tris;      // current triangles, 3 local ids each
  std::vector<std::uint32_t> offset;    // CSR vertex -> corners of the pass-start mesh
  std::vector<Corner> fans;
  std::vector<std::uint32_t> remap;     // collapses of the current pass: v -> u, else v
  std::vector<std::uint32_t> mark;      // link-condition stamps
  std::vector<std::uint32_t> target;    // best collapse target of each free vertex
  std::vector<std::uint8_t> locked;     // caller's locks + open boundary
  std::vector<std::uint8_t> busy;       // source or target of a collapse this pass
  std::vector<Quadric> q;
  std::vector<double> weight;           // sum of the plane weights in q[v]
  std::vector<std::uint32_t> banned;    // target whose collapse was last found invalid, else kNone
  std::vector<std::uint8_t> tries;      // re-proposals of the vertex in this pass
  std::vector<std::uint64_t> retry;     // min-heap of re-proposal keys
  // Positions and normals in float (the input is float; geometry is evaluated in double): small
  // per-vertex records keep the cost-ordered walk, which visits vertices randomly, in cache.
  std::vector<glm::vec3> pos;
  std::vector<glm::vec3> normal;        // area-weighted original surface normal (rounded sum)
  std::vector<glm::dvec3> normal_sum;   // its exact accumulation
  std::vector<std::uint64_t> keys, keys_tmp;  // (cost bits << 32) | vertex
  // For the edge-flip repair after the passes (simplify_flip.hpp): the original vertices each
  // vertex absorbed (a chain through absorbed_next, its end in absorbed_last) and the input's fans.
  std::vector<std::uint32_t> absorbed_next, absorbed_last;
  std::vector<std::uint32_t> original_offset;
  std::vector<Corner> original_fans;
  detail::FlipScratch flip;
};

Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

// LSD radix sort of 64-bit keys by their upper 31 bits (non-negative float costs): three passes
// of 11 bits. Ties keep vertex order, so the result is deterministic.
void sort_by_cost(std::vector<std::uint64_t>& keys, std::vector<std::uint64_t>& tmp) {
  tmp.resize(keys.size());
  std::uint32_t count[2048];
  for (int shift = 32; shift < 64; shift += 11) {
    std::memset(count, 0, sizeof(count));
    for (std::uint64_t k : keys) ++count[(k >> shift) & 2047u];
    std::uint32_t sum = 0;
    for (std::uint32_t& c : count) {
      const std::uint32_t n = c;
      c = sum;
      sum += n;
    }
    for (std::uint64_t k : keys) tmp[count[(k >> shift) & 2047u]++] = k;
    keys.swap(tmp);
  }
}

std::uint64_t cost_key(double cost, std::uint32_t v) {
  const float f = static_cast<float>(std::max(cost, 0.0));
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof(bits));
  return (static_cast<std::uint64_t>(bits) << 32) | v;
}

float key_cost(std::uint64_t key) {
  const std::uint32_t bits = static_cast<std::uint32_t>(key >> 32);
  float f;
  std::memcpy(&f, &bits, sizeof(f));
  return f;
}

// v's cheapest half-edge collapse on the pass-start fan: the cost of moving v onto u is
// Q_v(p_u) / (sum of Q_v's plane weights), the mean squared distance of p_u to the planes v
// stands for (meshoptimizer's normalisation; the queue reducer's area-weighted (Q_v + Q_u)(p_u)
// lets small triangles go first and raised the Hausdorff error by up to 1.7x on scans). Skips
// `exclude` and, when asked, targets already busy in this pass. Returns (cost, kNone) when no
// target is left.
std::pair<double, std::uint32_t> cheapest_target(const Scratch& s, std::uint32_t v, std::uint32_t exclude,
                                                 bool skip_busy) {
  double best = std::numeric_limits<double>::max();
  std::uint32_t best_u = kNone;
  const Quadric& qv = s.q[v];
  const double inv_weight = s.weight[v] > 0.0 ? 1.0 / s.weight[v] : 0.0;
  for (std::uint32_t i = s.offset[v]; i < s.offset[v + 1]; ++i) {
    const std::uint32_t u = s.fans[i].next;
    if (u == exclude || (skip_busy && s.busy[u])) continue;
    const double c = qv.error(glm::dvec3(s.pos[u])) * inv_weight;
    if (c < best) {
      best = c;
      best_u = u;
    }
  }
  return {best, best_u};
}

}  // namespace

// The collapse rules of simplify_qem (simplify_qem.cpp) organised in passes, in the spirit of the
// seed's reduction (§4.3) and of meshoptimizer's simplifier, but with every validity test exact:
//  * each free vertex proposes its cheapest half-edge collapse (cost Q_v(p_u) / weight(Q_v), see
//    cheapest_target), skipping the target whose collapse it last found invalid;
//  * the proposals are radix-sorted by cost and walked in order; when the target of a collapse
//    already took part in a collapse of this pass, or the collapse is invalid, the source
//    proposes its next cheapest target (at most kRetries times, merged into the walk in cost
//    order); the walk stops at the triangle target, or once past kGoalFactor x the cost of the
//    goal-th proposal and the largest cost accepted so far (with at least a sixth of the goal
//    done, so odd topology cannot stall a pass);
//  * the link condition and the geometric tests (degenerate, flip / 70 degree turn, facing against
//    the original surface) are evaluated on the *current* mesh: the pass-start adjacency seen
//    through this pass's remap table. Since sources and targets are never reused within a pass,
//    a vertex's triangles in the current mesh are exactly its pass-start triangles remapped, minus
//    the ones that became degenerate, so every accepted collapse is valid on the mesh it applies
//    to, exactly as in the queue reducer.
// Vertices on an open boundary are treated as locked (computed once: with locked boundary
// vertices and the link condition, collapses never create or remove boundary edges).
std::vector<std::uint32_t> simplify_qem_passes(std::span<const glm::vec3> positions,
                                               std::span<const std::uint32_t> indices,
                                               std::span<const std::uint8_t> locked_in,
                                               std::size_t target_triangles, SimplifyStats* stats) {
  Scratch& s = scratch();
  // Compact the used vertices (the global-size map is reset after use).
  if (s.local_of.size() < positions.size()) s.local_of.assign(positions.size(), kNone);
  s.global.clear();
  s.tris.resize(indices.size() - indices.size() % 3);
  for (std::size_t i = 0; i < s.tris.size(); ++i) {
    const std::uint32_t g = indices[i];
    std::uint32_t& l = s.local_of[g];
    if (l == kNone) {
      l = static_cast<std::uint32_t>(s.global.size());
      s.global.push_back(g);
    }
    s.tris[i] = l;
  }
  for (std::uint32_t g : s.global) s.local_of[g] = kNone;
  const std::size_t nv = s.global.size();
  s.pos.resize(nv);
  s.locked.resize(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    s.pos[i] = positions[s.global[i]];
    s.locked[i] = locked_in[s.global[i]] != 0;
  }
  s.q.assign(nv, Quadric{});
  s.normal_sum.assign(nv, glm::dvec3(0.0));
  s.weight.assign(nv, 0.0);
  for (std::size_t t = 0; t < s.tris.size(); t += 3) {
    const std::uint32_t a = s.tris[t], b = s.tris[t + 1], c = s.tris[t + 2];
    const glm::dvec3 pa(s.pos[a]);
    const glm::dvec3 n = glm::cross(glm::dvec3(s.pos[b]) - pa, glm::dvec3(s.pos[c]) - pa);
    const double len = glm::length(n);
    if (len > 0.0) {
      const glm::dvec3 nn = n / len;
      const double d = -glm::dot(nn, pa);
      // Weight sqrt(area), as meshoptimizer 1.x: the normalised cost below is then a mean squared
      // distance in which a large triangle counts like a length, not an area (better silhouettes).
      const double w = std::sqrt(0.5 * len);
      for (std::uint32_t v : {a, b, c}) {
        s.q[v].add_plane(nn, d, w);
        s.weight[v] += w;
      }
    }
    for (std::uint32_t v : {a, b, c}) s.normal_sum[v] += n;
  }
  s.normal.resize(nv);
  for (std::size_t i = 0; i < nv; ++i) s.normal[i] = glm::vec3(s.normal_sum[i]);

  build_fans(s.tris, nv, s.offset, s.fans);
  // Open boundary: a vertex is interior when its fan is closed, i.e. the vertices following it in
  // its triangles are the vertices preceding it (an edge a->b without b->a leaves b unmatched in
  // a's fan). Locked vertices need no test: an open edge locks both its ends, and each end sees
  // the edge in its own fan. Set membership by stamps (O(fan) per vertex; comparing every corner
  // with every other cost ~8 % of the whole reduction on the dragon).
  s.mark.assign(nv, 0u);
  std::uint32_t mark_id = 0;
  for (std::uint32_t a = 0; a < nv; ++a) {
    if (s.locked[a]) continue;
    const Corner* f = s.fans.data() + s.offset[a];
    const std::size_t n = s.offset[a + 1] - s.offset[a];
    mark_id += 2;
    for (std::size_t i = 0; i < n; ++i) s.mark[f[i].prev] = mark_id;
    bool closed = true;
    for (std::size_t i = 0; i < n; ++i) closed &= s.mark[f[i].next] == mark_id;
    for (std::size_t i = 0; i < n; ++i) s.mark[f[i].next] = mark_id + 1;
    for (std::size_t i = 0; i < n; ++i) closed &= s.mark[f[i].prev] == mark_id + 1;
    if (!closed) s.locked[a] = 1;
  }

  SimplifyStats st;
  s.remap.resize(nv);
  s.busy.resize(nv);
  s.target.resize(nv);
  std::size_t triangles = s.tris.size() / 3;
  bool first = true;
  float max_cost = 0.0f;
  s.banned.assign(nv, kNone);
  s.tries.resize(nv);
  s.absorbed_next.assign(nv, kNone);
  s.absorbed_last.resize(nv);
  for (std::uint32_t v = 0; v < nv; ++v) s.absorbed_last[v] = v;
  while (triangles > target_triangles) {
    ++st.passes;
    if (!first) {
      // The input's fans move aside for the repair (no copy), their buffers take this pass's.
      if (st.passes == 2) {
        s.original_offset.swap(s.offset);
        s.original_fans.swap(s.fans);
      }
      build_fans(s.tris, nv, s.offset, s.fans);
    }
    first = false;
    const Corner* fans = s.fans.data();
    // Every free vertex proposes its cheapest collapse. Boundary vertices are locked, so a free
    // vertex has a closed fan and each neighbour is the successor of v in exactly one triangle.
    s.keys.clear();
    for (std::uint32_t v = 0; v < nv; ++v) {
      s.remap[v] = v;
      s.busy[v] = 0;
      s.tries[v] = 0;
      if (s.locked[v] || s.offset[v] == s.offset[v + 1]) continue;
      const auto [best, best_u] = cheapest_target(s, v, s.banned[v], false);
      if (best_u == kNone) continue;
      s.target[v] = best_u;
      s.keys.push_back(cost_key(best, v));
    }
    if (s.keys.empty()) break;
    sort_by_cost(s.keys, s.keys_tmp);
    const std::size_t goal_triangles = triangles - target_triangles;
    const std::size_t goal_collapses = std::max<std::size_t>(1, goal_triangles / 2);
    // The pass's error goal: kGoalFactor x the goal-th proposal's cost. An invalid proposal moves
    // the goal index on (it must not count as an expected collapse; without this the dragon took
    // 32 passes, each removing a sixth of the rest), and a cost up to the largest accepted so far
    // never stops the walk (it adds no error beyond what the result already has).
    std::size_t goal_index = goal_collapses;
    auto error_goal = [&] {
      return goal_index < s.keys.size() ? kGoalFactor * key_cost(s.keys[goal_index])
                                        : std::numeric_limits<float>::max();
    };
    float goal_cost = error_goal();
    std::size_t removed = 0, accepted = 0;
    const std::size_t n_keys = s.keys.size();
    // Re-proposals (a vertex whose target became busy or whose collapse was invalid proposes its
    // best remaining target) are merged into the walk from a min-heap; a re-proposal costs at
    // least the proposal it replaces (unless it picks a target banned in an earlier pass), so the
    // walk stays in cost order. The costs stay exact: quadrics only change after the walk.
    s.retry.clear();
    auto repropose = [&](std::uint32_t v, std::uint32_t exclude) {
      if (s.tries[v] >= kRetries) return;
      ++s.tries[v];
      const auto [best, best_u] = cheapest_target(s, v, exclude, true);
      if (best_u == kNone) return;
      s.target[v] = best_u;
      s.retry.push_back(cost_key(best, v));
      std::push_heap(s.retry.begin(), s.retry.end(), std::greater<>());
    };
    std::size_t k = 0;
    for (;;) {
      std::uint64_t key;
      if (!s.retry.empty() && (k >= n_keys || s.retry.front() < s.keys[k])) {
        key = s.retry.front();
        std::pop_heap(s.retry.begin(), s.retry.end(), std::greater<>());
        s.retry.pop_back();
      } else if (k < n_keys) {
        key = s.keys[k++];
      } else {
        break;
      }
      if (removed >= goal_triangles) break;
      const float cost = key_cost(key);
      if (cost > goal_cost && cost > max_cost && removed > goal_triangles / 6) break;
      // The walk visits vertices in cost order, i.e. at random: fetch the records of the
      // candidates a few steps ahead (their CSR offsets first, then their corners).
      if (k + 16 < n_keys) {
        const std::uint32_t w = static_cast<std::uint32_t>(s.keys[k + 16] & 0xFFFFFFFFu);
        __builtin_prefetch(&s.offset[w]);
        __builtin_prefetch(&s.target[w]);
        __builtin_prefetch(&s.busy[w]);
      }
      if (k + 8 < n_keys) {
        const std::uint32_t w = static_cast<std::uint32_t>(s.keys[k + 8] & 0xFFFFFFFFu);
        __builtin_prefetch(&fans[s.offset[w]]);
        __builtin_prefetch(&s.remap[w]);
        __builtin_prefetch(&s.busy[s.target[w]]);
        __builtin_prefetch(&s.offset[s.target[w]]);
      }
      const std::uint32_t v = static_cast<std::uint32_t>(key & 0xFFFFFFFFu), u = s.target[v];
      if (s.busy[v]) continue;
      if (s.busy[u]) {
        repropose(v, kNone);
        continue;
      }
      const std::uint32_t* rm = s.remap.data();
      // Link condition on the current mesh: the common neighbours of v and u are exactly the
      // apexes of the triangles on the edge. A corner is dead when its triangle collapsed this
      // pass (v and u are no source or target yet, so only next and prev can have moved).
      mark_id += 2;
      std::size_t shared = 0;
      for (std::uint32_t i = s.offset[v]; i < s.offset[v + 1]; ++i) {
        const std::uint32_t b = rm[fans[i].next], c = rm[fans[i].prev];
        if (b == c) continue;
        shared += (b == u) | (c == u);
        s.mark[b] = s.mark[c] = mark_id;
      }
      std::size_t common = 0;
      for (std::uint32_t i = s.offset[u]; i < s.offset[u + 1]; ++i) {
        const std::uint32_t b = rm[fans[i].next], c = rm[fans[i].prev];
        if (b == c) continue;
        for (std::uint32_t w : {b, c}) {
          if (w == v || s.mark[w] != mark_id) continue;
          s.mark[w] = mark_id + 1;
          ++common;
        }
      }
      if (shared == 0 || common != shared) {
        ++st.rejected;
        ++goal_index; goal_cost = error_goal();
        s.banned[v] = u;
        repropose(v, u);
        continue;
      }
      // Geometry of v's other triangles after moving v onto u.
      bool ok = true;
      const glm::dvec3 pu(s.pos[u]), pv(s.pos[v]);
      for (std::uint32_t i = s.offset[v]; i < s.offset[v + 1] && ok; ++i) {
        const std::uint32_t b = rm[fans[i].next], c = rm[fans[i].prev];
        if (b == c || b == u || c == u) continue;
        const glm::dvec3 pb(s.pos[b]), pc(s.pos[c]);
        const glm::dvec3 n0 = glm::cross(pb - pv, pc - pv);
        const glm::dvec3 n1 = glm::cross(pb - pu, pc - pu);
        const double l1 = glm::dot(n1, n1);
        if (detail::degenerate_triangle(pu, pb, pc, n1)) ok = false;
        else if (glm::dot(n0, n1) <= kCosLimit * std::sqrt(glm::dot(n0, n0) * l1)) ok = false;
        else {
          const glm::dvec3 ref = glm::dvec3(s.normal[u]) + glm::dvec3(s.normal[b]) + glm::dvec3(s.normal[c]);
          if (!detail::faces_surface(n1, ref)) ok = false;
        }
      }
      if (!ok) {
        ++st.rejected;
        ++goal_index; goal_cost = error_goal();
        s.banned[v] = u;
        repropose(v, u);
        continue;
      }
      s.busy[v] = s.busy[u] = 1;
      s.remap[v] = u;
      removed += shared;
      ++accepted;
      max_cost = std::max(max_cost, cost);
    }
    if (accepted == 0) break;
    st.collapses += accepted;
    // Quadrics merge after the walk, in vertex order (a target receives one source per pass and
    // is never a source itself, and the walk's costs were fixed at the pass start).
    for (std::uint32_t v = 0; v < nv; ++v) {
      const std::uint32_t u = s.remap[v];
      if (u == v) continue;
      s.q[u] += s.q[v];
      s.weight[u] += s.weight[v];
      s.absorbed_next[s.absorbed_last[u]] = v;
      s.absorbed_last[u] = s.absorbed_last[v];
    }
    std::size_t out = 0;
    for (std::size_t t = 0; t < s.tris.size(); t += 3) {
      const std::uint32_t a = s.remap[s.tris[t]], b = s.remap[s.tris[t + 1]], c = s.remap[s.tris[t + 2]];
      if (a == b || b == c || a == c) continue;
      s.tris[out] = a;
      s.tris[out + 1] = b;
      s.tris[out + 2] = c;
      out += 3;
    }
    s.tris.resize(out);
    triangles = out / 3;
  }
  // The worst spots left between the vertices: bounded edge flips (simplify_flip.hpp).
  if (st.passes > 0) {
    if (st.passes == 1) {  // the input's fans are still the first pass's
      s.original_offset.swap(s.offset);
      s.original_fans.swap(s.fans);
    }
    const detail::FlipInputs in{s.pos, s.normal, s.q, s.weight, s.absorbed_next, s.original_offset, s.original_fans};
    st.flips = detail::flip_worst_edges(in, s.tris, nv, s.flip);
  }
  if (stats) *stats = st;
  std::vector<std::uint32_t> result(s.tris.size());
  for (std::size_t i = 0; i < s.tris.size(); ++i) result[i] = s.global[s.tris[i]];
  return result;
}

}  // namespace sylva::terrain

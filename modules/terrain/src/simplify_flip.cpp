#include "simplify_flip.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva::terrain::detail {

namespace {

using Candidate = FlipScratch::Candidate;

// Mean squared distance of the midpoint of (a, b) to the planes both vertices stand for.
double midpoint_cost(const FlipInputs& in, std::uint32_t a, std::uint32_t b) {
  const double w = in.weights[a] + in.weights[b];
  if (w <= 0.0) return 0.0;
  const glm::dvec3 mid = 0.5 * (glm::dvec3(in.positions[a]) + glm::dvec3(in.positions[b]));
  return in.quadrics[a].error_sum(in.quadrics[b], mid) / w;
}

// The third vertex of the only triangle holding the directed edge from -> to, kNoVertex when
// there is none or more than one.
std::uint32_t apex(const FlipScratch& s, std::uint32_t from, std::uint32_t to) {
  std::uint32_t found = kNoVertex;
  for (std::uint32_t i = s.offset[from]; i < s.offset[from + 1]; ++i) {
    if (s.fans[i].next != to) continue;
    if (found != kNoVertex) return kNoVertex;
    found = s.fans[i].prev;
  }
  return found;
}

bool adjacent(const FlipScratch& s, std::uint32_t c, std::uint32_t d) {
  for (std::uint32_t i = s.offset[c]; i < s.offset[c + 1]; ++i)
    if (s.fans[i].next == d || s.fans[i].prev == d) return true;
  return false;
}

// The collapse tests for the new triangle n_new against the old pair n0, n1.
bool valid_triangle(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& r, const glm::dvec3& n0,
                    const glm::dvec3& n1, const glm::dvec3& ref) {
  const glm::dvec3 n = glm::cross(q - p, r - p);
  if (degenerate_triangle(p, q, r, n)) return false;
  const double l = glm::dot(n, n);
  for (const glm::dvec3* o : {&n0, &n1})
    if (glm::dot(n, *o) <= kCosLimit * std::sqrt(l * glm::dot(*o, *o))) return false;
  return faces_surface(n, ref);
}

// Squared distance from p to the original triangles gathered in `nearby`.
double original_dist2(const FlipInputs& in, const std::vector<std::uint32_t>& nearby, const glm::dvec3& p) {
  double best = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < nearby.size(); i += 3)
    best = std::min(best, point_triangle_dist2(p, glm::dvec3(in.positions[nearby[i]]),
                                               glm::dvec3(in.positions[nearby[i + 1]]),
                                               glm::dvec3(in.positions[nearby[i + 2]])));
  return best;
}

// Largest squared distance to the original of the points of triangle (p, q, r) that a flip of its
// edge (p, q) moves: a barycentric grid of step 1/3 without the points on the two other edges
// (they are the same before and after the flip): the two inner points of (p, q) and the centre.
// Stops early once above `enough`.
double moved_points_dist2(const FlipInputs& in, const std::vector<std::uint32_t>& nearby, const glm::dvec3& p,
                          const glm::dvec3& q, const glm::dvec3& r, double enough) {
  const glm::dvec3 points[3] = {(2.0 * p + q) / 3.0, (p + 2.0 * q) / 3.0, (p + q + r) / 3.0};
  double worst = 0.0;
  for (const glm::dvec3& x : points) {
    worst = std::max(worst, original_dist2(in, nearby, x));
    if (worst >= enough) break;
  }
  return worst;
}

// The exact test: does the pair (a, d, c), (d, b, c) lie closer to the original surface than
// (a, b, c), (b, a, d), in both directions (see flip_worst_edges)?
bool closer_to_original(const FlipInputs& in, FlipScratch& s, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                        std::uint32_t d) {
  // Each original triangle once: from its lowest-numbered corner among the absorbed vertices.
  ++s.stamp;
  for (std::uint32_t x : {a, b, c, d})
    for (std::uint32_t o = x; o != kNoVertex; o = in.absorbed_next[o]) s.absorbed_mark[o] = s.stamp;
  s.nearby.clear();
  for (std::uint32_t x : {a, b, c, d})
    for (std::uint32_t o = x; o != kNoVertex; o = in.absorbed_next[o])
      for (std::uint32_t i = in.original_offset[o]; i < in.original_offset[o + 1]; ++i) {
        const Corner& k = in.original_fans[i];
        if ((k.next < o && s.absorbed_mark[k.next] == s.stamp) || (k.prev < o && s.absorbed_mark[k.prev] == s.stamp))
          continue;
        s.nearby.insert(s.nearby.end(), {o, k.next, k.prev});
      }
  const glm::dvec3 pa(in.positions[a]), pb(in.positions[b]), pc(in.positions[c]), pd(in.positions[d]);
  const double inf = std::numeric_limits<double>::max();
  const double old_far =
      std::max(moved_points_dist2(in, s.nearby, pa, pb, pc, inf), moved_points_dist2(in, s.nearby, pb, pa, pd, inf));
  if (moved_points_dist2(in, s.nearby, pc, pd, pa, old_far) >= old_far ||
      moved_points_dist2(in, s.nearby, pd, pc, pb, old_far) >= old_far)
    return false;
  // The other direction, at the absorbed original vertices whose nearest point changes.
  double old_worst = 0.0, new_worst = 0.0;
  for (std::uint32_t x : {a, b, c, d})
    for (std::uint32_t o = x; o != kNoVertex; o = in.absorbed_next[o]) {
      const glm::dvec3 p(in.positions[o]);
      const double before = std::min(point_triangle_dist2(p, pa, pb, pc), point_triangle_dist2(p, pb, pa, pd));
      const double after = std::min(point_triangle_dist2(p, pa, pd, pc), point_triangle_dist2(p, pd, pb, pc));
      if (before == after) continue;
      old_worst = std::max(old_worst, before);
      new_worst = std::max(new_worst, after);
    }
  return new_worst <= old_worst;
}

}  // namespace

std::size_t flip_worst_edges(const FlipInputs& in, std::vector<std::uint32_t>& tris, std::size_t nv,
                             FlipScratch& s) {
  build_fans(tris, nv, s.offset, s.fans);
  // Every edge once (from the triangle where it runs from the lower id to the higher); the worst
  // `keep` by midpoint cost are kept in a bounded heap whose front is the least bad (ties by
  // vertex ids: deterministic), then sorted worst first.
  const std::size_t keep = std::max<std::size_t>(8, tris.size() / 3 / 500);
  const auto worse = [](const Candidate& x, const Candidate& y) {
    if (x.cost != y.cost) return x.cost > y.cost;
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  };
  s.candidates.clear();
  for (std::uint32_t a = 0; a < nv; ++a)
    for (std::uint32_t i = s.offset[a]; i < s.offset[a + 1]; ++i) {
      const std::uint32_t b = s.fans[i].next;
      if (a > b) continue;
      const Candidate e{midpoint_cost(in, a, b), a, b, s.fans[i].prev};
      if (s.candidates.size() < keep) {
        s.candidates.push_back(e);
        std::push_heap(s.candidates.begin(), s.candidates.end(), worse);
      } else if (worse(e, s.candidates.front())) {
        std::pop_heap(s.candidates.begin(), s.candidates.end(), worse);
        s.candidates.back() = e;
        std::push_heap(s.candidates.begin(), s.candidates.end(), worse);
      }
    }
  std::sort(s.candidates.begin(), s.candidates.end(), worse);

  s.flip_of.assign(nv, kNoVertex);
  s.absorbed_mark.assign(nv, 0u);
  s.stamp = 0;
  s.flips.clear();
  for (const Candidate& e : s.candidates) {
    const std::uint32_t a = e.a, b = e.b, c = e.c;
    const std::uint32_t d = apex(s, b, a);
    if (d == kNoVertex || d == c || apex(s, a, b) != c) continue;
    if (s.flip_of[a] != kNoVertex || s.flip_of[b] != kNoVertex || s.flip_of[c] != kNoVertex ||
        s.flip_of[d] != kNoVertex || adjacent(s, c, d))
      continue;
    if (!(midpoint_cost(in, c, d) < e.cost)) continue;
    const glm::dvec3 pa(in.positions[a]), pb(in.positions[b]), pc(in.positions[c]), pd(in.positions[d]);
    const glm::dvec3 n0 = glm::cross(pb - pa, pc - pa), n1 = glm::cross(pa - pb, pd - pb);
    const glm::dvec3 na(in.normals[a]), nb(in.normals[b]), nc(in.normals[c]), nd(in.normals[d]);
    if (!valid_triangle(pa, pd, pc, n0, n1, na + nd + nc) || !valid_triangle(pd, pb, pc, n0, n1, nd + nb + nc)) continue;
    if (!closer_to_original(in, s, a, b, c, d)) continue;
    const std::uint32_t id = static_cast<std::uint32_t>(s.flips.size() / 4);
    s.flip_of[a] = s.flip_of[b] = s.flip_of[c] = s.flip_of[d] = id;
    s.flips.insert(s.flips.end(), {a, b, c, d});
  }
  if (s.flips.empty()) return 0;
  // A triangle whose three corners belong to one flip is one of its two old triangles ((a, c, d)
  // or (b, c, d) would need the edge (c, d), which did not exist); (a, b, c) holds c, (b, a, d) d.
  for (std::size_t t = 0; t < tris.size(); t += 3) {
    const std::uint32_t id = s.flip_of[tris[t]];
    if (id == kNoVertex || s.flip_of[tris[t + 1]] != id || s.flip_of[tris[t + 2]] != id) continue;
    const std::uint32_t* f = &s.flips[4 * std::size_t{id}];
    const bool holds_c = tris[t] == f[2] || tris[t + 1] == f[2] || tris[t + 2] == f[2];
    const std::uint32_t a = f[0], b = f[1], c = f[2], d = f[3];
    if (holds_c) {
      tris[t] = a, tris[t + 1] = d, tris[t + 2] = c;
    } else {
      tris[t] = d, tris[t + 1] = b, tris[t + 2] = c;
    }
  }
  return s.flips.size() / 4;
}

}  // namespace sylva::terrain::detail

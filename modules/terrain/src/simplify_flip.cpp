#include "simplify_flip.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace sylva::terrain::detail {

namespace {

using Candidate = FlipScratch::Candidate;

// Mean squared distance of the midpoint of (a, b) to the planes both vertices stand for. It runs
// on every edge, so the quadric sum (Q_a + Q_b)(mid) is written out in Horner form (12 products
// instead of Quadric::evaluate's 21).
inline double midpoint_cost(const FlipInputs& in, std::uint32_t a, std::uint32_t b) {
  const double w = in.weights[a] + in.weights[b];
  if (w <= 0.0) return 0.0;
  const glm::vec3 pa = in.positions[a], pb = in.positions[b];
  const double x = 0.5 * (double{pa.x} + double{pb.x}), y = 0.5 * (double{pa.y} + double{pb.y}),
               z = 0.5 * (double{pa.z} + double{pb.z});
  const std::array<double, 10>& qa = in.quadrics[a].m;
  const std::array<double, 10>& qb = in.quadrics[b].m;
  const auto q = [&](std::size_t i) { return qa[i] + qb[i]; };  // in registers, no summed copy
  return (x * (q(0) * x + 2.0 * (q(1) * y + q(2) * z + q(3))) + y * (q(4) * y + 2.0 * (q(5) * z + q(6))) +
          z * (q(7) * z + 2.0 * q(8)) + q(9)) /
         w;
}

// The fans of the candidates' vertices a, b, c (FlipScratch::slot_of): one pass over the
// triangles picks those holding such a vertex (a few per candidate), then the slots' corners are
// sorted into CSR like build_fans. The fans of the whole reduced mesh cost ~1 % of the reduction.
void build_candidate_fans(const std::vector<std::uint32_t>& tris, FlipScratch& s) {
  std::uint32_t slots = 0;
  for (const Candidate& e : s.candidates)
    for (std::uint32_t v : {e.a, e.b, e.c})
      if (s.slot_of[v] == kNoVertex) s.slot_of[v] = slots++;
  s.touching.clear();
  for (std::uint32_t t = 0; t < tris.size(); t += 3)  // all three kNoVertex (all bits set) or not
    if ((s.slot_of[tris[t]] & s.slot_of[tris[t + 1]] & s.slot_of[tris[t + 2]]) != kNoVertex) s.touching.push_back(t);
  s.offset.assign(slots + 1, 0u);
  for (std::uint32_t t : s.touching)
    for (std::uint32_t k = 0; k < 3; ++k)
      if (const std::uint32_t slot = s.slot_of[tris[t + k]]; slot != kNoVertex) ++s.offset[slot + 1];
  for (std::uint32_t i = 0; i < slots; ++i) s.offset[i + 1] += s.offset[i];
  s.fans.resize(s.offset[slots]);
  // Filled from the back with the end offsets, which end at each slot's start (as build_fans).
  for (std::size_t i = s.touching.size(); i-- > 0;) {
    const std::uint32_t t = s.touching[i];
    for (std::uint32_t k = 0; k < 3; ++k)
      if (const std::uint32_t slot = s.slot_of[tris[t + k]]; slot != kNoVertex)
        s.fans[--s.offset[slot + 1]] = {tris[t + (k + 1) % 3], tris[t + (k + 2) % 3]};
  }
  for (std::uint32_t i = 0; i < slots; ++i) s.offset[i] = s.offset[i + 1];
  s.offset[slots] = static_cast<std::uint32_t>(s.fans.size());
}

// The third vertex of the only triangle holding the directed edge from -> to (from has a slot),
// kNoVertex when there is none or more than one.
std::uint32_t apex(const FlipScratch& s, std::uint32_t from, std::uint32_t to) {
  std::uint32_t found = kNoVertex;
  const std::uint32_t slot = s.slot_of[from];
  for (std::uint32_t i = s.offset[slot]; i < s.offset[slot + 1]; ++i) {
    if (s.fans[i].next != to) continue;
    if (found != kNoVertex) return kNoVertex;
    found = s.fans[i].prev;
  }
  return found;
}

// Whether c (which has a slot) and d share an edge.
bool adjacent(const FlipScratch& s, std::uint32_t c, std::uint32_t d) {
  const std::uint32_t slot = s.slot_of[c];
  for (std::uint32_t i = s.offset[slot]; i < s.offset[slot + 1]; ++i)
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

// Squared distance from p to the nearest original triangle gathered in `nearby`, except that it
// returns the first distance found below `below` (the callers only need to know that the point
// is that close). The scan starts at `hint`, the triangle nearest to the caller's previous point
// (updated; the points of one test lie close together), so such a triangle comes early.
double original_dist2(const FlipInputs& in, const std::vector<std::uint32_t>& nearby, const glm::dvec3& p,
                      double below, std::size_t& hint) {
  double best = std::numeric_limits<double>::max();
  const std::size_t n = nearby.size();
  for (std::size_t k = 0, i = hint; k < n; k += 3, i = i + 3 == n ? 0 : i + 3) {
    const double d = point_triangle_dist2(p, glm::dvec3(in.positions[nearby[i]]), glm::dvec3(in.positions[nearby[i + 1]]),
                                          glm::dvec3(in.positions[nearby[i + 2]]));
    if (d >= best) continue;
    best = d;
    hint = i;
    if (d < below) break;
  }
  return best;
}

// The points of triangle (p, q, r) that a flip of its edge (p, q) moves: a barycentric grid of
// step 1/3 without the points on the two other edges (they are the same before and after the
// flip): the two inner points of (p, q) and the centre.
std::array<glm::dvec3, 3> moved_points(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& r) {
  return {(2.0 * p + q) / 3.0, (p + 2.0 * q) / 3.0, (p + q + r) / 3.0};
}

// max(worst, the largest squared distance of those points to the original), exact: a point stops
// at the first triangle nearer than `worst`, since it cannot raise the maximum then.
double farthest_moved_point(const FlipInputs& in, const std::vector<std::uint32_t>& nearby, const glm::dvec3& p,
                            const glm::dvec3& q, const glm::dvec3& r, double worst, std::size_t& hint) {
  for (const glm::dvec3& x : moved_points(p, q, r)) worst = std::max(worst, original_dist2(in, nearby, x, worst, hint));
  return worst;
}

// Whether every one of those points lies nearer than `limit` (squared) to the original: a point
// stops at the first triangle that near, the test at the first point that is not.
bool moved_points_nearer(const FlipInputs& in, const std::vector<std::uint32_t>& nearby, const glm::dvec3& p,
                         const glm::dvec3& q, const glm::dvec3& r, double limit, std::size_t& hint) {
  for (const glm::dvec3& x : moved_points(p, q, r))
    if (original_dist2(in, nearby, x, limit, hint) >= limit) return false;
  return true;
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
  std::size_t hint = 0;
  const double old_far =
      farthest_moved_point(in, s.nearby, pb, pa, pd, farthest_moved_point(in, s.nearby, pa, pb, pc, 0.0, hint), hint);
  if (!moved_points_nearer(in, s.nearby, pc, pd, pa, old_far, hint) ||
      !moved_points_nearer(in, s.nearby, pd, pc, pb, old_far, hint))
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
  // Every edge once (from the triangle where it runs from the lower id to the higher); the worst
  // `keep` by midpoint cost are kept in a bounded heap whose front is the least bad (ties by
  // vertex ids: deterministic, whatever the order of the triangles), then sorted worst first.
  const std::size_t keep = std::max<std::size_t>(8, tris.size() / 3 / 500);
  const auto worse = [](const Candidate& x, const Candidate& y) {
    if (x.cost != y.cost) return x.cost > y.cost;
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  };
  s.candidates.clear();
  // Inlined: it runs three times per triangle of the reduced mesh.
  const auto consider = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) __attribute__((always_inline)) {
    if (a > b) return;
    const Candidate e{midpoint_cost(in, a, b), a, b, c};
    if (s.candidates.size() < keep) {
      s.candidates.push_back(e);
      std::push_heap(s.candidates.begin(), s.candidates.end(), worse);
    } else if (worse(e, s.candidates.front())) {
      std::pop_heap(s.candidates.begin(), s.candidates.end(), worse);
      s.candidates.back() = e;
      std::push_heap(s.candidates.begin(), s.candidates.end(), worse);
    }
  };
  for (std::size_t t = 0; t < tris.size(); t += 3) {
    consider(tris[t], tris[t + 1], tris[t + 2]);
    consider(tris[t + 1], tris[t + 2], tris[t]);
    consider(tris[t + 2], tris[t], tris[t + 1]);
  }
  std::sort(s.candidates.begin(), s.candidates.end(), worse);
  if (s.slot_of.size() < nv) s.slot_of.resize(nv, kNoVertex);
  build_candidate_fans(tris, s);

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
  for (const Candidate& e : s.candidates) s.slot_of[e.a] = s.slot_of[e.b] = s.slot_of[e.c] = kNoVertex;
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

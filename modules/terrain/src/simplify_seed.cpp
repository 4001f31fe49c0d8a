#include <sylva/terrain/simplify.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace sylva::terrain {

namespace {
bool degenerate(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  // The seed's "two edges with the same direction", made robust (seed errata §9.8).
  const glm::dvec3 e1 = glm::dvec3(b) - glm::dvec3(a), e2 = glm::dvec3(c) - glm::dvec3(a);
  const glm::dvec3 cr = glm::cross(e1, e2);
  return glm::dot(cr, cr) <= 1e-12 * glm::dot(e1, e1) * glm::dot(e2, e2);
}
}  // namespace

std::vector<std::uint32_t> simplify_shortest_edge(std::span<const glm::vec3> positions,
                                                  std::span<const std::uint32_t> indices,
                                                  std::span<const std::uint8_t> locked, std::size_t target_triangles,
                                                  SimplifyStats* stats) {
  std::vector<std::uint32_t> tris(indices.begin(), indices.end());
  SimplifyStats st;
  struct EdgeEntry {
    float length;
    std::uint32_t del, tgt;
  };
  std::vector<EdgeEntry> edges;
  // Per-vertex flags of the seed's Table 4.2 (1 / -1 there; bytes here), reset per pass.
  std::vector<std::uint8_t> deleted(positions.size(), 0), merged_into_me(positions.size(), 0);
  std::vector<std::uint32_t> merge_to(positions.size(), 0);
  std::vector<std::uint32_t> touched;
  while (tris.size() / 3 > target_triangles) {
    ++st.passes;
    // Step 1: the shortest edge of every triangle, sorted ascending.
    edges.clear();
    for (std::size_t t = 0; t + 2 < tris.size(); t += 3) {
      float best = std::numeric_limits<float>::infinity();
      std::uint32_t del = 0, tgt = 0;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = tris[t + static_cast<std::size_t>(k)], b = tris[t + static_cast<std::size_t>((k + 1) % 3)];
        const float len = glm::length(positions[b] - positions[a]);
        if (len < best) {
          best = len;
          del = a;
          tgt = b;
        }
      }
      edges.push_back({best, del, tgt});
    }
    std::sort(edges.begin(), edges.end(), [](const EdgeEntry& a, const EdgeEntry& b) { return a.length < b.length; });
    // Step 2: walk the array; stop once enough triangles would go (about two per deleted vertex).
    const std::size_t to_remove = tris.size() / 3 - target_triangles;
    std::size_t deletions = 0;
    for (const EdgeEntry& e : edges) {
      if (2 * deletions >= to_remove) break;
      if (deleted[e.del] || merged_into_me[e.del] || locked[e.del] || deleted[e.tgt]) continue;
      deleted[e.del] = 1;
      merge_to[e.del] = e.tgt;
      merged_into_me[e.tgt] = 1;
      touched.push_back(e.del);
      touched.push_back(e.tgt);
      ++deletions;
    }
    // Step 3: delete or re-link triangles; then the collinear clean-up.
    std::vector<std::uint32_t> next;
    next.reserve(tris.size());
    for (std::size_t t = 0; t + 2 < tris.size(); t += 3) {
      std::array<std::uint32_t, 3> v{tris[t], tris[t + 1], tris[t + 2]};
      bool collapses = false;
      for (std::uint32_t a : v) {
        if (!deleted[a]) continue;
        for (std::uint32_t b : v) collapses = collapses || b == merge_to[a];
      }
      if (collapses) continue;
      for (auto& a : v)
        if (deleted[a]) a = merge_to[a];
      if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) continue;
      if (degenerate(positions[v[0]], positions[v[1]], positions[v[2]])) continue;
      next.insert(next.end(), v.begin(), v.end());
    }
    for (std::uint32_t a : touched) {
      deleted[a] = 0;
      merged_into_me[a] = 0;
    }
    touched.clear();
    st.collapses += deletions;
    const bool progress = next.size() < tris.size();
    tris = std::move(next);
    if (!progress) break;
  }
  if (stats) *stats = st;
  return tris;
}

}  // namespace sylva::terrain

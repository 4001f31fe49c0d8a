#include <sylva/terrain/seams.hpp>

#include <unordered_set>

#include <sylva/core/assert.hpp>

#include <algorithm>

namespace sylva::terrain {

namespace {
std::uint32_t along(const ChunkVertex& v, Edge e) { return (e == kWest || e == kEast) ? v.gz : v.gx; }
}  // namespace

MeshSource tree_meshes(const ChunkTree& tree) {
  SYLVA_ASSERT(tree.has_meshes(), "the chunk tree was built without its meshes (keep_meshes = false)");
  return [&tree](std::uint32_t i) -> const ChunkMesh* { return &tree.chunk(i).mesh; };
}

Seam build_seam(const ChunkTree& tree, const MeshSource& meshes, std::uint32_t fine, Edge e, std::uint32_t coarse) {
  SYLVA_ASSERT(tree.chunk(coarse).key.level < tree.chunk(fine).key.level, "seam from level {} to level {}",
               tree.chunk(fine).key.level, tree.chunk(coarse).key.level);
  const ChunkMesh* am = meshes(fine);
  const ChunkMesh* cm = meshes(coarse);
  SYLVA_ASSERT(am != nullptr && cm != nullptr, "seam between chunks {} and {} whose meshes are not loaded", fine, coarse);
  struct View {
    const ChunkMesh& mesh;
  } a{*am}, c{*cm};
  const Edge ce = static_cast<Edge>((e + 2) % 4);
  const std::vector<std::uint32_t>& fe = a.mesh.edges[e];
  const std::vector<std::uint32_t>& cev = c.mesh.edges[ce];
  SYLVA_ASSERT(fe.size() >= 2 && cev.size() >= 2, "chunk edges hold at least their corners");

  // Walk the fine edge in the up-facing boundary direction (west, north: increasing; east,
  // south: decreasing).
  const bool increasing = (e == kWest || e == kNorth);
  std::vector<std::uint32_t> f(fe.begin(), fe.end());
  if (!increasing) std::reverse(f.begin(), f.end());

  // Coarse coordinates along the shared line, ascending.
  std::vector<std::uint32_t> coarse_t(cev.size());
  for (std::size_t i = 0; i < cev.size(); ++i) coarse_t[i] = along(c.mesh.vertices[cev[i]], ce);

  Seam seam;
  const std::uint32_t base = static_cast<std::uint32_t>(a.mesh.vertices.size());
  std::int64_t extra_t = -1;  // coordinate of the extra anchor, if any
  // Index (into a's vertices or the extra list) of the coarse vertex at coordinate t.
  auto anchor_index = [&](std::uint32_t t, std::size_t coarse_pos) -> std::uint32_t {
    for (std::uint32_t vi : fe)
      if (along(a.mesh.vertices[vi], e) == t) return vi;
    if (extra_t != static_cast<std::int64_t>(t)) {
      SYLVA_ASSERT(seam.extra_vertices.empty(), "a seam needs at most one anchor outside the fine edge");
      seam.extra_vertices.push_back(c.mesh.vertices[cev[coarse_pos]]);
      extra_t = t;
    }
    return base;
  };

  for (std::size_t i = 0; i + 1 < f.size(); ++i) {
    const std::uint32_t ti = along(a.mesh.vertices[f[i]], e);
    // The coarse segment containing [t_i, t_i+1] starts (in walking direction) at the last coarse
    // vertex at or before t_i.
    std::size_t pos;
    if (increasing) {
      auto it = std::upper_bound(coarse_t.begin(), coarse_t.end(), ti);
      SYLVA_ASSERT(it != coarse_t.begin(), "fine edge point {} precedes the coarse edge", ti);
      pos = static_cast<std::size_t>(it - coarse_t.begin()) - 1;
    } else {
      auto it = std::lower_bound(coarse_t.begin(), coarse_t.end(), ti);
      SYLVA_ASSERT(it != coarse_t.end(), "fine edge point {} follows the coarse edge", ti);
      pos = static_cast<std::size_t>(it - coarse_t.begin());
    }
    const std::uint32_t tu = coarse_t[pos];
    if (tu == ti) continue;  // f_i is the coarse vertex itself: no triangle
    const std::uint32_t u = anchor_index(tu, pos);
    seam.indices.push_back(u);
    seam.indices.push_back(f[i + 1]);
    seam.indices.push_back(f[i]);
  }
  return seam;
}

const Seam& SeamCache::get(const ChunkTree& tree, const MeshSource& meshes, std::uint32_t fine, Edge e,
                           std::uint32_t coarse) {
  const std::uint64_t key = (static_cast<std::uint64_t>(fine) << 8) | (static_cast<std::uint64_t>(e) << 6) |
                            static_cast<std::uint64_t>(tree.chunk(coarse).key.level);
  auto it = map_.find(key);
  if (it != map_.end()) {
    ++hits_;
    lru_.splice(lru_.begin(), lru_, it->second.lru);
    return it->second.seam;
  }
  ++builds_;
  while (!map_.empty() && map_.size() >= capacity_) {
    map_.erase(lru_.back());
    lru_.pop_back();
  }
  lru_.push_front(key);
  Entry& entry = map_[key];
  entry.seam = build_seam(tree, meshes, fine, e, coarse);
  entry.lru = lru_.begin();
  entry.fine = fine;
  entry.coarse = coarse;
  return entry.seam;
}

std::size_t SeamCache::invalidate(const std::vector<std::uint32_t>& chunks) {
  std::unordered_set<std::uint32_t> changed(chunks.begin(), chunks.end());
  std::size_t dropped = 0;
  for (auto it = map_.begin(); it != map_.end();) {
    if (changed.count(it->second.fine) != 0 || changed.count(it->second.coarse) != 0) {
      lru_.erase(it->second.lru);
      it = map_.erase(it);
      ++dropped;
    } else {
      ++it;
    }
  }
  return dropped;
}

void SeamCache::clear() {
  map_.clear();
  lru_.clear();
}

}  // namespace sylva::terrain

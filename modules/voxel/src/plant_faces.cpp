#include <sylva/voxel/plant_faces.hpp>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace sylva::voxel {
namespace {

// Parts are placed by float turtle steps: positions of touching blocks agree to ~1e-6 block
// (the turtle renormalises its frame); 1e-4 of the part size accepts that and nothing visible.
constexpr float kTolerance = 1e-4f;

bool axis_aligned(const glm::quat& q) {
  return std::abs(std::abs(q.w) - 1.0f) < 1e-6f;
}

struct Box {
  glm::vec3 lo, hi;
};

Box box_of(const PlantPart& p) {
  const glm::vec3 h(0.5f * p.size);
  return {p.position - h, p.position + h};
}

// Does Q hide the face of P on `axis`, `negative` side (see the header's rule)?
bool covers(const Box& p, const Box& q, int axis, bool negative, float eps) {
  for (int a = 0; a < 3; ++a) {
    if (a == axis) continue;
    if (p.lo[a] < q.lo[a] - eps || p.hi[a] > q.hi[a] + eps) return false;
  }
  if (!negative) {
    const float plane = p.hi[axis];  // faces +axis: hidden inside Q or on Q's -axis face, not on its +axis face
    return plane >= q.lo[axis] - eps && plane < q.hi[axis] - eps;
  }
  const float plane = p.lo[axis];
  return plane > q.lo[axis] + eps && plane <= q.hi[axis] + eps;
}

bool same_part(const PlantPart& a, const PlantPart& b, float eps) {
  return std::abs(a.size - b.size) <= eps && glm::all(glm::lessThanEqual(glm::abs(a.position - b.position), glm::vec3(eps)));
}

struct CellHash {
  std::size_t operator()(const glm::ivec3& c) const {
    return static_cast<std::size_t>(c.x) * 73856093u ^ static_cast<std::size_t>(c.y) * 19349663u ^
           static_cast<std::size_t>(c.z) * 83492791u;
  }
};

}  // namespace

std::vector<std::uint8_t> hidden_faces(std::span<const FacePart> parts, bool cut_hides_cut) {
  std::vector<std::uint8_t> masks(parts.size(), 0);
  float cell = 0.0f;
  for (const FacePart& p : parts) cell = std::max(cell, p.part.size);
  if (parts.empty() || !(cell > 0.0f) || !std::isfinite(cell)) return masks;
  // Two parts that touch have centres at most (size_p + size_q) / 2 <= the largest size apart on
  // every axis, so a grid of that cell finds every such pair in the 27 cells around a part.
  auto cell_of = [cell](const glm::vec3& p) { return glm::ivec3(glm::floor(p / cell)); };
  std::unordered_map<glm::ivec3, std::vector<std::uint32_t>, CellHash> grid;
  grid.reserve(parts.size());
  for (std::uint32_t i = 0; i < parts.size(); ++i) {
    if (axis_aligned(parts[i].part.orientation)) grid[cell_of(parts[i].part.position)].push_back(i);
  }
  for (std::uint32_t i = 0; i < parts.size(); ++i) {
    const FacePart& p = parts[i];
    if (!axis_aligned(p.part.orientation)) continue;
    const Box pb = box_of(p.part);
    const float eps = kTolerance * p.part.size;
    const glm::ivec3 c = cell_of(p.part.position);
    std::uint8_t mask = 0;
    for (int dz = -1; dz <= 1 && mask != kAllFaces; ++dz)
      for (int dy = -1; dy <= 1 && mask != kAllFaces; ++dy)
        for (int dx = -1; dx <= 1 && mask != kAllFaces; ++dx) {
          auto it = grid.find(c + glm::ivec3(dx, dy, dz));
          if (it == grid.end()) continue;
          for (std::uint32_t j : it->second) {
            if (j == i) continue;
            const FacePart& q = parts[j];
            if (q.opaque == p.opaque && same_part(p.part, q.part, eps)) {
              // A duplicate (branches that meet lay the same block twice): the first one stays;
              // the second drew only where the first had already written the same depth.
              if (j < i) mask = kAllFaces;
              continue;
            }
            if (!q.opaque && (p.opaque || !cut_hides_cut)) continue;
            const Box qb = box_of(q.part);
            for (int axis = 0; axis < 3; ++axis)
              for (bool negative : {false, true}) {
                const std::uint8_t bit = face_bit(axis, negative);
                if (!(mask & bit) && covers(pb, qb, axis, negative, eps)) mask |= bit;
              }
          }
        }
    masks[i] = mask;
  }
  return masks;
}

std::vector<FacePart> snap_to_grid(std::span<const FacePart> parts, float cell) {
  if (!(cell > 0.0f) || !std::isfinite(cell)) return {parts.begin(), parts.end()};
  struct Cell {
    std::size_t order;
    int opaque = 0, cut = 0;
    int opaque_tag = 0, cut_tag = 0;
  };
  std::unordered_map<glm::ivec3, Cell, CellHash> cells;
  std::vector<glm::ivec3> order;
  for (const FacePart& p : parts) {
    const glm::ivec3 key(glm::round(p.part.position / cell));
    auto [it, fresh] = cells.try_emplace(key, Cell{order.size()});
    if (fresh) order.push_back(key);
    Cell& c = it->second;
    if (p.opaque) {
      if (c.opaque++ == 0) c.opaque_tag = p.tag;
    } else if (c.cut++ == 0) {
      c.cut_tag = p.tag;
    }
  }
  std::vector<FacePart> out;
  out.reserve(order.size());
  for (const glm::ivec3& key : order) {
    const Cell& c = cells.at(key);
    const bool opaque = c.opaque >= c.cut;
    FacePart f;
    f.part.position = glm::vec3(key) * cell;
    f.part.size = cell;
    f.opaque = opaque;
    f.tag = opaque ? c.opaque_tag : c.cut_tag;
    out.push_back(f);
  }
  return out;
}

std::uint8_t turn_faces(std::uint8_t mask, int yaw_quarters) {
  // A quarter turn about +y (glm::angleAxis(pi/2, y)) sends +x to -z, -x to +z, +z to +x, -z to -x.
  const int turns = ((yaw_quarters % 4) + 4) % 4;
  for (int t = 0; t < turns; ++t) {
    const auto has = [mask](int axis, bool negative) { return (mask & face_bit(axis, negative)) != 0; };
    std::uint8_t out = mask & (face_bit(1, false) | face_bit(1, true));
    if (has(0, false)) out |= face_bit(2, true);
    if (has(0, true)) out |= face_bit(2, false);
    if (has(2, false)) out |= face_bit(0, false);
    if (has(2, true)) out |= face_bit(0, true);
    mask = out;
  }
  return mask;
}

}  // namespace sylva::voxel

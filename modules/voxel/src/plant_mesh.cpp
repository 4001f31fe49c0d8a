#include <sylva/voxel/plant_mesh.hpp>

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva::voxel {
namespace {

// plant.vert's quad corners and triangle orders (common.glsl kVoxelCorners, kVoxelTriA and
// kVoxelTriARev): counter-clockwise seen from outside the cube on both sides of an axis.
constexpr int kCorners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
constexpr std::uint32_t kTrianglesPositive[6] = {0, 1, 2, 0, 2, 3};
constexpr std::uint32_t kTrianglesNegative[6] = {0, 2, 1, 0, 3, 2};

// Quarter turns about y keep a cube's normals on the axes up to rounding of the quaternion.
constexpr float kAxisTolerance = 1e-5f;

glm::vec2 voxel_uv(const glm::vec3& p, int axis) {
  if (axis == 1) return {p.x, p.z};
  if (axis == 0) return {p.z, -p.y};
  return {p.x, -p.y};
}

// The group of a chunk-space normal (plant_mesh.hpp): 2 * axis + negative, or 6.
int group_of(const glm::vec3& n) {
  for (int a = 0; a < 3; ++a) {
    if (std::abs(n[a]) > 1.0f - kAxisTolerance) return 2 * a + (n[a] < 0.0f ? 1 : 0);
  }
  return kPlantMeshGroups - 1;
}

// plant.vert's normalisation and quat_rotate, operation for operation: baked corners then round
// like the instanced cube's, and the two pictures match pixel for pixel.
glm::vec4 shader_normalize(const glm::quat& q) {
  const glm::vec4 rot(q.x, q.y, q.z, q.w);
  return rot / std::max(glm::length(rot), 1e-6f);
}
glm::vec3 shader_rotate(const glm::vec4& q, const glm::vec3& v) {
  const glm::vec3 u(q);
  return v + 2.0f * glm::cross(u, glm::cross(u, v) + q.w * v);
}

struct BakedFace {
  PlantMeshVertex v[4];
  std::uint32_t cluster;
};

}  // namespace

PlantMesh bake_plant_mesh(std::span<const PlantMeshPart> parts, std::span<const std::uint32_t> plant_starts) {
  std::vector<BakedFace> faces[kPlantMeshGroups];
  PlantMesh mesh;
  mesh.clusters.resize(plant_starts.empty() ? 1 : plant_starts.size());
  std::uint32_t cluster = 0;  // of the part being baked: the last start at or before it
  for (int g = 0; g < kPlantMeshGroups; ++g) {
    mesh.groups[static_cast<std::size_t>(g)].plane =
        g % 2 == 0 ? std::numeric_limits<float>::max() : std::numeric_limits<float>::lowest();
  }
  for (std::size_t i = 0; i < parts.size(); ++i) {
    while (cluster + 1 < plant_starts.size() && plant_starts[cluster + 1] <= i) ++cluster;
    const PlantMeshPart& part = parts[i];
    if (!(part.size > 0.0f) || !std::isfinite(part.size)) continue;
    const glm::vec4 q = shader_normalize(part.orientation);
    for (int f = 0; f < 6; ++f) {
      if ((part.hidden >> f) & 1u) continue;
      const int axis = f >> 1;
      const bool negative = (f & 1) != 0;
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      glm::vec3 normal(0.0f);
      normal[axis] = negative ? -1.0f : 1.0f;
      const glm::vec3 n = shader_rotate(q, normal);
      const int g = group_of(n);
      BakedFace face;
      face.cluster = cluster;
      for (int k = 0; k < 4; ++k) {
        glm::vec3 local(0.0f);
        if (!negative) local[axis] = 1.0f;
        local[u] = static_cast<float>(kCorners[k][0]);
        local[v] = static_cast<float>(kCorners[k][1]);
        const glm::vec3 p = shader_rotate(q, (local - 0.5f) * part.size) + part.center;
        const glm::vec2 uv = voxel_uv(local, axis);
        PlantMeshVertex& out = face.v[k];
        out.position[0] = p.x;
        out.position[1] = p.y;
        out.position[2] = p.z;
        out.uv[0] = uv.x;
        out.uv[1] = uv.y;
        out.normal = glm::packSnorm4x8(glm::vec4(n, 0.0f));
        out.block_face = static_cast<std::uint32_t>(part.block) | static_cast<std::uint32_t>(f) << 16;
        if (g < kPlantMeshGroups - 1) {
          float& plane = mesh.groups[static_cast<std::size_t>(g)].plane;
          plane = g % 2 == 0 ? std::min(plane, p[g / 2]) : std::max(plane, p[g / 2]);
        }
      }
      faces[g].push_back(face);
    }
  }
  for (int g = 0; g < kPlantMeshGroups; ++g) {
    PlantMesh::Group& group = mesh.groups[static_cast<std::size_t>(g)];
    group.first = static_cast<std::uint32_t>(mesh.indices.size());
    // Faces were collected part after part, so a group's faces are already in cluster order;
    // a cluster without faces here starts where the next one does (an empty range).
    std::size_t next = 0;  // first cluster whose start in this group is not yet set
    for (const BakedFace& face : faces[g]) {
      for (; next <= face.cluster; ++next) mesh.clusters[next].first[g] = static_cast<std::uint32_t>(mesh.indices.size());
      mesh.clusters[face.cluster].count[g] += 6;
      const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
      mesh.vertices.insert(mesh.vertices.end(), std::begin(face.v), std::end(face.v));
      const bool negative = (face.v[0].block_face >> 16 & 1u) != 0;
      for (std::uint32_t i : negative ? kTrianglesNegative : kTrianglesPositive) mesh.indices.push_back(base + i);
    }
    for (; next < mesh.clusters.size(); ++next) mesh.clusters[next].first[g] = static_cast<std::uint32_t>(mesh.indices.size());
    group.count = static_cast<std::uint32_t>(mesh.indices.size()) - group.first;
    if (group.count == 0) group.plane = 0.0f;
  }
  return mesh;
}

std::uint32_t PlantMesh::visible_groups(const glm::vec3& eye) const {
  std::uint32_t mask = 0;
  for (int g = 0; g < kPlantMeshGroups; ++g) {
    const Group& group = groups[static_cast<std::size_t>(g)];
    if (group.count == 0) continue;
    const bool seen = g == kPlantMeshGroups - 1 || (g % 2 == 0 ? eye[g / 2] > group.plane : eye[g / 2] < group.plane);
    if (seen) mask |= 1u << g;
  }
  return mask;
}

}  // namespace sylva::voxel

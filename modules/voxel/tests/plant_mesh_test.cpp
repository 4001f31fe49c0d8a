// The baked plant mesh (plant_mesh.hpp, issue #18): vertex, index and triangle counts with
// hidden faces, winding, face groups under quarter and free turns, and that skipping the groups
// visible_groups leaves out never drops a face turned to the eye; per-plant index ranges.

#include <sylva/voxel/plant_faces.hpp>
#include <sylva/voxel/plant_mesh.hpp>

#include <gtest/gtest.h>

#include <glm/gtc/packing.hpp>

#include <random>

namespace sylva::voxel {
namespace {

PlantMeshPart cube(glm::vec3 centre, float size = 1.0f, std::uint8_t hidden = 0, glm::quat q = glm::quat(1, 0, 0, 0)) {
  PlantMeshPart p;
  p.center = centre;
  p.size = size;
  p.orientation = q;
  p.block = 3;
  p.hidden = hidden;
  return p;
}

glm::vec3 position(const PlantMesh& m, std::uint32_t index) {
  const PlantMeshVertex& v = m.vertices[m.indices[index]];
  return {v.position[0], v.position[1], v.position[2]};
}

glm::vec3 normal(const PlantMesh& m, std::uint32_t index) {
  return glm::vec3(glm::unpackSnorm4x8(m.vertices[m.indices[index]].normal));
}

TEST(PlantMesh, ACubeIsFourVerticesAndTwoTrianglesPerFaceWoundOutward) {
  const std::vector<PlantMeshPart> parts = {cube({2, 3, 4}, 0.5f)};
  const PlantMesh m = bake_plant_mesh(parts);
  EXPECT_EQ(m.vertices.size(), 24u);
  EXPECT_EQ(m.indices.size(), 36u);
  EXPECT_EQ(m.triangles(), 12u);
  for (int g = 0; g < 6; ++g) EXPECT_EQ(m.groups[static_cast<std::size_t>(g)].count, 6u) << g;
  EXPECT_EQ(m.groups[6].count, 0u);
  for (std::uint32_t t = 0; t < m.indices.size(); t += 3) {
    const glm::vec3 a = position(m, t), b = position(m, t + 1), c = position(m, t + 2);
    const glm::vec3 n = glm::cross(b - a, c - a);
    EXPECT_GT(glm::dot(n, normal(m, t)), 0.0f) << "triangle " << t / 3;
    EXPECT_GT(glm::dot(n, (a + b + c) / 3.0f - glm::vec3(2, 3, 4)), 0.0f) << "triangle " << t / 3;
    EXPECT_NEAR(glm::length(n), 0.25f, 1e-5f);  // half of the 0.5 x 0.5 face, times two
  }
}

TEST(PlantMesh, HiddenFacesAndPartsAddNothing) {
  const std::uint8_t up_down = face_bit(1, false) | face_bit(1, true);
  const std::vector<PlantMeshPart> parts = {cube({0, 0, 0}, 1.0f, up_down), cube({0, 1, 0}, 1.0f, kAllFaces),
                                            cube({0, 2, 0}, 0.0f)};
  const PlantMesh m = bake_plant_mesh(parts);
  EXPECT_EQ(m.vertices.size(), 16u);
  EXPECT_EQ(m.triangles(), 8u);
  EXPECT_EQ(m.groups[2].count + m.groups[3].count, 0u);
}

TEST(PlantMesh, QuarterTurnsKeepAxisGroupsAndTurnTheHiddenFace) {
  // 90 degrees about +y takes the cube's +x face to -z (group 5).
  const glm::quat yaw = glm::angleAxis(1.5707963f, glm::vec3(0, 1, 0));
  const std::vector<PlantMeshPart> parts = {cube({0, 0, 0}, 1.0f, face_bit(0, false), yaw)};
  const PlantMesh m = bake_plant_mesh(parts);
  EXPECT_EQ(m.groups[5].count, 0u);
  EXPECT_EQ(m.groups[6].count, 0u);
  for (int g : {0, 1, 2, 3, 4}) EXPECT_EQ(m.groups[static_cast<std::size_t>(g)].count, 6u) << g;
}

TEST(PlantMesh, FreelyTurnedFacesGoToTheAlwaysDrawnGroup) {
  const glm::quat roll = glm::angleAxis(0.5f, glm::vec3(0, 0, 1));  // z faces stay on the z axis
  const std::vector<PlantMeshPart> parts = {cube({0, 0, 0}, 1.0f, 0, roll)};
  const PlantMesh m = bake_plant_mesh(parts);
  EXPECT_EQ(m.groups[6].count, 24u);
  EXPECT_EQ(m.groups[4].count + m.groups[5].count, 12u);
  EXPECT_EQ(m.visible_groups(glm::vec3(0, 0, 0)) & (1u << 6), 1u << 6);
}

TEST(PlantMesh, GroupsBehindTheEyeAreSkipped) {
  const std::vector<PlantMeshPart> one = {cube({0, 0, 0})};
  EXPECT_EQ(bake_plant_mesh(one).visible_groups({5.0f, 0.2f, 0.1f}), 1u << 0);  // only +x
  EXPECT_EQ(bake_plant_mesh(one).visible_groups({-5.0f, 5.0f, -5.0f}), (1u << 1) | (1u << 2) | (1u << 5));
  // Between two cubes along x both x groups face the eye.
  const std::vector<PlantMeshPart> two = {cube({0, 0, 0}), cube({10, 0, 0})};
  EXPECT_EQ(bake_plant_mesh(two).visible_groups({5.0f, 0.0f, 0.0f}), (1u << 0) | (1u << 1));
}

TEST(PlantMesh, PlantsAreConsecutiveRangesInEveryGroup) {
  // Three plants: two cubes, none (an empty plant), one cube with its +x face hidden.
  const std::vector<PlantMeshPart> parts = {cube({0, 0, 0}), cube({0, 1, 0}), cube({5, 0, 0}, 1.0f, face_bit(0, false))};
  const std::vector<std::uint32_t> starts = {0, 2, 2};
  const PlantMesh m = bake_plant_mesh(parts, starts);
  ASSERT_EQ(m.clusters.size(), 3u);
  for (int g = 0; g < 6; ++g) {
    const auto gi = static_cast<std::size_t>(g);
    const PlantMesh::Group& group = m.groups[gi];
    EXPECT_EQ(m.clusters[0].first[gi], group.first) << g;
    EXPECT_EQ(m.clusters[0].count[gi], 12u) << g;
    EXPECT_EQ(m.clusters[1].count[gi], 0u) << g;
    EXPECT_EQ(m.clusters[1].first[gi], m.clusters[2].first[gi]) << g;
    EXPECT_EQ(m.clusters[2].count[gi], g == 0 ? 0u : 6u) << g;
    // Back to back, covering the group.
    EXPECT_EQ(m.clusters[0].first[gi] + m.clusters[0].count[gi], m.clusters[2].first[gi]) << g;
    EXPECT_EQ(m.clusters[2].first[gi] + m.clusters[2].count[gi], group.first + group.count) << g;
    // Each plant's indices point at its own cubes: plant 2 lies at x > 4.
    for (std::uint32_t i = m.clusters[2].first[gi]; i < m.clusters[2].first[gi] + m.clusters[2].count[gi]; ++i)
      EXPECT_GT(position(m, i).x, 4.0f) << g;
    for (std::uint32_t i = m.clusters[0].first[gi]; i < m.clusters[0].first[gi] + m.clusters[0].count[gi]; ++i)
      EXPECT_LT(position(m, i).x, 1.0f) << g;
  }
  // Without starts: one cluster, the whole of every group.
  const PlantMesh whole = bake_plant_mesh(parts);
  ASSERT_EQ(whole.clusters.size(), 1u);
  for (int g = 0; g < kPlantMeshGroups; ++g) {
    EXPECT_EQ(whole.clusters[0].first[static_cast<std::size_t>(g)], whole.groups[static_cast<std::size_t>(g)].first);
    EXPECT_EQ(whole.clusters[0].count[static_cast<std::size_t>(g)], whole.groups[static_cast<std::size_t>(g)].count);
  }
}

TEST(PlantMesh, SkippedGroupsHoldNoFaceTurnedToTheEye) {
  std::mt19937 rng(18);
  std::uniform_real_distribution<float> pos(-16.0f, 16.0f), size(0.2f, 2.0f);
  std::vector<PlantMeshPart> parts;
  for (int i = 0; i < 200; ++i) {
    const glm::quat yaw = glm::angleAxis(1.5707963f * static_cast<float>(i % 4), glm::vec3(0, 1, 0));
    parts.push_back(cube({pos(rng), pos(rng), pos(rng)}, size(rng), static_cast<std::uint8_t>(i % 7), yaw));
  }
  const PlantMesh m = bake_plant_mesh(parts);
  std::uniform_real_distribution<float> far(-40.0f, 40.0f);
  std::uint64_t skipped = 0;
  for (int e = 0; e < 200; ++e) {
    const glm::vec3 eye(far(rng), far(rng), far(rng));
    const std::uint32_t seen = m.visible_groups(eye);
    for (int g = 0; g < kPlantMeshGroups; ++g) {
      const PlantMesh::Group& group = m.groups[static_cast<std::size_t>(g)];
      if ((seen >> g) & 1u) continue;
      for (std::uint32_t t = group.first; t < group.first + group.count; t += 3) {
        const glm::vec3 a = position(m, t);
        const glm::vec3 n = glm::cross(position(m, t + 1) - a, position(m, t + 2) - a);
        ASSERT_LE(glm::dot(n, eye - a), 1e-4f) << "group " << g << " eye " << e;
        ++skipped;
      }
    }
  }
  EXPECT_GT(skipped, 0u);
}

}  // namespace
}  // namespace sylva::voxel

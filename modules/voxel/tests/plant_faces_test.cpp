// Hidden faces of plant parts (plant_faces.hpp, issue #18): which faces of touching, nested,
// duplicate and cut-out cubes are hidden, quarter turns, and the far model's grid.

#include <sylva/voxel/plant_faces.hpp>

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

namespace sylva::voxel {
namespace {

FacePart cube(glm::vec3 centre, float size = 1.0f, bool opaque = true, int tag = 0) {
  FacePart f;
  f.part.position = centre;
  f.part.size = size;
  f.opaque = opaque;
  f.tag = tag;
  return f;
}

constexpr std::uint8_t kUp = face_bit(1, false), kDown = face_bit(1, true);

TEST(PlantFaces, ATrunkHidesTheFacesBetweenItsBlocks) {
  const std::vector<FacePart> trunk = {cube({0, 1, 0}), cube({0, 2, 0}), cube({0, 3, 0})};
  const auto m = hidden_faces(trunk, false);
  EXPECT_EQ(m[0], kUp);
  EXPECT_EQ(m[1], kUp | kDown);
  EXPECT_EQ(m[2], kDown);
}

TEST(PlantFaces, APartInsideAnotherIsHiddenButACoplanarFaceIsNot) {
  // A small cube in the middle of a big one: every face hidden (the part can be dropped).
  // One in the big cube's top corner keeps its top and side faces on the big cube's faces: those
  // are never hidden, so two coincident faces never hide each other.
  const std::vector<FacePart> parts = {cube({0, 0, 0}, 2.0f), cube({0, 0, 0}, 0.5f), cube({0.75f, 0.75f, 0.75f}, 0.5f)};
  const auto m = hidden_faces(parts, false);
  EXPECT_EQ(m[0], 0);
  EXPECT_EQ(m[1], kAllFaces);
  EXPECT_EQ(m[2], face_bit(0, true) | face_bit(1, true) | face_bit(2, true));
}

TEST(PlantFaces, DuplicatesKeepTheFirstAndOffsetCubesHideNothing) {
  const std::vector<FacePart> parts = {cube({0, 0, 0}), cube({0, 0, 0}), cube({0.3f, 1.0f, 0})};
  const auto m = hidden_faces(parts, false);
  EXPECT_EQ(m[0], 0);  // the offset cube above covers only part of its top face
  EXPECT_EQ(m[1], kAllFaces);
  EXPECT_EQ(m[2], 0);
}

TEST(PlantFaces, LeavesHideLeavesOnlyWhenAskedAndNeverLogs) {
  // A log between two leaves, and two leaves touching.
  const std::vector<FacePart> parts = {cube({0, 0, 0}, 1.0f, true), cube({0, 1, 0}, 1.0f, false), cube({0, 2, 0}, 1.0f, false)};
  const auto seen_through = hidden_faces(parts, false);
  EXPECT_EQ(seen_through[0], 0);      // leaves have holes: the log's top shows through
  EXPECT_EQ(seen_through[1], kDown);  // the leaf's face inside the log never shows
  EXPECT_EQ(seen_through[2], 0);
  const auto shell = hidden_faces(parts, true);
  EXPECT_EQ(shell[0], 0);
  EXPECT_EQ(shell[1], kUp | kDown);
  EXPECT_EQ(shell[2], kDown);
}

TEST(PlantFaces, TurnedPartsAreNeitherHiddenNorHide) {
  std::vector<FacePart> parts = {cube({0, 1, 0}), cube({0, 2, 0})};
  parts[1].part.orientation = glm::angleAxis(0.3f, glm::vec3(0, 1, 0));
  const auto m = hidden_faces(parts, false);
  EXPECT_EQ(m[0], 0);
  EXPECT_EQ(m[1], 0);
}

TEST(PlantFaces, QuarterTurnsMoveTheMaskWithTheNormals) {
  // glm::angleAxis(pi/2, +y) sends +x to -z: check against the quaternion itself.
  for (int turns = -1; turns <= 4; ++turns) {
    const glm::quat q = glm::angleAxis(static_cast<float>(turns) * 1.5707963f, glm::vec3(0, 1, 0));
    for (int axis = 0; axis < 3; ++axis)
      for (bool negative : {false, true}) {
        glm::vec3 n(0.0f);
        n[axis] = negative ? -1.0f : 1.0f;
        const glm::vec3 t = q * n;
        int to = 0;
        for (int a = 1; a < 3; ++a)
          if (std::abs(t[a]) > std::abs(t[to])) to = a;
        EXPECT_EQ(turn_faces(face_bit(axis, negative), turns), face_bit(to, t[to] < 0.0f))
            << "turns " << turns << " axis " << axis << " negative " << negative;
      }
  }
}

TEST(PlantFaces, TheFarGridMergesPartsPerCellByMajority) {
  const std::vector<FacePart> parts = {cube({0.1f, 1.2f, 0}, 0.6f, true, 0), cube({-0.2f, 0.9f, 0.3f}, 0.7f, false, 1),
                                       cube({0.2f, 1.1f, -0.1f}, 0.5f, false, 2), cube({0, 2.1f, 0}, 0.6f, true, 0)};
  const auto grid = snap_to_grid(parts, 1.0f);
  ASSERT_EQ(grid.size(), 2u);
  EXPECT_EQ(grid[0].part.position, glm::vec3(0, 1, 0));
  EXPECT_FALSE(grid[0].opaque);  // two leaves against one log
  EXPECT_EQ(grid[0].tag, 1);     // the first leaf's output
  EXPECT_EQ(grid[0].part.size, 1.0f);
  EXPECT_EQ(grid[1].part.position, glm::vec3(0, 2, 0));
  EXPECT_TRUE(grid[1].opaque);
  // On the grid the two cells touch: the shell hides the faces between them.
  const auto m = hidden_faces(grid, true);
  EXPECT_EQ(m[0], kUp);  // the log hides the leaf cell's top
  EXPECT_EQ(m[1], 0);    // a cut-out cell never hides a log
}

}  // namespace
}  // namespace sylva::voxel

// mesh_height_field (the far field on a mesh, issue 16): a rolling grid mesh is a height field whose
// samples lie on the mesh and whose density is the callback's; a box (its bottom faces down) and
// two upward sheets one above the other are not, and the message says where.
#include <sylva/grass/mesh_height_field.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace sylva::grass {
namespace {

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
};

float rolling(float x, float z) { return 1.5f * std::sin(0.2f * x) * std::cos(0.15f * z); }

// An n x n grid of quads over [-s, s]^2 at height y(x, z) + lift, wound to face up.
void add_sheet(Mesh& m, int n, float s, float lift, bool flat) {
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float x = -s + 2.0f * s * static_cast<float>(i) / static_cast<float>(n);
      const float z = -s + 2.0f * s * static_cast<float>(j) / static_cast<float>(n);
      m.positions.emplace_back(x, (flat ? 0.0f : rolling(x, z)) + lift, z);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = base + static_cast<std::uint32_t>(j * (n + 1) + i), b = a + 1, d = a + static_cast<std::uint32_t>(n + 1), c = d + 1;
      m.indices.insert(m.indices.end(), {a, d, b, b, d, c});  // (d - a) x (b - a) points up
    }
}

// Appends `other` moved by `shift`; `flip` reverses its winding (its faces then face down).
void append(Mesh& m, const Mesh& other, const glm::vec3& shift, bool flip) {
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  for (const glm::vec3& p : other.positions) m.positions.push_back(p + shift);
  for (std::size_t t = 0; t < other.indices.size(); t += 3) {
    m.indices.insert(m.indices.end(), {base + other.indices[t], base + other.indices[t + (flip ? 2 : 1)],
                                       base + other.indices[t + (flip ? 1 : 2)]});
  }
}

const MeshDensityAt kHalf = [](std::uint32_t, const glm::vec3&) { return 0.5f; };

TEST(FarMeshHeightField, RollingGridIsAHeightFieldOnTheMesh) {
  Mesh m;
  add_sheet(m, 40, 20.0f, 0.0f, false);
  auto hf = mesh_height_field(m.positions, m.indices, {0.0, 0.0, 0.0}, 0.5, kHalf);
  ASSERT_TRUE(hf.ok()) << hf.error().message;
  EXPECT_EQ(hf->heights.columns(), 81);
  EXPECT_EQ(hf->heights.rows(), 81);
  EXPECT_EQ(hf->covered, 81u * 81u);
  double worst = 0.0;
  for (int j = 0; j < 81; j += 3)
    for (int i = 0; i < 81; i += 3) {
      const double x = -20.0 + 0.5 * i, z = -20.0 + 0.5 * j;
      worst = std::max(worst, std::abs(static_cast<double>(hf->heights.sample(i, j)) - rolling(static_cast<float>(x), static_cast<float>(z))));
    }
  EXPECT_LT(worst, 0.02) << "samples lie on the mesh (linear between its 1 m vertices)";
  EXPECT_FLOAT_EQ(hf->density.at(40, 40, 0), 0.5f);
  EXPECT_DOUBLE_EQ(hf->rect.min.x, -20.25);
  EXPECT_DOUBLE_EQ(hf->rect.max.y, 20.25);
}

TEST(FarMeshHeightField, ABoxIsNotAHeightField) {
  // Top (up) and bottom (down) of a box: the bottom faces down.
  Mesh m;
  add_sheet(m, 4, 2.0f, 3.0f, true);
  Mesh bottom;
  add_sheet(bottom, 4, 2.0f, 0.0f, true);
  append(m, bottom, glm::vec3(0.0f), true);
  auto hf = mesh_height_field(m.positions, m.indices, {0.0, 0.0, 0.0}, 0.25, kHalf);
  ASSERT_FALSE(hf.ok());
  EXPECT_NE(hf.error().message.find("faces down"), std::string::npos) << hf.error().message;
}

TEST(FarMeshHeightField, TwoSheetsOverOnePointAreNotAHeightField) {
  Mesh m;
  add_sheet(m, 4, 2.0f, 0.0f, true);
  add_sheet(m, 4, 1.0f, 2.0f, true);  // a roof over part of the floor, facing up too
  auto hf = mesh_height_field(m.positions, m.indices, {0.0, 0.0, 0.0}, 0.25, kHalf);
  ASSERT_FALSE(hf.ok());
  EXPECT_NE(hf.error().message.find("at heights"), std::string::npos) << hf.error().message;
}

TEST(FarMeshHeightField, UncoveredSamplesTakeTheNearestHeightAndNoDensity) {
  // Two separate flat squares at different heights with a gap between them.
  Mesh m;
  add_sheet(m, 2, 1.0f, 0.0f, true);
  Mesh right;
  add_sheet(right, 2, 1.0f, 2.0f, true);
  append(m, right, glm::vec3(4.0f, 0.0f, 0.0f), false);
  auto hf = mesh_height_field(m.positions, m.indices, {0.0, 0.0, 0.0}, 0.5, kHalf);
  ASSERT_TRUE(hf.ok()) << hf.error().message;
  // x = 1.5 (column 5) lies in the gap, nearer the left square; x = 2.5 (column 7) nearer the right.
  EXPECT_FLOAT_EQ(hf->heights.sample(5, 2), 0.0f);
  EXPECT_FLOAT_EQ(hf->heights.sample(7, 2), 2.0f);
  EXPECT_FLOAT_EQ(hf->density.at(5, 2, 0), 0.0f);
  EXPECT_FLOAT_EQ(hf->density.at(2, 2, 0), 0.5f);
}

}  // namespace
}  // namespace sylva::grass

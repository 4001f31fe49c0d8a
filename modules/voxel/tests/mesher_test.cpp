// The three meshers produce the same visible surface (face-coverage count per unit face, block,
// AO and list) on random, terrain-like, checkerboard, empty, full and alpha-mixed chunks.

#include <sylva/voxel/mesher.hpp>

#include <gtest/gtest.h>

#include <vector>

#include "support/test_chunks.hpp"

namespace sylva::voxel {
namespace {

using testing::FaceCoverage;
using testing::Pattern;

void expect_same_coverage(const FaceCoverage& want, const FaceCoverage& got, const std::string& what) {
  ASSERT_EQ(want.count.size(), got.count.size()) << what;
  std::size_t mismatches = 0;
  for (std::size_t k = 0; k < want.count.size(); ++k) {
    const bool same = want.count[k] == got.count[k] &&
                      (want.count[k] == 0 || (want.block[k] == got.block[k] && want.ao[k] == got.ao[k] &&
                                              want.list[k] == got.list[k]));
    if (!same && ++mismatches <= 5) {
      ADD_FAILURE() << what << ": unit face " << k / 6 << " face " << k % 6 << " want count "
                    << int(want.count[k]) << " block " << want.block[k] << " ao " << int(want.ao[k])
                    << ", got count " << int(got.count[k]) << " block " << got.block[k] << " ao "
                    << int(got.ao[k]);
    }
  }
  EXPECT_EQ(mismatches, 0u) << what;
}

class MesherEquivalence : public ::testing::TestWithParam<std::tuple<Pattern, int>> {};

TEST_P(MesherEquivalence, AllMeshersCoverEveryVisibleFaceExactlyOnce) {
  const auto [pattern, n] = GetParam();
  const auto& palette = testing::test_palette();
  // Three seeds for the small chunks, one for 64^3 to keep the Debug test run short.
  const std::vector<std::uint64_t> seeds = n >= 64 ? std::vector<std::uint64_t>{1} : std::vector<std::uint64_t>{1, 2, 3};
  for (std::uint64_t seed : seeds) {
    const PaddedBlocks blocks = testing::make_pattern(pattern, n, seed);
    const FaceCoverage want = testing::reference_coverage(blocks, palette);
    std::size_t quads[3] = {};
    for (auto kind : {MesherKind::kCulled, MesherKind::kGreedy, MesherKind::kBitmask}) {
      auto mesher = make_mesher(kind);
      ChunkMesh mesh;
      mesher->mesh(blocks, palette, mesh);
      quads[static_cast<int>(kind)] = mesh.quad_count();
      expect_same_coverage(want, testing::coverage_of(mesh, n),
                           testing::to_string(pattern) + " n=" + std::to_string(n) + " " +
                               std::string(to_string(kind)));
    }
    // Merging never produces more quads than unit faces; the two greedy variants merge the same
    // key planes, so on these patterns they are within a small factor of each other.
    EXPECT_LE(quads[1], quads[0]);
    EXPECT_LE(quads[2], quads[0]);
  }
}

INSTANTIATE_TEST_SUITE_P(Patterns, MesherEquivalence,
                         ::testing::Combine(::testing::ValuesIn(testing::kAllPatterns),
                                            ::testing::Values(1, 5, 32, 64)),
                         [](const auto& info) {
                           return testing::to_string(std::get<0>(info.param)) + "_" +
                                  std::to_string(std::get<1>(info.param));
                         });

TEST(Mesher, EmptyAndFullChunksHaveNoInteriorFaces) {
  const auto& palette = testing::test_palette();
  for (auto kind : {MesherKind::kCulled, MesherKind::kGreedy, MesherKind::kBitmask}) {
    auto mesher = make_mesher(kind);
    ChunkMesh mesh;
    mesher->mesh(testing::make_pattern(Pattern::kEmpty, 32, 1), palette, mesh);
    EXPECT_TRUE(mesh.empty()) << to_string(kind);
    mesher->mesh(testing::make_pattern(Pattern::kFull, 32, 1), palette, mesh);
    EXPECT_TRUE(mesh.empty()) << to_string(kind) << " full chunk surrounded by full neighbours";
  }
}

TEST(Mesher, SingleBlockGivesSixUnitQuadsWithOpenAo) {
  const auto& palette = testing::test_palette();
  PaddedBlocks b(8);
  b.set(3, 3, 3, 1);
  for (auto kind : {MesherKind::kCulled, MesherKind::kGreedy, MesherKind::kBitmask}) {
    ChunkMesh mesh;
    make_mesher(kind)->mesh(b, palette, mesh);
    ASSERT_EQ(mesh.opaque.size(), 6u) << to_string(kind);
    EXPECT_TRUE(mesh.alpha_cut.empty());
    for (const auto& pq : mesh.opaque) {
      const Quad q = unpack_quad(pq);
      EXPECT_EQ(q.x, 3);
      EXPECT_EQ(q.y, 3);
      EXPECT_EQ(q.z, 3);
      EXPECT_EQ(q.du * q.dv, 1);
      for (auto a : q.ao) EXPECT_EQ(a, 3);
    }
  }
}

TEST(Mesher, FlatFloorMergesIntoOneQuadPerSideWhenAoIsUniform) {
  // A full 16x16 floor layer inside a 16^3 chunk whose ring is air: the top face has AO 3
  // everywhere, so greedy meshers emit a single 16x16 top quad.
  const auto& palette = testing::test_palette();
  PaddedBlocks b(16);
  for (int z = 0; z < 16; ++z)
    for (int x = 0; x < 16; ++x) b.set(x, 0, z, 2);
  for (auto kind : {MesherKind::kGreedy, MesherKind::kBitmask}) {
    ChunkMesh mesh;
    make_mesher(kind)->mesh(b, palette, mesh);
    int top = 0;
    for (const auto& pq : mesh.opaque) {
      const Quad q = unpack_quad(pq);
      if (q.face == static_cast<int>(Face::kPosY)) {
        ++top;
        EXPECT_EQ(q.du, 16);
        EXPECT_EQ(q.dv, 16);
      }
    }
    EXPECT_EQ(top, 1) << to_string(kind);
    EXPECT_EQ(mesh.opaque.size(), 6u) << to_string(kind);
  }
}

TEST(Mesher, AmbientOcclusionNextToAWall) {
  // A block on the floor against a wall: its top face's two vertices at the wall see one side
  // (ao 2), the others are open (3). Hand-checked against the 0fps formula.
  const auto& palette = testing::test_palette();
  PaddedBlocks b(8);
  b.set(2, 1, 2, 1);  // the block
  b.set(2, 2, 3, 1);  // wall block above-behind it (+z), in the layer in front of the top face
  std::uint8_t ao[4];
  face_ao(b, palette, 2, 1, 2, static_cast<int>(Face::kPosY), ao);
  // Top face: u = z, v = x. Corners (u,v): (0,0) z-, (1,0) z+, (1,1) z+, (0,1) z-.
  EXPECT_EQ(ao[0], 3);
  EXPECT_EQ(ao[1], 2);
  EXPECT_EQ(ao[2], 2);
  EXPECT_EQ(ao[3], 3);
}

TEST(Mesher, PackRoundTrip) {
  Quad q;
  q.x = 63;
  q.y = 0;
  q.z = 17;
  q.du = 64;
  q.dv = 1;
  q.face = 5;
  q.block = 65535;
  q.ao[0] = 0;
  q.ao[1] = 1;
  q.ao[2] = 2;
  q.ao[3] = 3;
  const Quad r = unpack_quad(pack_quad(q));
  EXPECT_EQ(r.x, q.x);
  EXPECT_EQ(r.y, q.y);
  EXPECT_EQ(r.z, q.z);
  EXPECT_EQ(r.du, q.du);
  EXPECT_EQ(r.dv, q.dv);
  EXPECT_EQ(r.face, q.face);
  EXPECT_EQ(r.block, q.block);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(r.ao[i], q.ao[i]);
}

TEST(Mesher, ParseKind) {
  EXPECT_EQ(*parse_mesher_kind("bitmask"), MesherKind::kBitmask);
  auto bad = parse_mesher_kind("binary");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("'binary'"), std::string::npos);
}

}  // namespace
}  // namespace sylva::voxel

namespace sylva::voxel {
namespace {

TEST(Mesher, WithoutAoAllMeshersAgreeAndMergeMore) {
  const auto& palette = testing::test_palette();
  for (auto pattern : {testing::Pattern::kTerrain, testing::Pattern::kRandom, testing::Pattern::kMixedAlpha}) {
    const PaddedBlocks blocks = testing::make_pattern(pattern, 32, 4);
    ChunkMesh with_ao, reference;
    make_mesher(MesherKind::kBitmask)->mesh(blocks, palette, with_ao);
    MesherOptions off;
    off.ambient_occlusion = false;
    make_mesher(MesherKind::kCulled, off)->mesh(blocks, palette, reference);
    const auto want = testing::coverage_of(reference, 32);
    for (auto kind : {MesherKind::kGreedy, MesherKind::kBitmask}) {
      ChunkMesh mesh;
      make_mesher(kind, off)->mesh(blocks, palette, mesh);
      const auto got = testing::coverage_of(mesh, 32);
      EXPECT_EQ(got.count, want.count) << to_string(kind);
      EXPECT_EQ(got.block, want.block) << to_string(kind);
      for (auto ao : got.ao) {
        ASSERT_TRUE(ao == 0 || ao == 0xff);
      }
      if (kind == MesherKind::kBitmask) {
        EXPECT_LE(mesh.quad_count(), with_ao.quad_count());
      }
    }
  }
}

}  // namespace
}  // namespace sylva::voxel

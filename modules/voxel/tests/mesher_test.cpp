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

namespace sylva::voxel {
namespace {

// The bitmask mesher reads a face's AO from a table indexed by the 3 x 3 opaque neighbourhood in
// front of it (bits of three mask rows); faces on a chunk edge row read the padding blocks
// instead. Every one of the 512 neighbourhoods, for every face direction, away from the edges and
// on them, must give the reference AO (face_ao) and the same coverage as the other meshers.
TEST(Mesher, BitmaskAoMatchesTheReferenceForEveryNeighbourhood) {
  const auto& palette = testing::test_palette();
  const BlockId stone = 1, dirt = 2;
  for (int face = 0; face < 6; ++face) {
    const int axis = face_axis(face);
    const int sign = face_sign(face);
    const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
    // 512 probes on a 4-block grid (3 x 3 neighbourhood plus a gap): 8 x 8 in the face plane,
    // 8 deep along the axis; a 32^3 chunk puts the first and last probes of a row on its edges.
    // The first and last probes along u and v sit on the chunk's edges (0 and 31), so their
    // neighbourhoods reach into the padding ring (bit edges and row edges of the masks).
    auto place = [](int i) { return i == 0 ? 0 : i == 7 ? 31 : 1 + 4 * i; };
    auto probe = [&](int c, int pos[3]) {
      pos[ua] = place(c & 7);
      pos[va] = place((c >> 3) & 7);
      pos[axis] = 1 + 4 * (c >> 6) + (sign < 0 ? 1 : 0);
    };
    PaddedBlocks b(32);
    for (int c = 0; c < 512; ++c) {
      int pos[3];
      probe(c, pos);
      b.set(pos[0], pos[1], pos[2], dirt);
      for (int k = 0; k < 9; ++k) {
        if (k == 4 || ((c >> (k < 4 ? k : k - 1)) & 1) == 0) continue;
        int q[3] = {pos[0], pos[1], pos[2]};
        q[axis] += sign;
        q[ua] += k % 3 - 1;
        q[va] += k / 3 - 1;
        b.set(q[0], q[1], q[2], stone);
      }
    }
    const FaceCoverage want = testing::reference_coverage(b, palette);
    ChunkMesh mesh;
    make_mesher(MesherKind::kBitmask)->mesh(b, palette, mesh);
    expect_same_coverage(want, testing::coverage_of(mesh, 32), "neighbourhoods, face " + std::to_string(face));
    // The probe faces themselves: each has its configuration's AO.
    std::size_t checked = 0;
    const auto got = testing::coverage_of(mesh, 32);
    for (int c = 0; c < 512; ++c) {
      int pos[3];
      probe(c, pos);
      std::uint8_t ao[4];
      face_ao(b, palette, pos[0], pos[1], pos[2], face, ao);
      const std::size_t k = got.index(pos[0], pos[1], pos[2], face);
      ASSERT_EQ(got.count[k], 1) << "face " << face << " probe " << c;
      EXPECT_EQ(got.ao[k], ao[0] | ao[1] << 2 | ao[2] << 4 | ao[3] << 6) << "face " << face << " probe " << c;
      ++checked;
    }
    EXPECT_EQ(checked, 512u);
  }
}

// Odd sizes and many seeds: the edge-row AO path (bits 0 and n - 1) and the run path.
TEST(Mesher, BitmaskMatchesTheReferenceOnOddSizesAndManySeeds) {
  const auto& palette = testing::test_palette();
  for (int n : {2, 3, 31, 33, 63}) {
    for (auto pattern : {Pattern::kRandom, Pattern::kTerrain, Pattern::kMixedAlpha}) {
      for (std::uint64_t seed = 10; seed < (n > 40 ? 11u : 13u); ++seed) {
        const PaddedBlocks blocks = testing::make_pattern(pattern, n, seed);
        ChunkMesh mesh;
        make_mesher(MesherKind::kBitmask)->mesh(blocks, palette, mesh);
        expect_same_coverage(testing::reference_coverage(blocks, palette), testing::coverage_of(mesh, n),
                             testing::to_string(pattern) + " n=" + std::to_string(n) + " seed " +
                                 std::to_string(seed));
      }
    }
  }
}

}  // namespace
}  // namespace sylva::voxel

namespace sylva::voxel {
namespace {

// The bitmask mesher writes into the ChunkMesh's own lists and cuts them at the end: meshing
// into a mesh that still holds a larger (or any) previous result must give exactly the fresh one.
TEST(Mesher, BitmaskReusedOutputEqualsFreshOutput) {
  const auto& palette = testing::test_palette();
  auto mesher = make_mesher(MesherKind::kBitmask);
  ChunkMesh reused;
  mesher->mesh(testing::make_pattern(Pattern::kCheckerboard, 32, 1), palette, reused);
  ASSERT_GT(reused.quad_count(), 10000u);
  for (auto pattern : {Pattern::kTerrain, Pattern::kMixedAlpha, Pattern::kEmpty, Pattern::kRandom}) {
    const PaddedBlocks blocks = testing::make_pattern(pattern, 32, 5);
    ChunkMesh fresh;
    make_mesher(MesherKind::kBitmask)->mesh(blocks, palette, fresh);
    mesher->mesh(blocks, palette, reused);
    EXPECT_EQ(reused.opaque, fresh.opaque) << testing::to_string(pattern);
    EXPECT_EQ(reused.alpha_cut, fresh.alpha_cut) << testing::to_string(pattern);
  }
  mesher->mesh(testing::make_pattern(Pattern::kEmpty, 32, 1), palette, reused);
  EXPECT_TRUE(reused.empty());
}

}  // namespace
}  // namespace sylva::voxel

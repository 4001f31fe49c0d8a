// The seed's -reduce per pass (seed 002 §4.3, Tab. 4.6-4.11) beside keep_per_level: a segment d
// levels above the leaves gets d passes, each removing the set share of what is left.
#include <sylva/terrain/model_tree.hpp>
#include <sylva/terrain/subdivision.hpp>

#include "support/terrain_test_support.hpp"

#include <gtest/gtest.h>

namespace sylva::terrain {
namespace {

TriangleMesh sheet() {
  SubdivisionSettings s;
  s.level = 3;
  return triangulate(subdivide(testing::overhang_cage(8, 200.0, 0.8f), s).value());
}

TEST(ModelReduce, ReducePerPassRemovesItsSharePerLevel) {
  const TriangleMesh mesh = sheet();
  for (float reduce : {0.25f, 0.5f}) {
    ModelTreeSettings ms;
    ms.levels = 3;
    ms.reduce_per_pass = reduce;
    auto tree = ModelTree::build(mesh, ms);
    ASSERT_TRUE(tree.ok()) << tree.error().describe();
    const ModelBuildReport& r = tree->report();
    EXPECT_EQ(r.holes + r.degenerate + r.non_manifold + r.flipped, 0u);
    const double n = static_cast<double>(mesh.triangle_count());
    EXPECT_EQ(r.levels[2].triangles, mesh.triangle_count()) << "leaves are not reduced";
    // One pass at level 1, two at level 0; locked borders keep a few more triangles than the share.
    const double keep = 1.0 - reduce;
    EXPECT_LE(r.levels[1].triangles, keep * n * 1.15) << reduce;
    EXPECT_GE(r.levels[1].triangles, keep * n * 0.9) << reduce;
    EXPECT_LE(r.levels[0].triangles, keep * keep * n * 1.15) << reduce;
    EXPECT_GE(r.levels[0].triangles, keep * keep * n * 0.9) << reduce;
  }
}

TEST(ModelReduce, OffByDefaultAndValidated) {
  EXPECT_EQ(ModelTreeSettings{}.reduce_per_pass, 0.0f);
  ModelTreeSettings bad;
  bad.reduce_per_pass = 1.5f;
  auto r = ModelTree::build(sheet(), bad);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("reduce_per_pass"), std::string::npos) << r.error().message;
}

}  // namespace
}  // namespace sylva::terrain

// The module's data files load: the seed's plain OBJT layout and a generated file with the Sylva
// extensions, which also round-trips exactly.
#include <sylva/vegetation/objt.hpp>
#include <sylva/vegetation/tree_mesh.hpp>

#include <sylva/core/atomic_file.hpp>

#include <gtest/gtest.h>

#include <filesystem>

namespace sylva::vegetation {
namespace {

const std::filesystem::path kData = SYLVA_VEGETATION_DATA_DIR;

TEST(Data, SeedExampleLoads) {
  Result<TreeModel> m = load_objt(kData / "seed_example.objt");
  ASSERT_TRUE(m.ok()) << m.error().describe();
  EXPECT_EQ(m->name, "seed example");
  EXPECT_EQ(m->branches.size(), 3u);
  EXPECT_EQ(m->leaves.size(), 2u);
  const TreeMesh mesh = build_tree_mesh(*m);
  EXPECT_GT(mesh.branch_vertices.size(), 30u);
}

TEST(Data, SaplingRoundTrips) {
  Result<TreeModel> m = load_objt(kData / "sapling.objt");
  ASSERT_TRUE(m.ok()) << m.error().describe();
  EXPECT_EQ(m->depth(), 3);
  Result<std::string> text = read_file(kData / "sapling.objt");
  ASSERT_TRUE(text.ok());
  EXPECT_EQ(format_objt(*m), *text);
}

}  // namespace
}  // namespace sylva::vegetation

// The voxel settings are parameters (DESIGN.md §2): every field is reachable by dotted path,
// validated, and the defaults are valid.

#include <sylva/core/params.hpp>
#include <sylva/voxel/voxel_world.hpp>

#include <gtest/gtest.h>

namespace sylva::voxel {
namespace {

TEST(VoxelSettings, DefaultsValidAndPathsSettable) {
  VoxelWorldSettings s;
  EXPECT_TRUE(validate_params(s, "voxel").ok());
  const auto params = describe_params(s, "voxel");
  EXPECT_GE(params.size(), 25u);
  ASSERT_TRUE(set_param(s, "mesher", "greedy").ok());
  EXPECT_EQ(s.mesher, MesherKind::kGreedy);
  ASSERT_TRUE(set_param(s, "generation.seed", "77").ok());
  EXPECT_EQ(s.generation.seed, 77u);
  ASSERT_TRUE(set_param(s, "render.light_kq", "0.02").ok());
  EXPECT_FLOAT_EQ(s.render.light_kq, 0.02f);
  const Status bad = set_param(s, "render.max_point_lights", "100");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("render.max_point_lights"), std::string::npos) << bad.error().message;
  EXPECT_FALSE(set_param(s, "mesher", "binary").ok());
  EXPECT_EQ(s.mesher, MesherKind::kGreedy) << "a failed set leaves the value unchanged";
  LSystemExecutorSettings e;
  EXPECT_TRUE(validate_params(e, "voxel.lsystem").ok());
  ASSERT_TRUE(set_param(e, "angle_variation", "0.5").ok());
  EXPECT_FALSE(set_param(e, "angle_variation", "2").ok());
}

}  // namespace
}  // namespace sylva::voxel

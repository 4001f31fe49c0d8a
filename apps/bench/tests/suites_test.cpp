// Every curated suite (--suite) whose module is in this build names only parameters its scene
// has, with values in range: validate_spec() checks the sweeps, the reference and the camera
// path without rendering (no GL). A module that renamed a path breaks this test, not a
// half-finished suite run. Suites whose module is missing must say "module not available".
#include "suites.hpp"

#include <gtest/gtest.h>

namespace sylva::bench {
namespace {

TEST(BenchSuites, EveryAvailableSuiteNamesExistingParameters) {
  int available = 0;
  for (const std::string& name : suite_names()) {
    Result<SuiteSpec> suite = make_suite(name);
    if (!suite.ok()) {
      EXPECT_EQ(suite.error().code, ErrorCode::kUnsupported) << name << ": " << suite.error().message;
      EXPECT_NE(suite.error().message.find("module not available"), std::string::npos) << suite.error().message;
      continue;
    }
    ++available;
    EXPECT_EQ(suite->name, name);
    EXPECT_FALSE(suite->run.sweep_groups.empty()) << name;
    EXPECT_FALSE(suite->run.reference.empty()) << name << ": a suite defines its maximum-quality reference";
    const Status valid = validate_spec(suite->run);
    EXPECT_TRUE(valid.ok()) << name << ": " << valid.error().message;
  }
#if defined(SYLVA_BENCH_WITH_SCENE) && defined(SYLVA_BENCH_WITH_TERRAIN) && defined(SYLVA_BENCH_WITH_GRASS) && \
    defined(SYLVA_BENCH_WITH_VEGETATION) && defined(SYLVA_BENCH_WITH_VOXEL)
  EXPECT_EQ(available, 5) << "every content module is built, so every suite must be available";
#endif
}

// The general model (seed 002 §4): tau on a 5-level tree and the tree height at tau 1 against the
// full-resolution mesh (a one-level tree), on the shipped scenes/model_terrain.obj.
TEST(BenchSuites, ModelSuiteSweepsTauAndLevelsAgainstTheFullMesh) {
  Result<SuiteSpec> suite = make_suite("model");
  if (!suite.ok()) {
    ASSERT_EQ(suite.error().code, ErrorCode::kUnsupported) << suite.error().message;
    GTEST_SKIP() << suite.error().message;
  }
  EXPECT_EQ(suite->module, "model_terrain");
  std::vector<std::string> taus, levels;
  for (const auto& group : suite->run.sweep_groups) {
    ASSERT_EQ(group.size(), 2u);
    if (group[0].path == "model_terrain.tree.levels") taus = group[1].values;
    if (group[1].path == "model_terrain.tree.levels") levels = group[1].values;
  }
  EXPECT_EQ(taus, (std::vector<std::string>{"0.5", "1", "2", "4", "8"}));
  EXPECT_EQ(levels, (std::vector<std::string>{"2", "3", "4", "6"}));
  ASSERT_EQ(suite->run.reference.size(), 1u);
  EXPECT_EQ(suite->run.reference[0].path, "model_terrain.tree.levels");
  EXPECT_EQ(suite->run.reference[0].value, "1") << "one level: the file's mesh itself";
  const Status valid = validate_spec(suite->run);
  EXPECT_TRUE(valid.ok()) << valid.error().message;
}

TEST(BenchSuites, UnknownSuiteIsNamed) {
  Result<SuiteSpec> suite = make_suite("forest");
  ASSERT_FALSE(suite.ok());
  EXPECT_EQ(suite.error().code, ErrorCode::kNotFound);
  EXPECT_NE(suite.error().message.find("\"forest\""), std::string::npos) << suite.error().message;
}

}  // namespace
}  // namespace sylva::bench

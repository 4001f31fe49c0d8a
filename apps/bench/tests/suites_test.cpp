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
  EXPECT_EQ(available, 4) << "every content module is built, so every suite must be available";
#endif
}

TEST(BenchSuites, UnknownSuiteIsNamed) {
  Result<SuiteSpec> suite = make_suite("forest");
  ASSERT_FALSE(suite.ok());
  EXPECT_EQ(suite.error().code, ErrorCode::kNotFound);
  EXPECT_NE(suite.error().message.find("\"forest\""), std::string::npos) << suite.error().message;
}

}  // namespace
}  // namespace sylva::bench

// builtin:terrain (the terrain module's chunk tree, selection, morphing and seams drawn by the
// bench): a tau sweep reports the largest projected geometric error of the drawn chunks, which
// must stay within tau (Ulrich's bound), and the seed's distance criterion is measured in the
// same units.
#include <sylva/core/atomic_file.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;

namespace {

#ifdef SYLVA_BENCH_WITH_TERRAIN

TEST(BenchTerrainSweep, ProjectedErrorStaysWithinTau) {
  const fs::path out = fs::temp_directory_path() / ("sylva-bench-terrain-test-" + std::to_string(::getpid()));
  fs::remove_all(out);
  fs::create_directories(out);
  const std::string cmd =
      std::string(SYLVA_BENCH_EXE) +
      " builtin:terrain --set terrain.field.size=257 --set terrain.field.spacing=8 --set terrain.tree.leaf_dimension=17"
      " --sweep terrain.lod.max_pixel_error=1,4 --reference terrain.lod.max_pixel_error=0.05 --camera-path descent"
      " --frames 3 --warmup 1 --size 96x54 --out '" + out.string() + "' > '" + (out / "log.txt").string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  auto log = sylva::read_file(out / "log.txt");
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << (log.ok() ? *log : "");
  auto text = sylva::read_file(out / "results.json");
  ASSERT_TRUE(text.ok());
  const nlohmann::json j = nlohmann::json::parse(*text);
  ASSERT_EQ(j["settings"].size(), 2u);
  const double taus[2] = {1.0, 4.0};
  std::uint64_t triangles[2] = {0, 0};
  for (int i = 0; i < 2; ++i) {
    const nlohmann::json& s = j["settings"][i];
    ASSERT_TRUE(s["image_error"].contains("max_geometric_error_px")) << s.dump();
    const double rho = s["image_error"]["max_geometric_error_px"].get<double>();
    EXPECT_GT(rho, 0.0) << "tau " << taus[i];
    EXPECT_LE(rho, taus[i] * (1.0 + 1e-6)) << "tau " << taus[i];
    triangles[i] = s["totals"]["triangles"].get<std::uint64_t>();
    EXPECT_FALSE(s["totals"]["lod_instances"].empty());
  }
  EXPECT_LT(triangles[1], triangles[0]);  // a larger tau draws fewer triangles
  EXPECT_LT(triangles[0], j["reference"]["totals"]["triangles"].get<std::uint64_t>());
  auto html = sylva::read_file(out / "report.html");
  ASSERT_TRUE(html.ok());
  EXPECT_NE(html->find("max geometric error px"), std::string::npos);
  fs::remove_all(out);
}

#else

TEST(BenchTerrainSweep, TerrainModuleNotInThisBuild) {
  GTEST_SKIP() << "the terrain module is not part of this build";
}

#endif

}  // namespace

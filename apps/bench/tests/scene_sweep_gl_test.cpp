// sylva-bench on a scene file through modules/scene (when the scene module is part of the
// build): the shipped ground-only scene swept over its mesh resolution, and the scene's own
// parameter paths in error messages.
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

#if defined(SYLVA_BENCH_WITH_SCENE) && defined(SYLVA_BENCH_SCENES_DIR)

int run(const std::string& args, const fs::path& log, std::string& output) {
  const std::string cmd = std::string(SYLVA_BENCH_EXE) + " " + args + " > '" + log.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  auto text = sylva::read_file(log);
  output = text.ok() ? *text : "";
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

fs::path test_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("sylva-bench-scene-test-" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

const std::string kGroundScene = std::string(SYLVA_BENCH_SCENES_DIR) + "/ground.json";

TEST(BenchSceneSweep, GroundSceneResolutionSweep) {
  const fs::path out = test_dir("ground");
  std::string output;
  const int code = run("'" + kGroundScene + "' --sweep ground.resolution=17,33 --reference ground.resolution=129 "
                       "--camera-path orbit --frames 2 --size 96x54 --warmup 1 --out '" + out.string() + "'",
                       out / "log.txt", output);
  ASSERT_EQ(code, 0) << output;
  auto text = sylva::read_file(out / "results.json");
  ASSERT_TRUE(text.ok());
  const nlohmann::json j = nlohmann::json::parse(*text);
  ASSERT_EQ(j["settings"].size(), 2u);
  EXPECT_EQ(j["run"]["camera_path"], "orbit");
  // The scene's ground module reports triangles; the coarser grid has fewer, the reference most.
  const auto tri = [&](const nlohmann::json& s) { return s["totals"]["triangles"].get<std::uint64_t>(); };
  EXPECT_LT(tri(j["settings"][0]), tri(j["settings"][1]));
  EXPECT_LT(tri(j["settings"][1]), tri(j["reference"]));
  EXPECT_GT(j["settings"][0]["totals"]["fragments"].get<std::uint64_t>(), 0u);
  // Per-module GPU time is recorded as a metric.
  EXPECT_TRUE(j["settings"][0]["metrics"].contains("ground.gpu_ms")) << j["settings"][0]["metrics"].dump();
  auto html = sylva::read_file(out / "report.html");
  ASSERT_TRUE(html.ok());
  EXPECT_NE(html->find("ground.resolution=33"), std::string::npos);
}

TEST(BenchSceneSweep, UnknownScenePathAndCameraPathAreNamed) {
  const fs::path out = test_dir("unknown");
  std::string output;
  EXPECT_EQ(run("'" + kGroundScene + "' --sweep grass.field.density=1,2 --out '" + (out / "o").string() + "'",
                out / "log.txt", output),
            2);
  EXPECT_NE(output.find("--sweep grass.field.density"), std::string::npos) << output;
  EXPECT_EQ(run("'" + kGroundScene + "' --camera-path nowhere --out '" + (out / "o").string() + "'", out / "log2.txt",
                output),
            2);
  EXPECT_NE(output.find("nowhere"), std::string::npos) << output;
  EXPECT_NE(output.find("orbit"), std::string::npos) << output;  // lists the paths the scene has
}

#else

TEST(BenchSceneSweep, SceneModuleNotInThisBuild) {
  GTEST_SKIP() << "modules/scene is not part of this build; scene files cannot be benchmarked";
}

#endif

}  // namespace

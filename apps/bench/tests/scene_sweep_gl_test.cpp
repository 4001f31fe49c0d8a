// sylva-bench on a scene file through modules/scene (when the scene module is part of the
// build): the shipped ground-only scene swept over its mesh resolution, and the scene's own
// parameter paths in error messages.
#include "bench_exe.hpp"

#include <sylva/core/atomic_file.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace {

#if defined(SYLVA_BENCH_WITH_SCENE) && defined(SYLVA_BENCH_SCENES_DIR)

using sylva::bench::testing::run_bench;

fs::path test_dir(const std::string& name) { return sylva::bench::testing::fresh_test_dir("sylva-bench-scene-test", name); }

const std::string kGroundScene = std::string(SYLVA_BENCH_SCENES_DIR) + "/ground.json";

TEST(BenchSceneSweep, GroundSceneResolutionSweep) {
  const fs::path out = test_dir("ground");
  std::string output;
  const int code = run_bench("'" + kGroundScene + "' --sweep ground.resolution=17,33 --reference ground.resolution=129 "
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
  // Memory columns (issue #20): tracked GPU memory and the process's peak RSS.
  const nlohmann::json& m = j["settings"][0]["metrics"];
  ASSERT_TRUE(m.contains("memory.gpu_mib") && m.contains("memory.peak_rss_mib")) << m.dump();
  EXPECT_GT(m["memory.gpu_mib"]["max"].get<double>(), 0.0);
  EXPECT_GT(m["memory.peak_rss_mib"]["max"].get<double>(), 10.0);
  EXPECT_GT(m["memory.gpu_mib.ground"]["max"].get<double>(), 0.0) << "the ground module's own GPU memory";
  // Per-pass and per-module-per-pass GPU time, and the module's set-up time.
  EXPECT_TRUE(m.contains("pass.opaque.gpu_ms")) << m.dump();
  EXPECT_TRUE(m.contains("ground.opaque.gpu_ms")) << m.dump();
  EXPECT_TRUE(m.contains("ground.build_ms")) << m.dump();
  auto html = sylva::read_file(out / "report.html");
  ASSERT_TRUE(html.ok());
  EXPECT_NE(html->find("ground.resolution=33"), std::string::npos);
}

#ifdef SYLVA_BENCH_WITH_TERRAIN
// A 1 km fBm terrain (257^2 samples, 17-vertex chunks) with its tree cached in dir/cache and a
// two-key camera path "fly"; returns the scene file (empty if it could not be written).
fs::path write_small_terrain_scene(const fs::path& dir) {
  const fs::path scene = dir / "terrain_small.json";
  const bool written = sylva::write_file_atomic(scene, R"({
  "sylva_scene": 1,
  "camera": {"position": [-400.0, 60.0, 400.0], "height_mode": "above_ground", "yaw_deg": -45.0, "pitch_deg": -10.0},
  "sun": {"azimuth_deg": 200.0, "elevation_deg": 35.0},
  "render": {"shadows": {"enabled": false}},
  "terrain": {"size": 1024.0, "resolution": 257, "height": 250.0, "generator": "fbm",
              "noise": {"octaves": 7, "frequency": 0.002, "seed": 21}, "tree": {"leaf_dimension": 17},
              "tree_cache": {"directory": "cache", "min_samples": 0}},
  "camera_paths": {"fly": {"keys": [
    {"time_s": 0.0, "position": [-400.0, 60.0, 400.0], "height_mode": "above_ground", "yaw_deg": -45.0, "pitch_deg": -10.0},
    {"time_s": 4.0, "position": [200.0, 40.0, -150.0], "height_mode": "above_ground", "yaw_deg": -40.0, "pitch_deg": -8.0}]}}
})").ok();
  return written ? scene : fs::path();
}

// sylva-bench on the small terrain scene in a fresh test folder `name` with `args`, along "fly",
// 2 frames at 96x54: `out` is the folder, `output` the console text, `j` its results.json (two
// settings expected).
void run_small_terrain_sweep(const std::string& name, const std::string& args, fs::path& out, std::string& output,
                             nlohmann::json& j) {
  out = test_dir(name);
  const fs::path scene = write_small_terrain_scene(out);
  ASSERT_FALSE(scene.empty());
  const int code = run_bench("'" + scene.string() + "' " + args + " --camera-path fly --frames 2 --warmup 1 --size 96x54 "
                             "--out '" + (out / "o").string() + "'",
                             out / "log.txt", output);
  ASSERT_EQ(code, 0) << output;
  auto text = sylva::read_file(out / "o" / "results.json");
  ASSERT_TRUE(text.ok());
  j = nlohmann::json::parse(*text);
  ASSERT_EQ(j["settings"].size(), 2u);
}

// The scene's terrain (modules/scene terrain section drawn by the terrain module's renderer):
// the bench reads the drawn chunks' largest projected geometric error and the chunks per LOD
// level. tau bounds the error of every chunk that could have been refined (the "certified"
// metric) and, since the leaves are exact (terrain README, "Meshes"), the drawn maximum too,
// although the path comes within 3 m of a leaf box (reduced leaves drew 1.27 px at tau 1 here).
TEST(BenchSceneSweep, SceneTerrainProjectedErrorWithinTau) {
  fs::path out;
  std::string output;
  nlohmann::json j;
  ASSERT_NO_FATAL_FAILURE(run_small_terrain_sweep(
      "terrain", "--sweep terrain.render.lod.max_pixel_error=1,4 --reference terrain.render.lod.max_pixel_error=0.05",
      out, output, j));
  const double taus[2] = {1.0, 4.0};
  for (int i = 0; i < 2; ++i) {
    const nlohmann::json& s = j["settings"][i];
    ASSERT_TRUE(s["image_error"].contains("max_geometric_error_px")) << s.dump();
    const double rho = s["image_error"]["max_geometric_error_px"].get<double>();
    ASSERT_TRUE(s["metrics"].contains("terrain.certified_projected_error_px")) << s["metrics"].dump();
    const double certified = s["metrics"]["terrain.certified_projected_error_px"]["max"].get<double>();
    EXPECT_GT(certified, 0.0);
    EXPECT_LE(certified, taus[i] * (1.0 + 1e-6)) << "tau " << taus[i];
    EXPECT_GE(rho, certified);
    EXPECT_LE(rho, taus[i] * (1.0 + 1e-6)) << "tau " << taus[i] << ": the drawn error, leaves included";
    bool has_level = false;
    for (auto it = s["totals"]["lod_instances"].begin(); it != s["totals"]["lod_instances"].end(); ++it) {
      has_level = has_level || it.key().rfind("terrain.level", 0) == 0;
    }
    EXPECT_TRUE(has_level) << s["totals"].dump();
  }
  // Issue 18: triangles per covered pixel beside the drawn chunks' projected-error histogram.
  // The histogram holds every drawn chunk (its bins sum to the renderer's chunks_drawn) and no
  // chunk above tau (the leaves are exact); a coarser tau draws fewer triangles per pixel.
  double per_pixel[2] = {0.0, 0.0};
  for (int i = 0; i < 2; ++i) {
    const nlohmann::json& m = j["settings"][i]["metrics"];
    ASSERT_TRUE(m.contains("terrain.triangles_per_pixel")) << m.dump();
    per_pixel[i] = m["terrain.triangles_per_pixel"]["mean"].get<double>();
    EXPECT_GT(per_pixel[i], 0.0);
    double chunks = 0.0, above_tau = 0.0;
    for (auto it = m.begin(); it != m.end(); ++it) {
      const std::string prefix = "terrain.error_hist.chunks.";
      if (it.key().rfind(prefix, 0) != 0) continue;
      chunks += it.value()["mean"].get<double>();
      const std::string bin = it.key().substr(prefix.size());
      const double low = bin == "exact" ? 0.0 : std::stod(bin);
      if (low >= taus[i]) above_tau += it.value()["max"].get<double>();
    }
    ASSERT_TRUE(m.contains("terrain.chunks_drawn")) << m.dump();
    EXPECT_NEAR(chunks, m["terrain.chunks_drawn"]["mean"].get<double>(), 1e-9) << "tau " << taus[i];
    EXPECT_EQ(above_tau, 0.0) << "tau " << taus[i] << ": chunks in a histogram bin at or above tau";
    // Every frame's figure is in the JSON, not only the aggregate.
    for (const nlohmann::json& f : j["settings"][i]["frame_records"]) {
      EXPECT_TRUE(f["metrics"].contains("terrain.triangles_per_pixel")) << f.dump();
    }
  }
  EXPECT_LT(per_pixel[1], per_pixel[0]) << "tau 4 against tau 1";
  EXPECT_NE(output.find("terrain terrain.render.lod.max_pixel_error=1: triangles/pixel mean"), std::string::npos)
      << output;
  // The chunk-tree cache (issue 15) as columns: every setting builds its own scene from the file,
  // so the first one built the tree into the scene's cache folder and the second reopened it.
  ASSERT_TRUE(j["settings"][1]["metrics"].contains("terrain.tree_cache_hit")) << j["settings"][1]["metrics"].dump();
  EXPECT_EQ(j["settings"][1]["metrics"]["terrain.tree_cache_hit"]["max"].get<double>(), 1.0);
  EXPECT_TRUE(j["settings"][0]["metrics"].contains("terrain.tree_build_ms"));
  EXPECT_TRUE(fs::exists(out / "cache"));
  EXPECT_LT(j["settings"][1]["totals"]["triangles"].get<std::uint64_t>(),
            j["settings"][0]["totals"]["triangles"].get<std::uint64_t>());
  auto html = sylva::read_file(out / "o" / "report.html");
  ASSERT_TRUE(html.ok());
  EXPECT_NE(html->find("max geometric error px"), std::string::npos);
}

// Issue 18: terrain.render.aerial_perspective reached from a scene file through sylva-bench.
// Against per_pixel in dense haze, per_vertex (the default) moves no pixel by 0.05 while off,
// the ground without air, moves many.
TEST(BenchSceneSweep, SceneTerrainAerialPerspectiveSettings) {
  fs::path out;
  std::string output;
  nlohmann::json j;
  ASSERT_NO_FATAL_FAILURE(run_small_terrain_sweep("terrain_air",
                                                  "--sweep terrain.render.aerial_perspective=per_vertex,off "
                                                  "--reference terrain.render.aerial_perspective=per_pixel "
                                                  "--set sun.fog_density=0.003",
                                                  out, output, j));
  EXPECT_EQ(j["settings"][0]["image_error"]["share_exceeding_max"].get<double>(), 0.0) << "per_vertex";
  EXPECT_GT(j["settings"][1]["image_error"]["share_exceeding_max"].get<double>(), 0.2) << "off";
}
#endif

TEST(BenchSceneSweep, UnknownScenePathAndCameraPathAreNamed) {
  const fs::path out = test_dir("unknown");
  std::string output;
  EXPECT_EQ(run_bench("'" + kGroundScene + "' --sweep grass.field.density=1,2 --out '" + (out / "o").string() + "'",
                out / "log.txt", output),
            2);
  EXPECT_NE(output.find("--sweep grass.field.density"), std::string::npos) << output;
  EXPECT_EQ(run_bench("'" + kGroundScene + "' --camera-path nowhere --out '" + (out / "o").string() + "'", out / "log2.txt",
                output),
            2);
  EXPECT_NE(output.find("nowhere"), std::string::npos) << output;
  EXPECT_NE(output.find("orbit"), std::string::npos) << output;  // lists the paths the scene has
}

// An --out that cannot be written is reported before anything renders (issue 17): the
// stability report used to run every case and fail only when writing its page.
TEST(BenchSceneSweep, UnwritableOutFailsBeforeRendering) {
  const fs::path dir = test_dir("unwritable");
  std::string output;
  // /proc refuses new entries even to root.
  EXPECT_EQ(run_bench("--stability --out /proc/sylva_bench_test", dir / "log.txt", output), 1);
  EXPECT_NE(output.find("--out /proc/sylva_bench_test: cannot create a file in the folder /proc"), std::string::npos)
      << output;
  EXPECT_EQ(output.find("passed"), std::string::npos) << "no case may run first:\n" << output;
  std::ofstream(dir / "file.txt") << "not a folder";
  EXPECT_EQ(run_bench("'" + kGroundScene + "' --sweep ground.height=5,10 --out '" + (dir / "file.txt" / "o").string() + "'",
                dir / "log2.txt", output),
            1);
  EXPECT_NE(output.find((dir / "file.txt").string() + " is not a folder"), std::string::npos) << output;
}

#else

TEST(BenchSceneSweep, SceneModuleNotInThisBuild) {
  GTEST_SKIP() << "modules/scene is not part of this build; scene files cannot be benchmarked";
}

#endif

}  // namespace

// End to end: the real sylva-bench executable on the built-in ground (no content module needed).
// A tiny sweep writes all three files with one report row per setting; an unknown parameter
// path or an out-of-range value fails before rendering with a message naming it; two runs agree
// in every count exactly.
#include "bench_exe.hpp"

#include <sylva/core/atomic_file.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;

namespace {

using sylva::bench::testing::run_bench;
using sylva::bench::testing::RunResult;

fs::path test_dir(const std::string& name) { return sylva::bench::testing::fresh_test_dir("sylva-bench-test", name); }

std::size_t count(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (auto pos = text.find(needle); pos != std::string::npos; pos = text.find(needle, pos + needle.size())) ++n;
  return n;
}

const char* kTinySweep =
    "builtin:ground --sweep ground.resolution=9,17 --sweep lighting.fog_density=0.0001,0.001 "
    "--reference ground.resolution=129 --frames 3 --size 128x72 --warmup 1";

nlohmann::json load_json(const fs::path& file) {
  auto text = sylva::read_file(file);
  EXPECT_TRUE(text.ok()) << file;
  return text.ok() ? nlohmann::json::parse(*text) : nlohmann::json();
}

TEST(BenchSweepRun, TinySweepWritesCsvJsonAndReportWithOneRowPerSetting) {
  const fs::path out = test_dir("tiny");
  const RunResult r = run_bench(std::string(kTinySweep) + " --out '" + out.string() + "'", out / "log.txt");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_TRUE(fs::exists(out / "results.csv"));
  ASSERT_TRUE(fs::exists(out / "results.json"));
  ASSERT_TRUE(fs::exists(out / "report.html"));

  auto csv = sylva::read_file(out / "results.csv");
  ASSERT_TRUE(csv.ok());
  EXPECT_EQ(count(*csv, "\n"), 1u + 1u + 4u) << *csv;  // header, reference, 4 settings

  const nlohmann::json j = load_json(out / "results.json");
  ASSERT_EQ(j["settings"].size(), 4u);
  // 9 vertices per side: 8 x 8 x 2 triangles per frame, 3 frames.
  EXPECT_EQ(j["settings"][0]["totals"]["triangles"], 3 * 8 * 8 * 2);
  EXPECT_EQ(j["settings"][2]["totals"]["triangles"], 3 * 16 * 16 * 2);
  EXPECT_EQ(j["reference"]["totals"]["triangles"], 3 * 128 * 128 * 2);
  for (const auto& s : j["settings"]) {
    const double ssim = s["image_error"]["ssim_mean"].get<double>();
    EXPECT_GT(ssim, 0.0);
    EXPECT_LT(ssim, 1.0);  // a 9- or 17-vertex grid is visibly not the 129-vertex reference
    EXPECT_TRUE(s["image_error"]["psnr_db"].is_number());
    EXPECT_GT(s["totals"]["fragments"].get<std::uint64_t>(), 0u);
    EXPECT_EQ(s["frame_records"].size(), 3u);
  }
  // The finer grid is closer to the reference on this path (same fog).
  EXPECT_GT(j["settings"][2]["image_error"]["ssim_mean"].get<double>(),
            j["settings"][0]["image_error"]["ssim_mean"].get<double>());

  auto html = sylva::read_file(out / "report.html");
  ASSERT_TRUE(html.ok());
  EXPECT_EQ(count(*html, "<tr class=\"setting"), 4u);
  EXPECT_EQ(count(*html, "<tr class=\"reference"), 1u);
  EXPECT_NE(html->find("<svg"), std::string::npos);
  EXPECT_NE(html->find("data:image/png;base64,"), std::string::npos);
  EXPECT_NE(html->find("ground.resolution=17, lighting.fog_density=0.001"), std::string::npos);
  EXPECT_TRUE(fs::exists(out / "images" / "s003-difference.png"));
}

TEST(BenchSweepRun, UnknownParameterPathFailsNamingThePath) {
  const fs::path out = test_dir("unknown");
  const RunResult r = run_bench("builtin:ground --sweep ground.resolutoin=9,17 --frames 2 --size 64x36 --out '" +
                                    (out / "o").string() + "'",
                                out / "log.txt");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--sweep ground.resolutoin"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("did you mean \"ground.resolution\""), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "o" / "report.html"));
}

TEST(BenchSweepRun, OutOfRangeValueFailsNamingPathAndValue) {
  const fs::path out = test_dir("range");
  const RunResult r = run_bench("builtin:ground --sweep ground.resolution=9,99999 --out '" + (out / "o").string() + "'",
                                out / "log.txt");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("ground.resolution=99999"), std::string::npos) << r.output;
  const RunResult ref = run_bench("builtin:ground --reference lighting.nope=1 --out '" + (out / "o").string() + "'",
                                  out / "log2.txt");
  EXPECT_EQ(ref.exit_code, 2) << ref.output;
  EXPECT_NE(ref.output.find("--reference lighting.nope"), std::string::npos) << ref.output;
}

TEST(BenchSweepRun, TwoRunsAgreeInEveryCount) {
  const fs::path a = test_dir("repro_a"), b = test_dir("repro_b");
  const RunResult ra = run_bench(std::string(kTinySweep) + " --out '" + a.string() + "'", a / "log.txt");
  const RunResult rb = run_bench(std::string(kTinySweep) + " --out '" + b.string() + "'", b / "log.txt");
  ASSERT_EQ(ra.exit_code, 0) << ra.output;
  ASSERT_EQ(rb.exit_code, 0) << rb.output;
  const nlohmann::json ja = load_json(a / "results.json"), jb = load_json(b / "results.json");
  auto compare = [](const nlohmann::json& x, const nlohmann::json& y, const std::string& what) {
    ASSERT_EQ(x["frame_records"].size(), y["frame_records"].size()) << what;
    for (std::size_t f = 0; f < x["frame_records"].size(); ++f) {
      const auto& fx = x["frame_records"][f];
      const auto& fy = y["frame_records"][f];
      EXPECT_EQ(fx["counts"], fy["counts"]) << what << " frame " << f;
      // Identical pixels give identical errors, bit for bit.
      EXPECT_EQ(fx["error"], fy["error"]) << what << " frame " << f;
      EXPECT_GT(fx["frame_ms"].get<double>(), 0.0);
      EXPECT_GT(fy["frame_ms"].get<double>(), 0.0);
    }
    EXPECT_EQ(x["totals"], y["totals"]) << what;
  };
  compare(ja["reference"], jb["reference"], "reference");
  ASSERT_EQ(ja["settings"].size(), jb["settings"].size());
  for (std::size_t i = 0; i < ja["settings"].size(); ++i) {
    compare(ja["settings"][i], jb["settings"][i], ja["settings"][i]["label"].get<std::string>());
  }
}

TEST(BenchSweepRun, SuiteNeverPassesSilently) {
  // Either the suite's module is available and the report is written, or the run says
  // "module not available" and exits with 3.
  const fs::path out = test_dir("suite");
  const RunResult r = run_bench("--suite voxel --frames 1 --warmup 0 --size 32x18 --out '" + (out / "o").string() + "'",
                                out / "log.txt");
  if (r.exit_code == 3) {
    EXPECT_NE(r.output.find("module not available"), std::string::npos) << r.output;
  } else {
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(fs::exists(out / "o" / "report.html")) << r.output;
  }
}

}  // namespace

// sylva-bench --suite stream (issue #15, "Benchmarks": flight frame times with streaming against
// the in-memory terrain) at CI size: a 1025^2 field baked, flown in memory and streamed within a
// 4 MiB budget (its file holds ~70 MB). The rows exist with sane counts: frames as asked,
// p50 <= p99 <= longest, resident bytes within the budget, requests, loads and misses counted,
// no failures, the temporary chunk file gone. No timing is compared.
#include "bench_exe.hpp"

#include <sylva/core/atomic_file.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace fs = std::filesystem;

namespace {

#ifdef SYLVA_BENCH_WITH_SCENE

using namespace sylva::bench::testing;

TEST(BenchStreamSuite, PrintsInMemoryAndStreamedFlightRows) {
  const fs::path dir = fresh_test_dir("sylva-bench-stream-test", "rows");
  std::string output;
  const int code = run_small_suite("stream", 12, "--set terrain.resolution=1025 --set terrain.stream.budget_mb=4", dir, output);
  ASSERT_EQ(code, 0) << output;

  const auto bakes = lines_of(output, "stream: bake ");
  ASSERT_EQ(bakes.size(), 1u) << output;
  EXPECT_NE(bakes[0].find("field=1025^2"), std::string::npos) << bakes[0];
  EXPECT_EQ(field(bakes[0], "chunks"), 1365.0) << bakes[0];  // a full 6-level tree of 33-vertex chunks
  EXPECT_GT(field(bakes[0], "triangles"), 2.5e5) << bakes[0];
  const double file_bytes = field(bakes[0], "file_bytes");

  for (const char* name : {"stream: memory ", "stream: streamed "}) {
    const auto rows = lines_of(output, name);
    ASSERT_EQ(rows.size(), 1u) << output;
    const std::string& row = rows[0];
    EXPECT_NE(row.find("field=1025^2"), std::string::npos) << row;
    EXPECT_EQ(field(row, "frames"), 12.0) << row;
    EXPECT_GT(field(row, "p50_ms"), 0.0) << row;
    EXPECT_LE(field(row, "p50_ms"), field(row, "p99_ms")) << row;
    EXPECT_LE(field(row, "p99_ms"), field(row, "longest_ms")) << row;
    EXPECT_GT(field(row, "max_triangles"), 0.0) << row;
  }
  const std::string streamed = lines_of(output, "stream: streamed ").at(0);
  const double budget = field(streamed, "budget_bytes");
  EXPECT_EQ(budget, 4.0 * 1024 * 1024) << streamed;
  EXPECT_LT(budget * 10, file_bytes) << streamed;  // the budget is far below the field's file
  EXPECT_GT(field(streamed, "max_resident_bytes"), 0.0) << streamed;
  EXPECT_LE(field(streamed, "max_resident_bytes"), budget) << streamed;
  EXPECT_GT(field(streamed, "loads"), 0.0) << streamed;
  EXPECT_LE(field(streamed, "loads"), field(streamed, "requests")) << streamed;  // a load answers a request
  EXPECT_GE(field(streamed, "misses"), 0.0) << streamed;
  EXPECT_EQ(field(streamed, "failures"), 0.0) << streamed;
  // The in-memory scene has no streamer: its row has no streaming fields.
  EXPECT_TRUE(std::isnan(field(lines_of(output, "stream: memory ").at(0), "requests"))) << output;

  auto csv = sylva::read_file(dir / "out" / "results.csv");
  ASSERT_TRUE(csv.ok());
  EXPECT_EQ(csv->rfind("kind,name,count,value,unit\n", 0), 0u) << *csv;
  for (const char* kind : {"bake,", "memory_p50,", "memory_p99,", "memory_longest,", "streamed_p50,", "streamed_p99,",
                           "streamed_longest,", "streamed_resident_max,", "streamed_requests,", "streamed_misses,"}) {
    EXPECT_EQ(lines_of(*csv, kind).size(), 1u) << kind << "\n" << *csv;
  }
  // The temporary chunk file is deleted (its name carries the bench's process id).
  const std::string log = output;
  for (const auto& entry : fs::directory_iterator(fs::temp_directory_path())) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() == ".sylvaterrain" && log.find(name) != std::string::npos) {
      ADD_FAILURE() << "left behind: " << name;
    }
  }
  fs::remove_all(dir);
}

TEST(BenchStreamSuite, RefusesASetPathItsSceneLacks) {
  const fs::path dir = fresh_test_dir("sylva-bench-stream-test", "set");
  std::string output;
  const int code = run_bench("--suite stream --set terrain.stream.budget_gb=1 --out '" + (dir / "out").string() + "'",
                             dir / "log.txt", output);
  EXPECT_EQ(code, 2) << output;
  EXPECT_NE(output.find("terrain.stream.budget_gb"), std::string::npos) << output;
  fs::remove_all(dir);
}

#endif

}  // namespace

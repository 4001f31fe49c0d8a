// The shipped sylva-bake as separate processes (issue 15): three `--tiles I/3` processes merged
// byte-identically to a one-process bake; SIGINT/SIGTERM stop a running bake with status 130
// and leave no output and no temporary; SIGKILL leaves the user's old file untouched; truncated
// and corrupt rasters, and a damaged share, are errors naming the file.
#include <sylva/core/atomic_file.hpp>

#include "bake_process.hpp"
#include "geotiff_fixture.hpp"

#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <thread>

namespace sylva::bake {
namespace {

namespace fs = std::filesystem;

using namespace testing;  // bake_process.hpp: test_dir, spawn_bake, wait_for, run_bake, text_of

// A float GeoTIFF of smooth hills with some roughness, side x side samples at 10 m.
fs::path write_dem(const fs::path& dir, int side) {
  test::GeoTiffSpec spec;
  spec.columns = side;
  spec.rows = side;
  spec.type = GDT_Float32;
  spec.pixel_x = spec.pixel_y = 10.0;
  spec.values.resize(static_cast<std::size_t>(side) * static_cast<std::size_t>(side));
  for (int z = 0; z < side; ++z)
    for (int x = 0; x < side; ++x)
      spec.values[static_cast<std::size_t>(z) * static_cast<std::size_t>(side) + static_cast<std::size_t>(x)] =
          300.0 + 120.0 * std::sin(x * 0.031) * std::cos(z * 0.023) + 7.0 * std::sin(x * 0.71 + z * 1.3);
  const fs::path file = dir / "dem.tif";
  test::write_geotiff(file, spec);
  return file;
}

// The folder's file names (to see that no temporary or share was left behind).
std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(BakeProcesses, ThreeTileProcessesMergeByteIdenticallyToOneProcess) {
  const fs::path dir = test_dir("tiles");
  const fs::path dem = write_dem(dir, 700);  // not 2^k+1: padded, absent chunks
  // --overview-side 257: the 700^2 field also stores its ground's overview (every 4th sample,
  // 175^2), which every process must write alike.
  const std::vector<std::string> set{"--set", "terrain.tree.leaf_dimension=17", "--set", "terrain.tree.threads=1",
                                     "--overview-side", "257"};
  auto with_set = [&](std::vector<std::string> a) {
    a.insert(a.end(), set.begin(), set.end());
    return a;
  };
  ASSERT_EQ(run_bake(with_set({"terrain", dem.string(), "--out", (dir / "one.sylvaterrain").string()}), dir / "one.log"),
            0) << text_of(dir / "one.log");
  std::vector<pid_t> pids;
  for (int i = 0; i < 3; ++i) {
    pids.push_back(spawn_bake(with_set({"terrain", dem.string(), "--tiles", fmt::format("{}/3", i), "--out",
                                        (dir / fmt::format("s{}.share", i)).string()}),
                              dir / fmt::format("s{}.log", i)));
  }
  for (int i = 0; i < 3; ++i) EXPECT_EQ(wait_for(pids[static_cast<std::size_t>(i)]), 0) << text_of(dir / fmt::format("s{}.log", i));
  ASSERT_EQ(run_bake({"merge", (dir / "s2.share").string(), (dir / "s0.share").string(), (dir / "s1.share").string(),
                      "--out", (dir / "merged.sylvaterrain").string()},
                     dir / "merge.log"),
            0) << text_of(dir / "merge.log");
  const std::string one = text_of(dir / "one.sylvaterrain");
  EXPECT_GT(one.size(), 100000u);
  EXPECT_TRUE(one == text_of(dir / "merged.sylvaterrain"));
  EXPECT_NE(text_of(dir / "one.log").find("ETA"), std::string::npos) << text_of(dir / "one.log");

  // The ground heights travel with the shares: every share and both files hold the 700^2 field
  // (3 x 3 tiles of 256^2) and its overview (1 tile of 175^2; 10 checksums and the table's) right
  // after the 128-byte header, whose uint16 at 78 is the overview's stride.
  EXPECT_EQ(static_cast<unsigned char>(one[78]) + 256 * static_cast<unsigned char>(one[79]), 4);
  const std::size_t field_end = 128 + 11 * 8 + 700 * 700 * 4, heights_end = field_end + 175 * 175 * 4;
  EXPECT_TRUE(one.compare(0, heights_end, text_of(dir / "s2.share"), 0, heights_end) != 0) << "headers differ";
  EXPECT_TRUE(one.compare(128, heights_end - 128, text_of(dir / "s2.share"), 128, heights_end - 128) == 0);
  // A damaged height tile in share 0 (the one whose heights are copied): named with its tile.
  const std::string good0 = text_of(dir / "s0.share");
  {
    std::string bad = good0;
    bad[field_end - 10] = static_cast<char>(bad[field_end - 10] ^ 0x40);  // the field's last tile
    ASSERT_TRUE(write_file_atomic(dir / "s0.share", bad).ok());
  }
  EXPECT_EQ(run_bake({"merge", (dir / "s0.share").string(), (dir / "s1.share").string(), (dir / "s2.share").string(),
                      "--out", (dir / "bad.sylvaterrain").string()},
                     dir / "bad.log"),
            1);
  EXPECT_NE(text_of(dir / "bad.log").find("s0.share: height tile 8 (samples x 512..699, z 512..699): checksum mismatch"),
            std::string::npos) << text_of(dir / "bad.log");
  EXPECT_FALSE(fs::exists(dir / "bad.sylvaterrain"));
  ASSERT_TRUE(write_file_atomic(dir / "s0.share", good0).ok());

  // A damaged share: the merge names it and the chunk, and writes nothing.
  {
    std::string bad = text_of(dir / "s1.share");
    bad[heights_end + 200] = static_cast<char>(bad[heights_end + 200] ^ 0x40);  // its first blob
    ASSERT_TRUE(write_file_atomic(dir / "s1.share", bad).ok());
  }
  EXPECT_EQ(run_bake({"merge", (dir / "s0.share").string(), (dir / "s1.share").string(), (dir / "s2.share").string(),
                      "--out", (dir / "bad.sylvaterrain").string()},
                     dir / "bad.log"),
            1);
  EXPECT_NE(text_of(dir / "bad.log").find("s1.share: chunk"), std::string::npos) << text_of(dir / "bad.log");
  EXPECT_FALSE(fs::exists(dir / "bad.sylvaterrain"));
  fs::remove_all(dir);
}

// Starts a slow bake (one thread, small chunks), waits for its first progress line, sends `sig`.
int interrupted_bake(const fs::path& dir, const fs::path& dem, const fs::path& out, int sig) {
  const fs::path log = dir / "interrupted.log";
  const pid_t pid = spawn_bake({"terrain", dem.string(), "--out", out.string(), "--set", "terrain.tree.threads=1",
                                "--set", "terrain.tree.leaf_dimension=9"},
                               log);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (text_of(log).find(" % (") == std::string::npos && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, sig);
  return wait_for(pid);
}

TEST(BakeProcesses, SigintAndSigtermLeaveNoOutputFile) {
  const fs::path dir = test_dir("signals");
  const fs::path dem = write_dem(dir, 1025);
  for (int sig : {SIGINT, SIGTERM}) {
    const fs::path out = dir / "cancelled.sylvaterrain";
    EXPECT_EQ(interrupted_bake(dir, dem, out, sig), 130) << text_of(dir / "interrupted.log");
    EXPECT_NE(text_of(dir / "interrupted.log").find("cancelled"), std::string::npos) << text_of(dir / "interrupted.log");
    EXPECT_FALSE(fs::exists(out));
    EXPECT_EQ(names_in(dir), (std::vector<std::string>{"dem.tif", "interrupted.log"})) << "signal " << sig;
  }
  // Killed outright (no cleanup possible): the user's old file is untouched.
  const fs::path old = dir / "old.sylvaterrain";
  ASSERT_TRUE(write_file_atomic(old, "the user's old file").ok());
  EXPECT_EQ(interrupted_bake(dir, dem, old, SIGKILL), 128 + SIGKILL);
  EXPECT_EQ(text_of(old), "the user's old file");
  fs::remove_all(dir);
}

TEST(BakeProcesses, TruncatedAndCorruptRastersAreErrorsNamingTheFile) {
  const fs::path dir = test_dir("bad_rasters");
  const fs::path dem = write_dem(dir, 300);
  const std::string good = text_of(dem);
  const fs::path truncated = dir / "truncated.tif";
  ASSERT_TRUE(write_file_atomic(truncated, good.substr(0, good.size() / 2)).ok());
  const fs::path junk = dir / "junk.tif";
  std::string j = good;
  for (std::size_t k = 8; k < j.size(); k += 97) j[k] = static_cast<char>(j[k] * 31 + 7);
  ASSERT_TRUE(write_file_atomic(junk, j).ok());
  for (const fs::path& bad : {truncated, junk, dir / "missing.tif"}) {
    const fs::path out = dir / "out.sylvaterrain";
    const int rc = run_bake({"terrain", bad.string(), "--out", out.string()}, dir / "bad.log");
    const std::string log = text_of(dir / "bad.log");
    // A damaged raster may still decode as other numbers (GDAL cannot tell); a crash never passes.
    EXPECT_TRUE(rc == 1 || rc == 0) << bad << ": status " << rc << "\n" << log;
    if (rc == 1) {
      EXPECT_NE(log.find(bad.filename().string()), std::string::npos) << log;
      EXPECT_FALSE(fs::exists(out));
    }
    fs::remove(out);
  }
  EXPECT_EQ(run_bake({"terrain", (dir / "missing.tif").string(), "--out", (dir / "o").string()}, dir / "m.log"), 1);
  // --out naming the source: refused, the raster untouched.
  EXPECT_EQ(run_bake({"terrain", dem.string(), "--out", (dir / "." / "dem.tif").string()}, dir / "same.log"), 1);
  EXPECT_NE(text_of(dir / "same.log").find("names an input"), std::string::npos) << text_of(dir / "same.log");
  EXPECT_TRUE(text_of(dem) == good);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sylva::bake

// Bake cache format (slice_bake.hpp): exact round trips through bytes and files, every kind of
// damage rejected as kCorrupt (magic, version, key, size, checksum, truncation, bad dimensions),
// and the Voronoi propagation that fills uncovered texels.
#include <sylva/vegetation/slice_bake.hpp>

#include <sylva/core/atomic_file.hpp>

#include "support/temp_path.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace sylva::vegetation {
namespace {

BakedTree synthetic(int res) {
  BakedTree t;
  const int cfg[2][2] = {{3, 3}, {2, 1}};
  std::uint32_t h = 99u;
  for (int lod = 0; lod < 2; ++lod) {
    BakedLod& b = t.lod[static_cast<std::size_t>(lod)];
    b.layout.directions = cfg[lod][0];
    b.layout.layers = cfg[lod][1];
    b.layout.center = {0.5f, 6.0f, -0.25f};
    b.layout.radius = 4.0f;
    b.layout.half_height = 6.0f;
    b.layout.margin = 1.0f;
    SliceImages& im = b.images;
    im.resolution = res;
    im.count = b.layout.count();
    im.color.resize(im.texels() * 4);
    im.normal.resize(im.texels() * 4);
    im.depth.resize(im.texels());
    im.branch.resize(im.texels() * 4);
    for (auto& v : im.color) v = static_cast<std::uint8_t>((h = h * 1664525u + 1013904223u) >> 24);
    for (auto& v : im.normal) v = static_cast<std::uint8_t>((h = h * 1664525u + 1013904223u) >> 24);
    for (auto& v : im.depth) v = static_cast<float>((h = h * 1664525u + 1013904223u) >> 8) * 1e-7f - 0.8f;
    for (auto& v : im.branch) v = static_cast<float>((h = h * 1664525u + 1013904223u) >> 20);
  }
  return t;
}

bool same(const BakedTree& a, const BakedTree& b) {
  for (int k = 0; k < 2; ++k) {
    const BakedLod& x = a.lod[static_cast<std::size_t>(k)];
    const BakedLod& y = b.lod[static_cast<std::size_t>(k)];
    if (!(x.images == y.images) || x.layout.directions != y.layout.directions || x.layout.layers != y.layout.layers ||
        x.layout.center != y.layout.center || x.layout.radius != y.layout.radius ||
        x.layout.half_height != y.layout.half_height || x.layout.margin != y.layout.margin)
      return false;
  }
  return true;
}

TEST(SliceCache, RoundTripIsIdentical) {
  const BakedTree t = synthetic(16);
  const std::string bytes = serialize_slices(t, 0x1234u);
  Result<BakedTree> back = deserialize_slices(bytes, 0x1234u);
  ASSERT_TRUE(back.ok()) << back.error().describe();
  EXPECT_TRUE(same(t, *back));
  EXPECT_TRUE(back->from_cache);
  // Through a file (atomic write), and the serialisation is deterministic.
  const std::filesystem::path dir = testing::unique_temp("slice_cache_test");
  const std::filesystem::path file = slice_cache_file(dir, 0x1234u);
  ASSERT_TRUE(save_slice_cache(file, t, 0x1234u).ok());
  Result<BakedTree> loaded = load_slice_cache(file, 0x1234u);
  ASSERT_TRUE(loaded.ok()) << loaded.error().describe();
  EXPECT_TRUE(same(t, *loaded));
  EXPECT_EQ(serialize_slices(*loaded, 0x1234u), bytes);
  std::filesystem::remove_all(dir);
}

TEST(SliceCache, DamagedFilesAreRejectedAsCorrupt) {
  const BakedTree t = synthetic(16);
  const std::string good = serialize_slices(t, 7u);
  const auto rejected = [](const std::string& bytes, std::uint64_t key, const char* what) {
    Result<BakedTree> r = deserialize_slices(bytes, key);
    ASSERT_FALSE(r.ok()) << what;
    EXPECT_EQ(r.error().code, ErrorCode::kCorrupt) << what;
    EXPECT_NE(r.error().message.find("slice cache"), std::string::npos) << r.error().message;
  };
  rejected(good, 8u, "other key");
  rejected("", 7u, "empty");
  rejected(good.substr(0, 20), 7u, "truncated header");
  rejected(good.substr(0, good.size() - 1), 7u, "truncated payload");
  rejected(good + "x", 7u, "trailing byte");
  std::string bad = good;
  bad[0] = 'X';
  rejected(bad, 7u, "magic");
  bad = good;
  bad[8] = 99;
  rejected(bad, 7u, "version");
  for (std::size_t pos : {good.size() / 2, good.size() - 3, std::size_t{40}}) {
    bad = good;
    bad[pos] = static_cast<char>(bad[pos] ^ 0x10);
    rejected(bad, 7u, "flipped payload bit");
  }
  // A file on disk: missing is kNotFound, damaged is kCorrupt naming the file.
  const std::filesystem::path dir = testing::unique_temp("slice_cache_test2");
  const std::filesystem::path file = slice_cache_file(dir, 7u);
  EXPECT_EQ(load_slice_cache(file, 7u).error().code, ErrorCode::kNotFound);
  std::filesystem::create_directories(dir);
  bad = good;
  bad[good.size() / 3] = static_cast<char>(bad[good.size() / 3] ^ 1);
  ASSERT_TRUE(write_file_atomic(file, bad).ok());
  Result<BakedTree> r = load_slice_cache(file, 7u);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kCorrupt);
  EXPECT_NE(r.error().message.find(file.filename().string()), std::string::npos) << r.error().message;
  std::filesystem::remove_all(dir);
}

TEST(SliceCache, VoronoiPropagationFindsTheNearestCoveredTexel) {
  const int res = 32;
  std::vector<std::uint8_t> covered(static_cast<std::size_t>(res * res), 0);
  const int seeds[][2] = {{3, 4}, {28, 2}, {15, 27}, {16, 16}};
  for (const auto& s : seeds) covered[static_cast<std::size_t>(s[1] * res + s[0])] = 1;
  const std::vector<std::int32_t> n = nearest_covered(covered, res);
  for (int y = 0; y < res; ++y)
    for (int x = 0; x < res; ++x) {
      int best = 1 << 30;
      for (const auto& s : seeds) best = std::min(best, (x - s[0]) * (x - s[0]) + (y - s[1]) * (y - s[1]));
      const std::int32_t got = n[static_cast<std::size_t>(y * res + x)];
      ASSERT_GE(got, 0);
      const int gx = got % res, gy = got / res;
      EXPECT_EQ((x - gx) * (x - gx) + (y - gy) * (y - gy), best) << x << "," << y;
    }
  // No covered texel at all: -1 everywhere.
  const std::vector<std::int32_t> none = nearest_covered(std::vector<std::uint8_t>(16 * 16, 0), 16);
  for (std::int32_t v : none) EXPECT_EQ(v, -1);
}

TEST(SliceCache, CacheFolderSetting) {
  EXPECT_TRUE(resolve_cache_directory("").empty());
  EXPECT_EQ(resolve_cache_directory("auto").filename(), "sylva-lod-cache");
  EXPECT_EQ(resolve_cache_directory("/tmp/x"), std::filesystem::path("/tmp/x"));
  EXPECT_NE(slice_cache_file("/a", 1u), slice_cache_file("/a", 2u));
}

}  // namespace
}  // namespace sylva::vegetation

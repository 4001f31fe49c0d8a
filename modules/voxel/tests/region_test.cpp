// Region files: round trip, corruption detection (header, payload, truncation, unknown block)
// and atomic replacement.

#include <sylva/core/file_fault.hpp>
#include <sylva/voxel/region.hpp>

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "support/test_chunks.hpp"

namespace sylva::voxel {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("sylva_voxel_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

Chunk pattern_chunk(std::uint32_t seed) {
  Chunk c;
  auto d = c.dense();
  for (int i = 0; i < kChunkVolume; ++i) d[static_cast<std::size_t>(i)] = static_cast<BlockId>((i / 97 + seed) % 4);
  return c;
}

std::vector<std::uint8_t> read_all(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}
void write_all(const fs::path& p, const std::vector<std::uint8_t>& b) {
  std::ofstream f(p, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

bool same_blocks(const Chunk& a, const Chunk& b) {
  for (int y = 0; y < kChunkSize; ++y)
    for (int z = 0; z < kChunkSize; ++z)
      for (int x = 0; x < kChunkSize; ++x)
        if (a.get(x, y, z) != b.get(x, y, z)) return false;
  return true;
}

TEST(Region, Crc32KnownValue) {
  const std::string s = "123456789";
  EXPECT_EQ(crc32({reinterpret_cast<const std::uint8_t*>(s.data()), s.size()}), 0xCBF43926u);
}

TEST(Region, RoundTripThroughStore) {
  const auto dir = temp_dir("roundtrip");
  const auto& palette = testing::test_palette();
  Chunk a = pattern_chunk(1), b = pattern_chunk(2), air, stone(1);
  const ChunkCoord ca{0, 0, 0}, cb{7, -1, 3}, cair{-8, 0, 0}, cstone{1000000, -5, 999999};
  RegionStore store(dir, palette);
  const std::vector<std::pair<ChunkCoord, const Chunk*>> list = {{ca, &a}, {cb, &b}, {cair, &air}, {cstone, &stone}};
  ASSERT_TRUE(store.save(list).ok());
  RegionStore fresh(dir, palette);
  for (const auto& [c, chunk] : list) {
    auto r = fresh.load(c);
    ASSERT_TRUE(r.ok()) << r.error().message;
    ASSERT_TRUE(r->has_value());
    EXPECT_TRUE(same_blocks(**r, *chunk));
  }
  auto missing = fresh.load({1, 1, 1});
  ASSERT_TRUE(missing.ok());
  EXPECT_FALSE(missing->has_value());
  // Saving one chunk again keeps the other chunks of its region.
  Chunk a2 = pattern_chunk(3);
  const std::vector<std::pair<ChunkCoord, const Chunk*>> update = {{ca, &a2}};
  ASSERT_TRUE(fresh.save(update).ok());
  RegionStore again(dir, palette);
  EXPECT_TRUE(same_blocks(**again.load(ca), a2));
  EXPECT_TRUE(same_blocks(**again.load(cb), b));
  for (const auto& e : fs::directory_iterator(dir)) {
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << "temporary file left: " << e.path();
  }
  fs::remove_all(dir);
}

TEST(Region, CorruptPayloadBreaksOnlyThatChunk) {
  const auto dir = temp_dir("payload");
  const auto& palette = testing::test_palette();
  Chunk a = pattern_chunk(1), b = pattern_chunk(2);
  RegionStore store(dir, palette);
  const std::vector<std::pair<ChunkCoord, const Chunk*>> list = {{{0, 0, 0}, &a}, {{1, 0, 0}, &b}};
  ASSERT_TRUE(store.save(list).ok());
  const auto path = store.path_of({0, 0, 0});
  auto bytes = read_all(path);
  bytes[bytes.size() - 3] ^= 0x5a;  // inside the last chunk's payload
  write_all(path, bytes);
  RegionStore reader(dir, palette);
  auto first = reader.load({0, 0, 0});
  ASSERT_TRUE(first.ok());
  EXPECT_TRUE(same_blocks(**first, a));
  auto second = reader.load({1, 0, 0});
  ASSERT_FALSE(second.ok());
  EXPECT_EQ(second.error().code, ErrorCode::kCorrupt);
  EXPECT_NE(second.error().message.find("r.0.0.0.svr"), std::string::npos) << second.error().message;
  EXPECT_NE(second.error().message.find("chunk (1, 0, 0)"), std::string::npos) << second.error().message;
  fs::remove_all(dir);
}

TEST(Region, CorruptHeaderTruncationAndGarbageAreReported) {
  const auto dir = temp_dir("header");
  const auto& palette = testing::test_palette();
  Chunk a = pattern_chunk(1);
  const std::vector<std::pair<ChunkCoord, const Chunk*>> list = {{{0, 0, 0}, &a}};
  const auto path = dir / region_file_name({0, 0, 0});
  ASSERT_TRUE(write_region_file(path, {0, 0, 0}, palette, list).ok());
  const auto good = read_all(path);
  {
    auto bytes = good;
    bytes[20] ^= 1;  // region coordinate: header checksum catches it
    auto r = decode_region(bytes, palette, "x.svr");
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("header checksum"), std::string::npos) << r.error().message;
  }
  for (std::size_t cut : {std::size_t{0}, std::size_t{5}, std::size_t{30}, good.size() - 1}) {
    std::vector<std::uint8_t> bytes(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(cut));
    auto r = decode_region(bytes, palette, "x.svr");
    ASSERT_FALSE(r.ok()) << "cut at " << cut;
    EXPECT_EQ(r.error().code, ErrorCode::kCorrupt);
    EXPECT_NE(r.error().message.find("x.svr"), std::string::npos);
  }
  {
    auto bytes = good;
    bytes[8] = 99;  // version
    auto r = decode_region(bytes, palette, "x.svr");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, ErrorCode::kUnsupported);
  }
  // A palette without the saved blocks: that chunk is unreadable, with the name in the message.
  BlockPalette other;
  auto r = decode_region(good, other, "x.svr");
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r->bad_chunks.size(), 1u);
  EXPECT_NE(r->bad_chunks.begin()->second.message.find("not in the palette"), std::string::npos);
  fs::remove_all(dir);
}

// A header may claim any region coordinate; one whose blocks have no int64 position (here from
// 2^55 on, the 2^60 of the issue included) is refused by name instead of overflowing.
TEST(Region, CoordinatesOutsideTheWorldAreRefused) {
  const auto& palette = testing::test_palette();
  Chunk a = pattern_chunk(1);
  const std::vector<std::pair<ChunkCoord, const Chunk*>> list = {{{0, 0, 0}, &a}};
  const auto good = encode_region({0, 0, 0}, palette, list);
  // The header checksum sits right after the header it covers: find it to re-sign the patch.
  std::size_t header_end = 0;
  for (std::size_t p = 16; p + 4 <= good.size() && header_end == 0; ++p) {
    std::uint32_t stored = 0;
    std::memcpy(&stored, good.data() + p, 4);
    if (crc32(std::span(good).first(p)) == stored) header_end = p;
  }
  ASSERT_GT(header_end, 0u);
  auto with_x = [&](std::int64_t rx) {
    auto bytes = good;
    std::memcpy(bytes.data() + 16, &rx, 8);  // after magic, version, chunk size
    const std::uint32_t crc = crc32(std::span(bytes).first(header_end));
    std::memcpy(bytes.data() + header_end, &crc, 4);
    return bytes;
  };
  const std::int64_t edge = std::numeric_limits<std::int64_t>::max() / 256;  // 2^55 - 1
  for (std::int64_t rx : {std::int64_t{1} << 60, std::numeric_limits<std::int64_t>::max(),
                          std::numeric_limits<std::int64_t>::min(), edge + 1, -edge - 2}) {
    auto r = decode_region(with_x(rx), palette, "far.svr");
    ASSERT_FALSE(r.ok()) << rx;
    EXPECT_EQ(r.error().code, ErrorCode::kCorrupt);
    EXPECT_NE(r.error().message.find("far.svr"), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find(fmt::format("region coordinate ({}, 0, 0) is outside the world", rx)),
              std::string::npos)
        << r.error().message;
  }
  // The last regions inside the world still decode, with their chunk where it belongs.
  for (std::int64_t rx : {edge, -edge - 1}) {
    auto r = decode_region(with_x(rx), palette, "edge.svr");
    ASSERT_TRUE(r.ok()) << r.error().message;
    ASSERT_EQ(r->chunks.size(), 1u);
    EXPECT_EQ(r->chunks.begin()->first, (ChunkCoord{rx * kRegionSize, 0, 0}));
  }
}

TEST(Region, CacheHoldsAtMostItsLimit) {
  const auto dir = temp_dir("cache");
  const auto& palette = testing::test_palette();
  Chunk a = pattern_chunk(1);
  RegionStore store(dir, palette, 3);
  for (int r = 0; r < 10; ++r) {
    const ChunkCoord c{r * kRegionSize, 0, 0};
    const std::vector<std::pair<ChunkCoord, const Chunk*>> list = {{c, &a}};
    ASSERT_TRUE(store.save(list).ok());
  }
  for (int r = 0; r < 10; ++r) {
    auto loaded = store.load({r * kRegionSize, 0, 0});
    ASSERT_TRUE(loaded.ok() && loaded->has_value());
    EXPECT_TRUE(same_blocks(**loaded, a));
    EXPECT_LE(store.cached_regions(), 3u);
  }
  fs::remove_all(dir);
}

// The old region file is put at risk: a new one for the same path fails half way (disk full) or
// at the rename, and the old bytes must survive with no temporary file left behind.
TEST(Region, FailedWriteKeepsTheOldFile) {
  const auto dir = temp_dir("atomic");
  const auto& palette = testing::test_palette();
  Chunk a = pattern_chunk(1), b = pattern_chunk(2);
  const std::vector<std::pair<ChunkCoord, const Chunk*>> old_list = {{{0, 0, 0}, &a}};
  const std::vector<std::pair<ChunkCoord, const Chunk*>> new_list = {{{0, 0, 0}, &b}, {{1, 0, 0}, &a}};
  const auto path = dir / region_file_name({0, 0, 0});
  ASSERT_TRUE(write_region_file(path, {0, 0, 0}, palette, old_list).ok());
  const auto before = read_all(path);
  for (const FileFaultPoint point : {FileFaultPoint::kWrite, FileFaultPoint::kRename}) {
    {
      ScopedFileFault fault([&](const fs::path& target, FileFaultPoint p) { return p == point && target == path; });
      const Status st = write_region_file(path, {0, 0, 0}, palette, new_list);
      ASSERT_FALSE(st.ok());
      EXPECT_NE(st.error().message.find(path.string()), std::string::npos) << st.error().message;
    }
    EXPECT_EQ(read_all(path), before) << "fault at " << static_cast<int>(point);
    std::size_t files = 0;
    for (const auto& e : fs::directory_iterator(dir)) {
      ++files;
      EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << "temporary file left: " << e.path();
    }
    EXPECT_EQ(files, 1u);
  }
  // Without the fault the same write goes through (the fault, not the data, failed it).
  ASSERT_TRUE(write_region_file(path, {0, 0, 0}, palette, new_list).ok());
  EXPECT_NE(read_all(path), before);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sylva::voxel

// The edit layer file of a painted baked terrain (edit_layer.hpp): sparse tiles of absolute
// heights, bit-exact round trip, and every kind of bad file named with the file (and tile).
#include <sylva/core/atomic_file.hpp>
#include <sylva/core/hash.hpp>
#include <sylva/terrain/edit_layer.hpp>

#include "support/terrain_test_support.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

namespace sylva::terrain {
namespace {

using namespace testing;
namespace fs = std::filesystem;

constexpr int kColumns = 300, kRows = 520;  // 2 x 3 tiles, clipped edge tiles

std::vector<float> field() {
  std::vector<float> v(static_cast<std::size_t>(kColumns) * kRows);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = 0.001f * static_cast<float>(i % 977) - 0.3f;
  return v;
}

struct Painted {
  std::vector<float> baked = field(), painted = baked;
  Painted() {
    painted[5 * kColumns + 7] += 1e-7f;                 // tile (0, 0): one ulp-ish change
    painted[519 * kColumns + 299] = 12.5f;              // tile (1, 2): the far corner
  }
};

std::string message_of(const Result<EditLayer>& r) { return r.ok() ? "ok" : r.error().message; }

TEST(EditLayer, KeepsOnlyTheChangedTilesAndGivesThePaintedFieldBackBitForBit) {
  Painted p;
  const EditLayer layer = diff_edit_layer(p.baked, p.painted, kColumns, kRows);
  ASSERT_EQ(layer.tiles.size(), 2u);
  EXPECT_EQ(layer.tiles[0].index, 0u);
  EXPECT_EQ(layer.tiles[1].index, 5u);
  EXPECT_EQ(layer.tiles[1].heights.size(), 44u * 8u) << "the clipped corner tile";
  const fs::path file = unique_temp("layer.sylvaedits");
  ASSERT_TRUE(write_file_atomic(file, encode_edit_layer(layer)).ok());
  auto read = read_edit_layer(file);
  ASSERT_TRUE(read.ok()) << read.error().message;
  std::vector<float> applied = p.baked;
  ASSERT_TRUE(apply_edit_layer(*read, applied, kColumns, kRows, file).ok());
  EXPECT_EQ(std::memcmp(applied.data(), p.painted.data(), applied.size() * 4), 0);
  EXPECT_TRUE(diff_edit_layer(p.baked, p.baked, kColumns, kRows).tiles.empty()) << "undone everywhere: empty";
  const auto rects = changed_rects(p.baked, p.painted, kColumns, kRows);
  ASSERT_EQ(rects.size(), 2u);
  EXPECT_EQ(rects[0].x0, 7);
  EXPECT_EQ(rects[0].x1, 8);
  EXPECT_EQ(rects[1].z0, 519);
  fs::remove(file);
}

TEST(EditLayer, BadFilesAreNamedWithTheTileAndChangeNothing) {
  Painted p;
  const std::string good = encode_edit_layer(diff_edit_layer(p.baked, p.painted, kColumns, kRows));
  const fs::path file = unique_temp("bad.sylvaedits");
  auto read_bytes = [&](std::string bytes) {
    EXPECT_TRUE(write_file_atomic(file, bytes).ok());
    return read_edit_layer(file);
  };
  std::string damaged = good;
  damaged[40 + 24 + 8] ^= 0x10;  // tile (0, 0)'s heights
  EXPECT_NE(message_of(read_bytes(damaged)).find("bad.sylvaedits: tile (0, 0): checksum mismatch"), std::string::npos)
      << message_of(read_bytes(damaged));
  EXPECT_NE(message_of(read_bytes(good.substr(0, good.size() - 3))).find("tile (1, 2): truncated"), std::string::npos);
  EXPECT_NE(message_of(read_bytes(good + "x")).find("1 bytes after the last tile"), std::string::npos);
  EXPECT_NE(message_of(read_bytes("junk")).find("not a Sylva edit layer"), std::string::npos);
  std::string header = good;
  header[17] ^= 1;  // the field's columns
  EXPECT_NE(message_of(read_bytes(header)).find("header checksum mismatch"), std::string::npos);
  std::string version = good;
  version[8] = 9;
  const std::uint64_t header_checksum = fnv1a64(version.data(), 32);  // a well-formed other version
  std::memcpy(version.data() + 32, &header_checksum, 8);
  const auto other = read_bytes(version);
  ASSERT_FALSE(other.ok());
  EXPECT_EQ(other.error().code, ErrorCode::kUnsupported);
  EXPECT_NE(other.error().message.find("edit layer version 9"), std::string::npos) << other.error().message;

  // Painted over other baked heights (a re-baked file): named, nothing written.
  auto layer = read_bytes(good);
  ASSERT_TRUE(layer.ok());
  std::vector<float> rebaked = p.baked;
  rebaked[519 * kColumns + 290] += 1.0f;  // tile (1, 2)
  const std::vector<float> before = rebaked;
  Status applied = apply_edit_layer(*layer, rebaked, kColumns, kRows, file);
  ASSERT_FALSE(applied.ok());
  EXPECT_NE(applied.error().message.find("tile (1, 2): the baked heights under it"), std::string::npos)
      << applied.error().message;
  EXPECT_TRUE(rebaked == before);
  EXPECT_FALSE(apply_edit_layer(*layer, rebaked, kColumns + 1, kRows, file).ok()) << "another field size";
  fs::remove(file);
}

}  // namespace
}  // namespace sylva::terrain

// The ground height section of chunk files (chunk_file.hpp, version 3; issue 15, "a baked file
// carries its ground"): a bake stores the field's samples exactly, in tiles, equal for one process
// and merged shares; a reader gets every sample or every n-th, the coarse ones from the overview
// only; a damaged tile or table is an error naming the file (and tile), never a crash; a version-1
// file tells the user to re-bake, a version-2 file (no overview) is still read.
#include <sylva/terrain/bake.hpp>
#include <sylva/terrain/chunk_file.hpp>

#include "support/terrain_test_support.hpp"

#include <sylva/core/atomic_file.hpp>

#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <fstream>

namespace sylva::terrain {
namespace {

namespace fs = std::filesystem;
using testing::fbm_field;
using testing::unique_temp;

// 520 x 300 samples: 3 x 2 tiles of 256^2 (the last column and row partial), padded in the tree.
HeightField test_field(std::uint32_t seed = 4) { return fbm_field(520, 300, 1.5, 90.0f, seed, {-300.0, 120.0}); }

BakeOptions options() {
  BakeOptions o;
  o.tree.leaf_dimension = 17;
  return o;
}

void patch(const fs::path& p, std::uint64_t at, char value) {
  std::fstream f(p, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(static_cast<std::streamoff>(at));
  f.put(value);
}

// Byte offset of tile t's first sample in a file whose section starts after the 128-byte header.
std::uint64_t tile_start(int columns, int t) {
  const int tiles_x = (columns + 255) / 256, tiles = tiles_x * 2;
  const int tx = t % tiles_x, tz = t / tiles_x;
  const int height = tz == 0 ? 256 : 300 - 256;
  return 128 + std::uint64_t(tiles) * 8 + 8 + 4 * (std::uint64_t(tz) * 256 * columns + std::uint64_t(tx) * 256 * height);
}

// Bakes `field` as shares 0, 1, 2 of 3 into temporary files named after `stem`.
std::vector<fs::path> bake_three_shares(const HeightField& field, BakeOptions o, const std::string& stem) {
  std::vector<fs::path> shares;
  o.shares = 3;
  for (o.share = 0; o.share < 3; ++o.share) {
    shares.push_back(unique_temp(fmt::format("{}_{}.share", stem, o.share)));
    EXPECT_TRUE(bake_share(field, shares.back(), o).ok());
  }
  return shares;
}

struct Baked {
  HeightField field = test_field();
  fs::path file = unique_temp("heights.sylvaterrain");
  Baked() { EXPECT_TRUE(bake_chunk_file(field, file, options()).ok()); }
  ~Baked() { fs::remove(file); }
};

TEST(ChunkFileHeights, ABakeCarriesEverySampleExactlyAndPlacedLikeTheTree) {
  Baked b;
  auto file = ChunkFile::open(b.file);
  ASSERT_TRUE(file.ok()) << file.error().describe();
  ASSERT_TRUE((*file)->has_heights());
  auto ground = (*file)->read_heights();
  ASSERT_TRUE(ground.ok()) << ground.error().describe();
  EXPECT_EQ(ground->columns(), 520);
  EXPECT_EQ(ground->rows(), 300);
  EXPECT_EQ(ground->spacing(), 1.5);
  EXPECT_EQ(ground->origin(), glm::dvec2(-300.0, 120.0));
  EXPECT_TRUE(ground->samples() == b.field.samples());  // bit for bit
  EXPECT_EQ(ground->min_height(), b.field.min_height());

  // Every 4th sample: (520 - 1) / 4 + 1 = 130 columns, 75 rows, 4 x the spacing.
  EXPECT_EQ((*file)->height_stride(520u * 300u), 1);
  EXPECT_EQ((*file)->height_stride(130u * 75u), 4);
  auto coarse = (*file)->read_heights(4);
  ASSERT_TRUE(coarse.ok()) << coarse.error().describe();
  ASSERT_EQ(coarse->columns(), 130);
  ASSERT_EQ(coarse->rows(), 75);
  EXPECT_EQ(coarse->spacing(), 6.0);
  for (int z = 0; z < 75; ++z)
    for (int x = 0; x < 130; ++x) ASSERT_EQ(coarse->sample(x, z), b.field.sample(4 * x, 4 * z)) << x << ", " << z;
}

TEST(ChunkFileHeights, MergedSharesAndTheInMemorySaveHoldTheSameSection) {
  Baked b;
  std::vector<fs::path> shares = bake_three_shares(b.field, options(), "heights");
  BakeOptions o = options();
  o.shares = 3;
  const fs::path merged = unique_temp("heights_merged.sylvaterrain");
  auto m = merge_bake_shares(shares, merged);
  ASSERT_TRUE(m.ok()) << m.error().describe();
  EXPECT_TRUE(read_file(merged).value() == read_file(b.file).value());
  fs::remove(merged);

  // Share 0's section is the one copied: a damaged tile there is named with the share.
  patch(shares[0], tile_start(520, 4) + 100, 0x13);
  auto bad = merge_bake_shares(shares, merged);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().code, ErrorCode::kCorrupt);
  EXPECT_NE(bad.error().message.find(shares[0].string()), std::string::npos) << bad.error().message;
  EXPECT_NE(bad.error().message.find("height tile 4"), std::string::npos) << bad.error().message;

  // A share of another field with the same geometry and settings: its heights give it away.
  o.share = 1;
  ASSERT_TRUE(bake_share(test_field(5), shares[1], o).ok());
  ASSERT_TRUE(bake_share(b.field, shares[0], (o.share = 0, o)).ok());
  auto foreign = merge_bake_shares(shares, merged);
  ASSERT_FALSE(foreign.ok());
  EXPECT_NE(foreign.error().message.find("ground heights differ"), std::string::npos) << foreign.error().message;
  EXPECT_FALSE(fs::exists(merged));

  auto tree = ChunkTree::build(b.field, options().tree);
  ASSERT_TRUE(tree.ok());
  const fs::path memory = unique_temp("heights_memory.sylvaterrain");
  ASSERT_TRUE(save_chunk_file(memory, *tree, 0, &b.field).ok());
  EXPECT_TRUE(read_file(memory).value() == read_file(b.file).value());
  for (const auto& p : shares) fs::remove(p);
  fs::remove(merged);
  fs::remove(memory);
}

TEST(ChunkFileHeights, ADamagedTileOrTableIsAnErrorNamingTheFileAndTile) {
  Baked b;
  const std::string good = read_file(b.file).value();
  patch(b.file, tile_start(520, 2) + 8, 0x7f);  // tile 2: x 512..519, z 0..255
  auto file = ChunkFile::open(b.file);  // opening reads the table only
  ASSERT_TRUE(file.ok()) << file.error().describe();
  auto ground = (*file)->read_heights();
  ASSERT_FALSE(ground.ok());
  EXPECT_EQ(ground.error().code, ErrorCode::kCorrupt);
  EXPECT_NE(ground.error().message.find(b.file.string()), std::string::npos) << ground.error().message;
  EXPECT_NE(ground.error().message.find("height tile 2 (samples x 512..519, z 0..255): checksum mismatch"),
            std::string::npos) << ground.error().message;

  ASSERT_TRUE(write_file_atomic(b.file, good).ok());
  patch(b.file, 128 + 3, 0x01);  // the table
  auto table = ChunkFile::open(b.file);
  ASSERT_FALSE(table.ok());
  EXPECT_NE(table.error().message.find("height tile table checksum mismatch"), std::string::npos)
      << table.error().message;

  ASSERT_TRUE(write_file_atomic(b.file, good.substr(0, 128 + 60)).ok());  // truncated in the heights
  EXPECT_FALSE(ChunkFile::open(b.file).ok());
}

TEST(ChunkFileHeights, AVersionOneFileTellsTheUserToRebake) {
  Baked b;
  patch(b.file, 8, 1);
  auto file = ChunkFile::open(b.file);
  ASSERT_FALSE(file.ok());
  EXPECT_EQ(file.error().code, ErrorCode::kUnsupported);
  EXPECT_NE(file.error().message.find(b.file.string() + ": chunk file version 1, this build reads versions 2"),
            std::string::npos) << file.error().message;
  EXPECT_NE(file.error().message.find("re-bake it with `sylva-bake terrain`"), std::string::npos)
      << file.error().message;
}

// With an overview limit of 260 x 150 samples the 520 x 300 field gets an overview of every 2nd
// sample: 260 x 150, two tiles (7 and 8, after the field's 6).
constexpr std::uint64_t kOverviewLimit = 260 * 150;
constexpr std::uint64_t kFieldBytes = 520 * 300 * 4, kOverviewBytes = 260 * 150 * 4;
std::uint64_t overview_tile_start(int t) {  // overview tile 6 + t (t = 0, 1) of that file
  return 128 + 9 * 8 + kFieldBytes + 4 * std::uint64_t(t) * 256 * 150;
}

BakeOptions overview_options() {
  BakeOptions o = options();
  o.overview_max_samples = kOverviewLimit;
  return o;
}

TEST(ChunkFileHeights, CoarseGroundsAreReadFromTheOverviewOnlyAndEqualTheStridedField) {
  const HeightField field = test_field();
  const fs::path baked = unique_temp("heights_overview.sylvaterrain");
  ASSERT_TRUE(bake_chunk_file(field, baked, overview_options()).ok());
  auto file = ChunkFile::open(baked);
  ASSERT_TRUE(file.ok()) << file.error().describe();
  EXPECT_EQ((*file)->version(), 3u);
  ASSERT_EQ((*file)->height_overview(), 2u);
  for (int stride : {2, 4}) {
    const std::uint64_t before = (*file)->height_bytes_read();
    auto coarse = (*file)->read_heights(stride);
    ASSERT_TRUE(coarse.ok()) << coarse.error().describe();
    EXPECT_EQ((*file)->height_bytes_read() - before, kOverviewBytes) << "stride " << stride;  // the overview only
    ASSERT_EQ(coarse->columns(), (520 - 1) / stride + 1);
    ASSERT_EQ(coarse->rows(), (300 - 1) / stride + 1);
    EXPECT_EQ(coarse->spacing(), 1.5 * stride);
    for (int z = 0; z < coarse->rows(); ++z)
      for (int x = 0; x < coarse->columns(); ++x)
        ASSERT_EQ(std::bit_cast<std::uint32_t>(coarse->sample(x, z)),
                  std::bit_cast<std::uint32_t>(field.sample(stride * x, stride * z)))
            << "stride " << stride << " at " << x << ", " << z;
  }
  const std::uint64_t before = (*file)->height_bytes_read();
  auto full = (*file)->read_heights(1);
  ASSERT_TRUE(full.ok()) << full.error().describe();
  EXPECT_TRUE(full->samples() == field.samples());
  EXPECT_EQ((*file)->height_bytes_read() - before, kFieldBytes);

  // The in-memory save and three merged shares write the same overview: the same bytes.
  auto tree = ChunkTree::build(field, options().tree);
  ASSERT_TRUE(tree.ok());
  const fs::path memory = unique_temp("heights_overview_memory.sylvaterrain");
  ASSERT_TRUE(save_chunk_file(memory, *tree, 0, &field, kOverviewLimit).ok());
  EXPECT_TRUE(read_file(memory).value() == read_file(baked).value());
  const std::vector<fs::path> shares = bake_three_shares(field, overview_options(), "heights_overview");
  BakeOptions o = overview_options();
  o.shares = 3;
  const fs::path merged = unique_temp("heights_overview_merged.sylvaterrain");
  auto m = merge_bake_shares(shares, merged);
  ASSERT_TRUE(m.ok()) << m.error().describe();
  EXPECT_TRUE(read_file(merged).value() == read_file(baked).value());
  // A share baked with another overview limit is named.
  o.share = 2;
  o.overview_max_samples = 130 * 75;
  ASSERT_TRUE(bake_share(field, shares[2], o).ok());
  auto other = merge_bake_shares(shares, merged);
  ASSERT_FALSE(other.ok());
  EXPECT_NE(other.error().message.find(shares[2].string() + ": its ground overview has stride 4"), std::string::npos)
      << other.error().message;
  for (const auto& p : shares) fs::remove(p);
  fs::remove(merged);
  fs::remove(memory);
  fs::remove(baked);
}

TEST(ChunkFileHeights, ADamagedOverviewTileIsAnErrorNamingTheFileAndTile) {
  const HeightField field = test_field();
  const fs::path baked = unique_temp("heights_overview_bad.sylvaterrain");
  ASSERT_TRUE(bake_chunk_file(field, baked, overview_options()).ok());
  patch(baked, overview_tile_start(1) + 8, 0x7f);  // overview tile 7: samples x 512..518, z 0..298
  auto file = ChunkFile::open(baked);
  ASSERT_TRUE(file.ok()) << file.error().describe();
  auto coarse = (*file)->read_heights(2);
  ASSERT_FALSE(coarse.ok());
  EXPECT_EQ(coarse.error().code, ErrorCode::kCorrupt);
  EXPECT_NE(coarse.error().message.find(baked.string() +
                                        ": overview tile 7 (every 2nd sample; samples x 512..518, z 0..298): "
                                        "checksum mismatch"),
            std::string::npos) << coarse.error().message;
  EXPECT_TRUE((*file)->read_heights(1).ok());  // the field's own tiles are intact
  fs::remove(baked);
}

TEST(ChunkFileHeights, AVersionTwoFileIsReadWithoutAnOverview) {
  // A version-2 file is a version-3 file without an overview: the header's version and checksum
  // differ, nothing else.
  Baked b;
  std::string bytes = read_file(b.file).value();
  bytes[8] = 2;
  const std::uint64_t checksum = fnv1a64(bytes.data(), 120);
  std::memcpy(bytes.data() + 120, &checksum, 8);
  ASSERT_TRUE(write_file_atomic(b.file, bytes).ok());
  auto file = ChunkFile::open(b.file);
  ASSERT_TRUE(file.ok()) << file.error().describe();
  EXPECT_EQ((*file)->version(), 2u);
  EXPECT_EQ((*file)->height_overview(), 0u);
  auto coarse = (*file)->read_heights(4);  // from the field's tiles
  ASSERT_TRUE(coarse.ok()) << coarse.error().describe();
  EXPECT_EQ((*file)->height_bytes_read(), kFieldBytes);
  EXPECT_EQ(coarse->sample(129, 74), b.field.sample(516, 296));
}

TEST(ChunkFileHeights, AFileWithoutHeightsSaysSo) {
  const HeightField field = test_field();
  auto tree = ChunkTree::build(field, options().tree);
  ASSERT_TRUE(tree.ok());
  const fs::path plain = unique_temp("heights_none.sylvaterrain");
  ASSERT_TRUE(save_chunk_file(plain, *tree).ok());  // as the tree cache writes
  auto file = ChunkFile::open(plain);
  ASSERT_TRUE(file.ok());
  EXPECT_FALSE((*file)->has_heights());
  auto ground = (*file)->read_heights();
  ASSERT_FALSE(ground.ok());
  EXPECT_NE(ground.error().message.find("holds no ground heights"), std::string::npos) << ground.error().message;
  fs::remove(plain);
}

}  // namespace
}  // namespace sylva::terrain

// Chunk files whose checksums are right but whose header or directory lies (found by the
// chunk_file fuzz target, fuzz/README.md): each is refused at open with a message naming the file
// and what is wrong, instead of undefined behaviour or a huge allocation later.
#include <sylva/terrain/chunk_file.hpp>

#include "support/terrain_test_support.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

namespace sylva::terrain {
namespace {

namespace fs = std::filesystem;

class HostileChunkFile : public ::testing::Test {
 protected:
  void SetUp() override {
    HeightField field = testing::fbm_field(33, 33, 2.0, 40.0f, 7);
    ChunkTreeSettings settings;
    settings.leaf_dimension = 9;
    auto tree = ChunkTree::build(field, settings);
    ASSERT_TRUE(tree.ok()) << tree.error().describe();
    ASSERT_TRUE(save_chunk_file(path_, *tree).ok());
    std::ifstream in(path_, std::ios::binary);
    good_.assign(std::istreambuf_iterator<char>(in), {});
    ASSERT_GT(good_.size(), 128u);
  }
  void TearDown() override { fs::remove(path_); }

  template <class T>
  static void put(std::string& bytes, std::size_t at, T v) {
    std::memcpy(bytes.data() + at, &v, sizeof(T));
  }
  template <class T>
  static T get(const std::string& bytes, std::size_t at) {
    T v;
    std::memcpy(&v, bytes.data() + at, sizeof(T));
    return v;
  }
  // Offset of directory entry i (header layout in chunk_file.hpp).
  std::size_t entry(const std::string& bytes, std::size_t i) const { return get<std::uint64_t>(bytes, 80) + 64 * i; }

  // Writes `bytes` with the directory and header checksums recomputed, so only the lie is left.
  void expect_refused(std::string bytes, const std::string& what) {
    const std::uint64_t dir = get<std::uint64_t>(bytes, 80), dir_bytes = get<std::uint64_t>(bytes, 88);
    if (dir <= bytes.size() && dir_bytes <= bytes.size() - dir) put(bytes, 96, fnv1a64(bytes.data() + dir, dir_bytes));
    put(bytes, 120, fnv1a64(bytes.data(), 120));
    {
      std::ofstream out(path_, std::ios::binary | std::ios::trunc);
      out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    }
    auto file = ChunkFile::open(path_);
    ASSERT_FALSE(file.ok()) << "accepted: " << what;
    EXPECT_EQ(file.error().code, ErrorCode::kCorrupt);
    EXPECT_NE(file.error().message.find(path_.string()), std::string::npos) << file.error().message;
    EXPECT_NE(file.error().message.find(what), std::string::npos) << file.error().message;
  }

  fs::path path_ = testing::unique_temp("hostile.chunks");
  std::string good_;
};

TEST_F(HostileChunkFile, TheUntouchedFileOpens) {
  std::ofstream(path_, std::ios::binary | std::ios::trunc).write(good_.data(), static_cast<std::streamsize>(good_.size()));
  EXPECT_TRUE(ChunkFile::open(path_).ok());
}

// The fuzzer's first find: a key of level 60 made compute_nodes shift a 32-bit value by 60.
TEST_F(HostileChunkFile, AChunkKeyThatDisagreesWithItsSlot) {
  std::string s = good_;
  s[entry(s, 1) + 1] = 60;  // level byte of the first level-1 chunk
  expect_refused(s, "chunk 1 is labelled level 60");
  s = good_;
  put(s, entry(s, 2) + 4, std::uint32_t{0xffffffff});  // x of the second level-1 chunk
  expect_refused(s, "but its slot is level 1 at 1, 0");
}

TEST_F(HostileChunkFile, ABlobRangeThatWrapsAround) {
  std::string s = good_;
  put(s, entry(s, 0) + 40, std::uint64_t{1} << 63);          // offset
  put(s, entry(s, 0) + 48, (std::uint64_t{1} << 63) + 200);  // bytes: offset + bytes wraps to 200
  expect_refused(s, "points outside the data");
}

// 16 levels hold 1,431,655,765 chunks: a 91 GB directory, which the file cannot contain even
// when its offset wraps around so that offset + size equals the file size.
TEST_F(HostileChunkFile, ADirectoryLargerThanTheFile) {
  std::string s = good_;
  const std::uint32_t count = 1431655765u, n = get<std::uint32_t>(s, 20);
  const std::uint64_t dir_bytes = std::uint64_t{count} * 64;
  put(s, 16, std::uint32_t{16});     // levels
  put(s, 24, n << 15);               // root intervals
  put(s, 36, count);                 // chunks
  put(s, 88, dir_bytes);
  put(s, 80, std::uint64_t{s.size()} - dir_bytes);  // wraps
  expect_refused(s, "the directory does not fit the file");
}

TEST_F(HostileChunkFile, ImplausibleFieldGeometry) {
  std::string s = good_;
  put(s, 28, std::int32_t{-5});  // columns
  expect_refused(s, "implausible field geometry");
  s = good_;
  put(s, 40, std::numeric_limits<double>::quiet_NaN());  // spacing
  expect_refused(s, "implausible field geometry");
  s = good_;
  put(s, 72, std::uint32_t{12});  // leaf dimension that is not the tree's
  expect_refused(s, "implausible field geometry");
}

}  // namespace
}  // namespace sylva::terrain

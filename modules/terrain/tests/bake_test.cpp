// The out-of-core bake (bake.hpp): byte-identical to the in-memory build, tiled shares merged in
// any order, cancellation and failed writes leaving nothing, damaged or mismatched shares refused
// with the file and chunk named.
#include <sylva/terrain/bake.hpp>
#include <sylva/terrain/chunk_file.hpp>

#include "support/terrain_test_support.hpp"

#include <sylva/core/atomic_file.hpp>

#include <gtest/gtest.h>

#include <sys/resource.h>

#include <csignal>
#include <fstream>

namespace sylva::terrain {
namespace {

namespace fs = std::filesystem;
using testing::fbm_field;
using testing::unique_temp;

std::string bytes_of(const fs::path& p) {
  Result<std::string> r = read_file(p);
  return r ? r.value() : std::string();
}

// Files in p's folder whose name contains p's stem (temporaries are ".<stem>.<pid>-<n>.tmp...").
std::vector<std::string> leftovers(const fs::path& p) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(p.parent_path()))
    if (e.path().filename().string().find(p.stem().string()) != std::string::npos) out.push_back(e.path().string());
  return out;
}

// First chunk whose metadata or mesh differs, "" when none (to say *where* two files differ).
std::string first_difference(const fs::path& a, const fs::path& b) {
  auto fa = ChunkFile::open(a), fb = ChunkFile::open(b);
  if (!fa || !fb) return "cannot open both files";
  const ChunkTree& ta = (*fa)->tree();
  const ChunkTree& tb = (*fb)->tree();
  if (ta.chunk_count() != tb.chunk_count()) return "chunk counts differ";
  for (std::uint32_t i = 0; i < ta.chunk_count(); ++i) {
    const Chunk& ca = ta.chunk(i);
    const Chunk& cb = tb.chunk(i);
    if (ca.present != cb.present || ca.error != cb.error || ca.error_bound != cb.error_bound ||
        ca.min_y != cb.min_y || ca.max_y != cb.max_y || ca.triangle_count != cb.triangle_count) {
      return fmt::format("chunk {} metadata", i);
    }
    if (!ca.present) continue;
    auto ma = (*fa)->read_chunk(i), mb = (*fb)->read_chunk(i);
    if (!ma || !mb || !testing::same_bytes(ma->indices, mb->indices) || ma->vertices.size() != mb->vertices.size()) {
      return fmt::format("chunk {} mesh", i);
    }
    for (std::size_t k = 0; k < ma->vertices.size(); ++k) {
      const ChunkVertex& va = ma->vertices[k];
      const ChunkVertex& vb = mb->vertices[k];
      if (va.gx != vb.gx || va.gz != vb.gz || va.height != vb.height || va.morph_target != vb.morph_target ||
          va.morph_error != vb.morph_error || va.intro_level != vb.intro_level) {
        return fmt::format("chunk {} vertex {}", i, k);
      }
    }
  }
  return "";
}

TEST(Bake, OutOfCoreBakeOf2049FieldWithSmallBudgetEqualsInMemoryBuild) {
  const HeightField field = fbm_field(2049, 2049, 2.0, 400.0f, 11);
  ChunkTreeSettings s;  // defaults: leaf 33, 7 levels, 21845 chunks
  const fs::path memory = unique_temp("bake_memory.sylvaterrain");
  const fs::path baked = unique_temp("bake_out.sylvaterrain");
  {
    auto tree = ChunkTree::build(field, s);
    ASSERT_TRUE(tree.ok()) << tree.error().describe();
    ASSERT_TRUE(save_chunk_file(memory, *tree, 0, &field).ok());
  }
  BakeOptions o;
  o.tree = s;
  o.batch_bytes = 1;  // one chunk per thread in flight: the smallest budget
  float last = -1.0f;
  bool monotone = true;
  o.control.progress = [&](float f) {
    monotone = monotone && f >= last;
    last = f;
  };
  auto r = bake_chunk_file(field, baked, o);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  EXPECT_TRUE(monotone);
  EXPECT_EQ(last, 1.0f);
  EXPECT_EQ(first_difference(memory, baked), "");
  EXPECT_TRUE(bytes_of(memory) == bytes_of(baked)) << "files differ although every chunk matches";
  EXPECT_EQ(r->bytes, fs::file_size(baked));
  EXPECT_EQ(leftovers(baked), std::vector<std::string>{baked.string()});  // no temporaries or shares left
  fs::remove(memory);
  fs::remove(baked);
}

TEST(Bake, SharesMergeByteIdenticallyInAnyOrderOnPaddedFields) {
  // Non-square and not 2^k+1: padding chunks absent, shares cut through levels.
  const HeightField field = fbm_field(300, 190, 1.5, 80.0f, 5, {-1000.0, 250.0});
  BakeOptions o;
  o.tree.leaf_dimension = 17;
  const fs::path one = unique_temp("bake_one.sylvaterrain");
  ASSERT_TRUE(bake_chunk_file(field, one, o).ok());
  for (int n : {2, 3, 7}) {
    std::vector<fs::path> shares;
    for (int i = n - 1; i >= 0; --i) {  // reverse order: merge sorts by share index
      o.share = i;
      o.shares = n;
      shares.push_back(unique_temp(fmt::format("bake_share_{}_{}.share", i, n)));
      auto r = bake_share(field, shares.back(), o);
      ASSERT_TRUE(r.ok()) << r.error().describe();
    }
    const fs::path merged = unique_temp("bake_merged.sylvaterrain");
    auto m = merge_bake_shares(shares, merged);
    ASSERT_TRUE(m.ok()) << m.error().describe();
    EXPECT_TRUE(bytes_of(one) == bytes_of(merged)) << n << " shares: " << first_difference(one, merged);
    for (const auto& p : shares) fs::remove(p);
    fs::remove(merged);
  }
  // Same as the in-memory tree, too.
  auto tree = ChunkTree::build(field, o.tree);
  const fs::path memory = unique_temp("bake_memory_padded.sylvaterrain");
  ASSERT_TRUE(save_chunk_file(memory, *tree, 0, &field).ok());
  EXPECT_TRUE(bytes_of(one) == bytes_of(memory)) << first_difference(one, memory);
  fs::remove(one);
  fs::remove(memory);
}

TEST(Bake, CancellationLeavesNoFileAndKeepsTheOldOne) {
  const HeightField field = fbm_field(513, 513, 1.0, 50.0f, 3);
  const fs::path out = unique_temp("bake_cancel.sylvaterrain");
  ASSERT_TRUE(write_file_atomic(out, "the user's old file").ok());
  std::atomic<bool> cancel{false};
  BakeOptions o;
  o.batch_bytes = 1;
  o.control.cancel = &cancel;
  o.control.progress = [&](float f) {
    if (f > 0.3f) cancel = true;
  };
  auto r = bake_chunk_file(field, out, o);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kCancelled) << r.error().describe();
  EXPECT_EQ(bytes_of(out), "the user's old file");
  EXPECT_EQ(leftovers(out), std::vector<std::string>{out.string()});
  fs::remove(out);
}

TEST(Bake, AFullDiskIsAClearErrorAndLeavesNothing) {
  // RLIMIT_FSIZE makes writes past 64 KiB fail (EFBIG) like a full disk would.
  const HeightField field = fbm_field(257, 257, 1.0, 50.0f, 4);
  const fs::path out = unique_temp("bake_full.sylvaterrain");
  std::signal(SIGXFSZ, SIG_IGN);
  rlimit old{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &old), 0);
  rlimit small = old;
  small.rlim_cur = 64 * 1024;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  auto r = bake_chunk_file(field, out, BakeOptions{});
  setrlimit(RLIMIT_FSIZE, &old);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kIo);
  EXPECT_NE(r.error().message.find(out.stem().string()), std::string::npos) << r.error().message;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(leftovers(out).empty());
}

class BadShares : public ::testing::Test {
 protected:
  void SetUp() override {
    const HeightField field = fbm_field(200, 200, 1.0, 40.0f, 9);
    o.tree.leaf_dimension = 17;
    for (int i = 0; i < 2; ++i) {
      o.share = i;
      o.shares = 2;
      shares.push_back(unique_temp(fmt::format("bad_share_{}.share", i)));
      ASSERT_TRUE(bake_share(field, shares.back(), o).ok());
    }
  }
  void TearDown() override {
    for (const auto& p : shares) fs::remove(p);
    fs::remove(out);
  }
  Error merge_error(const std::vector<fs::path>& given) {
    auto r = merge_bake_shares(given, out);
    EXPECT_FALSE(r.ok());
    EXPECT_FALSE(fs::exists(out));
    return r.ok() ? Error{} : r.error();
  }
  void patch(const fs::path& p, std::size_t at, char value) {
    std::fstream f(p, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(at));
    f.put(value);
  }
  BakeOptions o;
  std::vector<fs::path> shares;
  fs::path out = unique_temp("bad_share_out.sylvaterrain");
};

TEST_F(BadShares, ADamagedChunkIsNamedWithItsShare) {
  // Inside the share's first blob, after the header and the 200^2 ground heights (one tile: its
  // checksum and the table's, then the samples).
  patch(shares[1], 128 + 16 + 200 * 200 * 4 + 30, 0x55);
  const Error e = merge_error(shares);
  EXPECT_EQ(e.code, ErrorCode::kCorrupt);
  EXPECT_NE(e.message.find(shares[1].string()), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("chunk"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("checksum"), std::string::npos) << e.message;
}

TEST_F(BadShares, TruncatedOtherVersionMissingRepeatedAndForeignSharesAreRefused) {
  EXPECT_EQ(merge_error({shares[0]}).code, ErrorCode::kInvalidArgument);  // share 1 of 2 missing
  EXPECT_EQ(merge_error({shares[0], shares[0]}).code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(merge_error({shares[0], unique_temp("no_such.share")}).code, ErrorCode::kNotFound);

  const fs::path foreign = unique_temp("bad_share_foreign.share");
  BakeOptions other = o;
  other.share = 1;
  other.tree.flat_tolerance = 0.5f;
  ASSERT_TRUE(bake_share(fbm_field(200, 200, 1.0, 40.0f, 9), foreign, other).ok());
  const Error f = merge_error({shares[0], foreign});
  EXPECT_EQ(f.code, ErrorCode::kInvalidArgument);
  EXPECT_NE(f.message.find("settings"), std::string::npos) << f.message;
  fs::remove(foreign);

  const std::uint64_t size = fs::file_size(shares[1]);
  fs::resize_file(shares[1], size - 10);
  const Error t = merge_error(shares);
  EXPECT_EQ(t.code, ErrorCode::kCorrupt);
  EXPECT_NE(t.message.find("truncated"), std::string::npos) << t.message;

  patch(shares[0], 8, 9);  // version 9
  EXPECT_EQ(merge_error(shares).code, ErrorCode::kUnsupported);
  const Error magic = (patch(shares[0], 0, 'X'), merge_error(shares));
  EXPECT_EQ(magic.code, ErrorCode::kCorrupt);
  EXPECT_NE(magic.message.find(shares[0].string()), std::string::npos);
}

TEST_F(BadShares, RandomDamageNeverCrashesOrWritesAFile) {
  const std::string good = bytes_of(shares[0]);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 60; ++trial) {
    std::string bad = good;
    const int hits = 1 + trial % 4;
    for (int h = 0; h < hits; ++h) bad[rng() % bad.size()] = static_cast<char>(rng());
    ASSERT_TRUE(write_file_atomic(shares[0], bad).ok());
    auto r = merge_bake_shares(shares, out);
    if (bad != good) {
      EXPECT_FALSE(r.ok()) << "trial " << trial;
      EXPECT_FALSE(fs::exists(out));
    }
  }
}

}  // namespace
}  // namespace sylva::terrain

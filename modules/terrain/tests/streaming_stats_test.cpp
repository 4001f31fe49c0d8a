// The streamer's counters a scene reports (issue 15): requests count a chunk once while it is
// pending (the selection repeats its request every frame), misses add the frames' substituted
// chunks, and the budget key is terrain.stream.budget_mb.
#include <sylva/terrain/chunk_file.hpp>
#include <sylva/terrain/streaming.hpp>

#include "support/terrain_test_support.hpp"

#include <gtest/gtest.h>

#include <array>
#include <filesystem>

namespace sylva::terrain {
namespace {

using namespace testing;
namespace fs = std::filesystem;

struct SmallFile {
  fs::path path = unique_temp("stream_stats.chunks");
  SmallFile() {
    const HeightField field = fbm_field(129, 129, 2.0, 60.0f, 5);
    ChunkTreeSettings s;
    s.leaf_dimension = 17;
    EXPECT_TRUE(save_chunk_file(path, ChunkTree::build(field, s).value()).ok());
  }
  ~SmallFile() { fs::remove(path); }
};

TEST(StreamingStats, RequestsCountEachChunkOnceWhilePendingAndMissesAdd) {
  SmallFile f;
  auto file = ChunkFile::open(f.path).value();
  auto streamer = ChunkStreamer::create(file, StreamingSettings{}).value();
  const std::array<std::uint32_t, 4> children = file->tree().child_indices(0);
  Residency r = streamer->residency();
  for (int repeat = 0; repeat < 3; ++repeat)
    for (std::uint32_t c : children) r.request(c, 10.0);
  r.request(children[0], 20.0);  // a higher priority for a pending chunk is no new request
  EXPECT_EQ(streamer->stats().requests, 4u);
  streamer->wait_idle();
  const StreamingStats loaded = streamer->stats();
  EXPECT_EQ(loaded.loads, 5u) << "the root and the four children";
  EXPECT_EQ(loaded.pending_requests, 0u);
  r.request(children[1], 10.0);  // resident: not asked for again
  EXPECT_EQ(streamer->stats().requests, 4u);
  streamer->count_misses(3);
  streamer->count_misses(2);
  EXPECT_EQ(streamer->stats().misses, 5u);
}

TEST(StreamingStats, TheBudgetKeyIsNamedInItsErrors) {
  SmallFile f;
  auto file = ChunkFile::open(f.path).value();
  StreamingSettings tiny;
  tiny.memory_budget_mb = 0.01;  // 10 KiB: less than the root
  auto streamer = ChunkStreamer::create(file, tiny);
  ASSERT_FALSE(streamer.ok());
  EXPECT_NE(streamer.error().message.find("terrain.stream.budget_mb"), std::string::npos) << streamer.error().message;
}

}  // namespace
}  // namespace sylva::terrain

// Chunk files and streaming: round trip, corrupt and truncated files, the memory budget, evict +
// reload identity, "a missing chunk draws its parent", and watertight frames from streamed meshes.
#include <sylva/terrain/chunk_file.hpp>
#include <sylva/terrain/frame_mesh.hpp>
#include <sylva/terrain/streaming.hpp>

#include "support/terrain_test_support.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

namespace sylva::terrain {
namespace {

using namespace testing;
namespace fs = std::filesystem;

struct Built {
  HeightField field = fbm_field(257, 201, 2.0, 120.0f, 61);
  ChunkTree tree = [&] {
    ChunkTreeSettings s;
    s.leaf_dimension = 17;
    return std::move(ChunkTree::build(field, s)).value();
  }();
  fs::path path = unique_temp("stream_test.chunks");
  Built() { EXPECT_TRUE(save_chunk_file(path, tree).ok()); }
  ~Built() { fs::remove(path); }
};
Built& built() {
  static Built b;
  return b;
}

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}
void write_bytes(const fs::path& p, const std::string& s) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(s.data(), static_cast<std::streamsize>(s.size()));
}
bool same_mesh(const ChunkMesh& a, const ChunkMesh& b) {
  return same_bytes(a.vertices, b.vertices) && a.indices == b.indices && a.edges == b.edges;
}

TEST(ChunkFile, RoundTripKeepsMetadataAndMeshesBitExact) {
  Built& b = built();
  auto f = ChunkFile::open(b.path);
  ASSERT_TRUE(f.ok()) << f.error().describe();
  const ChunkTree& t = (*f)->tree();
  EXPECT_EQ(t.levels(), b.tree.levels());
  EXPECT_EQ(t.root_intervals(), b.tree.root_intervals());
  EXPECT_EQ(t.spacing(), b.tree.spacing());
  EXPECT_FALSE(t.has_meshes());
  for (std::uint32_t i = 0; i < t.chunk_count(); ++i) {
    const Chunk &x = t.chunk(i), &y = b.tree.chunk(i);
    ASSERT_EQ(x.present, y.present);
    EXPECT_EQ(x.key, y.key);
    EXPECT_EQ(x.error, y.error);
    EXPECT_EQ(x.error_bound, y.error_bound);
    EXPECT_EQ(x.min_y, y.min_y);
    EXPECT_EQ(x.triangle_count, y.triangle_count);
    if (!x.present) continue;
    auto m = (*f)->read_chunk(i);
    ASSERT_TRUE(m.ok()) << m.error().describe();
    EXPECT_TRUE(same_mesh(*m, y.mesh)) << "chunk " << i;
  }
}

TEST(ChunkFile, CorruptAndTruncatedFilesAreRejectedClearly) {
  Built& b = built();
  const std::string good = read_bytes(b.path);
  const fs::path bad = unique_temp("bad.chunks");
  auto expect_open_error = [&](const std::string& bytes, const char* what) {
    write_bytes(bad, bytes);
    auto f = ChunkFile::open(bad);
    ASSERT_FALSE(f.ok()) << what;
    EXPECT_NE(f.error().message.find(bad.string()), std::string::npos) << f.error().message;
    EXPECT_NE(f.error().message.find(what), std::string::npos) << f.error().message;
  };
  expect_open_error(good.substr(0, 50), "truncated");
  expect_open_error(good.substr(0, good.size() - 10), "truncated");
  expect_open_error(good.substr(0, good.size() / 2), "truncated");
  std::string s = good;
  s[0] = 'X';
  expect_open_error(s, "bad magic");
  s = good;
  s[8] = 9;  // version
  expect_open_error(s, "version 9");
  s = good;
  s[44] ^= 0x10;  // spacing: header checksum
  expect_open_error(s, "header checksum");
  s = good;
  s[s.size() - 30] ^= 0x01;  // directory
  expect_open_error(s, "directory checksum");
  // A flipped bit inside a chunk's data: the file opens, that chunk names itself.
  s = good;
  s[200] ^= 0x04;
  write_bytes(bad, s);
  auto f = ChunkFile::open(bad);
  ASSERT_TRUE(f.ok());
  std::size_t failures = 0;
  for (std::uint32_t i = 0; i < (*f)->tree().chunk_count(); ++i) {
    if (!(*f)->tree().chunk(i).present) continue;
    auto m = (*f)->read_chunk(i);
    if (!m.ok()) {
      ++failures;
      EXPECT_NE(m.error().message.find("checksum mismatch"), std::string::npos) << m.error().message;
      EXPECT_NE(m.error().message.find("level"), std::string::npos);
    }
  }
  EXPECT_EQ(failures, 1u);
  EXPECT_FALSE(ChunkFile::open(unique_temp("no_such_file.chunks")).ok());
  fs::remove(bad);
}

// Invariant: random byte damage anywhere never crashes; it is either rejected at open or per
// chunk, or (when it hits unused padding) harmless.
TEST(ChunkFile, RandomDamageNeverCrashes) {
  Built& b = built();
  const std::string good = read_bytes(b.path);
  const fs::path bad = unique_temp("fuzz.chunks");
  std::mt19937 rng(99);
  int rejected = 0;
  for (int round = 0; round < 60; ++round) {
    std::string s = good;
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < flips; ++k) s[rng() % s.size()] ^= static_cast<char>(1 + rng() % 255);
    if (round % 5 == 0) s.resize(rng() % s.size());
    write_bytes(bad, s);
    auto f = ChunkFile::open(bad);
    if (!f.ok()) {
      ++rejected;
      continue;
    }
    for (std::uint32_t i = 0; i < (*f)->tree().chunk_count(); ++i) {
      if (!(*f)->tree().chunk(i).present) continue;
      auto m = (*f)->read_chunk(i);
      if (!m.ok()) ++rejected;
    }
  }
  EXPECT_GT(rejected, 30);
  fs::remove(bad);
}

// A streamer whose budget is `share` of the decoded meshes of the file's whole tree.
std::unique_ptr<ChunkStreamer> streamer_with_share(const std::shared_ptr<const ChunkFile>& file, double share) {
  std::size_t total = 0;
  for (std::uint32_t i = 0; i < file->tree().chunk_count(); ++i)
    if (file->tree().chunk(i).present) total += file->mesh_bytes(i);
  StreamingSettings ss;
  ss.memory_budget_mb = static_cast<double>(total) / 1048576.0 * share;
  return ChunkStreamer::create(file, ss).value();
}

// Streams along a flight: the budget holds every frame, everything drawn is resident, and a
// chunk whose children are missing is drawn in their place.
TEST(Streaming, BudgetIsRespectedAndMissingChunksDrawTheirParent) {
  auto file = ChunkFile::open(built().path).value();
  auto streamer = streamer_with_share(file, 1.0 / 6.0);  // a sixth of the whole tree
  LodSelector selector(file->tree());
  SeamCache seams;
  LodSettings ls;
  ls.max_pixel_error = 0.5f;
  std::size_t substituted = 0, cracks = 0, frames_drawn = 0;
  for (int frame = 0; frame < 120; ++frame) {
    streamer->update();
    const StreamingStats st = streamer->stats();
    ASSERT_LE(st.resident_bytes, st.budget_bytes) << "frame " << frame;
    const double t = frame / 119.0;
    const glm::dvec3 eye(20.0 + 450.0 * t, 60.0, 30.0 + 300.0 * t);
    const LodView view = look_at_view(eye, eye + glm::dvec3(1.0, -0.3, 0.5), 70.0);
    Residency r = streamer->residency();
    const Selection& sel = selector.select(view, ls, &r);
    substituted += sel.stats.substituted;
    for (const SelectedChunk& c : sel.chunks) ASSERT_TRUE(streamer->resident(c.index));
    const VertexFrame vf = make_vertex_frame(file->tree(), view, ls);
    const FrameMesh mesh = assemble_frame(file->tree(), streamer->meshes(), sel, vf, CrackFix::kSeams, seams);
    cracks += check_watertight(file->tree(), selector, vf, mesh).crack_edges;
    frames_drawn += !sel.chunks.empty();
    if (frame % 10 == 9) streamer->wait_idle();
  }
  EXPECT_GT(substituted, 0u) << "early frames must draw parents while children load";
  EXPECT_EQ(cracks, 0u);
  EXPECT_EQ(frames_drawn, 120u);
  const StreamingStats st = streamer->stats();
  EXPECT_GT(st.loads, 10u);
  EXPECT_GT(st.evictions, 0u) << "a sixth of the tree must force evictions";
  EXPECT_EQ(st.failures, 0u);
}

// A still view that needs more than the budget settles: after the loads that fit, the chunks
// dropped for lack of room are not read again frame after frame (stats dropped and loads stop
// growing, nothing pending, budget_limited), their parents are drawn; once room is made
// (evict_all) they are asked for and loaded again.
TEST(Streaming, AViewNeedingMoreThanTheBudgetSettles) {
  auto file = ChunkFile::open(built().path).value();
  auto streamer = streamer_with_share(file, 1.0 / 20.0);
  LodSelector selector(file->tree());
  LodSettings ls;
  ls.max_pixel_error = 0.5f;
  const LodView view = look_at_view({30, 80, 40}, {300, 20, 250}, 60.0);
  // One update per selection, as the renderer does (wait_idle would integrate a second time, and
  // a chunk used one update ago counts as unused).
  auto frame = [&] {
    streamer->update();
    Residency r = streamer->residency();
    selector.select(view, ls, &r);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));  // the loader reads meanwhile
  };
  int settled_after = 0;
  while (settled_after < 3000 && !streamer->stats().budget_limited) {
    frame();
    ++settled_after;
  }
  const StreamingStats settled = streamer->stats();
  ASSERT_TRUE(settled.budget_limited) << "not settled after " << settled_after << " frames";
  EXPECT_GT(settled.dropped, 0u) << "the view must need more than the budget";
  EXPECT_GT(settled.budget_refused, 0u);
  for (int k = 0; k < 20; ++k) frame();
  const StreamingStats later = streamer->stats();
  EXPECT_EQ(later.dropped, settled.dropped) << "dropped chunks were read again";
  EXPECT_EQ(later.loads, settled.loads);
  EXPECT_EQ(later.requests, settled.requests);
  EXPECT_TRUE(later.budget_limited);
  EXPECT_LE(later.resident_bytes, later.budget_bytes);
  streamer->evict_all();
  for (int k = 0; k < 2; ++k) frame();
  streamer->wait_idle();
  EXPECT_GT(streamer->stats().loads, later.loads) << "room made: the refused chunks are asked for again";
}

TEST(Streaming, WithEnoughMemoryTheStreamedSelectionMatchesTheInMemoryOne) {
  Built& b = built();
  auto file = ChunkFile::open(b.path).value();
  auto streamer = ChunkStreamer::create(file, StreamingSettings{}).value();
  LodSelector streamed(file->tree()), direct(b.tree);
  const LodView view = look_at_view({30, 80, 40}, {300, 20, 250}, 60.0);
  LodSettings ls;
  std::vector<std::uint32_t> a, d;
  for (int round = 0; round < 12; ++round) {
    streamer->update();
    Residency r = streamer->residency();
    const Selection& s = streamed.select(view, ls, &r);
    if (s.stats.substituted == 0) break;
    streamer->wait_idle();
  }
  Residency r = streamer->residency();
  for (const SelectedChunk& c : streamed.select(view, ls, &r).chunks) a.push_back(c.index);
  for (const SelectedChunk& c : direct.select(view, ls).chunks) d.push_back(c.index);
  EXPECT_EQ(a, d);
}

TEST(Streaming, EvictAndReloadGiveIdenticalMeshes) {
  Built& b = built();
  auto file = ChunkFile::open(b.path).value();
  auto streamer = ChunkStreamer::create(file, StreamingSettings{}).value();
  const std::uint32_t probe = file->tree().index(2, 1, 1);
  Residency r = streamer->residency();
  r.request(probe, 1.0);
  streamer->wait_idle();
  ASSERT_TRUE(streamer->resident(probe));
  const ChunkMesh first = *streamer->mesh(probe);
  EXPECT_TRUE(same_mesh(first, b.tree.chunk(probe).mesh));
  streamer->evict_all();
  EXPECT_FALSE(streamer->resident(probe));
  EXPECT_TRUE(streamer->resident(0)) << "the root stays";
  r = streamer->residency();
  r.request(probe, 1.0);
  streamer->wait_idle();
  ASSERT_TRUE(streamer->resident(probe));
  EXPECT_TRUE(same_mesh(*streamer->mesh(probe), first));
}

TEST(Streaming, ACorruptChunkIsReportedAndItsParentKeepsDrawing) {
  Built& b = built();
  std::string s = read_bytes(b.path);
  // Damage the data of one level-1 chunk (find its blob through a clean open).
  auto clean = ChunkFile::open(b.path).value();
  const std::uint32_t victim = clean->tree().index(1, 0, 0);
  const auto probe = clean->read_chunk(victim);
  ASSERT_TRUE(probe.ok());
  // Blobs are written in chunk order after the 128-byte header: the root's blob comes first.
  const std::size_t root_blob = 24 + b.tree.chunk(0).mesh.vertices.size() * 24 +
                                (b.tree.chunk(0).mesh.indices.size() + [&] {
                                  std::size_t e = 0;
                                  for (const auto& v : b.tree.chunk(0).mesh.edges) e += v.size();
                                  return e;
                                }()) * 4;
  s[128 + root_blob + 40] ^= 0x20;
  const fs::path bad = unique_temp("badchunk.chunks");
  write_bytes(bad, s);
  auto file = ChunkFile::open(bad).value();
  auto streamer = ChunkStreamer::create(file, StreamingSettings{}).value();
  LodSelector selector(file->tree());
  LodSettings ls;
  const LodView view = look_at_view({10, 40, 10}, {100, 0, 100}, 60.0);
  for (int frame = 0; frame < 6; ++frame) {
    streamer->update();
    Residency r = streamer->residency();
    const Selection& sel = selector.select(view, ls, &r);
    for (const SelectedChunk& c : sel.chunks) ASSERT_TRUE(streamer->resident(c.index));
    streamer->wait_idle();
  }
  const StreamingStats st = streamer->stats();
  EXPECT_EQ(st.failures, 1u);
  EXPECT_NE(st.last_error.find("checksum mismatch"), std::string::npos) << st.last_error;
  EXPECT_FALSE(streamer->resident(victim));
  streamer.reset();
  fs::remove(bad);
}

}  // namespace
}  // namespace sylva::terrain

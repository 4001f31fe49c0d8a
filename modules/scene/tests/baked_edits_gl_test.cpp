// Painting a baked terrain through the scene (issue 15, "painting a streamed terrain works"): the
// test bakes a scene's 513^2 ground (as `sylva-bake terrain`), opens a scene streaming it, paints
// a bump into the ground map (Scene::map and map_changed, the editor brush's path) and draws the
// terrain alone on magenta: the streamed picture equals the in-memory terrain painted the same way,
// pixel for pixel, with no hole pixel, from three poses. Saving writes the painted tiles as the
// scene's edit layer (<stem>_maps/terrain_height.sylvaedits); reopening gives the same ground
// samples and the same picture. Undo (the old texels back) gives the unpainted ground and picture
// bit for bit. A damaged layer: a warning naming the file and tile, the scene opens unpainted and
// the file is left as it was.
#if SYLVA_HAS_TERRAIN
#include <sylva/core/log.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene.hpp>
#include <sylva/terrain/bake.hpp>
#include <sylva/terrain/chunk_file.hpp>
#include <sylva/terrain/decimated_ground_edits.hpp>
#include <sylva/terrain/renderer.hpp>
#include <sylva/terrain/streaming.hpp>

#include "baked_ground.hpp"
#include "scene_test_files.hpp"
#include "support/gl_support.hpp"
#ifdef SYLVA_PLAYER_EXE
#include "run_command.hpp"
#endif

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

using namespace sylva;
using namespace sylva::scene;
namespace fs = std::filesystem;
using terrain::testing::GlTarget;
using terrain::testing::is_color;
using terrain::testing::kMagenta;
using sylva::scene::testing::open_scene_file;
using sylva::scene::testing::TestDir;

namespace {

using BakedEditsGl = render::GlTest;

// 1024 m, 513^2 samples 2 m apart, 33-sample leaves (5 levels, 341 chunks).
std::string scene_text(const std::string& baked_file) {
  std::string terrain = R"("size": 1024, "resolution": 513, "height": 140, "generator": "fbm",
      "noise": {"frequency": 0.004, "octaves": 6, "seed": 23}, "tree": {"leaf_dimension": 33})";
  // A baked ground lies where the file's chunks are, whatever "center" says (baked_ground.hpp).
  if (!baked_file.empty()) {
    terrain += R"(, "center": [100, 0], "baked_file": ")" + baked_file + R"(", "stream": {"budget_mb": 64})";
  }
  return R"({"terrain": {)" + terrain + R"(}, "render": {"shadows": {"enabled": false}}})";
}

std::unique_ptr<Scene> write_and_load(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
  return open_scene_file(file);
}

terrain::TerrainRenderer* terrain_of(Scene& scene) {
  ModuleInstance* m = scene.module("terrain");
  return m == nullptr ? nullptr : dynamic_cast<terrain::TerrainRenderer*>(m->drawables().front());
}

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::size_t holes(const Image& image) {
  std::size_t n = 0;
  for (int y = image.height() / 2; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) n += is_color(image, x, y, kMagenta) ? 1 : 0;
  return n;
}

std::size_t differing_pixels(const Image& a, const Image& b) {
  std::size_t n = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x)
      for (int c = 0; c < 3; ++c)
        if (a.at(x, y, c) != b.at(x, y, c)) {
          ++n;
          break;
        }
  return n;
}

// The samples a stroke of radius r on (cx, cz) writes, clipped to a size^2 ground.
TexelRect stroke_rect(int cx, int cz, int r, int size = 513) {
  return {std::max(cx - r, 0), std::max(cz - r, 0), std::min(cx + r + 1, size), std::min(cz + r + 1, size)};
}

// A bump of `amount` metres of radius r samples on sample (cx, cz) of the scene's ground map, as
// a brush stroke: texels written, then map_changed. Returns the rectangle.
TexelRect paint(Scene& scene, int cx, int cz, int r, float amount) {
  SceneMap* map = scene.map("terrain.height");
  const TexelRect rect = stroke_rect(cx, cz, r, map->grid.width);
  for (int z = rect.y0; z < rect.y1; ++z) {
    for (int x = rect.x0; x < rect.x1; ++x) {
      const double d = std::hypot(x - cx, z - cz) / (r + 1);
      if (d < 1.0) map->grid.at(x, z) += amount * static_cast<float>(1.0 - d * d);
    }
  }
  EXPECT_TRUE(scene.map_changed("terrain.height", rect).ok());
  return rect;
}

std::vector<CameraView> poses() {
  std::vector<CameraView> v(3);
  v[0].position = {0.0, 320.0, 150.0};
  v[0].pitch_deg = -60.0f;
  v[1].position = {-150.0, 160.0, -40.0};
  v[1].yaw_deg = -60.0f;
  v[1].pitch_deg = -35.0f;
  v[2].position = {120.0, 90.0, -60.0};
  v[2].yaw_deg = 80.0f;
  v[2].pitch_deg = -30.0f;
  return v;
}

// The scene's terrain from each pose, drawn once the streamer has caught up (frames with
// wait_idle until no chunk is drawn for a missing child; at most 40). Every frame: no hole.
std::vector<Image> pictures(Scene& scene, GlTarget& target) {
  std::vector<Image> out;
  terrain::TerrainRenderer* r = terrain_of(scene);
  for (const CameraView& view : poses()) {
    const render::Camera camera = scene.make_camera(view, target.size());
    scene.update(camera, 0.0, 0.0f, target.size());  // settings sync: applies a pending edit
    Image image;
    for (int f = 0; f < 40; ++f) {
      image = target.render(*r, camera, kMagenta);
      EXPECT_EQ(holes(image), 0u) << "frame " << f;
      if (r->streamer() == nullptr || r->frame_stats().selection.substituted == 0) break;
      r->streamer()->wait_idle();
    }
    out.push_back(std::move(image));
  }
  return out;
}

void expect_same_pictures(const std::vector<Image>& a, const std::vector<Image>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(differing_pixels(a[i], b[i]), 0u) << what << ", pose " << i;
}

TEST_F(BakedEditsGl, PaintSaveReopenUndoAreBitExactAndADamagedLayerOpensUnpainted) {
  if (!find_module("terrain")) GTEST_SKIP() << "terrain is built out";
  TestDir dir("sylva_baked_edits");
  auto memory = write_and_load(dir.path / "memory.json", scene_text(""));
  ASSERT_TRUE(memory);
  terrain::BakeOptions options;
  options.tree.leaf_dimension = 33;
  ASSERT_TRUE(terrain::bake_chunk_file(*memory->ground(), dir.path / "valley.sylvaterrain", options).ok());
  auto baked = write_and_load(dir.path / "baked.json", scene_text("valley.sylvaterrain"));
  ASSERT_TRUE(baked);
  ASSERT_NE(terrain_of(*baked)->streamer(), nullptr);
  const std::vector<float> unpainted = baked->ground()->samples();
  GlTarget target = GlTarget::create(192, 108);
  const std::vector<Image> before = pictures(*baked, target);

  // The same strokes on the in-memory terrain and on the baked one; the second reaches the
  // field's east edge (the last column and the padding beyond it) and two more tiles.
  const TexelRect first = stroke_rect(256, 200, 20), second = stroke_rect(508, 300, 9);
  const std::vector<float> undo_first = baked->map("terrain.height")->grid.copy_rect(first);
  const std::vector<float> undo_second = baked->map("terrain.height")->grid.copy_rect(second);
  for (Scene* s : {memory.get(), baked.get()}) {
    paint(*s, 256, 200, 20, 40.0f);
    paint(*s, 508, 300, 9, -25.0f);
  }
  const std::vector<Image> painted = pictures(*baked, target);
  expect_same_pictures(painted, pictures(*memory, target), "painted: streamed vs in-memory");
  EXPECT_GT(differing_pixels(before[0], painted[0]), 100u) << "the bump is in view";
  const nlohmann::json stats = baked->module_stats()["terrain"];
  EXPECT_GT(stats["stream_edited_chunks"].get<std::size_t>(), 4u);
  EXPECT_LT(stats["stream_edited_chunks"].get<std::size_t>(), 120u) << "only the chunks the strokes reach";
  const std::vector<float> painted_ground = baked->ground()->samples();
  // A setting that rebuilds the ground and the section (kOffline) keeps the unsaved strokes
  // where they are and draws them.
  ASSERT_TRUE(baked->set_param("terrain.tree.leaf_dimension", "33").ok());
  EXPECT_TRUE(baked->ground()->samples() == painted_ground);
  EXPECT_EQ(baked->ground()->origin(), memory->ground()->origin());
  expect_same_pictures(pictures(*baked, target), painted, "painted, after an offline rebuild");
  const nlohmann::json in_memory = memory->module_stats()["terrain"];
  std::printf("two strokes, applied at the next frame as their bounding rectangle: streamed %s chunks rebuilt in "
              "%.1f ms (%s edited so far); in memory %s rebuilt + %s updated in %.1f ms\n",
              stats["chunks_rebuilt"].dump().c_str(), stats["tree_build_ms"].get<double>(),
              stats["stream_edited_chunks"].dump().c_str(), in_memory["chunks_rebuilt"].dump().c_str(),
              in_memory["chunks_updated"].dump().c_str(), in_memory["tree_build_ms"].get<double>());

  // Save: the painted tiles as the scene's edit layer; reopen: the same ground and picture.
  ASSERT_TRUE(baked->save(dir.path / "painted.json").ok());
  const fs::path layer = dir.path / "painted_maps" / "terrain_height.sylvaedits";
  ASSERT_TRUE(fs::exists(layer));
  // Tiles (0, 0), (1, 0), (1, 1) and the 1-column edge tile (2, 1) of the 3 x 3.
  EXPECT_EQ(fs::file_size(layer), 40u + 4u * 24u + (3u * 256u * 256u + 256u) * 4u) << "sparse: the painted tiles";
  nlohmann::json reopened_edited;
  {
    auto reopened = open_scene_file(dir.path / "painted.json");
    ASSERT_TRUE(reopened);
    EXPECT_TRUE(reopened->ground()->samples() == painted_ground) << "edit layer: bit-exact heights";
    reopened_edited = reopened->module_stats()["terrain"]["stream_edited_chunks"];
    EXPECT_GT(reopened_edited.get<std::size_t>(), 4u) << "the layer's chunks rebuilt at open";
    expect_same_pictures(pictures(*reopened, target), painted, "reopened");
  }

#ifdef SYLVA_PLAYER_EXE
  {
    // The shipped player opens the painted scene with its layer: the same chunks rebuilt.
    const fs::path stats_file = dir.path / "player.stats.json";
    const auto run = test::run_command(SYLVA_PLAYER_EXE, (dir.path / "painted.json").string() +
                                                             " --headless --size 96x54 --frames 2 --stats " +
                                                             stats_file.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    std::ifstream in(stats_file);
    const nlohmann::json player = nlohmann::json::parse(in, nullptr, false);
    ASSERT_FALSE(player.is_discarded());
    EXPECT_EQ(player["modules"]["terrain"]["stream_edited_chunks"], reopened_edited) << run.output;
  }
#endif

  // Undo the first stroke, then the second (the editor's undo pastes the old texels back).
  baked->map("terrain.height")->grid.paste_rect(first, undo_first);
  ASSERT_TRUE(baked->map_changed("terrain.height", first).ok());
  (void)pictures(*baked, target);
  baked->map("terrain.height")->grid.paste_rect(second, undo_second);
  ASSERT_TRUE(baked->map_changed("terrain.height", second).ok());
  EXPECT_TRUE(baked->ground()->samples() == unpainted);
  expect_same_pictures(pictures(*baked, target), before, "undone");

  // A damaged layer: the scene opens unpainted with a warning naming the file and tile; the file
  // stays as it was.
  std::string bytes = read_bytes(layer);
  bytes[40 + 24 + 1000] = static_cast<char>(bytes[40 + 24 + 1000] ^ 0x40);  // the first tile's heights
  std::ofstream(layer, std::ios::binary | std::ios::trunc) << bytes;
  std::vector<std::string> warnings;
  set_log_sink([&](LogLevel level, std::string_view m) {
    if (level >= LogLevel::kWarn) warnings.emplace_back(m);
  });
  auto damaged = open_scene_file(dir.path / "painted.json");
  set_log_sink(nullptr);
  ASSERT_TRUE(damaged) << "a bad layer does not stop the scene";
  std::string all;
  for (const std::string& w : warnings) all += w + "\n";
  EXPECT_NE(all.find("terrain_height.sylvaedits: tile (0, 0): checksum mismatch"), std::string::npos) << all;
  EXPECT_NE(all.find("opens without these edits"), std::string::npos) << all;
  EXPECT_TRUE(damaged->ground()->samples() == unpainted);
  expect_same_pictures(pictures(*damaged, target), before, "damaged layer");
  EXPECT_EQ(read_bytes(layer), bytes) << "a failed load never rewrites the layer";
}

// A field above the ground limit (issue 15): the ground is every 4th baked sample (the 513^2 bake
// with a 129^2 overview, read with a ground limit of 129^2, as baked_terrain_gl does for an 8193^2
// or 16385^2 field), painted through the scene (Scene::map + map_changed, the editor brush's path).
// The exact samples are read at the first stroke, not at open; every chunk the streamer makes
// resident equals ChunkTree::build of the painted exact field bit for bit, a field that keeps
// the baked samples wherever the ground around them is unpainted and IS the painted ground at the
// stride; the layer saved is the ground's one tile and reopens bit-exact with the same chunks;
// undoing both strokes gives the file's chunks back.
struct ChunkCompare {
  std::size_t compared = 0, differing = 0;
  std::string first;
};

// Makes every chunk of `s` resident and compares it with `built` (meshes and metadata, bit for bit).
ChunkCompare compare_chunks(terrain::ChunkStreamer& s, const terrain::ChunkTree& built) {
  ChunkCompare out;
  for (int round = 0; round < 8; ++round) {
    s.update();
    terrain::Residency r = s.residency();
    bool missing = false;
    for (std::uint32_t i = 0; i < s.tree().chunk_count(); ++i) {
      if (!s.tree().chunk(i).present || s.resident(i)) continue;
      r.request(i, 1.0 + i);
      missing = true;
    }
    if (!missing) break;
    s.wait_idle();
  }
  for (std::uint32_t i = 0; i < built.chunk_count(); ++i) {
    const terrain::Chunk &a = s.tree().chunk(i), &b = built.chunk(i);
    if (!b.present) continue;
    const terrain::ChunkMesh* m = s.mesh(i);
    const bool same = m != nullptr && a.error == b.error && a.error_bound == b.error_bound && a.min_y == b.min_y &&
                      a.max_y == b.max_y && m->vertices.size() == b.mesh.vertices.size() &&
                      std::memcmp(m->vertices.data(), b.mesh.vertices.data(),
                                  m->vertices.size() * sizeof(terrain::ChunkVertex)) == 0 &&
                      m->indices == b.mesh.indices && m->edges == b.mesh.edges;
    ++out.compared;
    if (!same && out.differing++ == 0) out.first = fmt::format("chunk {} (level {})", i, b.key.level);
  }
  return out;
}

// Applies a pending stroke (the section's settings sync, as a frame does).
void next_frame(Scene& scene) {
  const glm::ivec2 size{96, 54};
  scene.update(scene.make_camera(poses()[0], size), 0.0, 0.0f, size);
}

TEST_F(BakedEditsGl, ADecimatedGroundPaintsTheFieldsExactSamplesSavesReopensAndUndoes) {
  if (!find_module("terrain")) GTEST_SKIP() << "terrain is built out";
  TestDir dir("sylva_baked_edits_decimated");
  auto memory = write_and_load(dir.path / "memory.json", scene_text(""));
  ASSERT_TRUE(memory);
  terrain::BakeOptions options;
  options.tree.leaf_dimension = 33;
  options.overview_max_samples = 129 * 129;
  const fs::path file = dir.path / "valley.sylvaterrain";
  ASSERT_TRUE(terrain::bake_chunk_file(*memory->ground(), file, options).ok());
  terrain::ChunkTreeSettings tree_settings;
  tree_settings.leaf_dimension = 33;
  const terrain::ChunkTree unpainted_tree = terrain::ChunkTree::build(*memory->ground(), tree_settings).value();

  ScopedBakedGroundLimit limit(129 * 129);
  std::vector<std::string> infos;
  const LogLevel level = log_level();
  set_log_level(LogLevel::kInfo);
  set_log_sink([&](LogLevel, std::string_view m) { infos.emplace_back(m); });
  const auto exact_reads = [&] {
    return std::count_if(infos.begin(), infos.end(),
                         [](const std::string& m) { return m.find("painting the baked field's exact") != std::string::npos; });
  };
  auto baked = write_and_load(dir.path / "baked.json", scene_text("valley.sylvaterrain"));
  ASSERT_TRUE(baked);
  ASSERT_EQ(baked->ground()->columns(), 129);
  ASSERT_EQ(baked->ground()->spacing(), 8.0);
  terrain::ChunkStreamer* streamer = terrain_of(*baked)->streamer();
  ASSERT_NE(streamer, nullptr);
  EXPECT_EQ(baked->module_stats()["terrain"]["baked_ground_matches"], 0);
  const std::vector<float> unpainted = baked->ground()->samples();
  next_frame(*baked);
  EXPECT_EQ(exact_reads(), 0) << "no exact sample is read before the first stroke";
  EXPECT_EQ(baked->module_stats()["terrain"]["baked_exact_bytes"], 0);

  // Two strokes, the second over the field's east edge (the padding beyond it).
  const TexelRect first{59, 45, 70, 56}, second{123, 72, 129, 79};
  const std::vector<float> undo_first = baked->map("terrain.height")->grid.copy_rect(first);
  const std::vector<float> undo_second = baked->map("terrain.height")->grid.copy_rect(second);
  EXPECT_EQ(paint(*baked, 64, 50, 5, 40.0f).x0, first.x0);
  next_frame(*baked);
  EXPECT_EQ(exact_reads(), 1) << "read once, at the first stroke";
  // The 513^2 field and the baked samples of the 256^2 tiles the stroke wrote: (0, 0) and (1, 0).
  EXPECT_EQ(baked->module_stats()["terrain"]["baked_exact_bytes"], (513u * 513u + 2u * 256u * 256u) * 4u);
  EXPECT_EQ(paint(*baked, 127, 75, 3, -25.0f).x1, second.x1);
  next_frame(*baked);
  set_log_sink(nullptr);
  set_log_level(level);
  EXPECT_EQ(exact_reads(), 1);
  const std::vector<float> painted_ground = baked->ground()->samples();
  const nlohmann::json stats = baked->module_stats()["terrain"];
  EXPECT_GT(stats["stream_edited_chunks"].get<std::size_t>(), 4u);
  EXPECT_LT(stats["stream_edited_chunks"].get<std::size_t>(), 150u) << "only the chunks the strokes reach";

  // The painted exact field: the baked samples with the ground's change spread between its samples.
  auto chunks = terrain::ChunkFile::open(file);
  ASSERT_TRUE(chunks.ok());
  auto expected = terrain::DecimatedGroundEdits::open(**chunks, 4);
  ASSERT_TRUE(expected.ok());
  ASSERT_TRUE((*expected)->apply(painted_ground, {0, 0, 129, 129}).ok());
  const HeightField& exact = (*expected)->field();
  const std::vector<float>& source = memory->ground()->samples();
  std::size_t kept = 0, changed = 0;
  for (int z = 0; z < 513; ++z) {
    for (int x = 0; x < 513; ++x) {
      const std::size_t k = static_cast<std::size_t>(z) * 513 + x;
      if (x % 4 == 0 && z % 4 == 0) {
        ASSERT_EQ(std::bit_cast<std::uint32_t>(exact.samples()[k]),
                  std::bit_cast<std::uint32_t>(painted_ground[static_cast<std::size_t>(z / 4) * 129 + x / 4]))
            << "the ground is the exact field at its stride: " << x << ", " << z;
      }
      (std::bit_cast<std::uint32_t>(exact.samples()[k]) == std::bit_cast<std::uint32_t>(source[k]) ? kept : changed)++;
    }
  }
  EXPECT_GT(changed, 1000u) << "under the strokes";
  EXPECT_LT(changed, 3000u) << "only under the strokes";
  const terrain::ChunkTree painted_tree = terrain::ChunkTree::build(exact, tree_settings).value();
  ChunkCompare c = compare_chunks(*streamer, painted_tree);
  EXPECT_EQ(c.compared, 341u);
  EXPECT_EQ(c.differing, 0u) << "first: " << c.first;

  // Saved: the ground's one 129^2 tile; reopened: the same ground and chunks, bit for bit.
  ASSERT_TRUE(baked->save(dir.path / "painted.json").ok());
  const fs::path layer = dir.path / "painted_maps" / "terrain_height.sylvaedits";
  ASSERT_TRUE(fs::exists(layer));
  EXPECT_EQ(fs::file_size(layer), 40u + 24u + 129u * 129u * 4u);
  {
    auto reopened = open_scene_file(dir.path / "painted.json");
    ASSERT_TRUE(reopened);
    EXPECT_TRUE(reopened->ground()->samples() == painted_ground) << "edit layer: bit-exact ground";
    EXPECT_GT(reopened->module_stats()["terrain"]["stream_edited_chunks"].get<std::size_t>(), 4u);
    c = compare_chunks(*terrain_of(*reopened)->streamer(), painted_tree);
    EXPECT_EQ(c.differing, 0u) << "reopened, first: " << c.first;
  }

  // Undo both strokes (the editor pastes the old texels back): the file's chunks again.
  baked->map("terrain.height")->grid.paste_rect(second, undo_second);
  ASSERT_TRUE(baked->map_changed("terrain.height", second).ok());
  next_frame(*baked);
  baked->map("terrain.height")->grid.paste_rect(first, undo_first);
  ASSERT_TRUE(baked->map_changed("terrain.height", first).ok());
  next_frame(*baked);
  EXPECT_TRUE(baked->ground()->samples() == unpainted);
  c = compare_chunks(*streamer, unpainted_tree);
  EXPECT_EQ(c.compared, 341u);
  EXPECT_EQ(c.differing, 0u) << "undone, first: " << c.first;
}

}  // namespace
#endif

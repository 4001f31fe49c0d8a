// A baked terrain streamed through a scene file (issue 15, "bake once, stream always"): the test
// bakes the scene's own ground into a chunk file (terrain/bake.hpp, as `sylva-bake terrain`),
// opens a scene naming it with terrain.baked_file and a terrain.stream.budget_mb far below the
// file's decoded meshes, and flies a scripted camera over it, drawing the scene's terrain alone on
// magenta (the terrain tests' GlTarget): every frame the resident bytes stay within the budget and
// no magenta pixel shows below the horizon (a missing chunk draws its parent, never a hole). At
// the end, with the camera still and the loader caught up (ChunkStreamer::wait_idle, a frame
// limit, no timing), the picture equals the in-memory terrain's of the same scene without
// baked_file. Missing, corrupt and foreign-version files are scene errors naming the file.
#if SYLVA_HAS_TERRAIN
#include <sylva/core/log.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene.hpp>
#include <sylva/terrain/bake.hpp>
#include <sylva/terrain/chunk_file.hpp>
#include <sylva/terrain/renderer.hpp>

#include "baked_ground.hpp"
#include "support/gl_support.hpp"
#ifdef SYLVA_PLAYER_EXE
#include "run_command.hpp"
#endif

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <unistd.h>

using namespace sylva;
using namespace sylva::scene;
namespace fs = std::filesystem;
using terrain::testing::GlTarget;
using terrain::testing::is_color;
using terrain::testing::kMagenta;

namespace {

using BakedTerrainGl = render::GlTest;

// A 1024 m field of 513^2 samples, 33-sample leaves (5 levels, 341 chunks).
std::string scene_text(const std::string& baked_file, double budget_mb, int seed = 11) {
  std::string terrain = R"("size": 1024, "resolution": 513, "height": 140, "generator": "fbm",
      "noise": {"frequency": 0.004, "octaves": 6, "seed": )" + std::to_string(seed) + R"(}, "tree": {"leaf_dimension": 33})";
  if (!baked_file.empty()) {
    terrain += R"(, "baked_file": ")" + baked_file + R"(", "stream": {"budget_mb": )" + std::to_string(budget_mb) + "}";
  }
  return R"({"terrain": {)" + terrain + R"(}, "render": {"shadows": {"enabled": false}}})";
}

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("sylva_baked_terrain_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

std::unique_ptr<Scene> open_scene(const fs::path& file, const std::string& text, std::string* error = nullptr) {
  {
    std::ofstream out(file);
    out << text;
  }
  std::vector<std::string> warnings;
  auto doc = SceneDocument::load(file, warnings);
  EXPECT_TRUE(doc.ok()) << doc.error().message;
  if (!doc.ok()) return nullptr;
  auto scene = Scene::create(std::move(*doc));
  if (!scene.ok()) {
    if (error != nullptr) *error = scene.error().message;
    return nullptr;
  }
  return std::move(*scene);
}

terrain::TerrainRenderer* terrain_of(Scene& scene) {
  ModuleInstance* m = scene.module("terrain");
  if (m == nullptr || m->drawables().empty()) return nullptr;
  return dynamic_cast<terrain::TerrainRenderer*>(m->drawables().front());
}

std::uint64_t stat(const nlohmann::json& s, const char* key) { return s.at(key).get<std::uint64_t>(); }

// Magenta pixels in the lower half of the picture (below the horizon for these poses).
std::size_t holes_below_horizon(const Image& image) {
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
        if (std::abs(a.at(x, y, c) - b.at(x, y, c)) > 0.5f / 255.0f) {
          ++n;
          break;
        }
  return n;
}

// Bakes the reference scene's ground the way `sylva-bake terrain` does.
struct Baked {
  TempDir dir;
  fs::path file = dir.path / "valley.sylvaterrain";
  std::unique_ptr<Scene> reference;
  std::size_t decoded_bytes = 0;  // every chunk's mesh in memory

  Baked() {
    reference = open_scene(dir.path / "reference.json", scene_text("", 0.0));
    if (!reference) return;
    terrain::BakeOptions options;
    options.tree.leaf_dimension = 33;
    auto report = terrain::bake_chunk_file(*reference->ground(), file, options);
    EXPECT_TRUE(report.ok()) << report.error().message;
    auto chunks = terrain::ChunkFile::open(file);
    EXPECT_TRUE(chunks.ok()) << chunks.error().message;
    if (!chunks.ok()) return;
    for (std::uint32_t i = 0; i < (*chunks)->tree().chunk_count(); ++i) {
      if ((*chunks)->tree().chunk(i).present) decoded_bytes += (*chunks)->mesh_bytes(i);
    }
  }
};

render::Camera pose(const Scene& scene, double t, glm::ivec2 size) {
  // A circle of 250 m radius 200 m up, looking 55 degrees down toward the centre: the lower half
  // of the view meets the ground well inside the 512 m half size (asserted on the in-memory
  // terrain).
  CameraView v;
  const double a = t * 2.0 * 3.14159265358979;
  v.position = {250.0 * std::cos(a), 200.0, 250.0 * std::sin(a)};
  v.yaw_deg = static_cast<float>(90.0 - t * 360.0);  // yaw 0 looks along -z, positive turns left
  v.pitch_deg = -55.0f;
  v.fov_deg = 60.0f;
  return scene.make_camera(v, size);
}

TEST_F(BakedTerrainGl, StreamsWithinTheBudgetWithoutHolesAndCatchesUpToTheInMemoryPicture) {
  if (!find_module("terrain")) GTEST_SKIP() << "terrain is built out";
  Baked baked;
  ASSERT_TRUE(baked.reference);
  const std::uintmax_t file_bytes = fs::file_size(baked.file);
  // A sixth of the decoded meshes (and far below the file's size): the flight cannot hold them.
  const double budget_mb = static_cast<double>(baked.decoded_bytes) / 6.0 / 1048576.0;
  ASSERT_LT(budget_mb * 1048576.0, static_cast<double>(file_bytes) / 2.0);
  auto scene = open_scene(baked.dir.path / "baked.json", scene_text("valley.sylvaterrain", budget_mb));
  ASSERT_TRUE(scene);
  terrain::TerrainRenderer* streamed = terrain_of(*scene);
  ASSERT_NE(streamed, nullptr);
  ASSERT_NE(streamed->streamer(), nullptr) << "baked_file streams";
  EXPECT_NE(streamed->height_texture(), nullptr) << "the scene's ground is the baked field: it shades too";
  EXPECT_EQ(stat(scene->module_stats()["terrain"], "baked_ground_matches"), 1u);

  GlTarget target = GlTarget::create(256, 144);
  const int frames = 90;
  std::size_t max_resident = 0, holes = 0, most_holes_in_a_frame = 0;
  std::uint64_t budget = 0;
  terrain::TerrainRenderer* in_memory = terrain_of(*baked.reference);
  ASSERT_NE(in_memory, nullptr);
  for (int f = 0; f < frames; ++f) {
    const render::Camera camera = pose(*scene, f / static_cast<double>(frames), target.size());
    // The pose is good for the test: the in-memory terrain covers the lower half.
    ASSERT_EQ(holes_below_horizon(target.render(*in_memory, camera, kMagenta)), 0u) << "frame " << f;
    const Image image = target.render(*streamed, camera, kMagenta);
    const nlohmann::json s = scene->module_stats()["terrain"];
    budget = stat(s, "stream_budget_bytes");
    const std::size_t resident = stat(s, "stream_resident_bytes");
    EXPECT_LE(resident, budget) << "frame " << f;
    max_resident = std::max(max_resident, resident);
    const std::size_t h = holes_below_horizon(image);
    EXPECT_EQ(h, 0u) << "frame " << f;
    holes += h;
    most_holes_in_a_frame = std::max(most_holes_in_a_frame, h);
  }
  const nlohmann::json flown = scene->module_stats()["terrain"];
  EXPECT_GT(stat(flown, "stream_loads"), 1u) << "chunks beyond the root were loaded";
  EXPECT_GT(stat(flown, "stream_misses"), 0u) << "parents were drawn for missing children";
  EXPECT_GT(stat(flown, "stream_evictions"), 0u) << "the budget forced evictions";
  EXPECT_EQ(stat(flown, "stream_failures"), 0u);
  std::printf("flight: %d frames, budget %llu B (decoded meshes %zu B, file %ju B), max resident %zu B, loads %s, "
              "requests %s, misses %s, evictions %s, dropped %s, hole pixels %zu\n",
              frames, static_cast<unsigned long long>(budget), baked.decoded_bytes, file_bytes, max_resident,
              flown["stream_loads"].dump().c_str(), flown["stream_requests"].dump().c_str(),
              flown["stream_misses"].dump().c_str(), flown["stream_evictions"].dump().c_str(),
              flown["stream_dropped"].dump().c_str(), holes);

  // The end: higher up and still, everything but the root evicted; the loader catches up
  // (wait_idle after each frame, at most 50 frames), never leaving a hole meanwhile.
  CameraView end;
  end.position = {0.0, 320.0, 150.0};
  end.pitch_deg = -60.0f;
  const render::Camera still = scene->make_camera(end, target.size());
  const Image reference = target.render(*in_memory, baked.reference->make_camera(end, target.size()), kMagenta);
  ASSERT_EQ(holes_below_horizon(reference), 0u) << "the still pose sees only terrain below the horizon";
  streamed->streamer()->evict_all();
  Image last;
  int settled = -1;
  std::uint64_t first_misses = 0;
  for (int f = 0; f < 50 && settled < 0; ++f) {
    last = target.render(*streamed, still, kMagenta);
    EXPECT_EQ(holes_below_horizon(last), 0u) << "catching up, frame " << f;
    const std::uint64_t misses = scene->module_stats()["terrain"]["stream_misses_frame"].get<std::uint64_t>();
    if (f == 0) first_misses = misses;
    if (misses == 0) settled = f;
    streamed->streamer()->wait_idle();
  }
  EXPECT_GT(first_misses, 0u) << "the first still frame drew parents for the evicted chunks";
  ASSERT_GE(settled, 0) << "the still view never resolved within the budget";
  const nlohmann::json end_stats = scene->module_stats()["terrain"];
  EXPECT_LE(stat(end_stats, "stream_resident_bytes"), budget);
  EXPECT_EQ(stat(end_stats, "stream_pending"), 0u);
  const std::size_t differing = differing_pixels(last, reference);
  EXPECT_EQ(differing, 0u) << "the same chunks, the same field: the same picture";
  EXPECT_EQ(stat(end_stats, "triangles"), stat(baked.reference->module_stats()["terrain"], "triangles"));
  std::printf("still view: %llu misses in its first frame, resolved after %d frames, %s chunks / %s triangles drawn, %zu pixels differ from the "
              "in-memory terrain\n",
              static_cast<unsigned long long>(first_misses), settled + 1, end_stats["chunks_drawn"].dump().c_str(), end_stats["triangles"].dump().c_str(), differing);
}

TEST_F(BakedTerrainGl, MissingCorruptAndForeignFilesAreSceneErrorsNamingTheFile) {
  if (!find_module("terrain")) GTEST_SKIP() << "terrain is built out";
  Baked baked;
  ASSERT_TRUE(baked.reference);
  std::string error;
  EXPECT_FALSE(open_scene(baked.dir.path / "missing.json", scene_text("nowhere.sylvaterrain", 64.0), &error));
  EXPECT_NE(error.find("terrain.baked_file"), std::string::npos) << error;
  EXPECT_NE(error.find("nowhere.sylvaterrain"), std::string::npos) << error;

  std::string bytes;
  {
    std::ifstream in(baked.file, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const auto write = [&](const char* name, const std::string& content) {
    std::ofstream out(baked.dir.path / name, std::ios::binary | std::ios::trunc);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  };
  std::string corrupt = bytes;
  corrupt[corrupt.size() - 100] = static_cast<char>(corrupt[corrupt.size() - 100] ^ 0x5A);  // the directory
  write("corrupt.sylvaterrain", corrupt);
  error.clear();
  EXPECT_FALSE(open_scene(baked.dir.path / "corrupt.json", scene_text("corrupt.sylvaterrain", 64.0), &error));
  EXPECT_NE(error.find("corrupt.sylvaterrain"), std::string::npos) << error;

  std::string foreign = bytes;
  foreign[8] = 1;  // the header's version: a file baked before the ground heights
  write("foreign.sylvaterrain", foreign);
  error.clear();
  EXPECT_FALSE(open_scene(baked.dir.path / "foreign.json", scene_text("foreign.sylvaterrain", 64.0), &error));
  EXPECT_NE(error.find("foreign.sylvaterrain: chunk file version 1, this build reads versions 2"), std::string::npos)
      << error;
  EXPECT_NE(error.find("re-bake it with `sylva-bake terrain`"), std::string::npos) << error;
  EXPECT_NE(error.find("terrain.baked_file"), std::string::npos) << error;

  // A damaged ground height tile: 513^2 samples are 3 x 3 tiles of 256^2 (table of 9 checksums and
  // its own); tile 4 (x 256..511, z 256..511) starts after the two tile rows' first 256 rows and
  // tile 3.
  std::string tile = bytes;
  const std::size_t tile4 = 128 + 10 * 8 + 4 * (256 * 513 + 256 * 256);
  tile[tile4 + 100] = static_cast<char>(tile[tile4 + 100] ^ 0x21);
  write("tile.sylvaterrain", tile);
  error.clear();
  EXPECT_FALSE(open_scene(baked.dir.path / "tile.json", scene_text("tile.sylvaterrain", 64.0), &error));
  EXPECT_NE(error.find("tile.sylvaterrain: height tile 4 (samples x 256..511, z 256..511): checksum mismatch"),
            std::string::npos) << error;

  write("short.sylvaterrain", bytes.substr(0, bytes.size() / 2));
  error.clear();
  EXPECT_FALSE(open_scene(baked.dir.path / "short.json", scene_text("short.sylvaterrain", 64.0), &error));
  EXPECT_NE(error.find("short.sylvaterrain"), std::string::npos) << error;
  std::printf("errors: %s\n", error.c_str());
}

// Save as into another folder: terrain.baked_file is rebased (it names a user's file, never
// copied), and the saved scene streams the same file.
TEST_F(BakedTerrainGl, SaveAsRebasesTheBakedFile) {
  if (!find_module("terrain")) GTEST_SKIP() << "terrain is built out";
  Baked baked;
  ASSERT_TRUE(baked.reference);
  auto scene = open_scene(baked.dir.path / "baked.json", scene_text("valley.sylvaterrain", 64.0));
  ASSERT_TRUE(scene);
  fs::create_directories(baked.dir.path / "elsewhere");
  const fs::path saved = baked.dir.path / "elsewhere" / "saved.json";
  ASSERT_TRUE(scene->save(saved).ok());
  std::vector<std::string> warnings;
  auto doc = SceneDocument::load(saved, warnings);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  EXPECT_EQ(doc->to_json()["terrain"]["baked_file"].get<std::string>(), "../valley.sylvaterrain");
  auto reopened = Scene::create(std::move(*doc));
  ASSERT_TRUE(reopened.ok()) << reopened.error().message;
  EXPECT_EQ(stat((*reopened)->module_stats()["terrain"], "baked_file_bytes"), fs::file_size(baked.file));
  // A new budget (the editor's slider) reopens the streamer with it.
  ASSERT_TRUE((*reopened)->set_param("terrain.stream.budget_mb", "2").ok());
  EXPECT_EQ(stat((*reopened)->module_stats()["terrain"], "stream_budget_bytes"), 2u << 20);
}

#ifdef SYLVA_PLAYER_EXE
// The shipped player flies a camera path over the baked file (headless, 1/30 s a frame) with the
// same small budget, and its --stats carry the streaming numbers.
TEST_F(BakedTerrainGl, PlayerStatsReportStreaming) {
  if (!find_module("terrain")) GTEST_SKIP() << "terrain is built out";
  Baked baked;
  ASSERT_TRUE(baked.reference);
  const double budget_mb = static_cast<double>(baked.decoded_bytes) / 6.0 / 1048576.0;
  std::string text = scene_text("valley.sylvaterrain", budget_mb);
  text.pop_back();  // the closing brace: add a camera and a path
  text += R"(, "camera": {"position": [250, 200, 0], "yaw_deg": 90, "pitch_deg": -55},
    "camera_paths": {"flight": {"keys": [
      {"time_s": 0, "position": [250, 200, 0], "yaw_deg": 90, "pitch_deg": -55},
      {"time_s": 1, "position": [0, 200, 250], "yaw_deg": 0, "pitch_deg": -55},
      {"time_s": 2, "position": [-250, 200, 0], "yaw_deg": -90, "pitch_deg": -55}]}}})";
  const fs::path file = baked.dir.path / "flight.json";
  {
    std::ofstream out(file);
    out << text;
  }
  const fs::path stats_file = baked.dir.path / "flight.stats.json";
  const auto run = test::run_command(SYLVA_PLAYER_EXE, file.string() + " --headless --size 128x72 --frames 60 "
                                                       "--camera-path flight --stats " + stats_file.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  std::ifstream in(stats_file);
  const nlohmann::json stats = nlohmann::json::parse(in, nullptr, false);
  ASSERT_FALSE(stats.is_discarded());
  const nlohmann::json& t = stats["modules"]["terrain"];
  EXPECT_GT(stat(t, "stream_loads"), 1u) << t.dump();
  EXPECT_GT(stat(t, "stream_misses"), 0u) << t.dump();
  EXPECT_GT(stat(t, "stream_requests"), 0u);
  EXPECT_LE(stat(t, "stream_resident_bytes"), stat(t, "stream_budget_bytes"));
  EXPECT_EQ(stat(t, "stream_failures"), 0u);
  EXPECT_GT(stats["longest_frame_ms"].get<double>(), 0.0);
  std::printf("player: loads %s, misses %s, evictions %s, resident %s of %s B, longest frame %.1f ms\n",
              t["stream_loads"].dump().c_str(), t["stream_misses"].dump().c_str(), t["stream_evictions"].dump().c_str(),
              t["stream_resident_bytes"].dump().c_str(), t["stream_budget_bytes"].dump().c_str(),
              stats["longest_frame_ms"].get<double>());
}
#endif

// A baked field above the ground limit: the ground is every n-th sample, read from the file's
// overview alone (chunk_file.hpp version 3), not from every tile of the field. Small sizes stand
// in for the real ones: the 513^2 field baked with an overview of at most 129^2 samples (every
// 4th), read with a ground limit of 129^2 (the scene's is 4097^2 for fields up to 16385^2).
TEST_F(BakedTerrainGl, AGroundAboveTheLimitIsReadFromTheOverviewOnly) {
  if (!find_module("terrain")) GTEST_SKIP() << "terrain is built out";
  Baked baked;
  ASSERT_TRUE(baked.reference);
  const HeightField& source = *baked.reference->ground();
  ASSERT_EQ(source.columns(), 513);
  terrain::BakeOptions options;
  options.tree.leaf_dimension = 33;
  options.overview_max_samples = 129 * 129;
  const fs::path file = baked.dir.path / "overview.sylvaterrain";
  ASSERT_TRUE(terrain::bake_chunk_file(source, file, options).ok());

  BakedGroundRead read;
  auto ground = read_baked_ground(file, 129 * 129, &read);
  ASSERT_TRUE(ground.ok()) << ground.error().message;
  EXPECT_TRUE(read.overview);
  EXPECT_EQ(read.bytes, 129u * 129u * 4u) << "the overview's one tile, none of the field's 9";
  ASSERT_EQ(ground->width, 129);
  ASSERT_EQ(ground->height, 129);
  EXPECT_EQ(ground->texel_size.x, 4.0 * source.spacing());
  EXPECT_EQ(ground->texel_origin, source.origin());
  for (int z = 0; z < 129; ++z)
    for (int x = 0; x < 129; ++x)
      ASSERT_EQ(ground->values[static_cast<std::size_t>(z) * 129 + static_cast<std::size_t>(x)],
                source.sample(4 * x, 4 * z)) << x << ", " << z;

  // A limit the overview does not serve (every 2nd sample) reads the field's tiles, silently.
  auto finer = read_baked_ground(file, 257 * 257, &read);
  ASSERT_TRUE(finer.ok()) << finer.error().message;
  EXPECT_FALSE(read.overview);
  EXPECT_EQ(read.bytes, 513u * 513u * 4u);
  EXPECT_EQ(finer->values.back(), source.sample(512, 512));

  // A current bake without an overview (its field fitted the limit it was baked for), read at a
  // stride: every tile is read, and the log does not advise a re-bake that would change nothing.
  options.overview_max_samples = 513 * 513;
  const fs::path plain = baked.dir.path / "plain.sylvaterrain";
  ASSERT_TRUE(terrain::bake_chunk_file(source, plain, options).ok());
  std::vector<std::string> lines;
  set_log_sink([&](LogLevel, std::string_view m) { lines.emplace_back(m); });
  auto strided = read_baked_ground(plain, 129 * 129, &read);
  set_log_sink(nullptr);
  ASSERT_TRUE(strided.ok()) << strided.error().message;
  EXPECT_FALSE(read.overview);
  const auto said = [&](const char* text) {
    return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(text) != std::string::npos; });
  };
  EXPECT_TRUE(said("every 4th ground sample from all of the field's height tiles"));
  EXPECT_FALSE(said("re-bak")) << "version 3 already writes an overview where the limit needs one";
}

// A user who names only terrain.baked_file: the scene's ground is the baked field (the file
// carries its heights, chunk_file.hpp version 2), so grass, trees and the camera's above-ground
// height stand on the terrain drawn, whatever (or nothing) the height keys say.
TEST_F(BakedTerrainGl, ASceneNamingOnlyTheBakedFileStandsOnTheBakedGround) {
  if (!find_module("terrain")) GTEST_SKIP() << "terrain is built out";
  Baked baked;
  ASSERT_TRUE(baked.reference);
  std::string text = R"({"terrain": {"baked_file": "valley.sylvaterrain", "stream": {"budget_mb": 64}},
                         "render": {"shadows": {"enabled": false}})";
  if (find_module("grass")) {
    text += R"(, "grass": {"area_min": [94, -106], "area_max": [106, -94], "field": {"density": 8},
                           "render": {"simulate": false}})";
  }
  if (find_module("vegetation")) {
    text += R"(, "vegetation": {"area_min": [-200, -200], "area_max": [200, 200], "trees_per_hectare": 2,
                                "leaf_texture_size": 32})";
  }
  text += "}";
  std::vector<std::string> warnings;
  set_log_sink([&](LogLevel level, std::string_view m) {
    if (level >= LogLevel::kWarn) warnings.emplace_back(m);
  });
  auto scene = open_scene(baked.dir.path / "only_baked.json", text);
  set_log_sink(nullptr);
  ASSERT_TRUE(scene);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  EXPECT_EQ(stat(scene->module_stats()["terrain"], "baked_ground_matches"), 1u);
  EXPECT_NE(terrain_of(*scene)->height_texture(), nullptr) << "the ground is the baked field: it shades too";

  // The source field (the reference scene's ground, which was baked): same samples, same place.
  const HeightField& source = *baked.reference->ground();
  ASSERT_NE(scene->ground(), nullptr);
  EXPECT_EQ(scene->ground()->origin(), source.origin());
  EXPECT_EQ(scene->ground()->spacing(), source.spacing());
  EXPECT_TRUE(scene->ground()->samples() == source.samples()) << "float32 tiles: exact";
  for (int j = 0; j < 13; ++j) {
    for (int i = 0; i < 13; ++i) {
      const double x = -500.0 + 83.1 * i, z = -500.0 + 82.7 * j;
      ASSERT_EQ(scene->ground_height(x, z), source.height(x, z)) << x << ", " << z;
    }
  }
  CameraView walker;
  walker.position = {31.0, 1.7, -47.0};
  walker.height_mode = HeightMode::kAboveGround;
  EXPECT_NEAR(scene->make_camera(walker, {64, 36}).position().y, source.height(31.0, -47.0) + 1.7, 1e-6);

  // How many of a module's placed positions there are and how far the worst is off the source.
  const auto off_ground = [&](const char* module, std::size_t most) -> std::pair<std::size_t, double> {
    ModuleInstance* m = scene->module(module);
    if (m == nullptr) return {0, 0.0};
    const std::vector<glm::dvec3> placed = m->placed_positions(most);
    double worst = 0.0;
    for (const glm::dvec3& p : placed) worst = std::max(worst, std::abs(p.y - source.height(p.x, p.z)));
    return {placed.size(), worst};
  };
  const auto [blades, worst_blade] = off_ground("grass", 300);
  const auto [trees, worst_tree] = off_ground("vegetation", 1000);
  if (find_module("grass")) {
    EXPECT_GT(blades, 100u);
    EXPECT_LT(worst_blade, 2e-3) << "blade roots on the baked terrain";
  }
  if (find_module("vegetation")) {
    EXPECT_GT(trees, 5u);
    EXPECT_LT(worst_tree, 1e-4) << "trees on the baked terrain";
  }
  std::printf("baked ground: %zu blades (worst root %.2g m off the terrain), %zu trees (worst %.2g m)\n", blades,
              worst_blade, trees, worst_tree);
}

}  // namespace
#endif  // SYLVA_HAS_TERRAIN

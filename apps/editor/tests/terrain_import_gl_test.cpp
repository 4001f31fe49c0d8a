// File > Import terrain... through its script commands (issue 15; terrain_import.hpp): a GeoTIFF
// the test writes is used directly (the scene's ground holds its samples) or baked into a chunk
// file on the worker thread while frames go on (progress to 100 %, terrain.baked_file set, the
// scene streams it, the ground matches the file); a cancelled bake leaves no file and the scene
// as it was; broken sources are errors naming the file, the scene unchanged; a mesh becomes the
// model_terrain section. Each import is one undo step. And the model terrain tuned in the editor:
// tau 1 -> 8 px by `set` draws fewer triangles, undo restores the count.
#include "editor_session.hpp"
#include "script_runner.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/render/testing.hpp>

#include <support/geotiff_fixture.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace sylva;
using namespace sylva::editor;

namespace {

constexpr int kSide = 65;
constexpr double kSpacing = 8.0;  // metres (UTM)

// Hills in whole metres, 100..260 m.
test::GeoTiffSpec hills() {
  test::GeoTiffSpec s;
  s.columns = s.rows = kSide;
  s.pixel_x = s.pixel_y = kSpacing;
  s.values.resize(kSide * kSide);
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) s.values[j * kSide + i] = std::round(180.0 + 80.0 * std::sin(i * 0.15) * std::cos(j * 0.11));
  return s;
}

constexpr const char* kScene = R"({"sylva_scene": 1,
  "camera": {"position": [0, 400, 300], "yaw_deg": 0, "pitch_deg": -50, "fov_deg": 60},
  "terrain": {"size": 512, "resolution": 65, "generator": "flat", "tree": {"leaf_dimension": 17}}})";

class TerrainImportGl : public render::GlTest {
 protected:
  void SetUp() override {
    render::GlTest::SetUp();
    dir_ = fs::temp_directory_path() / ("sylva_editor_import_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    ASSERT_TRUE(write_file_atomic(dir_ / "scene.json", kScene).ok());
    test::write_geotiff(dir_ / "dem.tif", hills());
    auto session = EditorSession::create({64, 36});
    ASSERT_TRUE(session.ok()) << session.error().message;
    session_ = std::move(*session);
    ASSERT_TRUE(session_->load(dir_ / "scene.json").ok());
  }
  void TearDown() override {
    session_.reset();
    fs::remove_all(dir_);
  }
  // Runs script lines on the session; the output, or "ERROR <message>" appended on failure.
  std::string run(const std::string& text) {
    auto commands = parse_script(text, "test.sylva");
    EXPECT_TRUE(commands.ok()) << commands.error().message;
    if (!commands.ok()) return "";
    std::ostringstream out;
    auto outcome = run_script(*session_, *commands, "test.sylva", dir_, out);
    return out.str() + (outcome.ok() ? "" : "ERROR " + outcome.error().message);
  }
  std::string param(const std::string& path) { return session_->scene().get_param(path).value(); }
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path dir_;
  std::unique_ptr<EditorSession> session_;
};

TEST_F(TerrainImportGl, RasterUsedDirectlyGivesTheGroundItsSamplesInOneUndoStep) {
  const nlohmann::json before = session_->scene().document().to_json();
  const std::string out = run("frames 1\nimport_terrain dem.tif\nframes 2\n");
  ASSERT_EQ(out.find("ERROR"), std::string::npos) << out;
  EXPECT_NE(out.find("65 x 65 samples, 8 m apart"), std::string::npos) << out;
  EXPECT_EQ(param("terrain.elevation.file"), "dem.tif");
  const HeightField* ground = session_->scene().ground();
  ASSERT_NE(ground, nullptr);
  ASSERT_EQ(ground->columns(), kSide);
  EXPECT_EQ(ground->spacing(), kSpacing);
  const test::GeoTiffSpec spec = hills();
  for (int j = 0; j < kSide; j += 7)
    for (int i = 0; i < kSide; i += 5) ASSERT_EQ(ground->sample(i, j), static_cast<float>(spec.values[j * kSide + i])) << i << "," << j;
  EXPECT_EQ(session_->history().size(), 1u);
  EXPECT_TRUE(session_->unsaved());
  ASSERT_EQ(run("undo\nframes 1\n").find("ERROR"), std::string::npos);
  EXPECT_EQ(session_->scene().document().to_json(), before);
  EXPECT_EQ(session_->scene().ground()->sample(10, 10), 0.0f) << "the flat generated ground is back";
  ASSERT_EQ(run("redo\n").find("ERROR"), std::string::npos);
  EXPECT_EQ(param("terrain.elevation.file"), "dem.tif");
}

TEST_F(TerrainImportGl, BakeRunsWhileFramesGoOnAndTheSceneStreamsTheFile) {
  const std::string out = run("import_terrain dem.tif bake dem.sylvaterrain\nwait_import\nframes 3\n");
  ASSERT_EQ(out.find("ERROR"), std::string::npos) << out;
  EXPECT_NE(out.find("100 %"), std::string::npos) << out;
  ASSERT_TRUE(fs::exists(dir_ / "dem.sylvaterrain"));
  EXPECT_EQ(param("terrain.baked_file"), "dem.sylvaterrain");
  EXPECT_EQ(param("terrain.elevation.file"), "dem.tif");
  EXPECT_EQ(param("terrain.center"), "256,256") << "the middle of the baked field";
  const nlohmann::json stats = session_->scene().module_stats()["terrain"];
  EXPECT_EQ(stats.value("baked_ground_matches", -1), 1) << stats.dump();
  EXPECT_EQ(stats.value("baked_file_bytes", std::uint64_t{0}), fs::file_size(dir_ / "dem.sylvaterrain")) << stats.dump();
  EXPECT_GE(stats.value("stream_resident_chunks", 0), 1) << stats.dump();
  EXPECT_EQ(session_->history().size(), 1u);
  ASSERT_EQ(run("undo\n").find("ERROR"), std::string::npos);
  EXPECT_EQ(param("terrain.baked_file"), "");
  EXPECT_EQ(param("terrain.elevation.file"), "");
}

TEST_F(TerrainImportGl, CancelledBakeLeavesNoFileAndTheSceneUnchanged) {
  const nlohmann::json before = session_->scene().document().to_json();
  const std::vector<std::string> files_before = files();
  // hold: the bake waits at its first progress report, so the cancel lands in the middle.
  const std::string out = run("import_terrain dem.tif bake out.sylvaterrain hold\nframes 2\ncancel_import\nframes 1\n");
  ASSERT_EQ(out.find("ERROR"), std::string::npos) << out;
  EXPECT_NE(out.find("cancelled"), std::string::npos) << out;
  EXPECT_EQ(files(), files_before) << "no output file and no temporary";
  EXPECT_EQ(session_->scene().document().to_json(), before);
  EXPECT_EQ(session_->history().size(), 0u);
  EXPECT_NE(run("wait_import\n").find("no import is running"), std::string::npos);
}

TEST_F(TerrainImportGl, BrokenSourcesAreErrorsNamingTheFileAndChangeNothing) {
  const nlohmann::json before = session_->scene().document().to_json();
  ASSERT_TRUE(write_file_atomic(dir_ / "broken.tif", "II*\0 this is not a TIFF").ok());
  test::GeoTiffSpec empty = hills();
  empty.nodata = -32768.0;
  std::fill(empty.values.begin(), empty.values.end(), -32768.0);
  test::write_geotiff(dir_ / "nodata.tif", empty);
  for (const std::string file : {"broken.tif", "nodata.tif", "missing.tif", "broken.obj"}) {
    if (file == "broken.obj") {
      ASSERT_TRUE(write_file_atomic(dir_ / file, "v 0 0 0\nf 1 2 3\n").ok());  // face index 3 of 1 vertex
    }
    const std::string out = run("import_terrain " + file + "\n");
    EXPECT_NE(out.find("ERROR test.sylva:1: import_terrain: "), std::string::npos) << out;
    EXPECT_NE(out.find(file), std::string::npos) << out;
    EXPECT_EQ(session_->scene().document().to_json(), before) << file;
    EXPECT_EQ(session_->history().size(), 0u) << file;
  }
  // Unsaved painting of the ground would hide the raster: refused, the stroke kept.
  const std::string painted = run("brush op=raise radius=30 strength=5\nstroke terrain.height 0,0\nimport_terrain dem.tif\n");
  EXPECT_NE(painted.find("terrain.height has unsaved painting"), std::string::npos) << painted;
  EXPECT_EQ(param("terrain.elevation.file"), "");
  EXPECT_EQ(session_->history().size(), 1u) << "only the stroke";
  EXPECT_GT(session_->scene().ground()->sample(32, 32), 0.0f) << "the stroke is still there";
  ASSERT_EQ(run("undo\n").find("ERROR"), std::string::npos);
  // Baking over the source itself is refused before anything runs.
  EXPECT_NE(run("import_terrain dem.tif bake dem.tif\n").find("name another file"), std::string::npos);
  EXPECT_EQ(session_->scene().document().to_json(), before);
}

TEST_F(TerrainImportGl, MeshBecomesTheModelTerrainSection) {
  std::string obj;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) obj += "v " + std::to_string(i * 10) + " " + std::to_string((i * j) % 3) + " " + std::to_string(j * 10) + "\n";
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const int a = j * 5 + i + 1;
      obj += "f " + std::to_string(a) + " " + std::to_string(a + 5) + " " + std::to_string(a + 6) + " " + std::to_string(a + 1) + "\n";
    }
  ASSERT_TRUE(write_file_atomic(dir_ / "cliff.obj", obj).ok());
  const std::string out = run("import_terrain cliff.obj\nframes 1\n");
  ASSERT_EQ(out.find("ERROR"), std::string::npos) << out;
  EXPECT_NE(out.find("25 vertices, 16 faces"), std::string::npos) << out;
  EXPECT_EQ(param("model_terrain.file"), "cliff.obj");
  EXPECT_GT(session_->scene().module_stats()["model_terrain"].value("mesh_triangles", 0), 0);
  EXPECT_EQ(session_->history().size(), 1u);
  ASSERT_EQ(run("undo\n").find("ERROR"), std::string::npos);
  EXPECT_FALSE(session_->scene().document().has_module("model_terrain"));
}

// Issue 15, "the editor shows it and tunes it": tau set in the editor takes effect at once.
TEST_F(TerrainImportGl, ModelTerrainTauSetInTheEditorDrawsFewerTrianglesAndUndoRestoresThem) {
  // The "triangles" of the nth "model_terrain {...}" line print_stats wrote.
  auto triangles = [](const std::string& out, std::size_t nth) {
    std::size_t line = std::string::npos;
    for (std::size_t k = 0, from = 0; k <= nth; ++k, from = line + 1) {
      line = out.find("model_terrain {", from);
      if (line == std::string::npos) return -1;
    }
    const std::size_t json = line + std::string("model_terrain ").size();
    return nlohmann::json::parse(out.substr(json, out.find('\n', json) - json)).value("triangles", -1);
  };
  const std::string out = run(std::string("load ") + SYLVA_SCENES_DIR + "/model_terrain.json\nframes 2\n"
                              "print_stats model_terrain\nset model_terrain.render.lod.max_pixel_error 8\nframes 2\n"
                              "print_stats model_terrain\nundo\nframes 2\nprint_stats model_terrain\n");
  ASSERT_EQ(out.find("ERROR"), std::string::npos) << out;
  const int at_1px = triangles(out, 0), at_8px = triangles(out, 1), undone = triangles(out, 2);
  EXPECT_GT(at_1px, 0) << out;
  EXPECT_LT(at_8px, at_1px) << out;
  EXPECT_EQ(undone, at_1px) << out;
}

}  // namespace

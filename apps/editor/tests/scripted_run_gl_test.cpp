// sylva-editor without a person: scripted runs paint, undo, save and quit, and the saved scene
// and maps are exactly what the script asked for; script errors name their line; a save killed
// at any moment leaves the previous files whole. Plus the session in-process: undo/redo of
// strokes, parameters, modules and bookmarks restore the scene bit-exactly.
#include "editor_session.hpp"
#include "script_runner.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/image.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/height_source.hpp>
#include <sylva/scene/module_registry.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <random>
#include <signal.h>
#include <spawn.h>
#include <sstream>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

extern char** environ;

#include "run_command.hpp"

namespace fs = std::filesystem;
using namespace sylva;
using namespace sylva::editor;

namespace {

using sylva::test::RunResult;

RunResult run_editor(const std::string& args) { return sylva::test::run_command(SYLVA_EDITOR_EXE, args); }

fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("sylva_editor_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write(const fs::path& file, const std::string& text) { ASSERT_TRUE(write_file_atomic(file, text).ok()); }

const char* kSmallGround = R"({"ground": {"resolution": 65, "size": 128, "height": 10, "generator": "fbm",
                                           "noise": {"frequency": 0.02}},
                               "camera": {"position": [0, 40, 90], "pitch_deg": -25}})";

scene::MapGrid generated_ground() {
  scene::HeightSourceSettings s;
  s.resolution = 65;
  s.size = 128.0f;
  s.height = 10.0f;
  s.generator = scene::HeightGenerator::kFbm;
  s.noise.frequency = 0.02f;
  return scene::make_height_grid(s, std::nullopt).value();
}

}  // namespace

TEST(EditorScript, PaintsSavesAndQuitsWithExactlyTheRequestedResult) {
  const fs::path dir = temp_dir("paint");
  write(dir / "in.json", kSmallGround);
  std::string script = R"(set sun.elevation_deg 12.5
set ground.snow_fraction 0.5
undo
brush op=raise radius=10 strength=2 falloff=constant
stroke ground.height 20,10
brush op=lower strength=7
stroke ground.height -30,-30
undo
redo
stroke ground.height 40,40
undo
bookmark saved_view
expect sun.elevation_deg 12.5
expect_unsaved yes
frames 2
screenshot shot.png 64x36
save out/result.json
expect_unsaved no
quit
print never reached
)";
  const bool grass = scene::find_module("grass") != nullptr;
  if (grass) {
    script = std::string("add_module grass\nset grass.area_min -10,-10\nset grass.area_max 10,10\nset grass.field.density 5\n") +
             "brush op=erase radius=3 strength=1 falloff=constant\nstroke grass.density 0,0\n" + script;
  }
  script = "# paint, undo, save\nload in.json\nexpect_unsaved no\n" + script;
  write(dir / "run.sylva", script);
  const RunResult run = run_editor("--headless --size 64x36 --script " + (dir / "run.sylva").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run.output.find("never reached"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "shot.png"));

  std::vector<std::string> warnings;
  auto doc = scene::SceneDocument::load(dir / "out" / "result.json", warnings);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  EXPECT_EQ(doc->sun.elevation_deg, 12.5f);
  EXPECT_EQ(doc->params().get("ground.snow_fraction").value(), "0.8") << "that change was undone";
  EXPECT_TRUE(doc->bookmarks.count("saved_view"));
  ASSERT_TRUE(doc->module("ground")->maps.count("height"));
  const fs::path map_file = doc->resolve(doc->module("ground")->maps.at("height"));
  auto saved = scene::read_map_image(map_file, 1.0f, 0.0f, {0, 0}, {1, 1});
  ASSERT_TRUE(saved.ok()) << saved.error().message;

  // Expected: the generated ground, +2 m within 10 m of (20, 10), -7 m within 10 m of (-30, -30);
  // the third stroke was undone. Bit-exact (float EXR).
  scene::MapGrid expected = generated_ground();
  for (int j = 0; j < expected.height; ++j) {
    for (int i = 0; i < expected.width; ++i) {
      const glm::dvec2 p = expected.world(i, j);
      if (glm::distance(p, glm::dvec2(20, 10)) < 10.0) expected.at(i, j) += 2.0f;
      if (glm::distance(p, glm::dvec2(-30, -30)) < 10.0) expected.at(i, j) -= 7.0f;
    }
  }
  ASSERT_EQ(saved->values.size(), expected.values.size());
  int differing = 0;
  for (std::size_t k = 0; k < expected.values.size(); ++k) differing += saved->values[k] != expected.values[k];
  EXPECT_EQ(differing, 0);

  if (grass) {
    ASSERT_TRUE(doc->module("grass"));
    EXPECT_EQ(doc->params().get("grass.field.density").value(), "5");
    const fs::path density_file = doc->resolve(doc->module("grass")->maps.at("density"));
    auto density = scene::read_map_image(density_file, 1.0f, 0.0f, {0, 0}, {1, 1});
    ASSERT_TRUE(density.ok()) << density.error().message;
    // 128 texels over 20 m: texel centres within 3 m of the origin are 0, the rest 1.
    const double texel = 20.0 / density->width;
    for (int j = 0; j < density->height; ++j) {
      for (int i = 0; i < density->width; ++i) {
        const glm::dvec2 c(-10.0 + (i + 0.5) * texel, -10.0 + (j + 0.5) * texel);
        ASSERT_EQ(density->at(i, j), glm::length(c) < 3.0 ? 0.0f : 1.0f) << i << "," << j;
      }
    }
  }
}

TEST(EditorScript, ErrorsNameTheScriptLine) {
  const fs::path dir = temp_dir("errors");
  write(dir / "in.json", kSmallGround);
  write(dir / "bad_run.sylva", "load in.json\nbrush radius=5\n\nstroke terrain.height 1,1\nquit\n");
  const RunResult bad_map = run_editor("--headless --script " + (dir / "bad_run.sylva").string());
  EXPECT_EQ(bad_map.exit_code, 1);
  EXPECT_NE(bad_map.output.find("bad_run.sylva:4: stroke: no map \"terrain.height\""), std::string::npos) << bad_map.output;
  EXPECT_NE(bad_map.output.find("ground.height"), std::string::npos) << "lists the maps there are";

  write(dir / "bad_parse.sylva", "load in.json\nfly away\nundo twice\n");
  const RunResult bad_parse = run_editor("--headless --script " + (dir / "bad_parse.sylva").string());
  EXPECT_EQ(bad_parse.exit_code, 2);
  EXPECT_NE(bad_parse.output.find("bad_parse.sylva:2: unknown command \"fly\""), std::string::npos) << bad_parse.output;
  EXPECT_NE(bad_parse.output.find("bad_parse.sylva:3: undo"), std::string::npos) << bad_parse.output;

  write(dir / "bad_value.sylva", "load in.json\nset ground.height -5\n");
  const RunResult bad_value = run_editor("--headless --script " + (dir / "bad_value.sylva").string());
  EXPECT_EQ(bad_value.exit_code, 1);
  EXPECT_NE(bad_value.output.find("bad_value.sylva:2: set: ground.height"), std::string::npos) << bad_value.output;

  write(dir / "no_file.sylva", "save\n");
  const RunResult no_file = run_editor("--headless --script " + (dir / "no_file.sylva").string());
  EXPECT_EQ(no_file.exit_code, 1);
  EXPECT_NE(no_file.output.find("no_file.sylva:1: save: the scene has no file yet"), std::string::npos) << no_file.output;

  // Screenshot paths are checked before the first command: the missing scene on line 1 is
  // never loaded, the unwritable screenshot of line 2 is what the run reports (issue 17).
  write(dir / "late_output.sylva", "load missing.json\nscreenshot nodir/x.png\nquit\n");
  const RunResult late_output = run_editor("--headless --script " + (dir / "late_output.sylva").string());
  EXPECT_EQ(late_output.exit_code, 1);
  EXPECT_NE(late_output.output.find("late_output.sylva:2: screenshot: " + (dir / "nodir/x.png").string() +
                                    ": the folder " + (dir / "nodir").string() + " does not exist"),
            std::string::npos)
      << late_output.output;
  EXPECT_EQ(late_output.output.find("missing.json"), std::string::npos) << late_output.output;

  // A script that is not there is a bad argument, like a malformed one.
  const RunResult missing_script = run_editor("--headless --script " + (dir / "nothere.sylva").string());
  EXPECT_EQ(missing_script.exit_code, 2);
  EXPECT_NE(missing_script.output.find((dir / "nothere.sylva").string()), std::string::npos) << missing_script.output;

  const RunResult no_script = run_editor("--headless");
  EXPECT_EQ(no_script.exit_code, 2);
  EXPECT_EQ(run_editor("--bogus").exit_code, 2);
}

// Invariant: killing the editor at any moment of a save leaves the scene file and its map file
// whole (each is the old or the new version, never a torn one).
TEST(EditorScript, AnInterruptedSaveNeverCorruptsThePreviousFile) {
  const fs::path dir = temp_dir("interrupt");
  write(dir / "in.json", R"({"ground": {"resolution": 513, "size": 512, "height": 10}})");
  std::string script = "load in.json\nbrush op=raise radius=30 strength=0.5\nstroke ground.height 0,0\nsave work.json\n";
  for (int k = 0; k < 400; ++k) script += "stroke ground.height " + std::to_string(k % 40 * 5 - 100) + ",0\nsave\n";
  write(dir / "loop.sylva", script);
  std::mt19937 rng(7);
  int killed_during_run = 0;
  for (int attempt = 0; attempt < 6; ++attempt) {
    const std::string exe = SYLVA_EDITOR_EXE;
    const std::string script_path = (dir / "loop.sylva").string();
    std::vector<char*> argv = {const_cast<char*>(exe.c_str()), const_cast<char*>("--headless"), const_cast<char*>("--script"),
                               const_cast<char*>(script_path.c_str()), nullptr};
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid = 0;
    ASSERT_EQ(posix_spawn(&pid, exe.c_str(), &actions, nullptr, argv.data(), environ), 0);
    posix_spawn_file_actions_destroy(&actions);
    // Wait until the first save exists (however long a loaded machine takes to start the editor:
    // a time limit here killed it before its first save), then kill at a random moment of the
    // save loop.
    int status = 0;
    bool ended = false;
    while (!fs::exists(dir / "work.json") && !(ended = ::waitpid(pid, &status, WNOHANG) == pid)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (!ended) {
      std::this_thread::sleep_for(std::chrono::milliseconds(std::uniform_int_distribution<int>(30, 900)(rng)));
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
    }
    killed_during_run += WIFSIGNALED(status) ? 1 : 0;

    std::vector<std::string> warnings;
    auto doc = scene::SceneDocument::load(dir / "work.json", warnings);
    ASSERT_TRUE(doc.ok()) << "attempt " << attempt << ": " << doc.error().message;
    ASSERT_TRUE(doc->module("ground")->maps.count("height")) << "attempt " << attempt;
    auto map = scene::read_map_image(doc->resolve(doc->module("ground")->maps.at("height")), 1.0f, 0.0f, {0, 0}, {1, 1});
    ASSERT_TRUE(map.ok()) << "attempt " << attempt << ": " << map.error().message;
    EXPECT_EQ(map->width, 513);
    fs::remove(dir / "work.json");
  }
  EXPECT_GE(killed_during_run, 4) << "the kills must land while the editor is saving";
}

using EditorSessionGl = render::GlTest;

TEST_F(EditorSessionGl, UndoRestoresTheSceneBitExactly) {
  auto session = EditorSession::create({64, 36});
  ASSERT_TRUE(session.ok()) << session.error().message;
  EditorSession& s = **session;
  const fs::path dir = temp_dir("session");
  write(dir / "in.json", kSmallGround);
  ASSERT_TRUE(s.load(dir / "in.json").ok());
  EXPECT_FALSE(s.unsaved());
  const std::vector<float> original = s.scene().map("ground.height")->grid.values;
  const HeightField before_field = *s.scene().ground();

  s.brush().op = BrushOp::kNoise;
  s.brush().strength = 3.0f;
  ASSERT_TRUE(s.stroke("ground.height", {{-40, -40}, {0, 10}, {35, 20}}).ok());
  s.brush().op = BrushOp::kSmooth;
  s.brush().strength = 1.0f;
  ASSERT_TRUE(s.stroke("ground.height", {{-20, 0}, {20, 0}}).ok());
  EXPECT_TRUE(s.unsaved());
  EXPECT_NE(s.scene().map("ground.height")->grid.values, original);
  ASSERT_TRUE(s.undo().ok());
  ASSERT_TRUE(s.undo().ok());
  const std::vector<float>& restored = s.scene().map("ground.height")->grid.values;
  ASSERT_EQ(restored.size(), original.size());
  EXPECT_EQ(std::memcmp(restored.data(), original.data(), original.size() * sizeof(float)), 0);
  EXPECT_EQ(std::memcmp(s.scene().ground()->samples().data(), before_field.samples().data(), original.size() * sizeof(float)), 0)
      << "the ground height field follows the map";
  EXPECT_FALSE(s.unsaved());

  // Slider drags merge into one undo entry.
  ASSERT_TRUE(s.set_param("sun.intensity", "2.5").ok());
  ASSERT_TRUE(s.set_param("sun.intensity", "2.0", true).ok());
  ASSERT_TRUE(s.set_param("sun.intensity", "1.5", true).ok());
  EXPECT_EQ(s.history().position(), 1u);
  ASSERT_TRUE(s.undo().ok());
  EXPECT_EQ(s.scene().get_param("sun.intensity").value(), "3");

  // Modules: add, paint its map, remove, undo both: the module and its painted map come back.
  if (scene::find_module("grass")) {
    ASSERT_TRUE(s.add_module("grass").ok());
    ASSERT_TRUE(s.set_param("grass.field.density", "3").ok());
    EXPECT_EQ(scene::live_module_instances("grass"), 1);
    s.brush().op = BrushOp::kErase;
    ASSERT_TRUE(s.stroke("grass.density", {{0, 0}}).ok());
    const std::vector<float> painted = s.scene().map("grass.density")->grid.values;
    ASSERT_TRUE(s.remove_module("grass").ok());
    EXPECT_EQ(scene::live_module_instances("grass"), 0);
    ASSERT_TRUE(s.undo().ok());
    EXPECT_EQ(scene::live_module_instances("grass"), 1);
    EXPECT_EQ(s.scene().map("grass.density")->grid.values, painted);
    EXPECT_EQ(s.scene().get_param("grass.field.density").value(), "3");
    ASSERT_TRUE(s.undo().ok());
    ASSERT_TRUE(s.undo().ok());
    ASSERT_TRUE(s.undo().ok());
    EXPECT_FALSE(s.scene().document().has_module("grass"));
    EXPECT_EQ(scene::live_module_instances("grass"), 0);
  }
  ASSERT_TRUE(s.add_bookmark("here").ok());
  ASSERT_TRUE(s.undo().ok());
  EXPECT_EQ(s.scene().document().bookmarks.count("here"), 0u);
  ASSERT_TRUE(s.redo().ok());
  EXPECT_EQ(s.scene().document().bookmarks.count("here"), 1u);

  // Picking: the ray through the image centre hits the ground where the camera looks.
  s.set_camera({{0.0, 60.0, 0.0}, 0.0f, -89.0f, 60.0f, scene::HeightMode::kAbsolute});
  auto hit = s.pick_ground({32.0f, 18.0f});
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->y, s.scene().ground_height(hit->x, hit->z), 1e-3);
  EXPECT_LT(glm::length(glm::dvec2(hit->x, hit->z)), 2.0);
}

// The saves that lost work: "save as" in the same folder rewrote the original's maps, and a
// read-only scene file was silently replaced. Through the shipped editor.
TEST(EditorScript, SaveAsKeepsTheOriginalAndReadOnlyScenesAreRefused) {
  const fs::path dir = temp_dir("save_as");
  write(dir / "in.json", kSmallGround);
  const std::string paint = "brush op=raise radius=10 strength=2 falloff=constant\nstroke ground.height 0,0\n";
  write(dir / "first.sylva", "load in.json\n" + paint + "save a.json\nquit\n");
  RunResult run = run_editor("--headless --size 32x32 --script " + (dir / "first.sylva").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string a_scene = read_file(dir / "a.json").value_or("");
  const std::string a_map = read_file(dir / "a_maps" / "ground_height.exr").value_or("");
  ASSERT_FALSE(a_map.empty());

  write(dir / "second.sylva", "load a.json\n" + paint + "save b.json\nquit\n");
  run = run_editor("--headless --size 32x32 --script " + (dir / "second.sylva").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(read_file(dir / "a_maps" / "ground_height.exr").value_or(""), a_map) << "save as changed the original's map";
  EXPECT_EQ(read_file(dir / "a.json").value_or(""), a_scene);
  std::vector<std::string> warnings;
  auto b = scene::SceneDocument::load(dir / "b.json", warnings);
  ASSERT_TRUE(b.ok()) << b.error().message;
  EXPECT_EQ(b->module("ground")->maps.at("height"), "b_maps/ground_height.exr");

  fs::permissions(dir / "a.json", fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  write(dir / "third.sylva", "load a.json\n" + paint + "save\nquit\n");
  run = run_editor("--headless --size 32x32 --script " + (dir / "third.sylva").string());
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("read-only"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("a.json"), std::string::npos) << run.output;
  EXPECT_EQ(read_file(dir / "a.json").value_or(""), a_scene);
  EXPECT_EQ(read_file(dir / "a_maps" / "ground_height.exr").value_or(""), a_map);
  EXPECT_EQ(fs::status(dir / "a.json").permissions() & fs::perms::owner_write, fs::perms::none);
  fs::permissions(dir / "a.json", fs::perms::owner_all);
}

// File > Export tree... as a script command (issue #16, tree export): the forest's first species
// file, exported with the scene's texture size and slice resolution; the second export replaces
// the first; a scene without a forest is an error naming the script line.
TEST(EditorScript, ExportsTheForestsFirstSpecies) {
  if (scene::find_module("vegetation") == nullptr) GTEST_SKIP() << "built without the vegetation module";
  const fs::path dir = temp_dir("export_tree");
  const std::string species = (fs::path(SYLVA_SCENES_DIR) / "species" / "seed_example.json").string();
  write(dir / "in.json", R"({"vegetation": {"area_min": [-4, -4], "area_max": [4, 4], "trees_per_hectare": 50,
                             "leaf_texture_size": 32, "forest": {"lod": {"slice_resolution": 32}},
                             "species_files": {"0": {"file": ")" + species + R"("}}}})");
  write(dir / "run.sylva", "load in.json\nexport_tree out\nexport_tree out\nquit\n");
  const RunResult run = run_editor("--headless --size 64x36 --script " + (dir / "run.sylva").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("exported 'seed example' to " + (dir / "out").string()), std::string::npos) << run.output;

  const nlohmann::json gltf = nlohmann::json::parse(read_file(dir / "out" / "seed_example.gltf").value_or("{}"));
  ASSERT_EQ(gltf["meshes"].size(), 2u);
  std::size_t triangles = 0;
  for (const auto& m : gltf["meshes"])
    triangles += gltf["accessors"][m["primitives"][0]["indices"].get<std::size_t>()]["count"].get<std::size_t>() / 3;
  EXPECT_EQ(triangles, 544u);  // the seed's example: 540 bark + 4 leaf triangles (sylva-bake tree gives the same)
  auto leaf = read_image(dir / "out" / "seed_example_leaf_color.png");
  ASSERT_TRUE(leaf.ok());
  EXPECT_EQ(leaf->width(), 32);  // vegetation.leaf_texture_size
  const nlohmann::json slices =
      nlohmann::json::parse(read_file(dir / "out" / "seed_example_slices" / "slices.json").value_or("{}"));
  ASSERT_EQ(slices["levels"].size(), 2u);
  EXPECT_EQ(slices["levels"][0]["resolution"], 32);  // vegetation.forest.lod.slice_resolution
  EXPECT_TRUE(fs::exists(dir / "out" / "seed_example.objt"));

  write(dir / "in_bare.json", kSmallGround);
  write(dir / "bare.sylva", "load in_bare.json\nexport_tree out2\n");
  const RunResult bare = run_editor("--headless --script " + (dir / "bare.sylva").string());
  EXPECT_EQ(bare.exit_code, 1);
  EXPECT_NE(bare.output.find("bare.sylva:2: export_tree: the scene has no vegetation section"), std::string::npos)
      << bare.output;
  EXPECT_FALSE(fs::exists(dir / "out2"));
}

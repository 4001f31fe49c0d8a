// The editor's file watcher (issue #16, "a species change picked up without rebuilding the
// program"): a scripted sylva-editor run rewrites a voxel species table's grammar, then breaks
// it, and rewrites a tree species file while the scene runs; each change is reloaded in place
// (the world's plant blocks, the forest's species), a broken grammar's error reaches the
// messages with its line:column and the scene keeps running. Plus the watcher on its own, and
// the plant preview (`preview`): its block counts follow the derivation slider and a broken
// grammar shows its line:column.
#include "source_watcher.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/scene/module_registry.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <sstream>
#include <unistd.h>

#include "run_command.hpp"

namespace fs = std::filesystem;
using namespace sylva;
using namespace sylva::editor;

namespace {

fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("sylva_editor_reload_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  ASSERT_TRUE(write_file_atomic(file, text).ok());
}

// The lines "MODULE {json}" a print_stats wrote, in order.
std::vector<nlohmann::json> printed_stats(const std::string& output, const std::string& module) {
  std::vector<nlohmann::json> out;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(module + " {", 0) == 0) out.push_back(nlohmann::json::parse(line.substr(module.size() + 1)));
  }
  return out;
}

// One species growing everywhere: a column of glowstone, U doubled (tripled) per derivation.
constexpr const char* kPillar2 = "0 0 1\nU\nU > UU\n";
constexpr const char* kPillar3 = "0 0 1\nU\nU > UUU\n";
constexpr const char* kBroken = "0 0 1\nU\nU UU\n";  // line 3: no '>'
constexpr const char* kPillarTable = R"({"species": [{"name": "pillar", "grammar": "pillar.lsys", "derivations": [3, 3],
    "size": [1, 1], "blocks": {"0": "glowstone"}, "biomes": {"jungle": {"spacing": 5, "chance": 1},
    "savanna": {"spacing": 5, "chance": 1}, "plains": {"spacing": 5, "chance": 1}, "shrubland": {"spacing": 5, "chance": 1},
    "birch_forest": {"spacing": 5, "chance": 1}, "oak_forest": {"spacing": 5, "chance": 1}}}]})";

TEST(SourceWatcher, ListsTheNamedFilesAndReportsChanges) {
  if (!scene::find_module("voxel")) GTEST_SKIP() << "voxel is built out";
  const fs::path dir = temp_dir("watcher");
  write(dir / "species/pillar.lsys", kPillar2);
  write(dir / "species/pillars.json", kPillarTable);
  write(dir / "scene.json", R"({"voxel": {"radius_chunks": 1, "flora": {"species_file": "species/pillars.json"}}})");
  std::vector<std::string> warnings;
  auto doc = scene::SceneDocument::load(dir / "scene.json", warnings);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  const std::vector<WatchedSource> sources = scene_sources(*doc);
  const std::vector<WatchedSource> want = {{"voxel.flora.species_file", dir / "species/pillars.json"},
                                           {"voxel.flora.species_file", dir / "species/pillar.lsys"}};
  EXPECT_EQ(sources, want);

  SourceWatcher watcher;
  watcher.watch(sources);
  EXPECT_TRUE(watcher.poll().empty());
  write(dir / "species/pillar.lsys", kPillar3);
  EXPECT_EQ(watcher.poll(), std::vector<WatchedSource>{want[1]});
  EXPECT_TRUE(watcher.poll().empty()) << "reported once";
  fs::remove(dir / "species/pillars.json");
  EXPECT_EQ(watcher.poll(), std::vector<WatchedSource>{want[0]}) << "a removed file is a change";
}

TEST(SourceReload, GrammarAndTreeSpeciesChangesArePickedUpWhileTheSceneRuns) {
  if (!scene::find_module("voxel") || !scene::find_module("vegetation")) GTEST_SKIP() << "voxel or vegetation is built out";
  const fs::path dir = temp_dir("run");
  write(dir / "species/pillar.lsys", kPillar2);
  write(dir / "species/pillar3.lsys", kPillar3);
  write(dir / "species/broken.lsys", kBroken);
  write(dir / "species/pillars.json", kPillarTable);
  write(dir / "voxel.json", R"({"camera": {"position": [16, 95, 16], "pitch_deg": -89.9},
      "render": {"msaa_samples": 1, "shadows": {"enabled": false}},
      "voxel": {"radius_chunks": 1, "threads": 2, "worldgen": {"seed": 3, "variants_per_species": 2},
                "flora": {"species_file": "species/pillars.json"}}})");
  write(dir / "trees/alpha.json", R"({"name": "alpha", "model": {"preset": "conifer", "seed": 5}})");
  write(dir / "trees/beta.json", R"({"name": "beta tree", "model": {"preset": "conifer", "seed": 5}})");
  write(dir / "trees/species.json", R"({"name": "alpha", "model": {"preset": "conifer", "seed": 5}})");
  write(dir / "forest.json", R"({"camera": {"position": [0, 5, 80]}, "render": {"msaa_samples": 1, "shadows": {"enabled": false}},
      "ground": {"size": 200, "resolution": 33, "generator": "flat"},
      "vegetation": {"area_min": [-1, -1], "area_max": [1, 1], "layout": "grid", "trees_per_hectare": 1,
                     "leaf_texture_size": 32, "forest": {"lod": {"enabled": false}},
                     "species_files": {"0": {"file": "trees/species.json"}}}})");
  write(dir / "run.sylva", R"(load voxel.json
frames 1
print_stats voxel
copy_file species/pillar3.lsys species/pillar.lsys
wait_reload species/pillar.lsys 2000
print_stats voxel
copy_file species/broken.lsys species/pillar.lsys
wait_reload species/pillar.lsys 2000
frames 2
print_stats voxel
load forest.json
frames 1
print_stats vegetation
copy_file trees/beta.json trees/species.json
wait_reload trees/species.json 2000
print_stats vegetation
quit
)");
  const sylva::test::RunResult run =
      sylva::test::run_command(SYLVA_EDITOR_EXE, "--headless --size 64x64 --script " + (dir / "run.sylva").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;

  const std::vector<nlohmann::json> voxel = printed_stats(run.output, "voxel");
  ASSERT_EQ(voxel.size(), 3u) << run.output;
  const int plants = voxel[0]["plants_per_species"].value("pillar", 0);
  ASSERT_GT(plants, 0) << voxel[0].dump();
  EXPECT_EQ(voxel[0]["plant_blocks"], nlohmann::json({{"glowstone", 8 * plants}})) << "U > UU, 3 derivations: 8 blocks a plant";
  EXPECT_EQ(voxel[1]["plants_per_species"].value("pillar", 0), plants) << voxel[1].dump();
  EXPECT_EQ(voxel[1]["plant_blocks"], nlohmann::json({{"glowstone", 27 * plants}})) << "U > UUU: 27 blocks a plant";
  EXPECT_NE(run.output.find("sylva-editor: reloaded " + (dir / "species/pillar.lsys").string() + " (voxel.flora.species_file)"),
            std::string::npos)
      << run.output;
  // The broken grammar: its error with line:column in the messages, the species left out, the
  // scene still running (the frames and the stats after it).
  EXPECT_NE(run.output.find("sylva-editor: warning: voxel.flora.species_file: "), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("pillar.lsys:3:1: expected a rule"), std::string::npos) << run.output;
  EXPECT_FALSE(voxel[2]["plants_per_species"].contains("pillar")) << voxel[2].dump();

  const std::vector<nlohmann::json> forest = printed_stats(run.output, "vegetation");
  ASSERT_EQ(forest.size(), 2u) << run.output;
  EXPECT_EQ(forest[0]["trees_per_species"], nlohmann::json({{"alpha", 1}})) << forest[0].dump();
  EXPECT_EQ(forest[1]["trees_per_species"], nlohmann::json({{"beta tree", 1}})) << forest[1].dump();
  EXPECT_NE(run.output.find("sylva-editor: reloaded " + (dir / "trees/species.json").string() + " (vegetation.species_files.0.file)"),
            std::string::npos)
      << run.output;
  if (::testing::Test::HasFailure() == false) fs::remove_all(dir.parent_path());
}

// The lines the `preview` command wrote, without the "preview " prefix.
std::vector<std::string> previews(const std::string& output) {
  std::vector<std::string> out;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("preview ", 0) == 0) out.push_back(line.substr(8));
  }
  return out;
}

TEST(PlantPreview, CountsFollowTheDerivationsAndABrokenGrammarShowsItsLineAndColumn) {
  if (!scene::find_module("voxel")) GTEST_SKIP() << "voxel is built out";
  const fs::path dir = temp_dir("preview");
  write(dir / "species/pillar.lsys", kPillar2);
  write(dir / "species/pillar3.lsys", kPillar3);
  write(dir / "species/broken.lsys", kBroken);
  write(dir / "species/pillars.json", kPillarTable);
  write(dir / "scene.json", R"({"voxel": {"radius_chunks": 1, "threads": 2, "flora": {"species_file": "species/pillars.json"}}})");
  write(dir / "run.sylva", R"(load scene.json
preview species=pillar derivations=2 seed=7
preview derivations=3
preview derivations=5 angle_variation=0.5
preview species=species/pillar3.lsys derivations=2
preview species=species/broken.lsys
copy_file species/broken.lsys species/pillar.lsys
preview species=pillar derivations=3
quit
)");
  const sylva::test::RunResult run =
      sylva::test::run_command(SYLVA_EDITOR_EXE, "--headless --size 64x64 --script " + (dir / "run.sylva").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::vector<std::string> p = previews(run.output);
  ASSERT_EQ(p.size(), 6u) << run.output;
  // U > UU from one U: 2^n blocks and symbols after n derivations.
  EXPECT_EQ(p[0], "pillar (species/pillars.json): 4 blocks (glowstone 4), 4 symbols, 2 derivations");
  EXPECT_EQ(p[1], "pillar (species/pillars.json): 8 blocks (glowstone 8), 8 symbols, 3 derivations");
  EXPECT_EQ(p[2], "pillar (species/pillars.json): 32 blocks (glowstone 32), 32 symbols, 5 derivations");
  EXPECT_EQ(p[3], "species/pillar3.lsys: 9 blocks (output 0 9), 9 symbols, 2 derivations") << "a grammar file: U > UUU";
  EXPECT_EQ(p[4].rfind("species/broken.lsys: error: " + (dir / "species/broken.lsys").string() + ":3:1: expected a rule", 0), 0u)
      << p[4];
  // The table's species whose grammar broke: the table's error for it, with the grammar's line:column.
  EXPECT_EQ(p[5].rfind("pillar (species/pillars.json): error: ", 0), 0u) << p[5];
  EXPECT_NE(p[5].find("species[0].grammar: pillar.lsys:3:1: expected a rule"), std::string::npos) << p[5];
  fs::remove_all(dir);
}

}  // namespace

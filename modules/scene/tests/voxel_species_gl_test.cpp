// A voxel world's plants from the user's files (issue #16, seed 004 §4.5-§4.7): a scene file names
// a species table (`voxel.flora.species_file`, relative to the scene) whose species name .lsys
// grammars; written while the program runs, they change the plants of the generated world
// (counted per species and per block from the world's plants, and seen on pixels). Bad files
// leave the scene open with a warning naming the file and the JSON path or the grammar's
// file:line:column; a grammar that would explode is refused before it is derived.
#include <sylva/core/atomic_file.hpp>
#include <sylva/core/image.hpp>
#include <sylva/core/log.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene.hpp>

#include "scene_test_files.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include <unistd.h>

using namespace sylva;
using namespace sylva::scene;
namespace fs = std::filesystem;

namespace {

// One species growing everywhere: a column of glowstone doubled per derivation (3 -> 8 blocks).
constexpr const char* kPillar = "# a pillar: U doubles every derivation\n0 0 1\nU\nU > UU\n";
std::string pillar_species(int derivations, const std::string& blocks = R"({"0": "glowstone"})") {
  return fmt::format(R"({{"species": [{{"name": "pillar", "grammar": "pillar.lsys", "derivations": [{0}, {0}], "size": [1, 1],
      "blocks": {1}, "biomes": {{"jungle": {{"spacing": 5, "chance": 1}}, "savanna": {{"spacing": 5, "chance": 1}},
      "plains": {{"spacing": 5, "chance": 1}}, "shrubland": {{"spacing": 5, "chance": 1}},
      "birch_forest": {{"spacing": 5, "chance": 1}}, "oak_forest": {{"spacing": 5, "chance": 1}}}}}}]}})",
                     derivations, blocks);
}

class VoxelSpeciesGl : public render::GlTest {
 protected:
  void SetUp() override {
    render::GlTest::SetUp();
    if (!find_module("voxel")) GTEST_SKIP() << "voxel is built out";
    dir_ = fs::temp_directory_path() /
           fmt::format("sylva_voxel_species_gl_{}_{}", ::getpid(), ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "species");
    fs::create_directories(dir_ / "blocks");
    write("species/pillar.lsys", kPillar);
    set_log_sink([this](LogLevel level, std::string_view message) {
      if (level == LogLevel::kWarn) logged_ += std::string(message) + "\n";
    });
  }
  void TearDown() override {
    set_log_sink(nullptr);
    fs::remove_all(dir_);
    render::GlTest::TearDown();
  }

  void write(const std::string& name, const std::string& text) { ASSERT_TRUE(write_file_atomic(dir_ / name, text).ok()); }

  // scene.json with a 3 x 3 column voxel world (seed 3), `flora` and `blocks`, opened from the file.
  std::unique_ptr<Scene> open(const std::string& flora, int variants = 2, const std::string& blocks = "{}") {
    const std::string text = fmt::format(R"({{"camera": {{"position": [16, 95, 16], "yaw_deg": 0, "pitch_deg": -89.9, "fov_deg": 60}},
        "render": {{"msaa_samples": 1, "shadows": {{"enabled": false}}}},
        "voxel": {{"radius_chunks": 1, "threads": 2, "worldgen": {{"seed": 3, "variants_per_species": {}}}, "flora": {},
                   "blocks": {}}}}})",
                                         variants, flora, blocks);
    EXPECT_TRUE(write_file_atomic(dir_ / "scene.json", text).ok());
    return sylva::scene::testing::open_scene_file(dir_ / "scene.json");
  }

  static nlohmann::json stats(Scene& scene) { return scene.module_stats()["voxel"]; }

  // Glowstone pixels looking straight down on the world: emissive, it is drawn near white
  // (0.86, 0.92, 0.95 measured) where grass, leaves, logs and dry grass have a channel below
  // 0.8; counted in the middle 100 x 100 pixels, inside the fade into the sky at the edge.
  static int glow_pixels(Scene& scene) {
    return count_pixels(scene, [](float r, float g, float b) { return std::min({r, g, b}) > 0.8f; });
  }
  // Pixels of a pure red image texture, lit: red well above green and blue.
  static int red_pixels(Scene& scene) {
    return count_pixels(scene, [](float r, float g, float b) { return r > 0.25f && g < 0.3f * r && b < 0.3f * r; });
  }
  template <class Pick>
  static int count_pixels(Scene& scene, Pick pick) {
    const glm::ivec2 size(160, 160);
    auto fb = render::Framebuffer::create({.width = size.x, .height = size.y}).value();
    render::FrameProfiler profiler;
    const render::Camera camera = scene.make_camera(scene.document().camera, size);
    scene.update(camera, 1.0, 0.0f, size);
    scene.render(fb, profiler);
    const Image img = render::read_color(fb).value();
    int n = 0;
    for (int y = 30; y < 130; ++y)
      for (int x = 30; x < 130; ++x) {
        n += pick(img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2)) ? 1 : 0;
      }
    return n;
  }

  fs::path dir_;
  std::string logged_;
};

TEST_F(VoxelSpeciesGl, AUserGrammarChangesThePlants) {
  auto shipped = open(R"({"species_file": ""})");
  ASSERT_TRUE(shipped);
  const nlohmann::json before = stats(*shipped);
  EXPECT_EQ(before["species_table"], "species.json");
  EXPECT_FALSE(before["plants_per_species"].empty()) << before.dump();
  EXPECT_FALSE(before["plants_per_species"].contains("pillar"));
  EXPECT_FALSE(before["plant_blocks"].contains("glowstone")) << before.dump();
  const int glow_before = glow_pixels(*shipped);
  shipped.reset();

  write("species/pillars.json", pillar_species(3));
  auto scene = open(R"({"species_file": "species/pillars.json"})");
  ASSERT_TRUE(scene);
  const nlohmann::json s = stats(*scene);
  EXPECT_EQ(s["species_table"], (dir_ / "species/pillars.json").string());
  ASSERT_EQ(s["plants_per_species"].size(), 1u) << s.dump();
  const int plants = s["plants_per_species"]["pillar"].get<int>();
  EXPECT_GT(plants, 50) << "one pillar per 5 x 5 blocks of a 96 x 96 area (snow and sand aside)";
  EXPECT_EQ(s["plant_blocks"], nlohmann::json({{"glowstone", 8 * plants}})) << "3 derivations of U > UU: 8 blocks a plant";
  const int glow = glow_pixels(*scene);
  EXPECT_GT(glow, 20 * glow_before + 200) << "before " << glow_before;

  // Another grammar depth, picked up by the running program through the scene's parameter.
  write("species/taller.json", pillar_species(4));
  ASSERT_TRUE(scene->set_param("voxel.flora.species_file", "species/taller.json").ok());
  const nlohmann::json taller = stats(*scene);
  EXPECT_EQ(taller["plants_per_species"]["pillar"].get<int>(), plants) << "same places: same species index, biomes and grid";
  EXPECT_EQ(taller["plant_blocks"], nlohmann::json({{"glowstone", 16 * plants}}));
  EXPECT_TRUE(logged_.empty()) << logged_;
  std::printf("plants %d, glow pixels shipped %d, pillars %d\n", plants, glow_before, glow);
}

TEST_F(VoxelSpeciesGl, AGrammarErrorNamesTheFileLineAndColumn) {
  write("species/pillar.lsys", "0 0 1\nU\nU UU\n");
  write("species/pillars.json", pillar_species(3));
  auto scene = open(R"({"species_file": "species/pillars.json"})");
  ASSERT_TRUE(scene) << "a bad species does not fail the scene";
  EXPECT_NE(logged_.find(fmt::format("voxel.flora.species_file: {}: species[0].grammar: pillar.lsys:3:1: expected a rule "
                                     "'letter > production' or a new header 'yaw_angle pitch_angle shrink_ratio'; the species is left out",
                                     (dir_ / "species/pillars.json").string())),
            std::string::npos)
      << logged_;
  EXPECT_TRUE(stats(*scene)["plants_per_species"].empty()) << stats(*scene).dump();
}

TEST_F(VoxelSpeciesGl, ABadBlockNameNamesTheJsonPathAndLeavesOnlyThatSpeciesOut) {
  // Two species: the first lays "glass" on output 1 (no such block), the second is fine.
  nlohmann::json table = nlohmann::json::parse(pillar_species(3, R"({"0": "glowstone", "1": "glass"})"));
  nlohmann::json good = table["species"][0];
  good["name"] = "lamp";
  good["blocks"] = {{"0", "lantern"}};
  table["species"].push_back(good);
  write("species/pillars.json", table.dump());
  auto scene = open(R"({"species_file": "species/pillars.json"})");
  ASSERT_TRUE(scene);
  EXPECT_NE(logged_.find(fmt::format("voxel.flora.species_file: {}: species[0].blocks.1: no block 'glass' in the palette; "
                                     "the species is left out",
                                     (dir_ / "species/pillars.json").string())),
            std::string::npos)
      << logged_;
  const nlohmann::json s = stats(*scene);
  ASSERT_EQ(s["plants_per_species"].size(), 1u) << s.dump();
  const int lamps = s["plants_per_species"]["lamp"].get<int>();
  EXPECT_GT(lamps, 50);
  EXPECT_EQ(s["plant_blocks"], nlohmann::json({{"lantern", 8 * lamps}}));
}

TEST_F(VoxelSpeciesGl, AnExplodingGrammarIsRefusedBeforeItIsDerived) {
  write("species/boom.lsys", "0 0 1\nUU\nU > UUUU\n");
  nlohmann::json table = nlohmann::json::parse(pillar_species(20));
  table["species"][0]["grammar"] = "boom.lsys";
  write("species/boom.json", table.dump());
  auto scene = open(R"({"species_file": "species/boom.json"})");
  ASSERT_TRUE(scene);
  EXPECT_NE(logged_.find("species[0].derivations: boom.lsys:1 may grow to 2.2e+12 symbols in 20 derivations, above the limit of "
                         "2097152; lower the most derivations; the species is left out"),
            std::string::npos)
      << logged_;
  EXPECT_TRUE(stats(*scene)["plants_per_species"].empty());

  // 131 072 blocks a plant pass alone, but not 256 cached variants of it: the shipped species.
  logged_.clear();
  table["species"][0]["derivations"] = {8, 8};
  write("species/boom.json", table.dump());
  scene = open(R"({"species_file": "species/boom.json"})", 256);
  ASSERT_TRUE(scene);
  EXPECT_NE(logged_.find("the plant cache may hold 3.36e+07 blocks (256 variants per species), above the limit of 16777216"),
            std::string::npos)
      << logged_;
  EXPECT_NE(logged_.find("; the shipped species are used"), std::string::npos) << logged_;
  EXPECT_EQ(stats(*scene)["species_table"], "species.json");
}

TEST_F(VoxelSpeciesGl, AMissingOrBrokenFileGivesTheShippedSpecies) {
  auto scene = open(R"({"species_file": "species/none.json"})");
  ASSERT_TRUE(scene);
  EXPECT_NE(logged_.find(fmt::format("voxel.flora.species_file: {}: no such file; the shipped species are used",
                                     (dir_ / "species/none.json").string())),
            std::string::npos)
      << logged_;
  EXPECT_EQ(stats(*scene)["species_table"], "species.json");
  EXPECT_FALSE(stats(*scene)["plants_per_species"].empty());
  logged_.clear();
  write("species/cut.json", R"({"species": [{"name": "pillar", "grammar": )");
  scene = open(R"({"species_file": "species/cut.json"})");
  ASSERT_TRUE(scene);
  EXPECT_NE(logged_.find(fmt::format("voxel.flora.species_file: {}:1:", (dir_ / "species/cut.json").string())), std::string::npos)
      << logged_;
  EXPECT_EQ(stats(*scene)["species_table"], "species.json");
}

// The seed's acacia (seed 004 §4.5.4, verbatim, its typo included) in a user's file with the
// shipped acacia's growth, blocks and habitat grows the shipped acacias: same places, same blocks.
TEST_F(VoxelSpeciesGl, TheSeedsAcaciaFromAUserFileGrowsTheShippedAcacias) {
  write("species/acacia.lsys", R"(45.0 45.0 0.8
# make sure the plant has splits
# random lenght stem - then split
^uA1S&F+F+F+F
U > uU
A > +uuE
A > -uE
A > +uE
A > -E
A > uuE
A > uE
# top of the plant
E > x [++++UE1S&F+F+F+F] +UE
E > x [++++++UE1S&F+F+F+F] ++UE
E > x [++UE1S&F+F+F+F] -UE
)");
  write("species/acacia.json", R"({"species": [{"name": "acacia", "grammar": "acacia.lsys", "derivations": [5, 7], "size": [1.0, 1.2],
      "blocks": {"0": "acacia_log", "1": "acacia_leaves"}, "biomes": {"savanna": {"spacing": 14, "chance": 0.4}}}]})");
  auto shipped = open("{}");
  ASSERT_TRUE(shipped);
  const nlohmann::json want = stats(*shipped);
  shipped.reset();
  auto scene = open(R"({"species_file": "species/acacia.json"})");
  ASSERT_TRUE(scene);
  EXPECT_TRUE(logged_.empty()) << logged_;
  const nlohmann::json got = stats(*scene);
  ASSERT_EQ(got["plants_per_species"].size(), 1u) << got.dump();
  EXPECT_EQ(got["plants_per_species"]["acacia"], want["plants_per_species"]["acacia"]) << want.dump();
  EXPECT_GE(got["plants_per_species"]["acacia"].get<int>(), 2);
  EXPECT_EQ(got["plant_blocks"], nlohmann::json({{"acacia_log", want["plant_blocks"]["acacia_log"]},
                                                 {"acacia_leaves", want["plant_blocks"]["acacia_leaves"]}}))
      << want.dump();
}

// The blocks the generator lays (worldgen.cpp) and a brick from a red image, a user's palette.
std::string small_palette(const std::string& more = "") {
  return R"({"blocks": [{"name": "stone", "texture": "stone"}, {"name": "dirt", "texture": "dirt"},
      {"name": "grass", "texture": {"top": "grass_top", "side": "grass_side", "bottom": "dirt"}},
      {"name": "dry_grass", "texture": {"top": "dry_grass_top", "side": "dry_grass_side", "bottom": "dirt"}},
      {"name": "sand", "texture": "sand"}, {"name": "snow", "texture": "snow"},
      {"name": "tall_grass", "render": "alpha_cut", "texture": "tall_grass", "cull_same": false, "sides_only": true},
      {"name": "flowers", "render": "alpha_cut", "texture": "flowers", "cull_same": false, "sides_only": true})" +
         more + "]}";
}

TEST_F(VoxelSpeciesGl, AUserPaletteGivesImageTexturedBlocks) {
  Image red(8, 8, 3);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) red.at(x, y, 0) = 1.0f;
  ASSERT_TRUE(write_image(dir_ / "blocks" / "red.png", red, PixelFormat::kU8).ok());
  write("blocks/palette.json", small_palette(R"(, {"name": "brick", "texture": "red.png"})"));
  write("species/pillars.json", pillar_species(3, R"({"0": "brick"})"));
  auto shipped = open("{}");
  ASSERT_TRUE(shipped);
  const int red_before = red_pixels(*shipped);
  EXPECT_EQ(stats(*shipped)["palette_blocks"], 21);
  shipped.reset();

  auto scene = open(R"({"species_file": "species/pillars.json"})", 2, R"({"palette_file": "blocks/palette.json"})");
  ASSERT_TRUE(scene);
  EXPECT_TRUE(logged_.empty()) << logged_;
  const nlohmann::json s = stats(*scene);
  EXPECT_EQ(s["palette_blocks"], 9);
  const int plants = s["plants_per_species"]["pillar"].get<int>();
  EXPECT_EQ(plants, 371) << "the same places as with the shipped palette";
  EXPECT_EQ(s["plant_blocks"], nlohmann::json({{"brick", 8 * plants}}));
  const int red_after = red_pixels(*scene);
  EXPECT_GT(red_after, 20 * red_before + 200) << "before " << red_before;
  std::printf("red pixels shipped %d, brick pillars %d\n", red_before, red_after);
}

TEST_F(VoxelSpeciesGl, APaletteLackingBlocksLeavesOutWhatNeedsThem) {
  // The shipped species need woods and leaves this palette lacks: each is left out.
  write("blocks/palette.json", small_palette());
  auto scene = open("{}", 2, R"({"palette_file": "blocks/palette.json"})");
  ASSERT_TRUE(scene);
  EXPECT_NE(logged_.find("voxel.blocks.palette_file: species.json: species[0].blocks.0: no block 'acacia_log' in the palette; "
                         "the species is left out"),
            std::string::npos)
      << logged_;
  EXPECT_EQ(stats(*scene)["palette_blocks"], 8);
  EXPECT_TRUE(stats(*scene)["plants_per_species"].empty());
  // Without a block the generator lays (stone), the standard palette is used.
  logged_.clear();
  write("blocks/palette.json", R"({"blocks": [{"name": "dirt", "texture": "dirt"}]})");
  scene = open("{}", 2, R"({"palette_file": "blocks/palette.json"})");
  ASSERT_TRUE(scene);
  EXPECT_NE(logged_.find("stone"), std::string::npos) << logged_;
  EXPECT_NE(logged_.find("; the standard palette is used"), std::string::npos) << logged_;
  EXPECT_EQ(stats(*scene)["palette_blocks"], 21);
  // A palette error names the file and the JSON path.
  logged_.clear();
  write("blocks/palette.json", small_palette(R"(, {"name": "brick", "texture": "granite"})"));
  scene = open("{}", 2, R"({"palette_file": "blocks/palette.json"})");
  ASSERT_TRUE(scene);
  EXPECT_NE(logged_.find(fmt::format("voxel.blocks.palette_file: {}: blocks[8].texture: no procedural texture 'granite'",
                                     (dir_ / "blocks/palette.json").string())),
            std::string::npos)
      << logged_;
  EXPECT_EQ(stats(*scene)["palette_blocks"], 21);
}

}  // namespace

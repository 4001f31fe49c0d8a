// Species tables as data (species.hpp, issue #16): the shipped table is data/species.json read by
// the same parser as a user's file; errors name the file and the JSON path or the grammar's
// file:line:column; a grammar that would explode is refused before anything is derived.

#include <sylva/voxel/species.hpp>
#include <sylva/voxel/worldgen.hpp>

#include <sylva/core/atomic_file.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <unistd.h>

namespace sylva::voxel {
namespace {

namespace fs = std::filesystem;

class SpeciesFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("sylva_voxel_species_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  void write(const std::string& name, const std::string& text) { ASSERT_TRUE(write_file_atomic(dir_ / name, text).ok()); }
  Result<SpeciesTable> load(std::vector<std::string>& warnings) {
    return load_species_table(dir_ / "species.json", BlockPalette::standard(), warnings);
  }
  // One species using `grammar` with `extra` keys, written to species.json.
  void write_one(const std::string& extra, const std::string& blocks = R"({"0": "oak_log", "1": "glowstone"})") {
    write("species.json", R"({"species": [{"name": "column", "grammar": "column.lsys", "derivations": [3, 3], "size": [1, 1],
        "blocks": )" + blocks + R"(, "biomes": {"plains": {"spacing": 6, "chance": 1}})" + extra + "}]}");
  }

  fs::path dir_;
};

TEST(SpeciesTableShipped, SixSpeciesFromTheEmbeddedJson) {
  auto table = builtin_species_table();
  ASSERT_TRUE(table.ok()) << table.error().message;
  const char* names[] = {"acacia", "birch", "oak", "jungle", "forked_bush", "berry_bush"};
  ASSERT_EQ(table->species.size(), 6u);
  for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(table->species[i].name, names[i]);
  const BlockPalette& p = BlockPalette::standard();
  const SpeciesDef& berry = table->species[5];
  EXPECT_EQ(berry.grammar, "bushes.lsys");
  EXPECT_EQ(berry.system, 1);
  EXPECT_EQ(berry.growth.min_derivations, 2);
  EXPECT_EQ(berry.growth.max_derivations, 4);
  EXPECT_FLOAT_EQ(berry.growth.size_at_max, 0.7f);
  EXPECT_EQ(berry.blocks[0], p.id("birch_log"));
  EXPECT_EQ(berry.blocks[1], p.id("berry_leaves"));
  EXPECT_EQ(berry.blocks[2], kAir);
  ASSERT_EQ(berry.habitats.size(), 2u);
  EXPECT_EQ(table->species[2].habitats.size(), 2u) << "oak: plains and oak forest";
  EXPECT_TRUE(table->rejected.empty());
}

// The worst case bounds every derivation the stochastic rules can give (checked on 64 salts of
// every shipped species at its most derivations).
TEST(SpeciesTableShipped, WorstCaseBoundsEveryDerivation) {
  auto table = builtin_species_table();
  ASSERT_TRUE(table.ok());
  for (const SpeciesDef& def : table->species) {
    for (std::uint64_t salt = 0; salt < 64; ++salt) {
      auto s = derive(def.lsystem, def.growth.max_derivations, salt);
      ASSERT_TRUE(s.ok());
      std::size_t parts = 0;
      for (char c : *s) parts += c == 'U' || c == 'u' || c == 'F' || c == 'f';
      EXPECT_LE(static_cast<double>(s->size()), def.worst_symbols) << def.name;
      EXPECT_LE(static_cast<double>(parts), def.worst_parts) << def.name;
    }
  }
  // U > UU from U: exactly 2^n symbols and blocks.
  auto doubling = parse_lsystems("0 0 1\nU\nU > UU\n", "d");
  ASSERT_TRUE(doubling.ok());
  EXPECT_EQ(worst_case_growth(doubling->front(), 10), std::make_pair(1024.0, 1024.0));
  // Blocks a plant lays at fewer derivations count too (rules may remove blocks): U > a.
  auto shrinking = parse_lsystems("0 0 1\nUUU\nU > a\n", "s");
  ASSERT_TRUE(shrinking.ok());
  EXPECT_EQ(worst_case_growth(shrinking->front(), 2), std::make_pair(3.0, 3.0));
}

TEST_F(SpeciesFile, UserGrammarLoadsAndGrows) {
  write("column.lsys", "# a column of three blocks that doubles\n0 0 1\nU1U\nU > UU\n");
  write_one("");
  std::vector<std::string> warnings;
  auto table = load(warnings);
  ASSERT_TRUE(table.ok()) << table.error().message;
  ASSERT_EQ(table->species.size(), 1u);
  EXPECT_TRUE(table->rejected.empty());
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  EXPECT_EQ(table->species[0].worst_parts, 16.0);
  WorldGenSettings gs;
  gs.variants_per_species = 2;
  auto gen = WorldGenerator::create(gs, BlockPalette::standard(), std::make_shared<const SpeciesTable>(std::move(*table)));
  ASSERT_TRUE(gen.ok()) << gen.error().message;
  const PlantModel& m = (*gen)->variants(0).at(0);
  EXPECT_EQ(m.outputs[0].size(), 8u);
  EXPECT_EQ(m.outputs[1].size(), 8u);
  EXPECT_EQ((*gen)->part_block(0, 1), BlockPalette::standard().id("glowstone"));
}

TEST_F(SpeciesFile, GrammarErrorNamesTheFileLineAndColumn) {
  write("column.lsys", "0 0 1\nU\nU UU\n");
  write_one("");
  std::vector<std::string> warnings;
  auto table = load(warnings);
  ASSERT_TRUE(table.ok()) << table.error().message;
  EXPECT_TRUE(table->species.empty());
  ASSERT_EQ(table->rejected.size(), 1u);
  const std::string& m = table->rejected[0].message;
  EXPECT_EQ(m, (dir_ / "species.json").string() +
                   ": species[0].grammar: column.lsys:3:1: expected a rule 'letter > production' or a new header "
                   "'yaw_angle pitch_angle shrink_ratio'");
}

TEST_F(SpeciesFile, BadBlockNameNamesTheJsonPath) {
  write("column.lsys", "0 0 1\nU\n");
  write_one("", R"({"0": "oak_log", "3": "glass_pane"})");
  std::vector<std::string> warnings;
  auto table = load(warnings);
  ASSERT_TRUE(table.ok()) << table.error().message;
  ASSERT_EQ(table->rejected.size(), 1u);
  EXPECT_EQ(table->rejected[0].message,
            (dir_ / "species.json").string() + ": species[0].blocks.3: no block 'glass_pane' in the palette");
  write_one("", R"({"0": "oak_log", "12": "stone"})");
  table = load(warnings);
  ASSERT_TRUE(table.ok());
  ASSERT_EQ(table->rejected.size(), 1u);
  EXPECT_EQ(table->rejected[0].message, (dir_ / "species.json").string() + ": species[0].blocks.12: not an output (0-9)");
}

TEST_F(SpeciesFile, RangesUnknownBiomesAndUnusedOutputs) {
  write("column.lsys", "0 0 1\nU2U\n");
  write_one(R"(, "derivations": [3, 40])");
  std::vector<std::string> warnings;
  auto table = load(warnings);
  ASSERT_TRUE(table.ok());
  ASSERT_EQ(table->rejected.size(), 1u);
  EXPECT_NE(table->rejected[0].message.find("species[0].derivations"), std::string::npos) << table->rejected[0].message;
  EXPECT_NE(table->rejected[0].message.find("above the maximum 32"), std::string::npos) << table->rejected[0].message;

  write("species.json", R"({"species": [{"name": "c", "grammar": "column.lsys", "blocks": {"0": "stone"},
      "biomes": {"tundra": {"spacing": 4, "chance": 1}}}]})");
  table = load(warnings);
  ASSERT_TRUE(table.ok());
  ASSERT_EQ(table->rejected.size(), 1u);
  EXPECT_EQ(table->rejected[0].message,
            (dir_ / "species.json").string() +
                ": species[0].biomes.tundra: no such biome (one of jungle, savanna, plains, shrubland, birch_forest, oak_forest)");

  // Output 2 is used but has no block: a warning, the species stays.
  warnings.clear();
  write_one("", R"({"0": "oak_log"})");
  table = load(warnings);
  ASSERT_TRUE(table.ok());
  EXPECT_EQ(table->species.size(), 1u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("species[0].blocks.2: column.lsys:1 lays blocks on output 2 but it has no block"), std::string::npos)
      << warnings[0];
}

TEST_F(SpeciesFile, ExplodingGrammarIsRefusedBeforeDeriving) {
  // 2 * 4^20 = 2.2e12 symbols: refused from the letter counts, nothing is derived.
  write("column.lsys", "0 0 1\nUU\nU > UUUU\n");
  write_one(R"(, "derivations": [20, 20])");
  std::vector<std::string> warnings;
  auto table = load(warnings);
  ASSERT_TRUE(table.ok());
  ASSERT_EQ(table->rejected.size(), 1u);
  EXPECT_EQ(table->rejected[0].message,
            (dir_ / "species.json").string() +
                ": species[0].derivations: column.lsys:1 may grow to 2.2e+12 symbols in 20 derivations, above the limit of "
                "2097152; lower the most derivations");
  // Within the symbol cap but past the blocks a plant may lay.
  write_one(R"(, "derivations": [9, 9])");
  table = load(warnings);
  ASSERT_TRUE(table.ok());
  ASSERT_EQ(table->rejected.size(), 1u);
  EXPECT_NE(table->rejected[0].message.find("may lay 5.24e+05 blocks in 9 derivations, above the limit of 200000 a plant"),
            std::string::npos)
      << table->rejected[0].message;
  // 8 derivations (131 072 blocks a plant) pass, but 256 cached variants would hold 33.6 M blocks.
  write_one(R"(, "derivations": [8, 8])");
  table = load(warnings);
  ASSERT_TRUE(table.ok());
  ASSERT_EQ(table->species.size(), 1u);
  WorldGenSettings gs;
  gs.variants_per_species = 256;
  auto gen = WorldGenerator::create(gs, BlockPalette::standard(), std::make_shared<const SpeciesTable>(std::move(*table)));
  ASSERT_FALSE(gen.ok());
  EXPECT_NE(gen.error().message.find("the plant cache may hold 3.36e+07 blocks (256 variants per species), above the limit of 16777216"),
            std::string::npos)
      << gen.error().message;
}

TEST_F(SpeciesFile, WholeFileFailures) {
  std::vector<std::string> warnings;
  auto table = load(warnings);
  ASSERT_FALSE(table.ok());
  EXPECT_EQ(table.error().message, (dir_ / "species.json").string() + ": no such file");
  write("species.json", R"({"species": [{"name": )");
  table = load(warnings);
  ASSERT_FALSE(table.ok());
  EXPECT_NE(table.error().message.find("species.json:1:"), std::string::npos) << table.error().message;
  write("species.json", R"({"plants": []})");
  table = load(warnings);
  ASSERT_FALSE(table.ok());
  EXPECT_EQ(table.error().message, (dir_ / "species.json").string() + ": species: missing or not an array of species");
}

}  // namespace
}  // namespace sylva::voxel

// sylva-bench --suite species (issue #16, "Benchmarks") at a tiny size: its rows are printed and
// written to results.csv with sane values: every shipped species file loads cold and cached, the
// user's grammar table (given with --set, as a user would) grows plants of the expected block
// count, and the mixed forest and each of its species alone have the same tree count. No timing
// is compared; times only have to be positive.
#include "bench_exe.hpp"

#include <sylva/core/atomic_file.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

#ifdef SYLVA_BENCH_WITH_SCENE

using namespace sylva::bench::testing;

TEST(BenchSpeciesSuite, PrintsLoadGrammarAndForestRows) {
  const fs::path dir = fresh_test_dir("sylva-bench-species-test", "rows");
  // A user's grammar table: a pillar doubled per derivation, 3 derivations = 8 blocks a plant.
  ASSERT_TRUE(sylva::write_file_atomic(dir / "pillar.lsys", "0 0 1\nU\nU > UU\n").ok());
  ASSERT_TRUE(sylva::write_file_atomic(dir / "plants.json",
                                       R"({"species": [{"name": "pillar", "grammar": "pillar.lsys", "derivations": [3, 3],
                                       "size": [1, 1], "blocks": {"0": "glowstone"}, "biomes": {"plains": {"spacing": 5, "chance": 1}}}]})")
                  .ok());
  std::string output;
  const int code = run_small_suite("species", 1,
                                   "--set vegetation.forest.lod.slice_resolution=64 --set voxel.flora.species_file='" +
                                       (dir / "plants.json").string() + "'",
                                   dir, output);
  ASSERT_EQ(code, 0) << output;

  const auto loads = lines_of(output, "species load: ");
  ASSERT_EQ(loads.size(), 3u) << output;
  std::set<std::string> files;
  for (const std::string& l : loads) {
    EXPECT_GT(field(l, "cold_ms"), 0.0) << l;
    EXPECT_GT(field(l, "cached_ms"), 0.0) << l;
    EXPECT_GT(field(l, "ground_ms"), 0.0) << l;
    files.insert(l.substr(14, l.find(' ', 14) - 14));
  }
  EXPECT_EQ(files, (std::set<std::string>{"painted_birch.json", "slender_conifer.json", "sapling.json"})) << output;

  const auto grammars = lines_of(output, "grammar: ");
  ASSERT_EQ(grammars.size(), 1u) << output;
  EXPECT_NE(grammars[0].find("pillar (pillar.lsys #0)"), std::string::npos) << grammars[0];
  EXPECT_EQ(field(grammars[0], "plants"), 1000.0) << grammars[0];
  EXPECT_EQ(field(grammars[0], "blocks_per_plant"), 8.0) << grammars[0];
  EXPECT_GT(field(grammars[0], "plants_per_s"), 0.0) << grammars[0];

  const auto forests = lines_of(output, "forest: ");
  ASSERT_EQ(forests.size(), 5u) << output;  // mixed, three alone, the ratio
  ASSERT_NE(forests[0].find("forest: mixed species=3"), std::string::npos) << forests[0];
  const double trees = field(forests[0], "trees");
  EXPECT_GT(trees, 0.0) << forests[0];
  // The mixed forest holds all three species; each alone has the mixed forest's tree count.
  for (const char* name : {"painted birch: ", "slender conifer: ", "sapling: "}) {
    EXPECT_NE(forests[0].find(name), std::string::npos) << forests[0];
  }
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(field(forests[k], "trees"), trees) << forests[k];
    EXPECT_GT(field(forests[k], "ms_per_frame"), 0.0) << forests[k];
    if (k > 0) {
      EXPECT_NE(forests[k].find("species=1"), std::string::npos) << forests[k];
    }
  }
  EXPECT_NE(forests[4].find("forest: mixed / composition-weighted one-species = "), std::string::npos) << forests[4];

  auto csv = sylva::read_file(dir / "out" / "results.csv");
  ASSERT_TRUE(csv.ok());
  EXPECT_EQ(csv->rfind("kind,name,count,value,unit\n", 0), 0u) << *csv;
  EXPECT_EQ(lines_of(*csv, "load_cold,").size(), 3u) << *csv;
  EXPECT_EQ(lines_of(*csv, "grammar,").size(), 1u) << *csv;
  EXPECT_EQ(lines_of(*csv, "forest_one,").size(), 3u) << *csv;
  EXPECT_EQ(lines_of(*csv, "forest_mixed_ratio,").size(), 1u) << *csv;
  fs::remove_all(dir);
}

TEST(BenchSpeciesSuite, RefusesASetPathItsScenesLack) {
  const fs::path dir = fresh_test_dir("sylva-bench-species-test", "set");
  std::string output;
  const int code = run_bench("--suite species --set grass.field.density=3 --out '" + dir.string() + "'", dir / "log.txt", output);
  EXPECT_EQ(code, 2) << output;
  EXPECT_NE(output.find("--set grass.field.density=3:"), std::string::npos) << output;
  EXPECT_EQ(output.find("species load:"), std::string::npos) << "nothing is measured after a bad --set\n" << output;
  fs::remove_all(dir);
}

#endif

}  // namespace

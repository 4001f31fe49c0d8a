// sylva-bake's command line: commands, --tiles, --set through the reflected settings, errors.
#include "bake_options.hpp"

#include <gtest/gtest.h>

namespace sylva::bake {
namespace {

TEST(BakeOptions, TerrainWithTilesAndSettings) {
  auto c = parse_bake_args({"terrain", "dem.tif", "--out", "x.sylvaterrain", "--tiles", "2/3", "--set",
                            "terrain.tree.leaf_dimension=65", "--set", "terrain.elevation.spacing=5", "--quiet"});
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->kind, BakeCommand::Kind::kTerrain);
  EXPECT_EQ(c->source, "dem.tif");
  EXPECT_EQ(c->out, "x.sylvaterrain");
  EXPECT_EQ(c->share, 2);
  EXPECT_EQ(c->shares_total, 3);
  EXPECT_TRUE(c->tiled);
  EXPECT_EQ(c->settings.tree.leaf_dimension, 65);
  EXPECT_EQ(c->settings.elevation.spacing, 5.0);
  EXPECT_TRUE(c->quiet);
}

TEST(BakeOptions, MergeTakesEveryShare) {
  auto c = parse_bake_args({"merge", "a.share", "b.share", "c.share", "--out", "x.sylvaterrain"});
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->kind, BakeCommand::Kind::kMerge);
  EXPECT_EQ(c->shares.size(), 3u);
  EXPECT_FALSE(parse_bake_args({"terrain", "a.tif", "--out", "x"})->tiled);
}

TEST(BakeOptions, MistakesAreNamed) {
  auto message = [](std::vector<std::string> args) {
    auto c = parse_bake_args(args);
    return c.ok() ? std::string("accepted") : c.error().message;
  };
  EXPECT_NE(message({"bake"}).find("unknown command 'bake'"), std::string::npos);
  EXPECT_NE(message({"terrain", "dem.tif"}).find("--out"), std::string::npos);
  EXPECT_NE(message({"terrain", "--out", "x"}).find("SOURCE"), std::string::npos);
  for (const char* t : {"3/3", "-1/2", "1", "a/b", "0/0", "0/2000", "1/2x"})
    EXPECT_NE(message({"terrain", "dem.tif", "--out", "x", "--tiles", t}).find("--tiles"), std::string::npos) << t;
  EXPECT_NE(message({"terrain", "dem.tif", "--out", "x", "--set", "terrain.tree.leaf_dimension=1000"})
                .find("leaf_dimension"), std::string::npos);
  EXPECT_NE(message({"terrain", "dem.tif", "--out", "x", "--set", "terrain.tree.nope=1"}).find("nope"),
            std::string::npos);
  EXPECT_NE(message({"merge", "--out", "x"}).find("share"), std::string::npos);
  EXPECT_NE(message({"merge", "a", "--out", "x", "--tiles", "0/2"}).find("unknown option '--tiles'"),
            std::string::npos);
  EXPECT_EQ(parse_bake_args({"--help"})->kind, BakeCommand::Kind::kHelp);
}

#if SYLVA_BAKE_TREE  // built with the vegetation module
TEST(BakeOptions, TreeFromAPresetOrASpeciesFile) {
  auto c = parse_bake_args({"tree", "--preset", "conifer", "--seed", "4294967295", "--out", "dir", "--format", "gltf", "--slices"});
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->kind, BakeCommand::Kind::kTree);
  EXPECT_EQ(c->tree.preset, "conifer");
  EXPECT_EQ(c->tree.seed, 4294967295u);
  EXPECT_TRUE(c->tree.gltf);
  EXPECT_FALSE(c->tree.objt);
  EXPECT_TRUE(c->tree.slices);
  auto f = parse_bake_args({"tree", "oak.json", "--out", "dir", "--format", "objt"});
  ASSERT_TRUE(f.ok()) << f.error().message;
  EXPECT_EQ(f->tree.species, "oak.json");
  EXPECT_TRUE(f->tree.objt);
  EXPECT_FALSE(f->tree.gltf);
  EXPECT_FALSE(f->tree.slices);
  auto both = parse_bake_args({"tree", "oak.json", "--out", "dir"});
  EXPECT_TRUE(both->tree.objt && both->tree.gltf);
  auto message = [](std::vector<std::string> args) {
    auto r = parse_bake_args(args);
    return r.ok() ? std::string("accepted") : r.error().message;
  };
  EXPECT_NE(message({"tree", "a.json", "--preset", "shrub", "--out", "d"}).find("either"), std::string::npos);
  EXPECT_NE(message({"tree", "a.json", "b.json", "--out", "d"}).find("one SPECIES.json"), std::string::npos);
  EXPECT_NE(message({"tree", "--preset", "shrub", "--seed", "4294967296", "--out", "d"}).find("--seed"), std::string::npos);
  EXPECT_NE(message({"tree", "--preset", "shrub", "--seed", "1x", "--out", "d"}).find("--seed"), std::string::npos);
  EXPECT_NE(message({"tree", "--preset", "Shrub", "--out", "d"}).find("expected one of"), std::string::npos);
  EXPECT_NE(message({"tree", "--preset", "shrub", "--out", "d", "--tiles", "0/2"}).find("unknown option '--tiles'"),
            std::string::npos);
  EXPECT_NE(message({"terrain", "dem.tif", "--out", "x", "--slices"}).find("unknown option '--slices'"), std::string::npos);
}
#endif

}  // namespace
}  // namespace sylva::bake

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

}  // namespace
}  // namespace sylva::bake

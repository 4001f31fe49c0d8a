// Slices of a tree loaded from a species file are baked like a generated tree's and cached by
// content (issue #16): the second load comes from the bake cache; an edited OBJT model or a
// changed `units` or bark colour bakes anew; a comment added to the OBJT file (no change to the
// tree) or a leaf tint (applied when drawing) does not.
#include <sylva/vegetation/forest.hpp>
#include <sylva/vegetation/species_file.hpp>

#include <sylva/core/atomic_file.hpp>
#include <sylva/render/testing.hpp>

#include "support/temp_path.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace sylva::vegetation {
namespace {

namespace fs = std::filesystem;

using SpeciesCacheGl = render::GlTest;

std::string objt(const std::string& trunk_length) {
  return "name = \"cached\"\nB 0 {\n l 0\n d " + trunk_length + "\n z 0 0 0\n k 0 " + trunk_length +
         " 0\n r 1 0 0\n s 0 0 -1\n t 0 1 0\n p -1\n x 0\n}\n"
         "B 1 {\n l 1\n d 2\n z 0 3 0\n k 2 3 0\n r 0 1 0\n s 0 0 1\n t 1 0 0\n p 0\n x 0.6\n}\n"
         "L 1 {\n r 0 1 0\n s 0 0 1\n t 1 0 0\n p 1\n x 0.9\n}\n";
}

TEST_F(SpeciesCacheGl, LoadedTreesBakeOnceAndAgainWhenTheTreeChanges) {
  const fs::path dir = testing::unique_temp("species_cache");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto write = [&](const std::string& name, const std::string& text) { ASSERT_TRUE(write_file_atomic(dir / name, text).ok()); };
  // Whether adding the species to a new forest took its slices from the cache (and how long).
  const auto from_cache = [&] {
    std::vector<std::string> warnings;
    Result<SpeciesFile> species = load_species_file(dir / "tree.json", warnings);
    EXPECT_TRUE(species.ok()) << species.error().message;
    Result<TreeTextureSet> textures = make_species_textures(*species, 32);
    EXPECT_TRUE(textures.ok());
    ForestSettings settings;
    settings.lod.slice_resolution = 32;
    settings.lod.cache_directory = (dir / "cache").string();
    Forest forest = Forest::create(settings).value();
    Result<int> added = forest.add_species(species->model, *textures);
    EXPECT_TRUE(added.ok()) << added.error().message;
    EXPECT_NE(forest.slices(0), nullptr) << "a loaded tree has slices";
    return forest.stats().species[0].bake_from_cache;
  };
  write("tree.objt", objt("5"));
  write("tree.json", R"({"model": {"objt": "tree.objt"}, "units": 2})");
  EXPECT_FALSE(from_cache()) << "first load: baked";
  EXPECT_TRUE(from_cache()) << "second load: from the cache";
  write("tree.objt", "// a comment changes the bytes, not the tree\n" + objt("5"));
  EXPECT_TRUE(from_cache()) << "the key is the tree (mesh and textures), not the file's bytes";
  write("tree.objt", objt("6"));
  EXPECT_FALSE(from_cache()) << "an edited model bakes anew";
  write("tree.json", R"({"model": {"objt": "tree.objt"}, "units": 3})");
  EXPECT_FALSE(from_cache()) << "other units bake anew";
  write("tree.json", R"({"model": {"objt": "tree.objt"}, "units": 3, "leaf_tint": [1, 0.5, 1]})");
  EXPECT_TRUE(from_cache()) << "the leaf tint is in the season texture, applied when drawing, not baked";
  write("tree.json", R"({"model": {"objt": "tree.objt"}, "units": 3, "bark_color": [0.5, 0.1, 0.1]})");
  EXPECT_FALSE(from_cache()) << "another bark colour bakes anew";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sylva::vegetation

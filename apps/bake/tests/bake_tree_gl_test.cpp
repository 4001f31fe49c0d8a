// `sylva-bake tree` through the shipped executable (issue #16, tree export): a preset with its
// slices and the shipped species files (an OBJT model, a preset with painted images) exported,
// their glTF read back and compared with the mesh the vegetation module builds for the same
// species; mistakes on the command line and unwritable folders exit with the documented status
// and a message naming the option or path, leaving nothing behind.
#include <sylva/core/atomic_file.hpp>
#include <sylva/core/image.hpp>
#include <sylva/vegetation/generator.hpp>
#include <sylva/vegetation/objt.hpp>
#include <sylva/vegetation/species_file.hpp>
#include <sylva/vegetation/tree_mesh.hpp>

#include "bake_process.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <map>

namespace sylva::bake {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace testing;  // bake_process.hpp

// Vertices and triangles of the glTF's meshes by name, with the bounds of every POSITION
// accessor; checks each accessor's buffer view lies inside the .bin.
struct GltfSummary {
  std::map<std::string, std::pair<std::size_t, std::size_t>> meshes;  // name -> (vertices, triangles)
  glm::vec3 lo{INFINITY}, hi{-INFINITY};
  std::size_t images = 0;
};

GltfSummary summarize(const fs::path& gltf) {
  GltfSummary s;
  const json doc = json::parse(text_of(gltf));
  const std::string bin = text_of(gltf.parent_path() / doc["buffers"][0]["uri"].get<std::string>());
  EXPECT_EQ(doc["buffers"][0]["byteLength"].get<std::size_t>(), bin.size());
  for (const json& v : doc["bufferViews"])
    EXPECT_LE(v["byteOffset"].get<std::size_t>() + v["byteLength"].get<std::size_t>(), bin.size());
  for (const json& m : doc["meshes"]) {
    const json& p = m["primitives"][0];
    const json& pos = doc["accessors"][p["attributes"]["POSITION"].get<std::size_t>()];
    const json& idx = doc["accessors"][p["indices"].get<std::size_t>()];
    EXPECT_LT(idx["max"][0].get<std::size_t>(), pos["count"].get<std::size_t>()) << m["name"];
    s.meshes[m["name"].get<std::string>()] = {pos["count"].get<std::size_t>(), idx["count"].get<std::size_t>() / 3};
    for (int k = 0; k < 3; ++k) {
      s.lo[k] = std::min(s.lo[k], pos["min"][static_cast<std::size_t>(k)].get<float>());
      s.hi[k] = std::max(s.hi[k], pos["max"][static_cast<std::size_t>(k)].get<float>());
    }
  }
  for (const json& im : doc["images"]) {
    EXPECT_TRUE(read_image(gltf.parent_path() / im["uri"].get<std::string>()).ok()) << im["uri"];
    ++s.images;
  }
  return s;
}

void expect_matches(const GltfSummary& s, const vegetation::TreeMesh& mesh) {
  EXPECT_EQ(s.meshes.at("bark").first, mesh.branch_vertices.size());
  EXPECT_EQ(s.meshes.at("bark").second, mesh.branch_indices.size() / 3);
  EXPECT_EQ(s.meshes.at("leaves").first, mesh.leaf_vertices.size());
  EXPECT_EQ(s.meshes.at("leaves").second, mesh.leaf_indices.size() / 3);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(s.lo[k], mesh.bounds_min[k], 1e-5f) << k;
    EXPECT_NEAR(s.hi[k], mesh.bounds_max[k], 1e-5f) << k;
  }
}

TEST(BakeTree, PresetWithSlices) {
  const fs::path dir = test_dir("tree_preset");
  const fs::path out = dir / "out";
  ASSERT_EQ(run_bake({"tree", "--preset", "broadleaf", "--seed", "2", "--out", out.string(), "--slices"}, dir / "log"), 0)
      << text_of(dir / "log");
  const std::string log = text_of(dir / "log");
  std::printf("%s", log.substr(0, log.find('\n') + 1).c_str());
  EXPECT_NE(log.find("wrote tree 'broadleaf_2'"), std::string::npos) << log;
  EXPECT_NE(log.find("11 slice layers"), std::string::npos) << log;

  Result<vegetation::TreeModel> model = vegetation::generate_tree(vegetation::species_preset(vegetation::SpeciesPreset::kBroadleaf, 2));
  ASSERT_TRUE(model.ok());
  const GltfSummary s = summarize(out / "broadleaf_2.gltf");
  expect_matches(s, vegetation::build_tree_mesh(*model));
  EXPECT_EQ(s.images, 4u);
  EXPECT_TRUE(fs::exists(out / "broadleaf_2.objt"));
  // The slice set: 9 LOD1 + 2 LOD2 layers, a colour and a normal image each, 128 px.
  const json manifest = json::parse(text_of(out / "broadleaf_2_slices" / "slices.json"));
  std::size_t layers = 0;
  for (const json& level : manifest["levels"])
    for (const json& slice : level["slices"]) {
      ++layers;
      Result<Image> c = read_image(out / "broadleaf_2_slices" / slice["color"].get<std::string>());
      ASSERT_TRUE(c.ok()) << slice["color"];
      EXPECT_EQ(c->width(), 128);
      EXPECT_TRUE(fs::exists(out / "broadleaf_2_slices" / slice["normal_map"].get<std::string>()));
    }
  EXPECT_EQ(layers, 11u);
  std::size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(out)) files += e.is_regular_file() ? 1 : 0;
  EXPECT_EQ(files, 7u + 22u + 1u);  // objt, gltf, bin, 4 textures; 22 slice images, manifest
  fs::remove_all(dir);
}

TEST(BakeTree, ShippedSpeciesFiles) {
  const fs::path dir = test_dir("tree_species");
  const fs::path species_dir = SYLVA_SPECIES_DIR;
  // The seed's example tree (an OBJT model) in both formats, the painted birch (images) as glTF.
  for (const char* name : {"seed_example.json", "painted_birch.json"}) {
    const bool objt = std::string(name) == "seed_example.json";
    const fs::path out = dir / fs::path(name).stem();
    std::vector<std::string> args{"tree", (species_dir / name).string(), "--out", out.string(), "--quiet"};
    if (!objt) args.insert(args.end(), {"--format", "gltf"});
    ASSERT_EQ(run_bake(args, dir / "log"), 0) << text_of(dir / "log");
    std::vector<std::string> warnings;
    Result<vegetation::SpeciesFile> species = vegetation::load_species_file(species_dir / name, warnings);
    ASSERT_TRUE(species.ok()) << species.error().message;
    const std::string stem = objt ? "seed_example" : "painted_birch";
    const GltfSummary s = summarize(out / (stem + ".gltf"));
    expect_matches(s, vegetation::build_tree_mesh(species->model));
    EXPECT_EQ(fs::exists(out / (stem + ".objt")), objt) << name;
    std::printf("%s: bark %zu triangles, leaves %zu triangles, height %.3f m\n", name, s.meshes.at("bark").second,
                s.meshes.at("leaves").second, s.hi.y - s.lo.y);
    if (objt) {
      Result<vegetation::TreeModel> back = vegetation::load_objt(out / (stem + ".objt"));
      ASSERT_TRUE(back.ok()) << back.error().message;
      EXPECT_EQ(back->branches.size(), species->model.branches.size());
      EXPECT_EQ(back->leaves.size(), species->model.leaves.size());
    }
  }
  fs::remove_all(dir);
}

TEST(BakeTree, MistakesAreNamedAndLeaveNothing) {
  const fs::path dir = test_dir("tree_errors");
  const auto run = [&](std::vector<std::string> args) { return run_bake(args, dir / "log"); };
  const auto log = [&] { return text_of(dir / "log"); };
  EXPECT_EQ(run({"tree", "--preset", "oak", "--out", (dir / "o").string()}), 2);
  EXPECT_NE(log().find("--preset 'oak': expected one of broadleaf, conifer, birch, shrub"), std::string::npos) << log();
  EXPECT_EQ(run({"tree", "--preset", "shrub", "--format", "fbx", "--out", (dir / "o").string()}), 2);
  EXPECT_NE(log().find("--format 'fbx'"), std::string::npos) << log();
  EXPECT_EQ(run({"tree", "--preset", "shrub", "--seed", "-3", "--out", (dir / "o").string()}), 2);
  EXPECT_NE(log().find("--seed '-3'"), std::string::npos) << log();
  EXPECT_EQ(run({"tree", "--preset", "shrub"}), 2);
  EXPECT_NE(log().find("--out DIR"), std::string::npos) << log();
  EXPECT_EQ(run({"tree", (dir / "a.json").string(), "--seed", "3", "--out", (dir / "o").string()}), 2);
  EXPECT_NE(log().find("--seed applies to --preset"), std::string::npos) << log();
  EXPECT_EQ(run({"tree", "--out", (dir / "o").string()}), 2);
  EXPECT_NE(log().find("either a SPECIES.json or --preset"), std::string::npos) << log();
  // A missing species file (exit 1, named), a folder under a regular file (exit 1, named).
  EXPECT_EQ(run({"tree", (dir / "missing.json").string(), "--out", (dir / "o").string()}), 1);
  EXPECT_NE(log().find("missing.json"), std::string::npos) << log();
  ASSERT_TRUE(write_file_atomic(dir / "plain", "x").ok());
  EXPECT_EQ(run({"tree", "--preset", "shrub", "--out", (dir / "plain" / "o").string()}), 1);
  EXPECT_NE(log().find("plain/o"), std::string::npos) << log();
  EXPECT_FALSE(fs::exists(dir / "o"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sylva::bake

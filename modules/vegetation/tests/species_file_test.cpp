// Species files (species_file.hpp, issue #16): an OBJT model or a preset with parameters, units,
// the OBJT rules for missing radii and leaf sizes, colours; and every bad input refused with the
// file and the JSON path in the message, nothing crashing.
#include <sylva/vegetation/species_file.hpp>

#include <sylva/core/atomic_file.hpp>

#include "support/models.hpp"
#include "support/temp_path.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace sylva::vegetation {
namespace {

namespace fs = std::filesystem;

// The seed's example tree (no radii, no leaf sizes) with the trunk written as its own parent, a
// layout the loader repairs with a warning.
std::string trunk_naming_itself_as_parent() {
  std::string objt = testing::seed_example_objt();
  const std::string root = "p    -1";
  return objt.replace(objt.find(root), root.size(), "p    0");
}

class SpeciesFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::unique_temp(std::string("species_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "trees");
    ASSERT_TRUE(write_file_atomic(dir_ / "trees" / "seed.objt", testing::seed_example_objt()).ok());
  }
  void TearDown() override { fs::remove_all(dir_); }

  Result<SpeciesFile> load(const std::string& json) {
    warnings_.clear();
    EXPECT_TRUE(write_file_atomic(dir_ / "oak.json", json).ok());
    return load_species_file(dir_ / "oak.json", warnings_);
  }
  std::string error_of(const std::string& json) {
    Result<SpeciesFile> r = load(json);
    EXPECT_FALSE(r.ok()) << json;
    return r.ok() ? std::string() : r.error().message;
  }

  fs::path dir_;
  std::vector<std::string> warnings_;
};

TEST_F(SpeciesFileTest, ObjtModelWithUnitsAndRules) {
  Result<SpeciesFile> one = load(R"({"name": "Oak", "model": {"objt": "trees/seed.objt"}})");
  ASSERT_TRUE(one.ok()) << one.error().message;
  EXPECT_EQ(one->name, "Oak");
  EXPECT_EQ(one->model.branches.size(), 2u);
  EXPECT_EQ(one->objt_file, dir_ / "trees" / "seed.objt");
  EXPECT_FLOAT_EQ(one->model.leaves[0].width, 0.05f) << "the loader's default leaf";
  EXPECT_FLOAT_EQ(one->model.branches[0].radius_base, 0.03f * 5.0f);

  Result<SpeciesFile> two = load(R"({"model": {"objt": "trees/seed.objt"}, "units": 2,
      "objt": {"branch_radius": 0.05, "branch_taper": 0.5, "leaf_width": 0.3, "leaf_length": 0.4}})");
  ASSERT_TRUE(two.ok()) << two.error().message;
  EXPECT_EQ(two->name, "oak") << "the file stem without a name";
  EXPECT_FLOAT_EQ(two->model.branches[0].length, 10.0f) << "units: metres per file unit";
  EXPECT_FLOAT_EQ(two->model.branches[1].start.y, 6.0f);
  EXPECT_FLOAT_EQ(two->model.branches[0].radius_base, 0.05f * 10.0f) << "branch_radius relative to the length";
  EXPECT_FLOAT_EQ(two->model.branches[0].radius_tip, 0.5f * 0.5f);
  EXPECT_FLOAT_EQ(two->model.leaves[0].width, 0.3f) << "leaf sizes in metres, whatever the units";
  EXPECT_FLOAT_EQ(two->model.leaves[0].length, 0.4f);
}

TEST_F(SpeciesFileTest, PresetWithParametersAndColours) {
  Result<SpeciesFile> s = load(R"({"model": {"preset": "conifer", "seed": 3, "parameters": {"trunk_length": 4, "level1": {"count": 5}}},
      "leaf_tint": [1, 0.5, 0.5], "bark_color": [0.6, 0.1, 0.1]})");
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(s->look, SpeciesPreset::kConifer) << "a preset's own textures";
  EXPECT_LT(s->model.bounds_max().y, 6.0f) << "trunk_length 4 (the conifer's default is taller)";
  ASSERT_TRUE(s->bark_color.has_value());
  Result<TreeTextureSet> tex = make_species_textures(*s, 16);
  ASSERT_TRUE(tex.ok()) << tex.error().message;
  Result<TreeTextureSet> plain = make_texture_set(SpeciesPreset::kConifer, 1, 16, 16);
  ASSERT_TRUE(plain.ok());
  const Image& a = tex->season;
  const Image& b = plain->season;
  const int y = a.height() / 2;
  EXPECT_FLOAT_EQ(a.at(0, y, 0), b.at(0, y, 0));
  EXPECT_FLOAT_EQ(a.at(0, y, 1), 0.5f * b.at(0, y, 1)) << "leaf_tint multiplies the seasonal colour";
  EXPECT_GT(tex->bark.albedo.at(0, 0, 0), 1.5f * tex->bark.albedo.at(0, 0, 1)) << "red bark";
}

TEST_F(SpeciesFileTest, LodAndAnimationOverrideOnlyWhatTheyName) {
  Result<SpeciesFile> plain = load(R"({"model": {"objt": "trees/seed.objt"}})");
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  EXPECT_EQ(plain->tuning.wind_scale, 1.0f);
  EXPECT_LT(plain->tuning.v1, 0.0f) << "the forest's";
  Result<SpeciesFile> s = load(R"({"model": {"objt": "trees/seed.objt"}, "lod": {"v1": 20, "s2": 9, "slice_resolution": 64},
                                   "animation": {"wind_scale": 0.25}})");
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(s->tuning.v1, 20.0f);
  EXPECT_LT(s->tuning.v2, 0.0f) << "not named: the forest's";
  EXPECT_LT(s->tuning.s1, 0.0f);
  EXPECT_EQ(s->tuning.s2, 9.0f);
  EXPECT_EQ(s->tuning.wind_scale, 0.25f);
  ASSERT_EQ(warnings_.size(), 1u);
  EXPECT_NE(warnings_[0].find("oak.json: lod.slice_resolution"), std::string::npos) << warnings_[0];
  EXPECT_NE(error_of(R"({"model": {"objt": "trees/seed.objt"}, "lod": {"v1": -3}})").find("oak.json: lod.v1"), std::string::npos);
  EXPECT_NE(error_of(R"({"model": {"objt": "trees/seed.objt"}, "lod": 3})").find("oak.json: lod: must be"), std::string::npos);
  EXPECT_NE(error_of(R"({"model": {"objt": "trees/seed.objt"}, "animation": {"wind_scale": 1e30}})").find("oak.json: animation.wind_scale"),
            std::string::npos);
}

TEST_F(SpeciesFileTest, ErrorsNameTheFileAndThePath) {
  EXPECT_EQ(error_of(R"({"model": {"objt": "trees/oak.objt"}})"), "oak.json: model.objt: no such file trees/oak.objt");
  EXPECT_NE(error_of(R"({"model": {"objt": 7}})").find("oak.json: model.objt"), std::string::npos);
  EXPECT_NE(error_of(R"({"model": {"objt": "trees/seed.objt"}, "units": "big"})").find("oak.json: units"), std::string::npos);
  EXPECT_NE(error_of(R"({"model": {"objt": "trees/seed.objt"}, "units": 1e9})").find("oak.json: units"), std::string::npos);
  EXPECT_NE(error_of(R"({"model": {"objt": "trees/seed.objt"}, "units": NaN})").find("oak.json:1:"), std::string::npos)
      << "NaN is not JSON: a parse error with line and column";
  EXPECT_NE(error_of(R"({"model": {"objt": "trees/seed.objt"}, "leaf_tint": [1, 1]})").find("oak.json: leaf_tint"), std::string::npos);
  EXPECT_NE(error_of(R"({"units": 1})").find("oak.json: model: missing"), std::string::npos);
  EXPECT_NE(error_of(R"({"model": {"objt": "trees/seed.objt", "preset": "birch"}})").find("oak.json: model: must be"), std::string::npos);
  EXPECT_NE(error_of(R"({"model": "trees/seed.objt"})").find("oak.json: model: must be"), std::string::npos);
  EXPECT_NE(error_of(R"([1, 2])").find("oak.json: the species must be a JSON object"), std::string::npos);
  EXPECT_NE(error_of(R"({"model": {"preset": "palm"}})").find("oak.json: model.preset"), std::string::npos);
  EXPECT_NE(error_of(R"({"model": {"preset": "birch", "parameters": 3}})").find("oak.json: model.parameters"), std::string::npos);
  EXPECT_NE(error_of(R"({"model": {"preset": "birch", "parameters": {"trunk_length": 900}}})").find("oak.json: model.parameters.trunk_length"),
            std::string::npos);
  // Huge: a 5 m model at 500 m per unit.
  const std::string huge = error_of(R"({"model": {"objt": "trees/seed.objt"}, "units": 500})");
  EXPECT_NE(huge.find("oak.json: units: the tree is"), std::string::npos) << huge;
  // A species naming itself as its model: not an OBJT file, refused with the OBJT line.
  const std::string self = error_of(R"({"model": {"objt": "oak.json"}})");
  EXPECT_NE(self.find("oak.json: model.objt: oak.json:1"), std::string::npos) << self;
  // OBJT errors keep the OBJT file and line.
  ASSERT_TRUE(write_file_atomic(dir_ / "trees" / "bad.objt", "name = \"x\"\nB 0 {\n  l 0\n  d -1\n}\n").ok());
  const std::string bad = error_of(R"({"model": {"objt": "trees/bad.objt"}})");
  EXPECT_NE(bad.find("oak.json: model.objt: trees/bad.objt:"), std::string::npos) << bad;
  // A species file too big to be one.
  EXPECT_EQ(load(std::string(kMaxSpeciesFileBytes + 1, ' ')).error().code, ErrorCode::kLimit);
  // A missing species file.
  std::vector<std::string> w;
  Result<SpeciesFile> missing = load_species_file(dir_ / "nope.json", w);
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().code, ErrorCode::kNotFound);
  EXPECT_NE(missing.error().message.find("nope.json"), std::string::npos);
}

TEST_F(SpeciesFileTest, UnknownKeysAndRepairsWarn) {
  ASSERT_TRUE(write_file_atomic(dir_ / "trees" / "self.objt",
                                trunk_naming_itself_as_parent())
                  .ok());
  Result<SpeciesFile> s = load(R"({"model": {"objt": "trees/self.objt", "scale": 2}, "colour": [1, 0, 0]})");
  ASSERT_TRUE(s.ok()) << s.error().message;
  std::string all;
  for (const std::string& x : warnings_) all += x + "\n";
  EXPECT_NE(all.find("oak.json: model.scale"), std::string::npos) << all;
  EXPECT_NE(all.find("oak.json: colour"), std::string::npos) << all;
  EXPECT_NE(all.find("oak.json: trees/self.objt:"), std::string::npos) << "the OBJT repair of the trunk's own parent\n" << all;
  // strict turns the repair into an error.
  const std::string strict = error_of(R"({"model": {"objt": "trees/self.objt"}, "objt": {"strict": true}})");
  EXPECT_NE(strict.find("oak.json: model.objt: trees/self.objt:"), std::string::npos) << strict;
}

}  // namespace
}  // namespace sylva::vegetation

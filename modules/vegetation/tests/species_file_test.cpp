// Species files (species_file.hpp, issue #16): an OBJT model or a preset with parameters, units,
// the OBJT rules for missing radii and leaf sizes, colours; and every bad input refused with the
// file and the JSON path in the message, nothing crashing.
#include <sylva/vegetation/species_file.hpp>

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/image.hpp>
#include <sylva/vegetation/slice_bake.hpp>

#include "support/models.hpp"
#include "support/temp_path.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
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

// An 8-bit image file of w x h with `channels` channels; texel (x, y) (top row first) is the first
// `channels` components of fn(x, y), sRGB-encoded as an image editor stores colours.
void write_png(const fs::path& path, int w, int h, int channels, const std::function<glm::vec4(int, int)>& fn) {
  Image img(w, h, channels, PixelFormat::kU8);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c) img.at(x, y, c) = fn(x, y)[c];
  ASSERT_TRUE(write_image(path, img).ok()) << path;
}

// A leaf: the ellipse inscribed in the image in `color`, transparent white around it.
std::function<glm::vec4(int, int)> leaf_shape(int w, int h, glm::vec3 color) {
  return [=](int x, int y) {
    const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(w) - 0.5f;
    const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(h) - 0.5f;
    return u * u + v * v < 0.2f ? glm::vec4(color, 1.0f) : glm::vec4(1.0f, 1.0f, 1.0f, 0.0f);
  };
}

float srgb_decoded(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

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

// Leaf, bark and season images (issue #16) replace the procedural textures: a solid leaf colour is
// no deviation (c_v = 0, eq. 3.34) and its mean becomes the seasonal colour; colour images are
// decoded from sRGB; the season image is the seed's column (§4.6).
TEST_F(SpeciesFileTest, LeafBarkAndSeasonImagesReplaceTheProceduralTextures) {
  write_png(dir_ / "leaf.png", 16, 24, 4, leaf_shape(16, 24, {0.0f, 0.0f, 1.0f}));
  const glm::vec3 tilt = glm::normalize(glm::vec3(0.3f, 0.0f, 0.95f));
  write_png(dir_ / "leaf_n.png", 16, 16, 3, [&](int, int) { return glm::vec4(tilt * 0.5f + 0.5f, 1.0f); });
  write_png(dir_ / "leaf_t.png", 8, 8, 1, [](int, int) { return glm::vec4(0.3f); });
  write_png(dir_ / "bark.png", 8, 8, 3, [](int, int) { return glm::vec4(0.2f, 0.6f, 0.2f, 1.0f); });
  // Top half (season 0.5-1) red, bottom half blue; the top row without leaves.
  write_png(dir_ / "season.png", 1, 8, 4, [](int, int y) {
    return y < 4 ? glm::vec4(1.0f, 0.0f, 0.0f, y == 0 ? 0.0f : 1.0f) : glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
  });
  Result<SpeciesFile> s = load(R"({"model": {"objt": "trees/seed.objt"}, "texture_seed": 4,
      "leaf": {"color": "leaf.png", "normal": "leaf_n.png", "translucency": "leaf_t.png"},
      "bark": {"color": "bark.png"}, "season": "season.png"})");
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_TRUE(warnings_.empty()) << warnings_.front();
  EXPECT_EQ(s->images.files.size(), 5u);
  EXPECT_EQ(s->images.files[0], dir_ / "leaf.png");
  Result<TreeTextureSet> tex = make_species_textures(*s, 32);
  ASSERT_TRUE(tex.ok()) << tex.error().message;
  const LeafTextures& leaves = tex->leaves;
  ASSERT_EQ(leaves.front.color.width(), 32) << "resampled to the texture size";
  ASSERT_EQ(leaves.back.translucency.height(), 32);
  for (const LeafSide* side : {&leaves.front, &leaves.back}) {
    EXPECT_FLOAT_EQ(side->color.at(16, 16, 3), 1.0f) << "inside the outline";
    EXPECT_FLOAT_EQ(side->color.at(0, 0, 3), 0.0f) << "outside";
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(side->color.at(16, 16, c), 0.5f, 1e-4f) << "one colour: no deviation c_v";
    EXPECT_NEAR(side->translucency.at(16, 16, 3), 77.0f / 255.0f, 1e-4f) << "rho_t from the intensity image";
    EXPECT_FLOAT_EQ(side->translucency.at(0, 0, 3), 0.0f);
  }
  // The outline's edge texels keep the leaf's colour, not the white background's.
  int edge = 0;
  for (int x = 0; x < 32; ++x) {
    const float a = leaves.front.color.at(x, 16, 3);
    if (a <= 0.05f || a >= 0.95f) continue;
    ++edge;
    EXPECT_NEAR(leaves.front.color.at(x, 16, 0), 0.5f, 0.01f) << "column " << x;
  }
  EXPECT_GT(edge, 0);
  const auto normal = [](const Image& img, int x, int y) {
    return glm::vec3(img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2)) * 2.0f - 1.0f;
  };
  EXPECT_NEAR(normal(leaves.front.normal, 16, 16).x, tilt.x, 0.01f);
  EXPECT_NEAR(normal(leaves.back.normal, 16, 16).x, tilt.x, 0.01f) << "the same surface seen from below: x stays (x = -u there)";
  EXPECT_NEAR(normal(leaves.front.normal, 16, 16).z, tilt.z, 0.01f);
  EXPECT_NEAR(tex->bark.albedo.at(3, 3, 1), srgb_decoded(153.0f / 255.0f), 1e-4f) << "bark colour decoded from sRGB";
  EXPECT_NEAR(tex->bark.albedo.at(3, 3, 0), srgb_decoded(51.0f / 255.0f), 1e-4f);
  ASSERT_EQ(tex->season.width(), 1);
  ASSERT_EQ(tex->season.height(), 8);
  EXPECT_EQ(sample_season(tex->season, 0.8f), glm::vec4(1.0f, 0.0f, 0.0f, 1.0f)) << "late in the year: red";
  EXPECT_EQ(sample_season(tex->season, 0.2f), glm::vec4(0.0f, 0.0f, 1.0f, 1.0f)) << "early: blue";
  EXPECT_EQ(sample_season(tex->season, 1.0f - 0.5f / 8.0f).a, 0.0f) << "the top row: no leaves";

  // Without a season image the leaf image's colour is the leaves' colour all year, with the
  // look's budding and leaf fall; leaf_tint still multiplies it.
  Result<SpeciesFile> plain = load(R"({"model": {"objt": "trees/seed.objt"}, "leaf": {"color": "leaf.png"}, "leaf_tint": [1, 1, 0.5]})");
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  Result<TreeTextureSet> ptex = make_species_textures(*plain, 16);
  ASSERT_TRUE(ptex.ok()) << ptex.error().message;
  const Image palette = generate_season_texture(season_palette_for(SpeciesPreset::kBroadleaf));
  ASSERT_EQ(ptex->season.height(), palette.height());
  for (int y = 0; y < palette.height(); ++y) {
    EXPECT_EQ(ptex->season.at(0, y, 0), 0.0f);
    EXPECT_NEAR(ptex->season.at(0, y, 2), 0.5f, 1e-6f) << "the blue leaf, tinted";
    EXPECT_EQ(ptex->season.at(0, y, 3), palette.at(0, y, 3)) << "the look's presence, row " << y;
  }
  EXPECT_NEAR(ptex->leaves.front.normal.at(8, 8, 2), 1.0f, 1e-6f) << "no normal image: flat";
}

// Changing an image that the slices show changes the slice cache key (slice_bake.hpp), so the
// slices are baked again; the same images give the same key.
TEST_F(SpeciesFileTest, ALeafImageIsInTheSliceCacheKey) {
  write_png(dir_ / "leaf.png", 16, 16, 4, leaf_shape(16, 16, {0.2f, 0.5f, 0.1f}));
  const std::string json = R"({"model": {"objt": "trees/seed.objt"}, "leaf": {"color": "leaf.png"}})";
  const auto key = [&] {
    Result<SpeciesFile> s = load(json);
    EXPECT_TRUE(s.ok()) << s.error().message;
    if (!s.ok()) return std::uint64_t{0};
    Result<TreeTextureSet> tex = make_species_textures(*s, 16);
    EXPECT_TRUE(tex.ok());
    return slice_cache_key(build_tree_mesh(s->model), *tex, 64, 0.05f);
  };
  const std::uint64_t first = key();
  EXPECT_EQ(key(), first);
  // A lighter stripe across the leaf: a colour deviation the slices bake.
  write_png(dir_ / "leaf.png", 16, 16, 4, [](int x, int y) {
    return leaf_shape(16, 16, y == 8 ? glm::vec3(0.4f, 0.7f, 0.2f) : glm::vec3(0.2f, 0.5f, 0.1f))(x, y);
  });
  EXPECT_NE(key(), first);
}

TEST_F(SpeciesFileTest, ImageErrorsNameTheFileTheKeyAndTheImage) {
  const std::string model = R"("model": {"objt": "trees/seed.objt"})";
  const auto with = [&](const std::string& keys) { return "{" + model + ", " + keys + "}"; };
  write_png(dir_ / "leaf.png", 16, 16, 4, leaf_shape(16, 16, {0.2f, 0.5f, 0.1f}));
  EXPECT_EQ(error_of(with(R"("leaf": {"color": "nope.png"})")), "oak.json: leaf.color: no such file nope.png");
  EXPECT_EQ(load(with(R"("leaf": {"color": "nope.png"})")).error().code, ErrorCode::kNotFound);
  EXPECT_EQ(error_of(with(R"("leaf": {"normal": "leaf.png"})")),
            "oak.json: leaf.color: missing (the leaf block needs a colour image with the outline in alpha)");
  EXPECT_EQ(error_of(with(R"("bark": {"normal": "leaf.png"})")), "oak.json: bark.color: missing (the bark block needs a colour image)");
  write_png(dir_ / "rgb.png", 16, 16, 3, [](int, int) { return glm::vec4(0.2f, 0.5f, 0.1f, 1.0f); });
  EXPECT_EQ(error_of(with(R"("leaf": {"color": "rgb.png"})")),
            "oak.json: leaf.color: rgb.png has 3 channels; a leaf colour image needs an alpha channel for the outline (RGBA)");
  write_png(dir_ / "clear.png", 16, 16, 4, [](int, int) { return glm::vec4(0.2f, 0.5f, 0.1f, 0.4f); });
  EXPECT_EQ(error_of(with(R"("leaf": {"color": "clear.png"})")),
            "oak.json: leaf.color: clear.png has no texel with alpha above 0.5 (the leaf outline is empty)");
  write_png(dir_ / "grey.png", 16, 16, 1, [](int, int) { return glm::vec4(0.5f); });
  EXPECT_EQ(error_of(with(R"("leaf": {"color": "leaf.png", "normal": "grey.png"})")),
            "oak.json: leaf.normal: grey.png has 1 channel; a normal map needs RGB (or RGBA)");
  EXPECT_EQ(error_of(with(R"("bark": {"color": "grey.png"})")),
            "oak.json: bark.color: grey.png has 1 channel; a colour image needs RGB (or RGBA)");
  write_png(dir_ / "dot.png", 1, 1, 4, [](int, int) { return glm::vec4(1.0f); });
  const Result<SpeciesFile> dot = load(with(R"("leaf": {"color": "dot.png"})"));
  ASSERT_FALSE(dot.ok());
  EXPECT_EQ(dot.error().code, ErrorCode::kLimit);
  EXPECT_EQ(dot.error().message, "oak.json: leaf.color: dot.png is 1x1, below the 4x4 minimum");
  write_png(dir_ / "wide.png", kMaxSpeciesImageSide + 1, 4, 3, [](int, int) { return glm::vec4(0.5f); });
  const Result<SpeciesFile> wide = load(with(R"("bark": {"color": "wide.png"})"));
  ASSERT_FALSE(wide.ok());
  EXPECT_EQ(wide.error().code, ErrorCode::kLimit);
  EXPECT_EQ(wide.error().message, "oak.json: bark.color: " + (dir_ / "wide.png").string() +
                                      ": image is 4097x4, larger than the limit of 4096 per side");
  EXPECT_EQ(error_of(with(R"("season": "leaf.png")")),
            "oak.json: season: leaf.png is 16x16; a season image is one column (1 x rows, top = season 1) or one row");
  write_png(dir_ / "row.png", 8, 1, 1, [](int, int) { return glm::vec4(0.5f); });
  EXPECT_EQ(error_of(with(R"("season": "row.png")")), "oak.json: season: row.png has 1 channel; a colour image needs RGB (or RGBA)");
  // A damaged image: the reader's message with the image's path.
  ASSERT_TRUE(write_file_atomic(dir_ / "cut.png", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16)).ok());
  const Result<SpeciesFile> cut = load(with(R"("leaf": {"color": "cut.png"})"));
  ASSERT_FALSE(cut.ok());
  EXPECT_EQ(cut.error().message.rfind("oak.json: leaf.color: " + (dir_ / "cut.png").string() + ": ", 0), 0u) << cut.error().message;
  EXPECT_NE(error_of(with(R"("leaf": {"color": 3})")).find("oak.json: leaf.color"), std::string::npos);
  EXPECT_NE(error_of(with(R"("leaf": "leaf.png")")).find("oak.json: leaf"), std::string::npos);
  EXPECT_EQ(error_of(with(R"("season": "")")), "oak.json: season: empty path");
  // A season image given as one row is the column (errata 16); unknown keys in a block warn.
  write_png(dir_ / "row.png", 8, 1, 3, [](int x, int) { return glm::vec4(x < 4 ? 1.0f : 0.0f, 0.0f, 0.0f, 1.0f); });
  Result<SpeciesFile> row = load(with(R"("season": "row.png", "leaf": {"color": "leaf.png", "colour": "x.png"})"));
  ASSERT_TRUE(row.ok()) << row.error().message;
  ASSERT_EQ(row->images.season.width(), 1);
  ASSERT_EQ(row->images.season.height(), 8);
  EXPECT_EQ(row->images.season.at(0, 0, 0), 1.0f);
  EXPECT_EQ(row->images.season.at(0, 7, 0), 0.0f);
  EXPECT_EQ(row->images.season.at(0, 7, 3), 1.0f) << "RGB: leaves all year";
  ASSERT_EQ(warnings_.size(), 1u);
  EXPECT_NE(warnings_[0].find("oak.json: leaf.colour"), std::string::npos) << warnings_[0];
}

}  // namespace
}  // namespace sylva::vegetation

// Block palettes as data (palette_file.hpp, issue #16): the standard palette is data/palette.json
// read by the same parser as a user's; textures are procedural names or image files; errors name
// the file and the JSON path.

#include <sylva/voxel/palette_file.hpp>

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/image.hpp>
#include <sylva/voxel/block_textures.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <unistd.h>

namespace sylva::voxel {
namespace {

namespace fs = std::filesystem;

TEST(PaletteShipped, TheStandardPaletteIsTheEmbeddedJson) {
  const BlockPalette& p = BlockPalette::standard();
  ASSERT_EQ(p.size(), 22u);  // air + 21
  const char* names[] = {"air",        "stone",        "dirt",          "grass",         "dry_grass",   "sand",
                         "snow",       "gravel",       "oak_log",       "birch_log",     "acacia_log",  "jungle_log",
                         "oak_leaves", "birch_leaves", "acacia_leaves", "jungle_leaves", "bush_leaves", "berry_leaves",
                         "tall_grass", "flowers",      "lantern",       "glowstone"};
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_EQ(p[static_cast<BlockId>(i)].name, names[i]);
  const BlockType& grass = p[p.id("grass")];
  EXPECT_EQ(grass.texture_top, static_cast<int>(TextureId::kGrassTop));
  EXPECT_EQ(grass.texture_side, static_cast<int>(TextureId::kGrassSide));
  EXPECT_EQ(grass.texture_bottom, static_cast<int>(TextureId::kDirt));
  EXPECT_EQ(p.first_alpha_cut(), p.id("oak_leaves"));
  EXPECT_FALSE(p.culls_same(p.id("oak_leaves")));
  EXPECT_TRUE(p.sides_only(p.id("flowers")));
  EXPECT_EQ(p[p.id("lantern")].emission, glm::vec3(1.0f, 0.75f, 0.4f));
  EXPECT_FLOAT_EQ(p[p.id("snow")].shininess, 48.0f);
  EXPECT_TRUE(p.images().empty());
}

class PaletteFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("sylva_voxel_palette_" + std::to_string(::getpid()) + "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "textures");
  }
  void TearDown() override { fs::remove_all(dir_); }

  void write(const std::string& text) { ASSERT_TRUE(write_file_atomic(dir_ / "palette.json", text).ok()); }
  Result<BlockPalette> load() {
    std::vector<std::string> warnings;
    return load_palette(dir_ / "palette.json", warnings);
  }
  std::string file() const { return (dir_ / "palette.json").string(); }

  fs::path dir_;
};

TEST_F(PaletteFile, ImageAndProceduralTextures) {
  Image red(2, 3, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 2; ++x) red.at(x, y, 0) = 1.0f;
  ASSERT_TRUE(write_image(dir_ / "textures" / "red.png", red, PixelFormat::kU8).ok());
  write(R"({"blocks": [
      {"name": "brick", "texture": "textures/red.png", "specular": 0.3},
      {"name": "crate", "texture": {"top": "log_top", "side": "textures/red.png", "bottom": "stone"}},
      {"name": "fence", "render": "alpha_cut", "texture": "snow"},
      {"name": "glass", "render": "translucent", "texture": "snow", "opacity": 0.4}]})");
  auto p = load();
  ASSERT_TRUE(p.ok()) << p.error().message;
  ASSERT_EQ(p->size(), 5u);
  ASSERT_EQ(p->images().size(), 1u) << "one layer per image file";
  const Image& layer = p->images()[0];
  EXPECT_EQ(layer.width(), 2);
  EXPECT_EQ(layer.height(), 3);
  ASSERT_EQ(layer.channels(), 4);
  EXPECT_FLOAT_EQ(layer.at(1, 2, 0), 1.0f);
  EXPECT_FLOAT_EQ(layer.at(1, 2, 1), 0.0f);
  EXPECT_FLOAT_EQ(layer.at(1, 2, 3), 1.0f) << "RGB gets an opaque alpha";
  const BlockType& brick = (*p)[p->id("brick")];
  EXPECT_EQ(brick.texture_top, kTextureCount);
  EXPECT_EQ(brick.texture_bottom, kTextureCount);
  EXPECT_FLOAT_EQ(brick.specular, 0.3f);
  const BlockType& crate = (*p)[p->id("crate")];
  EXPECT_EQ(crate.texture_top, static_cast<int>(TextureId::kLogTop));
  EXPECT_EQ(crate.texture_side, kTextureCount);
  EXPECT_EQ(crate.texture_bottom, static_cast<int>(TextureId::kStone));
  EXPECT_EQ(p->render(p->id("fence")), RenderClass::kAlphaCut);
  EXPECT_FALSE(p->translucent(p->id("fence")));
  // Translucent blocks mesh as alpha-cut ones and are drawn blended (voxel_translucent_gl_test).
  EXPECT_TRUE(p->translucent(p->id("glass")));
  EXPECT_EQ(p->render(p->id("glass")), RenderClass::kAlphaCut);
  EXPECT_FALSE(p->is_opaque(p->id("glass")));
  EXPECT_FLOAT_EQ((*p)[p->id("glass")].opacity, 0.4f);
  EXPECT_EQ(p->first_alpha_cut(), p->id("fence"));
}

TEST_F(PaletteFile, ErrorsNameTheFileAndTheJsonPath) {
  write(R"({"blocks": [{"name": "stone", "texture": "stone"}, {"name": "slab", "texture": {"top": "stone", "side": "granite", "bottom": "stone"}}]})");
  auto p = load();
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error().message.rfind(file() + ": blocks[1].texture.side: no procedural texture 'granite' (one of stone, dirt, ", 0), 0u)
      << p.error().message;

  write(R"({"blocks": [{"name": "brick", "texture": "textures/none.png"}]})");
  p = load();
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error().message.rfind(file() + ": blocks[0].texture: ", 0), 0u) << p.error().message;
  EXPECT_NE(p.error().message.find("none.png"), std::string::npos) << p.error().message;

  write(R"({"blocks": [{"name": "window", "render": "glass", "texture": "snow"}]})");
  p = load();
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error().message.rfind(file() + ": blocks[0].render: ", 0), 0u) << p.error().message;

  write(R"({"blocks": [{"name": "stone", "texture": "stone"}, {"name": "stone", "texture": "dirt"}]})");
  p = load();
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error().message, file() + ": blocks[1].name: block palette: duplicate name 'stone'");

  write(R"({"blocks": [{"name": "lamp", "texture": "lantern", "emission": [1, "x", 0]}]})");
  p = load();
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error().message.rfind(file() + ": blocks[0].emission", 0), 0u) << p.error().message;

  write(R"({"blocks": [{"name": "lamp", "texture": {"top": "stone", "sides": "stone", "bottom": "stone"}}]})");
  p = load();
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error().message, file() + ": blocks[0].texture.sides: not a face group (top, side, bottom)");
}

TEST_F(PaletteFile, ImagesAreCheckedBeforeTheirPixelsAreRead) {
  Image wide(kMaxPaletteImageSide + 1, 1, 3);
  ASSERT_TRUE(write_image(dir_ / "textures" / "wide.png", wide, PixelFormat::kU8).ok());
  write(R"({"blocks": [{"name": "wide", "texture": "textures/wide.png"}]})");
  auto p = load();
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error().code, ErrorCode::kLimit) << p.error().message;
  EXPECT_EQ(p.error().message.rfind(file() + ": blocks[0].texture: ", 0), 0u) << p.error().message;
  // The embedded palette (and the fuzz target) never reads files.
  std::vector<std::string> warnings;
  auto embedded = parse_palette(R"({"blocks": [{"name": "wide", "texture": "wide.png"}]})", "fuzz.json", {}, warnings);
  ASSERT_FALSE(embedded.ok());
  EXPECT_EQ(embedded.error().message, "fuzz.json: blocks[0].texture: image files are not read here (wide.png)");
}

}  // namespace
}  // namespace sylva::voxel

// Procedural block textures: deterministic, cut-out textures have holes, solid ones none, and
// every texture of the standard palette exists.

#include <sylva/voxel/block.hpp>
#include <sylva/voxel/block_textures.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace sylva::voxel {
namespace {

TEST(BlockTextures, DeterministicAndCutOutOnlyWhereExpected) {
  for (int i = 0; i < kTextureCount; ++i) {
    const auto id = static_cast<TextureId>(i);
    const auto a = generate_block_texture(id, 16, 7);
    const auto b = generate_block_texture(id, 16, 7);
    ASSERT_EQ(a.diffuse.width(), 16);
    ASSERT_EQ(a.diffuse.channels(), 4);
    ASSERT_EQ(a.specular.channels(), 1);
    EXPECT_TRUE(std::equal(a.diffuse.data().begin(), a.diffuse.data().end(), b.diffuse.data().begin()))
        << texture_name(id);
    std::size_t cut = 0;
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) cut += a.diffuse.at(x, y, 3) < 0.5f;
    const std::string name(texture_name(id));
    const bool cutout = name.find("leaves") != std::string::npos || name == "tall_grass" || name == "flowers";
    if (cutout) {
      EXPECT_GT(cut, 10u) << name << " has holes";
      EXPECT_LT(cut, 250u) << name << " is not empty";
    } else {
      EXPECT_EQ(cut, 0u) << name << " is solid";
    }
  }
}

TEST(BlockTextures, StandardPaletteUsesValidLayers) {
  const BlockPalette& p = BlockPalette::standard();
  int emissive = 0, alpha = 0;
  for (std::size_t i = 1; i < p.size(); ++i) {
    const BlockType& t = p[static_cast<BlockId>(i)];
    for (int layer : {t.texture_top, t.texture_side, t.texture_bottom}) {
      EXPECT_GE(layer, 0);
      EXPECT_LT(layer, kTextureCount);
    }
    emissive += t.emits_light();
    alpha += t.render == RenderClass::kAlphaCut;
  }
  EXPECT_GE(emissive, 2);
  EXPECT_GE(alpha, 6);
  EXPECT_EQ(p.first_alpha_cut(), p.id("oak_leaves"));
}

}  // namespace
}  // namespace sylva::voxel

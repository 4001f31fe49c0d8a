// A height edit whose field no longer has the height texture's size (issue 15, the renderer's
// edit path, renderer.cpp update_height_textures): the stroke's rectangle cannot be uploaded into
// a texture of another size, so the whole texture is made again from the field. The counter grows
// by every sample of the new field, not the stroke's one, and the texture then holds the field.
#include <sylva/render/testing.hpp>
#include <sylva/terrain/renderer.hpp>

#include <gtest/gtest.h>

#include <memory>
#include <vector>

namespace sylva::terrain {
namespace {

using HeightEditTextureGl = render::GlTest;

TEST_F(HeightEditTextureGl, AFieldOfAnotherSizeReplacesTheWholeTexture) {
  HeightField field(37, 23, 3.0);
  for (std::size_t i = 0; i < field.samples().size(); ++i) field.samples()[i] = static_cast<float>(i % 13) * 0.5f;
  ChunkTreeSettings ts;
  ts.leaf_dimension = 9;
  auto tree = std::make_shared<const ChunkTree>(std::move(ChunkTree::build(field, ts)).value());
  const HeightField old_ground(20, 20, 3.0);  // the texture is made from a ground of another size
  auto renderer = TerrainRenderer::create(tree, &old_ground, {});
  ASSERT_TRUE(renderer.ok()) << renderer.error().describe();
  ASSERT_NE((*renderer)->height_texture(), nullptr);
  const std::int64_t before = (*renderer)->height_texels_uploaded();
  field.samples()[7 * 37 + 10] = 40.0f;
  ASSERT_TRUE((*renderer)->apply_height_edit(field, 10, 7, 11, 8).ok());
  EXPECT_EQ((*renderer)->height_texels_uploaded() - before, 37 * 23) << "the whole texture, not the stroke's texel";
  const render::Texture* tex = (*renderer)->height_texture();
  ASSERT_NE(tex, nullptr);
  GLint w = 0, h = 0;
  glGetTextureLevelParameteriv(tex->id(), 0, GL_TEXTURE_WIDTH, &w);
  glGetTextureLevelParameteriv(tex->id(), 0, GL_TEXTURE_HEIGHT, &h);
  EXPECT_EQ(w, 37);
  EXPECT_EQ(h, 23);
  std::vector<float> back(field.samples().size());
  glGetTextureImage(tex->id(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(back.size() * sizeof(float)), back.data());
  EXPECT_TRUE(back == field.samples());
}

}  // namespace
}  // namespace sylva::terrain

// Voxel block palettes (modules/voxel palette_file.hpp): JSON text -> palette, image files not
// read (an empty directory). What parses must be a palette the meshers and the renderer can take:
// air at 0, one entry per block, names [a-z0-9_]+, texture layers among the procedural ones,
// finite non-negative emission, the flat tables as long as the palette.
#include "support/fuzz_support.hpp"

#include <sylva/voxel/block_textures.hpp>
#include <sylva/voxel/palette_file.hpp>

#include <cmath>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sylva::voxel;
  std::vector<std::string> warnings;
  auto palette = parse_palette(sylva::fuzz::as_text(data, size), "fuzz.json", {}, warnings);
  for (const std::string& w : warnings) sylva::fuzz::require(!w.empty(), "an empty warning");
  if (!palette.ok()) {
    sylva::fuzz::require_message(palette.error());
    return 0;
  }
  const BlockPalette& p = *palette;
  sylva::fuzz::require(p.size() >= 2 && p.render(kAir) == RenderClass::kAir, "a palette without air at 0 or without blocks");
  sylva::fuzz::require(p.opaque_table().size() == p.size() && p.render_table().size() == p.size() && p.sides_only_table().size() == p.size(),
                       "lookup tables of another length than the palette");
  sylva::fuzz::require(p.images().empty(), "an image read without a directory");
  for (std::size_t i = 1; i < p.size(); ++i) {
    const BlockType& t = p[static_cast<BlockId>(i)];
    sylva::fuzz::require(!t.name.empty() && p.find(t.name).ok() && *p.find(t.name) == i, "a block name that does not find its block");
    for (int layer : {t.texture_top, t.texture_side, t.texture_bottom}) {
      sylva::fuzz::require(layer >= 0 && layer < kTextureCount, "a texture layer outside the procedural ones");
    }
    for (int c = 0; c < 3; ++c) sylva::fuzz::require(std::isfinite(t.emission[c]) && t.emission[c] >= 0.0f, "a bad emission");
    sylva::fuzz::require(t.render != RenderClass::kAir, "an air block after id 0");
  }
  return 0;
}

#pragma once
// The block palette as data (issue #16; seed 004 §1.3 blocks with top/side/bottom parts, §2.2
// opaque and cut-out textures, §2.3.2 specular maps, §2.3.3.2 light-emitting blocks): a JSON file
// lists the blocks in id order after air; the standard palette is data/palette.json, embedded and
// read by this parser, so a user's palette and the shipped one take the same path.
//
//   {"blocks": [
//     {"name": "stone", "texture": "stone", "specular": 0.25, "shininess": 24},
//     {"name": "grass", "texture": {"top": "grass_top", "side": "grass_side", "bottom": "dirt"}},
//     {"name": "oak_leaves", "render": "alpha_cut", "texture": "oak_leaves", "cull_same": false},
//     {"name": "brick", "texture": "textures/brick.png"},
//     {"name": "lantern", "texture": "lantern", "emission": [1.0, 0.75, 0.4]}]}
//
// A texture is one of the procedural textures by name (block_textures.hpp: stone, dirt,
// grass_top, ... glowstone) or an image file (a name ending in .png, .jpg, .jpeg, .tga, .tif,
// .tiff, .bmp or .exr) relative to the palette file, read as RGBA (alpha below 0.5 is cut for
// alpha_cut blocks) and resampled to the renderer's texture_size; at most 256 images, each side at
// most 4096. "render" is opaque (default) or alpha_cut. Numbers go through the params reflection
// (ranges, types, unknown keys warned). Any error fails the whole palette (blocks are referred to
// by name from worlds, species and generators, so leaving one out would move the error
// elsewhere); messages name the file and the JSON path, e.g. "blocks[3].texture.side".

#include <sylva/core/result.hpp>
#include <sylva/voxel/block.hpp>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::voxel {

// Largest palette file and largest image side read.
inline constexpr std::uintmax_t kMaxPaletteFileBytes = std::uintmax_t{4} << 20;
inline constexpr int kMaxPaletteImageSide = 4096;

// `directory` resolves image files (an empty path: images are refused, e.g. for the embedded
// palette and the fuzz target).
Result<BlockPalette> parse_palette(std::string_view text, std::string_view source, const std::filesystem::path& directory,
                                   std::vector<std::string>& warnings);
Result<BlockPalette> load_palette(const std::filesystem::path& path, std::vector<std::string>& warnings);
// data/palette.json (what BlockPalette::standard() holds).
Result<BlockPalette> builtin_palette();

}  // namespace sylva::voxel

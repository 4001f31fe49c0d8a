#pragma once
// Procedurally generated block textures (GL-free): one diffuse RGBA layer and one specular
// layer per TextureId, laid into a texture array by the renderer. Seed 004 used a sprite
// sheet of square tiles (§1.4); an array texture avoids bleeding between tiles under mipmapping.

#include <sylva/core/image.hpp>

#include <cstdint>
#include <string_view>

namespace sylva::voxel {

// The layer index of each procedural texture in the array.
enum class TextureId : int {
  kStone = 0,
  kDirt,
  kGrassTop,
  kGrassSide,
  kDryGrassTop,   // savanna and shrubland ground
  kDryGrassSide,
  kSand,
  kSnow,
  kGravel,
  kOakBark,
  kBirchBark,
  kAcaciaBark,
  kJungleBark,
  kLogTop,        // cut wood rings
  kOakLeaves,
  kBirchLeaves,
  kAcaciaLeaves,
  kJungleLeaves,
  kBushLeaves,
  kBerryLeaves,
  kTallGrass,     // cut-out grass tuft
  kFlowers,
  kLantern,       // emissive
  kGlowstone,     // emissive
  kCount
};
inline constexpr int kTextureCount = static_cast<int>(TextureId::kCount);

std::string_view texture_name(TextureId id);

// An RGBA diffuse image (alpha 0 = cut out) and a one-channel specular intensity image, both
// `size` x `size` (size in [4, 1024], asserted), deterministic for (id, seed).
struct BlockTextureImages {
  Image diffuse;
  Image specular;
};
BlockTextureImages generate_block_texture(TextureId id, int size, std::uint64_t seed = 1);

}  // namespace sylva::voxel
